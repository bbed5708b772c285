#!/usr/bin/env bash
# A/B of the reflection passes under camera motion (docs/reflections.md, "Motion"): the packed
# `bounce` against `bounce-base` (an earlier build copied into .devicepack/bin/), 1920x1080
# desktop, 240 animated frames (the camera moves: the motion-only parallax tests run), two
# rounds alternating the builds. Pack first, from the project root:
#   ../shared/device/pack.sh build/bounce && cp OLD_BUILD/bounce .devicepack/bin/bounce-base
#   cp scripts/device/reflections_motion_ab.sh .devicepack/
# then run `bash .devicepack/reflections_motion_ab.sh` there (carry .devicepack); $OUT/timings.tgz
# holds the --timings files (SCENE-BUILD-ROUND.json).
set -u
mkdir -p /tmp/b
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader
run() {  # build, label, then render arguments
  local b=$1 name=$2
  shift 2
  bash .devicepack/run.sh "$b" render --preset desktop --vbuffer trace --res 1920x1080 \
    --frames 240 --animate "$@" --timings "/tmp/b/$name.json" --out "/tmp/b/$name.png" 2>&1 |
    grep -iE "error"
}
# A fresh machine's first run is slow.
bash .devicepack/run.sh bounce render --scene sunroom --preset mobile --frames 16 --out /tmp/w.png > /dev/null 2>&1
for round in 1 2; do
  for b in bounce-base bounce; do
    for s in sunroom-glossy city spheres; do run $b "$s-$b-$round" --scene $s; done
  done
done
tar czf "$OUT/timings.tgz" -C /tmp/b $(cd /tmp/b && ls ./*.json)
cp /tmp/b/sunroom-glossy-bounce-1.png /tmp/b/spheres-bounce-1.png "$OUT/"
