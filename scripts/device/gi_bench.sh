#!/usr/bin/env bash
# The README's GI tables on the GPU machine (../shared/device/README.md): per-pass GPU times of
# the diffuse GI chain (--gi evolve) and of the cache alone (--gi cache), both presets, 240
# animated frames each, plus a validation run. Pack first, from the project root:
#   ../shared/device/pack.sh --validation build/bounce ../shared/scenes/glass_vase_flowers/glTF
#   cp scripts/device/gi_bench.sh .devicepack/
# then run `bash .devicepack/gi_bench.sh` there (carry .devicepack); $OUT/timings.tgz holds the
# --timings files for scripts/plot_pass_times.py, $OUT/pictures.tgz the README's pictures
# (gi/ -> docs/images/gi, cache/ -> docs/images/cache).
set -u
R="bash .devicepack/run.sh bounce"
# The vase's glTF has no light: a sun and a sky as in the README's vase pictures.
VASE=".devicepack/data/glTF/GlassVaseFlowers.gltf --sun=-0.4,-0.8,-0.45:100 --sky 0.5,0.6,0.9"
run() {  # label, then render arguments
  local label=$1; shift
  echo "== $label"
  $R render --vbuffer trace --frames 240 --animate --timings "$OUT/$label.json" \
    --out "/tmp/$label.png" "$@" 2>&1 | grep -E "^  (cache|gi-|composite|frame)" | grep -v cascade
}
# A throw-away run first: the first run on a freshly started machine measured up to 3x slower.
$R render --scene sunroom --preset mobile --vbuffer trace --frames 240 --animate --gi evolve \
  --out /tmp/warm-up.png > /dev/null 2>&1
for scene in sunroom city vase; do
  path=$scene; [ "$scene" = vase ] && path=$VASE
  # $path unquoted: the vase's carries its lighting options
  for preset in mobile desktop; do run "$scene-$preset-evolve" --scene $path --preset $preset --gi evolve; done
done
run sunroom-1440p-evolve --scene sunroom --preset desktop --res 2560x1440 --gi evolve
run city-1440p-evolve --scene city --preset desktop --res 2560x1440 --gi evolve
# Ablations in the same run: full-resolution textures for x2 (the coarse mip's saving), and
# the occluder visibility test off (its cost in gi-restir-resolve and gi-spatial-denoise).
run vase-desktop-fullmip --scene $VASE --preset desktop --gi evolve --gi-texture-side 0
run sunroom-1440p-no-occluder --scene sunroom --preset desktop --res 2560x1440 --gi evolve \
  --no-occluder-visibility
for preset in mobile desktop; do
  run "sunroom-$preset-cache" --scene sunroom --preset $preset --gi cache
  run "city-$preset-cache" --scene city --preset $preset --gi cache
done
VK_INSTANCE_LAYERS=VK_LAYER_KHRONOS_validation $R render --scene city --preset desktop \
  --vbuffer trace --gi evolve --frames 20 --animate --validate --out /tmp/validate.png \
  > /tmp/validate.log 2>&1
echo "validation run: exit code $? (non-zero on any validation message)"
# The README's pictures: the chain's passes on a static view, the final frame, the cache.
mkdir -p "$OUT/gi" "$OUT/cache"
for view in gi-resolve-diffuse-rays gi-restir-temporal gi-restir-spatial-1 \
    gi-trace-spatial-validation-rays gi-spatial-denoise tonemap; do
  $R render --scene sunroom --preset desktop --res 960x540 --vbuffer trace --gi evolve \
    --frames 64 --view $view --out "$OUT/gi/$view.png" > /dev/null 2>&1
done
$R render --scene sunroom --preset desktop --vbuffer trace --gi evolve --frames 64 --animate \
  --out "$OUT/gi/sunroom-desktop.png" > /dev/null 2>&1
$R render --scene $VASE --preset desktop --vbuffer trace --gi evolve --frames 64 \
  --out "$OUT/gi/vase-desktop.png" > /dev/null 2>&1
$R render --scene sunroom --preset desktop --res 480x270 --gi cache --frames 48 \
  --out "$OUT/cache/sunroom-gi-cache-desktop.png" > /dev/null 2>&1
$R render --scene sunroom --preset desktop --res 480x270 --gi cache --frames 48 --view cache \
  --out "$OUT/cache/sunroom-cache-view-desktop.png" > /dev/null 2>&1
# At most 8 files come back from the GPU machine: two archives.
cd "$OUT" && tar czf timings.tgz ./*.json && rm ./*.json && tar czf pictures.tgz gi cache &&
  rm -rf gi cache
