#!/bin/bash
# The GPU cost of ReSTIR GI's energy fix (docs/gi/restir-gi.md, "Energy"): `bounce bench` of
# Evolve on sunroom (sun fixed at noon) and city, 1920x1080 desktop, 120 frames, for each
# program packed (PROGRAMS, default: bounce-base, the build before the fix, then bounce),
# alternated twice. Pack first (from the repository root):
#   cp BASE_BUILD/bounce /tmp/base/bounce-base
#   ../shared/device/pack.sh build/bounce /tmp/base/bounce-base
# then run from the repository root on the GPU machine with .devicepack carried.
set -u
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader
passes="gi-|frame \(GPU\)|error"
for round in 1 2; do
  for program in ${PROGRAMS:-bounce-base bounce}; do
    for scene in sunroom city; do
      echo "== $program $scene (round $round)"
      bash .devicepack/run.sh $program bench --scene $scene --res 1920x1080 --gi evolve \
        --frames 120 --time-of-day 12 --day-cycle 100000 --out /tmp/energy/$program-$scene-$round \
        2>&1 | tr '\r' '\n' | grep -E "$passes"
    done
  done
done
