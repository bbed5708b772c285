#!/bin/bash
# Issue 21 item 7's ghosting column (docs/denoise.md, "Ghosting along moving objects"): on
# `sunroom` at 480x270, desktop preset, a still camera while the scene's objects move (the
# yellow cube slides towards the window, the blue panel swings open), each GI mode and denoiser
# renders 48 animated frames (the last at t = 47/30 s) and, for comparison, 48 frames of the
# scene frozen at that pose. Both against `bounce reference` at that pose (2,048 spp), whole
# image (HDR-FLIP, relMSE) and in the trail (`bounce compare --trail`: the pixels that changed
# since the reference 10 frames earlier). Pack first (../shared/device/pack.sh build/bounce), run
# from the repository root on the GPU machine with .devicepack carried; the table on stdout,
# each run against the reference as /tmp/ghost/{moving,frozen}-CONFIG.png.
set -u
B="bash .devicepack/run.sh bounce"
R=${RES:-480x270}
T=1.5666667   # frame 47 at 30 frames a second
TP=1.2333333  # frame 37
CAM=7.7,1.7,5.7:2.5,0.6,2.4:65  # sunroom's own camera, held still
D=/tmp/ghost
mkdir -p $D
cat > $D/still.json <<JSON
{"keyframes": [{"time": 0, "position": [7.7, 1.7, 5.7], "target": [2.5, 0.6, 2.4], "vfov": 65},
               {"time": 100, "position": [7.7, 1.7, 5.7], "target": [2.5, 0.6, 2.4], "vfov": 65}],
 "loop": false, "interpolation": "linear"}
JSON
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader 2>/dev/null
for t in $T $TP; do
  $B reference --scene sunroom --res $R --pose-time $t --camera $CAM --spp 2048 \
    --out $D/ref-$t.exr > /dev/null 2>&1 || echo "reference at $t s failed"
done
declare -A CONFIG=([evolve]="--gi evolve --denoiser evolve" [svgf]="--gi evolve --denoiser svgf"
  [reblur]="--gi evolve --denoiser reblur" [hybrid]="--gi evolve --denoiser hybrid"
  [none]="--gi evolve --denoiser none" [gi10]="--gi gi10" [lux]="--gi lux")
echo "| config | moving: HDR-FLIP / relMSE / trail relMSE / trail luminance ratio | frozen: the same |"
for c in evolve svgf reblur hybrid none gi10 lux; do
  $B render --scene sunroom ${CONFIG[$c]} --preset desktop --res $R --frames 48 --animate \
    --camera-path $D/still.json --view taa --out $D/moving-$c.exr > /dev/null 2>&1 || echo "moving $c failed"
  $B render --scene sunroom ${CONFIG[$c]} --preset desktop --res $R --frames 48 --pose-time $T \
    --camera $CAM --view taa --out $D/frozen-$c.exr > /dev/null 2>&1 || echo "frozen $c failed"
  row="| $c |"
  for k in moving frozen; do
    $B compare $D/$k-$c.exr $D/ref-$T.exr --trail $D/ref-$TP.exr --json $D/$k-$c.json \
      --side-by-side $D/$k-$c.png > /dev/null 2>&1 || echo "compare $k $c failed"
    row="$row $(python3 -c "import json; j = json.load(open('$D/$k-$c.json')); t = j['trail']; print(f\"{j['flip']['mean']:.3f} / {j['rel_mse']:.4f} / {t['rel_mse_trail']:.3f} / {t['luminance_ratio']:.3f}\")") |"
  done
  echo "$row"
done
python3 -c "import json; t = json.load(open('$D/moving-evolve.json'))['trail']; print('trail pixels', t['pixels'])"
