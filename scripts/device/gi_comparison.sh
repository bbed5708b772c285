#!/bin/bash
# Issue 23's comparison of the GI systems (docs/gi/comparison.md): Evolve, GI-1.0, Lux and the
# cache alone on cornell, sunroom, foliage, city and a glTF scene (sheen_chair), desktop preset
# at 480x270: HDR-FLIP and relMSE of the linear `taa` view after 1, 16 and 64 static frames
# against the path tracer (2,048 spp, 16 bounces), then the same modes' bench (rays per pixel,
# memory, GPU ms) at 1920x1080. Pack first:
#   ../shared/device/pack.sh build/bounce ../shared/scenes/cornell_box ../shared/scenes/sheen_chair
# then run from the repository root on the GPU machine with .devicepack carried.
set -u
B="bash .devicepack/run.sh bounce"
D=.devicepack/data
R=480x270
mkdir -p /tmp/cmp
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader
declare -A SCENE=([cornell]="--scene $D/cornell_box/cornell_box.gltf --lambert"
  [sunroom]="--scene sunroom" [foliage]="--scene foliage" [city]="--scene city"
  [chair]="--scene $D/sheen_chair/glTF/SheenChair.gltf --sky 1,1,1")
for s in cornell sunroom foliage city chair; do
  $B reference ${SCENE[$s]} --res $R --spp 2048 --out /tmp/cmp/$s-ref.exr 2>&1 | grep -iE "error|spp" | tail -1
  for gi in evolve gi10 lux cache; do
    for n in 1 16 64; do
      $B render ${SCENE[$s]} --preset desktop --res $R --gi $gi --frames $n --view taa \
        --out /tmp/cmp/$s-$gi-$n.exr > /dev/null 2>&1 || echo "render $s $gi $n failed"
      $B compare /tmp/cmp/$s-$gi-$n.exr /tmp/cmp/$s-ref.exr --json /tmp/cmp/$s-$gi-$n.json \
        > /dev/null 2>&1 || echo "compare $s $gi $n failed"
    done
  done
  for gi in evolve gi10 lux; do
    $B compare /tmp/cmp/$s-$gi-64.exr /tmp/cmp/$s-ref.exr --side-by-side /tmp/cmp/$s-$gi-sbs.png > /dev/null 2>&1
  done
done
python3 - <<'PY'
import json
for s in ["cornell", "sunroom", "foliage", "city", "chair"]:
    for gi in ["evolve", "gi10", "lux", "cache"]:
        row = []
        for n in [1, 16, 64]:
            try:
                j = json.load(open(f"/tmp/cmp/{s}-{gi}-{n}.json"))
                row.append(f"{j['flip']['mean']:.3f}/{j['rel_mse']:.4f}")
            except Exception as e:
                row.append("n/a")
        print(f"{s:8s} {gi:7s} " + "  ".join(row))
PY
for s in ${BENCH_SCENES-sunroom city}; do
  $B bench --scene $s --res 1920x1080 --gi none,evolve,gi10,lux,cache --frames 240 \
    --out /tmp/cmp/bench-$s 2>&1 | tr '\r' '\n' | grep -E "frame \(GPU\)|error|^sunroom|^city"
done
(cd /tmp && tar czf $OUT/cmp.tgz $(find cmp -name '*.json'))
for s in cornell sunroom; do for gi in evolve gi10 lux; do cp /tmp/cmp/$s-$gi-sbs.png $OUT/; done; done
