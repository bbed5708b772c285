#!/bin/bash
# bench-rays with both BLAS layouts (issue 22; docs/ray-tracing.md, "The wide compressed BLAS"):
# city and sunroom at 1920x1080, the two layouts alternated twice (binary, wide, binary, wide) so
# that drift of the GPU's clocks shows. Pack first:
#   ../shared/device/pack.sh build/bounce
# then run from the repository root on the GPU machine with .devicepack carried.
set -u
B="bash .devicepack/run.sh bounce"
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader
for scene in city sunroom; do
  for round in 1 2; do
    for layout in binary wide; do
      echo "== $scene --bvh $layout (round $round)"
      $B bench-rays --scene $scene --bvh $layout 2>&1 | grep -vE "^$"
    done
  done
done
