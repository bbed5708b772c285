#!/bin/bash
# GPU benchmark of the reflection and ReSTIR DI passes (docs/benchmarks.md, "Reflections and
# ReSTIR DI"). Pack first: ../shared/device/pack.sh build/bounce ../shared/scenes/cornell_box;
# then run on the GPU machine from the repository root with .devicepack carried. Writes the
# --timings files as $OUT/timings.tgz (each holds every pass of every frame; the median per
# pass is what docs/benchmarks.md reports).
set -u
mkdir -p /tmp/b
R="bash .devicepack/run.sh bounce render --preset desktop --vbuffer trace --res 1920x1080 --frames 240 --animate"
run() { name=$1; shift; echo "== $name: $*"; $R "$@" --timings /tmp/b/$name.json --out /tmp/b/$name.png 2>&1 | grep -E "wall time|error|Error" ; }
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader
run manylights --scene manylights
run manylights-uniform --scene manylights --di uniform
run manylights-dioff --scene manylights --di off
run city-night --scene city --time-of-day 22
run city10k-night --scene city-10k --time-of-day 22
run city-day --scene city
run sunroom-glossy --scene sunroom-glossy
run spheres --scene spheres
run cornell --scene .devicepack/data/cornell_box/cornell_box.gltf --lambert
run spheres-nobrdf --scene spheres --di-brdf-candidates 0
run cornell-nobrdf --scene .devicepack/data/cornell_box/cornell_box.gltf --lambert --di-brdf-candidates 0
run city-night-uniform --scene city --time-of-day 22 --di uniform
run city-night-dioff --scene city --time-of-day 22 --di off
tar czf $OUT/timings.tgz -C /tmp/b $(cd /tmp/b && ls *.json)
for f in manylights city-night spheres sunroom-glossy; do cp /tmp/b/$f.png $OUT/ 2>/dev/null; done
