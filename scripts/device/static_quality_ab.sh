#!/bin/bash
# A/B of a static view's quality on the GPU machine: two builds of `bounce` (packed as `bounce`
# and `bounce-base`, as for ab_bench.sh) render cornell (--lambert), sunroom and foliage at
# 480x270, desktop preset, default GI, 64 static frames. Per build and scene: HDR-FLIP and
# relMSE of the linear `taa` view against `bounce reference` (2,048 spp) and the temporal
# stability, the mean LDR-FLIP between consecutive tonemapped frames 48-64 (as
# denoiser_comparison.sh measures them). Pack first:
#   ../shared/device/pack.sh build/bounce /tmp/bounce-base ../shared/scenes/cornell_box
# then run `bash .devicepack/static_quality_ab.sh` there (carry .devicepack). Extra arguments
# go to both builds' renders.
set -u
D=.devicepack/data
R=480x270
mkdir -p /tmp/sq
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader
declare -A SCENE=([cornell]="--scene $D/cornell_box/cornell_box.gltf --lambert"
  [sunroom]="--scene sunroom" [foliage]="--scene foliage")
run() { bash .devicepack/run.sh "$@"; }
run bounce render --scene sunroom --preset mobile --frames 16 --out /tmp/w.png > /dev/null 2>&1
for s in cornell sunroom foliage; do
  run bounce reference ${SCENE[$s]} --res $R --spp 2048 --out /tmp/sq/$s-ref.exr > /dev/null 2>&1 ||
    echo "reference $s failed"
  for b in bounce bounce-base; do
    run $b render ${SCENE[$s]} --preset desktop --res $R --frames 64 --view taa "$@" \
      --out /tmp/sq/$s-$b.exr > /dev/null 2>&1 || echo "render $s $b failed"
    flip=$(run bounce compare /tmp/sq/$s-$b.exr /tmp/sq/$s-ref.exr 2>/dev/null |
      awk '/FLIP mean/ {f=$3} /relMSE/ {r=$2} END {print f, r}')
    rm -rf /tmp/sq/frames && mkdir -p /tmp/sq/frames
    run $b render ${SCENE[$s]} --preset desktop --res $R --frames 64 "$@" \
      --out /tmp/sq/frames/ > /dev/null 2>&1 || echo "frames $s $b failed"
    stability=$(for i in $(seq 47 62); do
      run bounce compare $(printf /tmp/sq/frames/frame_%04d.png $((i + 1))) \
        $(printf /tmp/sq/frames/frame_%04d.png $i) 2>/dev/null | awk '/FLIP mean/ {print $3}'
    done | awk '{s += $1; n++} END {if (n) printf "%.4f", s / n}')
    echo "$s $b: HDR-FLIP relMSE $flip stability $stability"
  done
  cp /tmp/sq/$s-bounce.exr /tmp/sq/$s-bounce-base.exr /tmp/sq/$s-ref.exr "$OUT/" 2>/dev/null
done
