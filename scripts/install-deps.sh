#!/usr/bin/env bash
# Installs the Debian packages Bounce needs, and only those that are missing.
# Idempotent: a second run installs nothing. Needs root or sudo for apt-get.
# Arguments name extra packages for one task (scripts/fuzz.sh: clang, libFuzzer).
set -euo pipefail

packages=(
  build-essential cmake ninja-build pkg-config
  glslc spirv-tools                          # shader compiler (SPIR-V embedded at build time)
  libvulkan-dev mesa-vulkan-drivers          # Vulkan loader + lavapipe (CPU Vulkan device)
  vulkan-validationlayers vulkan-tools       # validation in tests, vulkaninfo
  libtinygltf-dev nlohmann-json3-dev         # glTF 2.0 loader; the JSON bounce writes
  libstb-dev libtinyexr-dev                  # PNG/JPEG and EXR image I/O
  libglm-dev libcli11-dev libfmt-dev         # maths, command line, formatting
  libgtest-dev libgmock-dev                  # tests
  libglfw3-dev libimgui-dev                  # the viewer, bounce-view (window, Dear ImGui)
  xvfb xauth                                 # the viewer's test on a virtual X server (xvfb-run)
  ccache                                     # compile cache (scripts/check-consumer.sh)
  clang-format                               # make format, make format-check (CI)
  "$@"
)

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then
  echo "install-deps: all ${#packages[@]} packages present"
  exit 0
fi

echo "install-deps: installing ${missing[*]}"
if [ "$(id -u)" -eq 0 ]; then
  sudo=()
elif command -v sudo >/dev/null && sudo -n true 2>/dev/null; then
  sudo=(sudo -n)
else
  echo "install-deps: these packages are missing: ${missing[*]}" >&2
  echo "install-deps: installing them needs root or password-less sudo; run as root:" >&2
  echo "  apt-get install -y ${missing[*]}" >&2
  exit 1
fi
export DEBIAN_FRONTEND=noninteractive
"${sudo[@]}" apt-get update -qq
"${sudo[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}"
