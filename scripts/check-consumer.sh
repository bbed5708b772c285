#!/usr/bin/env bash
# Checks that a project outside Bounce can use it as a library (tests/consumer/), both ways:
#   (a) find_package: builds Bounce (build/, the release preset, configured if missing),
#       installs it into a temporary prefix, builds the consumer against that prefix, runs it;
#   (b) add_subdirectory: builds the consumer with Bounce's source tree added as a subdirectory
#       in a fresh build directory (build-consumer/), which compiles Bounce's libraries again
#       (tests, examples and the program stay off), and runs it.
# Uses ccache when it is installed, so that (b) and later runs reuse earlier compiles.
# Usage: scripts/check-consumer.sh        Exit code 0 when both work.
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
cd "$root"

launcher=()
if command -v ccache >/dev/null; then
  launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
fi
generator=()
if command -v ninja >/dev/null; then
  generator=(-G Ninja)
fi
jobs="${JOBS:-$(nproc)}"

prefix="$(mktemp -d "${TMPDIR:-/tmp}/bounce-install.XXXXXX")"
consumerBuild="$(mktemp -d "${TMPDIR:-/tmp}/bounce-consumer.XXXXXX")"
# Beside build/, at the same depth, so that ccache (with CCACHE_BASEDIR) sees the same relative
# source paths as in build/ and reuses its compiles.
subdirBuild="$root/build-consumer"
trap 'rm -rf "$prefix" "$consumerBuild" "$subdirBuild"' EXIT

step() { echo "check-consumer: $* (${SECONDS}s)"; }
# Runs a command quietly; shows its output only when it fails.
quiet() {
  local log
  log="$(mktemp)"
  if ! "$@" >"$log" 2>&1; then
    cat "$log"
    rm -f "$log"
    echo "check-consumer: failed: $*" >&2
    exit 1
  fi
  rm -f "$log"
}

step "(a) find_package(bounce) from an installed prefix"
if [ ! -f build/CMakeCache.txt ]; then
  quiet cmake --preset release "${launcher[@]}"
fi
quiet cmake --build build -j "$jobs"
quiet cmake --install build --prefix "$prefix"
quiet cmake -S tests/consumer -B "$consumerBuild" "${generator[@]}" -DCMAKE_BUILD_TYPE=Release \
  -DCMAKE_PREFIX_PATH="$prefix" "${launcher[@]}"
quiet cmake --build "$consumerBuild" -j "$jobs"
"$consumerBuild/bounce_consumer"

step "(b) add_subdirectory(bounce) in a fresh build directory"
rm -rf "$subdirBuild"
quiet cmake -S tests/consumer -B "$subdirBuild" "${generator[@]}" -DCMAKE_BUILD_TYPE=Release \
  -DBOUNCE_SOURCE_DIR="$root" -DBOUNCE_BUILD_TESTS=OFF -DBOUNCE_BUILD_EXAMPLES=OFF \
  "${launcher[@]}"
quiet cmake --build "$subdirBuild" -j "$jobs"
"$subdirBuild/bounce_consumer"

step "both ways work"
