#!/usr/bin/env bash
# make fuzz: builds the libFuzzer targets (fuzz/, clang + ASan + UBSan) and runs each one from a
# corpus seeded with the test scenes, the references and the malformed files the tests write.
# FUZZ_RUNS (default 1000000) executions per target.
# A crash leaves its input in build-fuzz/crashes/ and fails; turn it into a regression test.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build=$root/build-fuzz
runs=${FUZZ_RUNS:-1000000}
shared=$root/../shared

packages=(clang libfuzzer-14-dev)
bash "$root/scripts/install-deps.sh" "${packages[@]}"

cmake -S "$root/fuzz" -B "$build" -G Ninja -DCMAKE_CXX_COMPILER=clang++ \
  -DCMAKE_BUILD_TYPE=RelWithDebInfo >/dev/null
cmake --build "$build"

# Seeds: small scene files (a fuzzer learns little from megabytes) and images.
seed() {  # seed TARGET FILE...
  mkdir -p "$build/corpus/$1"
  for f in "${@:2}"; do
    [ -f "$f" ] && [ "$(stat -c %s "$f")" -le 262144 ] && cp "$f" "$build/corpus/$1/" || true
  done
}
seed fuzz_gltf "$shared"/scenes/*/*.gltf "$shared"/scenes/*/*/*.gltf \
  "$shared"/scenes/*/*.glb "$shared"/scenes/*/*/*.glb
seed fuzz_image "$shared"/references/*/*.png \
  "$shared"/scenes/*/*.png "$shared"/scenes/*/*/*.png "$shared"/scenes/*/*.jpg
mkdir -p "$build/crashes"
for target in fuzz_gltf fuzz_image; do
  echo "fuzz: $target, $runs runs"
  "$build/$target" "$build/corpus/$target" -runs="$runs" -max_len=65536 -timeout=10 \
    -rss_limit_mb=4096 \
    -artifact_prefix="$build/crashes/$target-" -print_final_stats=1 2>&1 | tail -20
done
