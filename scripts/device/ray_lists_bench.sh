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
passes="gi-|cache-trace-diffuse-rays |frame \(GPU\)|error"
for round in 1 2; do
  for program in bounce-base bounce; do
    for scene in sunroom city; do
      echo "== $program $scene (round $round)"
      bash .devicepack/run.sh $program bench --scene $scene --res 1920x1080 --gi evolve \
        --frames 120 --time-of-day 12 --day-cycle 100000 --out /tmp/rl/$program-$scene-$round \
        2>&1 | tr '\r' '\n' | grep -E "$passes"
    done
  done
done
for scene in sunroom city; do
  echo "== bounce --bvh wide $scene"
  bash .devicepack/run.sh bounce bench --scene $scene --res 1920x1080 --gi evolve --bvh wide \
    --frames 120 --time-of-day 12 --day-cycle 100000 --out /tmp/rl/wide-$scene \
    2>&1 | tr '\r' '\n' | grep -E "$passes|vbuffer|shadows-trace|di-generate|reflections-trace"
done
