#!/bin/bash
# Issue 23's comparison along a camera path (docs/gi/comparison.md, "Along a camera path"):
# sunroom at 480x270, desktop preset, the camera dollying and panning linearly from the scene's
# camera over 64 frames (scripts/device/gi_path.json; the scene's objects still), each GI mode's
# linear `taa` view at frames 8, 16, 32, 48 and 64 of the path against `bounce reference`
# (2,048 spp, 16 bounces) from that frame's camera; then 64 static frames at the path's last
# camera. Pack first: ../shared/device/pack.sh build/bounce, then run from the repository root
# on the GPU machine with .devicepack carried. Prints HDR-FLIP / relMSE; the JSON and frame 32's
# side-by-side pictures in $OUT/path.tgz.
set -u
B="bash .devicepack/run.sh bounce"
R=480x270
P=scripts/device/gi_path.json
mkdir -p /tmp/path
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader
# The camera of the path's last frame of an N-frame run (frame N-1 at (N-1)/30 s of 2.1 s).
camera() {
  python3 -c "
import sys; n=int(sys.argv[1]); t=(n-1)/63.0
p0=(7.7,1.7,5.7); p1=(6.4,1.45,4.9); t0=(2.5,0.6,2.4); t1=(2.5,0.7,3.7)
l=lambda a,b: ','.join('%.6f'%(x+(y-x)*t) for x,y in zip(a,b))
print(l(p0,p1)+':'+l(t0,t1)+':65')" $1
}
$B render --scene sunroom --preset mobile --frames 16 --out /tmp/w.png > /dev/null 2>&1  # warm-up
for n in 8 16 32 48 64; do
  $B reference --scene sunroom --camera "$(camera $n)" --res $R --spp 2048 \
    --out /tmp/path/ref-$n.exr > /dev/null 2>&1 || echo "reference $n failed"
done
for gi in evolve gi10 lux; do
  for n in 8 16 32 48 64; do
    $B render --scene sunroom --preset desktop --res $R --gi $gi --frames $n --camera-path $P \
      --view taa --out /tmp/path/$gi-$n.exr > /dev/null 2>&1 || echo "render $gi $n failed"
    $B compare /tmp/path/$gi-$n.exr /tmp/path/ref-$n.exr --json /tmp/path/$gi-$n.json > /dev/null 2>&1
  done
  $B render --scene sunroom --preset desktop --res $R --gi $gi --frames 64 --camera "$(camera 64)" \
    --view taa --out /tmp/path/$gi-static.exr > /dev/null 2>&1 || echo "render $gi static failed"
  $B compare /tmp/path/$gi-static.exr /tmp/path/ref-64.exr --json /tmp/path/$gi-static.json > /dev/null 2>&1
  $B compare /tmp/path/$gi-32.exr /tmp/path/ref-32.exr --side-by-side /tmp/path/$gi-32-sbs.png > /dev/null 2>&1
done
python3 - /tmp/path <<'PY'
import json, sys
out = sys.argv[1]
for gi in ["evolve", "gi10", "lux"]:
    row = []
    for n in ["8", "16", "32", "48", "64", "static"]:
        try:
            j = json.load(open(f"{out}/{gi}-{n}.json"))
            row.append(f"{n}: {j['flip']['mean']:.3f}/{j['rel_mse']:.4f}")
        except Exception as e:
            row.append(f"{n}: -")
    print(gi, " | ".join(row))
PY
tar czf $OUT/path.tgz -C /tmp/path $(cd /tmp/path && ls *.json *.png)
