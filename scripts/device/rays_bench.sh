#!/bin/bash
# Rays per pass on the GPU machine (issue 24, docs/benchmarks.md "Rays per pass"): `bounce bench`
# with the GPU ray counter on sunroom and city, 1920x1080 desktop, the three GI modes, then
# Evolve again without counting to measure what counting costs. Last, where the resident set of
# a long run grows: /proc/PID/smaps sampled twice and compared mapping by mapping. Pack first:
#   ../shared/device/pack.sh build/bounce ../shared/scenes/cornell_box
# then run from the repository root on the GPU machine with .devicepack carried.
set -u
B="bash .devicepack/run.sh bounce"
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader
for scene in sunroom city; do
  $B bench --scene $scene --res 1920x1080 --gi evolve,gi10,lux --frames 240 \
    --out /tmp/rays/$scene 2>&1 | tr '\r' '\n' | grep -vE "frames:|^$"
  $B bench --scene $scene --res 1920x1080 --gi evolve --frames 240 --no-count-rays \
    --out /tmp/rays/$scene-uncounted 2>&1 | tr '\r' '\n' | grep -E "frame \(GPU\)|error"
done
# Resident set by mapping: sunroom at 1280x720, sampled at 60 s and 150 s later, then stopped.
$B bench --scene sunroom --res 1280x720 --frames 100000 --out /tmp/rss > /tmp/rss.log 2>&1 &
sleep 5
pid=
for p in $(pgrep -f "bench --scene sunroom --res 1280x720"); do
  readlink /proc/$p/exe | grep -q bash || pid=$p  # the program, not run.sh's shell
done
smaps() { awk '/^[0-9a-f]+-[0-9a-f]+ /{name=$6; if (name=="") name="[anon]"} /^Rss:/{rss[name]+=$2} END{for (n in rss) print n, rss[n]}' /proc/$pid/smaps | sort; }
sleep 55; smaps > /tmp/rss-a.txt; grep VmRSS /proc/$pid/status
sleep 150; smaps > /tmp/rss-b.txt; grep VmRSS /proc/$pid/status
echo "Rss growth by mapping (kB, 150 s apart):"
join -a2 -e0 -o 0,1.2,2.2 /tmp/rss-a.txt /tmp/rss-b.txt | awk '$3-$2 != 0 {print $3-$2, $1}' | sort -rn | head -15
kill $pid; wait
tar czf $OUT/rays.tgz --exclude='*.png' --exclude='*.svg' -C /tmp rays
cp /tmp/rays/sunroom/desktop-evolve-passes.png $OUT/ 2>/dev/null
