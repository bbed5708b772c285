#!/bin/bash
# GPU benchmark of the GI denoisers (evolve, svgf) and TAA, and a re-timing of ReSTIR DI with the
# BRDF candidate limited to glossy pixels (docs/benchmarks.md, "Denoisers and TAA"). Pack first:
# ../shared/device/pack.sh build/bounce ../shared/scenes/cornell_box; then run on the GPU machine
# from the repository root with .devicepack carried. Writes the --timings files as
# $OUT/timings.tgz (the median per pass is what docs/benchmarks.md reports) and a few pictures.
set -u
mkdir -p /tmp/b
run() {
  name=$1 res=$2; shift 2
  echo "== $name: $res $*"
  bash .devicepack/run.sh bounce render --preset desktop --vbuffer trace --res $res --frames 240 \
    --animate "$@" --timings /tmp/b/$name.json --out /tmp/b/$name.png 2>&1 | grep -E "wall time|rror"
}
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader
CORNELL=".devicepack/data/cornell_box/cornell_box.gltf --lambert"
run sunroom-evolve 1920x1080 --scene sunroom
run sunroom-svgf 1920x1080 --scene sunroom --denoiser svgf
run sunroom-none-notaa 1920x1080 --scene sunroom --denoiser none --no-taa
run sunroom-evolve-1440 2560x1440 --scene sunroom
run sunroom-svgf-1440 2560x1440 --scene sunroom --denoiser svgf
run cornell-evolve 1920x1080 --scene $CORNELL
run cornell-svgf 1920x1080 --scene $CORNELL --denoiser svgf
run spheres 1920x1080 --scene spheres
tar czf $OUT/timings.tgz -C /tmp/b $(cd /tmp/b && ls *.json)
for f in sunroom-evolve sunroom-svgf cornell-svgf; do cp /tmp/b/$f.png $OUT/ 2>/dev/null; done
