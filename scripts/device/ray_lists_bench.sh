#!/bin/bash
# The GI chain with and without the ray lists (docs/benchmarks.md, "Ray lists"): `bounce bench`
# of Evolve on sunroom (sun fixed at noon) and city, 1920x1080 desktop, 120 frames, this build
# against a build of the commit before (`bounce-base`, packed beside it), alternated twice.
# Then the frame with the wide BLAS. Pack first (from the repository root):
#   cp BASE_BUILD/bounce /tmp/base/bounce-base
#   ../shared/device/pack.sh build/bounce /tmp/base/bounce-base
# then run from the repository root on the GPU machine with .devicepack carried.
set -u
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader
source "$(dirname "${BASH_SOURCE[0]}")/evolve_rounds.sh"
passes="gi-|cache-trace-diffuse-rays |frame \(GPU\)|error"
evolve_rounds /tmp/rl "$passes" bounce-base bounce
for scene in sunroom city; do
  echo "== bounce --bvh wide $scene"
  evolve_bench bounce $scene /tmp/rl/wide-$scene \
    "$passes|vbuffer|shadows-trace|di-generate|reflections-trace" --bvh wide
done
