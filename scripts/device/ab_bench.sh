#!/usr/bin/env bash
# A/B timing on the GPU machine: two builds of `bounce` (packed as `bounce` and `bounce-base`)
# render the same animated runs in turn (A B B A, so that a drift of the machine's clocks falls
# on both), 240 frames each with per-pass GPU timestamps. Pack first, from the project root:
#   cp <other build>/bounce /tmp/bounce-base
#   ../shared/device/pack.sh build/bounce /tmp/bounce-base && cp scripts/device/ab_bench.sh .devicepack/
# then run `bash .devicepack/ab_bench.sh` there (carry .devicepack). $OUT/ab.tgz holds the
# --timings files, named <scene>-<preset>-<new|base>-<round>.json; scripts/ab_summary.py reads them.
set -u
run() {  # build, label, then render arguments
  local build=$1 label=$2; shift 2
  bash .devicepack/run.sh "$build" render --vbuffer trace --frames 240 --animate --gi evolve \
    --timings "$OUT/$label.json" --out /tmp/ab.png "$@" > /dev/null 2>&1 || echo "failed: $build $label"
}
# A throw-away run first: the first run on a freshly started machine measured up to 3x slower.
run bounce warm-up --scene sunroom --preset mobile
rm -f "$OUT/warm-up.json"
for scene in sunroom city; do
  for preset in mobile desktop; do
    for round in 1 2; do
      order="bounce bounce-base"; [ $round = 2 ] && order="bounce-base bounce"
      for build in $order; do
        name=new; [ $build = bounce-base ] && name=base
        run $build "$scene-$preset-$name-$round" --scene $scene --preset $preset
      done
    done
  done
done
cd "$OUT" && tar czf ab.tgz ./*.json && rm ./*.json
