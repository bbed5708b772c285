#!/bin/bash
# Issue 21's comparison of the GI modes and denoisers (docs/denoise.md, "Every mode and
# denoiser"): Evolve with each --denoiser, GI-1.0 and Lux (which bring their own), on cornell,
# sunroom and foliage at 480x270, desktop preset, 64 static frames: HDR-FLIP and relMSE of the
# linear `taa` view against `bounce reference` (2,048 spp, 16 bounces), and the temporal
# stability: the mean LDR-FLIP between consecutive tonemapped frames 48-64. Pack first:
#   ../shared/device/pack.sh build/bounce ../shared/scenes/cornell_box
# then run from the repository root on the GPU machine with .devicepack carried.
set -u
B="bash .devicepack/run.sh bounce"
D=.devicepack/data
R=480x270
mkdir -p /tmp/dc
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader
declare -A SCENE=([cornell]="--scene $D/cornell_box/cornell_box.gltf --lambert"
  [sunroom]="--scene sunroom" [foliage]="--scene foliage")
declare -A CONFIG=([evolve]="--gi evolve --denoiser evolve" [svgf]="--gi evolve --denoiser svgf"
  [reblur]="--gi evolve --denoiser reblur" [hybrid]="--gi evolve --denoiser hybrid"
  [none]="--gi evolve --denoiser none" [gi10]="--gi gi10" [lux]="--gi lux")
CONFIGS="evolve svgf reblur hybrid none gi10 lux"
$B render --scene sunroom --preset mobile --frames 16 --out /tmp/w.png > /dev/null 2>&1  # warm-up
for s in cornell sunroom foliage; do
  $B reference ${SCENE[$s]} --res $R --spp 2048 --out /tmp/dc/$s-ref.exr > /dev/null 2>&1 ||
    echo "reference $s failed"
  for c in $CONFIGS; do
    $B render ${SCENE[$s]} ${CONFIG[$c]} --preset desktop --res $R --frames 64 --view taa \
      --out /tmp/dc/$s-$c.exr > /dev/null 2>&1 || echo "render $s $c failed"
    $B compare /tmp/dc/$s-$c.exr /tmp/dc/$s-ref.exr --json /tmp/dc/$s-$c.json > /dev/null 2>&1
    rm -rf /tmp/dc/frames && mkdir -p /tmp/dc/frames
    $B render ${SCENE[$s]} ${CONFIG[$c]} --preset desktop --res $R --frames 64 \
      --out /tmp/dc/frames/ > /dev/null 2>&1 || echo "frames $s $c failed"
    for i in $(seq 47 62); do
      a=$(printf /tmp/dc/frames/frame_%04d.png $i)
      b=$(printf /tmp/dc/frames/frame_%04d.png $((i + 1)))
      $B compare $b $a 2>/dev/null | awk '/FLIP mean/ {print $3}'
    done > /tmp/dc/$s-$c.stability
  done
done
python3 - <<'PY'
import json
print("| scene | config | HDR-FLIP | relMSE | frame-to-frame LDR-FLIP, 48-64 |")
for s in ["cornell", "sunroom", "foliage"]:
    for c in ["evolve", "svgf", "reblur", "hybrid", "none", "gi10", "lux"]:
        try:
            j = json.load(open(f"/tmp/dc/{s}-{c}.json"))
            v = [float(x) for x in open(f"/tmp/dc/{s}-{c}.stability").read().split()]
            st = sum(v) / len(v) if v else float("nan")
            print(f"| {s} | {c} | {j['flip']['mean']:.3f} | {j['rel_mse']:.4f} | {st:.4f} ({len(v)}) |")
        except Exception as e:
            print(f"| {s} | {c} | - | - | - | {e}")
PY
