#!/bin/bash
# GPU timing of a library denoiser on Evolve's GI, builds against each other: usage
#   bash scripts/device/denoiser_bench.sh DENOISER LABEL...
# renders sunroom (desktop preset, --vbuffer trace, 240 animated frames) at 1920x1080 and
# 2560x1440 with --denoiser DENOISER, and at 1920x1080 with --denoiser hybrid, with each build
# .devicepack/bin/LABEL, two rounds in alternating order. Session 24 timed SVGF with the labels
# bounce-base bounce-stop bounce, session 25 ReBLUR with bounce-base bounce (docs/decisions.md).
# Pack first: ../shared/device/pack.sh build/bounce, copy the other builds next to bin/bounce,
# then run from the repository root with .devicepack carried. Writes the --timings files to
# $OUT/timings.tgz (the median per pass over frames 16+) and round 1's 1080p pictures.
set -u
denoiser=$1
shift
labels="$*"
reversed=$(for label in $labels; do echo $label; done | tac | tr '\n' ' ')
mkdir -p /tmp/b
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader
run() {
  label=$1 name=$2 res=$3
  shift 3
  bash .devicepack/run.sh $label render --preset desktop \
    --vbuffer trace --res $res --frames 240 --animate --scene sunroom "$@" \
    --timings /tmp/b/$name-$label.json --out /tmp/b/$name-$label.png 2>&1 | grep -E "rror"
}
# A fresh machine's first run is slow.
bash .devicepack/run.sh bounce render --scene sunroom --preset mobile --frames 16 --out /tmp/w.png > /dev/null 2>&1
for round in 1 2; do
  order=$labels
  [ $round = 2 ] && order=$reversed
  for label in $order; do
    run $label $denoiser-1080-r$round 1920x1080 --denoiser $denoiser
    run $label $denoiser-1440-r$round 2560x1440 --denoiser $denoiser
    run $label hybrid-1080-r$round 1920x1080 --denoiser hybrid
  done
done
tar czf $OUT/timings.tgz -C /tmp/b $(cd /tmp/b && ls *.json)
for label in $labels; do cp /tmp/b/$denoiser-1080-r1-$label.png $OUT/ 2>/dev/null; done
