#!/usr/bin/env bash
# make soak: long animated runs of `bounce bench --soak` (camera path, day-night cycle, moving
# objects): every frame checked for NaN or infinite pixels, host and device memory for growth
# after the warm-up; then a shorter run with the validation layer on, which must stay silent.
# On lavapipe the defaults take a few minutes; on a GPU (docs/testing.md, "Soak") run it with
#   SOAK_FRAMES=10000 SOAK_RES=1280x720 SOAK_VALIDATED_FRAMES=200 scripts/soak.sh
# SOAK_SCENES (default "sunroom city"), SOAK_OUT (default out/soak), BOUNCE (the program: a
# command of several words, such as "bash .devicepack/run.sh bounce", is fine).
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
read -ra bounce <<<"${BOUNCE:-$root/build/bounce}"
frames=${SOAK_FRAMES:-300}
res=${SOAK_RES:-96x54}
validated=${SOAK_VALIDATED_FRAMES:-40}
warmup=${SOAK_WARMUP:-100}
out=${SOAK_OUT:-$root/out/soak}
scenes=${SOAK_SCENES:-sunroom city}

for scene in $scenes; do
  echo "soak: $scene, $frames frames at $res"
  "${bounce[@]}" bench --scene "$scene" --res "$res" --frames "$frames" --soak \
    --soak-warmup "$warmup" --contact-frames 8 --out "$out/$scene"
  echo "soak: $scene, $validated frames with validation"
  "${bounce[@]}" bench --scene "$scene" --res "$res" --frames "$validated" --validate \
    --contact-frames 1 --out "$out/$scene-validated" >/dev/null
done
echo "soak: passed ($scenes; reports in $out)"
