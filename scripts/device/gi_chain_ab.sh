#!/usr/bin/env bash
# A/B of two builds on the GI chain and the whole frame (docs/benchmarks.md, "Session 21"): the
# packed `bounce` against `bounce-base` (an earlier build copied into .devicepack/bin/), sunroom
# and city at the mobile preset, desktop 1080p and desktop 1440p, 160 animated frames, two rounds
# alternating the builds; then both builds' static composite against a 2,048-spp reference. Pack
# first, from the project root:
#   ../shared/device/pack.sh build/bounce && cp OLD_BUILD/bounce .devicepack/bin/bounce-base
#   cp scripts/device/gi_chain_ab.sh .devicepack/
# then run `bash .devicepack/gi_chain_ab.sh` there (carry .devicepack); $OUT/timings.tgz holds
# the --timings files (NAME-PRESET-BUILD-ROUND.json).
set -u
mkdir -p /tmp/b /tmp/q
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader
run() {  # build, label, then render arguments
  local b=$1 name=$2
  shift 2
  bash .devicepack/run.sh "$b" render --vbuffer trace --frames 160 --animate --gi evolve "$@" \
    --timings "/tmp/b/$name.json" --out "/tmp/b/$name.png" 2>&1 | grep -iE "error"
}
run bounce warm-up --scene sunroom --preset mobile  # the first run on a fresh machine is slow
for round in 1 2; do
  for b in bounce-base bounce; do
    for s in sunroom city; do
      run $b "$s-1440-$b-$round" --scene $s --preset desktop --res 2560x1440
      run $b "$s-1080-$b-$round" --scene $s --preset desktop
      run $b "$s-mobile-$b-$round" --scene $s --preset mobile
    done
  done
done
rm -f /tmp/b/warm-up.json
tar czf "$OUT/timings.tgz" -C /tmp/b $(cd /tmp/b && ls ./*.json)
Q="--preset desktop --res 1280x720 --vbuffer trace --gi evolve --frames 64 --view composite"
for s in sunroom city; do
  bash .devicepack/run.sh bounce reference --scene $s --res 1280x720 --pixel-centre --spp 2048 \
    --out "/tmp/q/$s-ref.exr" > /dev/null 2>&1
  for b in bounce-base bounce; do
    # $Q unquoted: several options
    bash .devicepack/run.sh $b render --scene $s $Q --out "/tmp/q/$s-$b.exr" > /dev/null 2>&1
    echo "quality $s $b: $(bash .devicepack/run.sh bounce compare "/tmp/q/$s-$b.exr" \
      "/tmp/q/$s-ref.exr" 2>&1 | grep -E 'relMSE|FLIP mean' | tr -s ' ' | tr '\n' ' ')"
  done
done
