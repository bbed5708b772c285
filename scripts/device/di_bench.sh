#!/bin/bash
# GPU benchmark of the ReSTIR DI passes alone (docs/di.md, "On the GPU"): the scenes of issue 20's
# budget and the ones that showed DI's costs. Pack first:
#   ../shared/device/pack.sh build/bounce ../shared/scenes/cornell_box
# then run on the GPU machine from the repository root with .devicepack carried. An optional
# .devicepack/bin/bounce-base runs the same list for an A/B in the same call, and the packed
# build runs it again with the candidates' shadow ray on ("bounce-vis"). Writes the --timings
# files as $OUT/timings.tgz (<build>/<scene>.json: every pass of every frame; docs report the
# median per pass, frames 16-239).
set -u
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader
run() {
  label=$1 name=$2; shift 2
  build=${label%-vis}
  extra=()
  [ "$label" != "$build" ] && extra=(--di-candidate-visibility on)
  mkdir -p "/tmp/di/$label"
  echo "== $label $name: $*"
  bash .devicepack/run.sh "$build" render --preset desktop --vbuffer trace \
    --res 1920x1080 --frames 240 --animate "${extra[@]}" "$@" --timings "/tmp/di/$label/$name.json" \
    --out "/tmp/di/$label-$name.png" 2>&1 | grep -E "wall time|error|Error"
}
# A fresh machine's first run is slow.
bash .devicepack/run.sh bounce render --scene sunroom --preset mobile --frames 16 --out /tmp/w.png > /dev/null 2>&1
builds="bounce bounce-vis"
[ -x .devicepack/bin/bounce-base ] && builds="bounce-base bounce bounce-vis"
for b in $builds; do
  run "$b" manylights --scene manylights
  run "$b" city-night --scene city --time-of-day 22
  run "$b" city10k-night --scene city-10k --time-of-day 22
  run "$b" spheres --scene spheres
  run "$b" cornell --scene .devicepack/data/cornell_box/cornell_box.gltf --lambert
done
tar czf "$OUT/timings.tgz" -C /tmp/di $(cd /tmp/di && ls -d */)
cp /tmp/di/bounce-manylights.png /tmp/di/bounce-city-night.png "$OUT/" 2>/dev/null
true
