#!/bin/bash
# GPU timings of the three seed GI systems side by side (Evolve, GI-1.0, Lux; issue 23) and of
# the library denoisers on Evolve's GI (SVGF, ReBLUR-style, hybrid; issue 21): 240 animated
# frames each (docs/benchmarks.md, "GI modes and denoisers"). Pack first:
#   ../shared/device/pack.sh build/bounce ../shared/scenes/cornell_box
# then run from the repository root on the GPU machine with .devicepack carried. Writes the
# --timings files as $OUT/timings.tgz (the median per pass is what the docs report) and pictures.
set -u
mkdir -p /tmp/b
run() {
  name=$1 preset=$2 res=$3; shift 3
  echo "== $name: $preset $res $*"
  bash .devicepack/run.sh bounce render --preset $preset ${res:+--res $res} --frames 240 \
    --animate "$@" --timings /tmp/b/$name.json --out /tmp/b/$name.png 2>&1 | grep -E "wall time|rror"
}
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader
for scene in sunroom city; do
  run $scene-evolve desktop 1920x1080 --scene $scene
  run $scene-gi10 desktop 1920x1080 --scene $scene --gi gi10
  run $scene-lux desktop 1920x1080 --scene $scene --gi lux
  run $scene-evolve-mobile mobile "" --scene $scene
  run $scene-gi10-mobile mobile "" --scene $scene --gi gi10
done
for denoiser in svgf reblur hybrid; do
  run sunroom-$denoiser desktop 1920x1080 --scene sunroom --denoiser $denoiser
  run sunroom-$denoiser-1440 desktop 2560x1440 --scene sunroom --denoiser $denoiser
done
run sunroom-evolve-1440 desktop 2560x1440 --scene sunroom
tar czf $OUT/timings.tgz -C /tmp/b $(cd /tmp/b && ls *.json)
for f in sunroom-gi10 sunroom-lux city-gi10 city-lux sunroom-reblur sunroom-hybrid; do
  cp /tmp/b/$f.png $OUT/ 2>/dev/null
done
