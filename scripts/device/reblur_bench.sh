#!/bin/bash
# GPU timing of the library ReBLUR on Evolve's GI (docs/decisions.md, "ReBLUR's blurs rotated
# per 8x8 tile" and "ReBLUR's anti-firefly window in shared memory"): bounce-base and bounce in
# .devicepack/bin on sunroom at 1920x1080 and 2560x1440 with --denoiser reblur, and at 1920x1080
# with --denoiser hybrid, two rounds in alternating order. Pack first: ../shared/device/pack.sh
# build/bounce <base build>/bounce-base, then run from the repository root with .devicepack
# carried. Writes the --timings files to $OUT/timings.tgz (the median per pass over frames 16+).
set -u
mkdir -p /tmp/b
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader
run() {
  label=$1 name=$2 res=$3; shift 3
  bash .devicepack/run.sh $label render --preset desktop \
    --vbuffer trace --res $res --frames 240 --animate --scene sunroom "$@" \
    --timings /tmp/b/$name-$label.json --out /tmp/b/$name-$label.png 2>&1 | grep -E "rror"
}
# A fresh machine's first run is slow.
bash .devicepack/run.sh bounce render --scene sunroom --preset mobile --frames 16 --out /tmp/w.png > /dev/null 2>&1
for round in 1 2; do
  labels="bounce-base bounce"
  [ $round = 2 ] && labels="bounce bounce-base"
  for label in $labels; do
    run $label reblur-1080-r$round 1920x1080 --denoiser reblur
    run $label reblur-1440-r$round 2560x1440 --denoiser reblur
    run $label hybrid-1080-r$round 1920x1080 --denoiser hybrid
  done
done
tar czf $OUT/timings.tgz -C /tmp/b $(cd /tmp/b && ls *.json)
cp /tmp/b/reblur-1080-r1-bounce.png /tmp/b/reblur-1080-r1-bounce-base.png $OUT/ 2>/dev/null
