#!/bin/bash
# The GPU machine's soak and benchmark comparison (issue 24; docs/testing.md "Soak" and
# docs/benchmarks.md). Pack first with the validation layer:
#   ../shared/device/pack.sh --validation build/bounce ../shared/scenes/cornell_box
# then run from the repository root on the GPU machine with .devicepack carried.
# Writes $OUT/soak.tgz (the bench.json reports), the comparison plot and a few pictures.
set -u
nvidia-smi --query-gpu=name,driver_version,memory.total --format=csv,noheader
# 10,000 animated frames of sunroom and city (camera path, day-night cycle, moving objects), every
# frame checked; then 200 frames with the validation layer.
BOUNCE="bash .devicepack/run.sh bounce" SOAK_FRAMES=${SOAK_FRAMES:-10000} SOAK_RES=1280x720 \
  SOAK_WARMUP=200 SOAK_VALIDATED_FRAMES=200 SOAK_OUT=/tmp/soak bash scripts/soak.sh 2>&1 |
  tr '\r' '\n' | grep -E "soak|error|-> " | grep -v "frames:"
echo "soak exit: ${PIPESTATUS[0]}"
# Presets x GI modes side by side at each preset's resolution.
bash .devicepack/run.sh bounce bench --scene sunroom --preset mobile,desktop --gi evolve,cache \
  --frames 240 --out /tmp/compare 2>&1 | tr '\r' '\n' | grep -E "error|-> "
# A frame too large for the device: the out-of-memory message.
bash .devicepack/run.sh bounce render --scene sunroom --res 16384x16384 --frames 1 \
  --out /tmp/huge.png > /tmp/huge.log 2>&1
echo "huge exit: $?"; tail -2 /tmp/huge.log
tar czf $OUT/soak.tgz --exclude='*.png' --exclude='*.svg' -C /tmp soak compare
cp /tmp/compare/comparison.png /tmp/compare/comparison.svg $OUT/
cp /tmp/soak/city/desktop-evolve-contact.png $OUT/city-soak-contact.png
cp /tmp/soak/sunroom/desktop-evolve-passes.png $OUT/sunroom-soak-passes.png
