#!/bin/bash
# The hardware tracer against the software BVH on the GPU machine (issue 22, deliverable 4;
# docs/ray-tracing.md "The hardware tracer"): its agreement test, a validation run, then
# `bench-rays --tracer both` at 1920x1080 on sunroom and city. Pack first:
#   ../shared/device/pack.sh --validation build/bounce build/tests/test_hardware_tracer
# then run from the repository root on the GPU machine with .devicepack carried.
set -u
B="bash .devicepack/run.sh bounce"
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader
BOUNCE_VALIDATE=1 bash .devicepack/run.sh test_hardware_tracer 2>&1 | tail -30
$B bench-rays --scene city --res 320x180 \
  --iterations 1 --tracer both --validate --verbose 2>&1 | tail -25
for scene in sunroom city; do
  $B bench-rays --scene $scene --res 1920x1080 --tracer both --verbose --json $OUT/$scene.json
done
