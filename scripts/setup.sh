#!/usr/bin/env bash
# Installs the Debian packages Ripple needs to build, test and benchmark. Idempotent: packages already
# present are skipped, and apt is not touched at all when nothing is missing. Needs root (or sudo).
set -euo pipefail

packages=(
  build-essential cmake ninja-build pkg-config
  libvulkan-dev mesa-vulkan-drivers vulkan-validationlayers glslc spirv-tools  # Vulkan + lavapipe, shaders
  libglm-dev libtbb-dev doctest-dev libtinygltf-dev libcli11-dev libstb-dev libtinyexr-dev
  libembree-dev                                                                # ripple-bench comparison only
  nlohmann-json3-dev                                                           # glTF importer: JSON checks
  libopenmpi-dev openmpi-bin                                                   # data-parallel rendering
  clang-14 libclang-rt-14-dev                                                  # libFuzzer (scripts/fuzz.sh)
)

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then
  echo "setup: all ${#packages[@]} packages present"
  exit 0
fi

sudo=""
[ "$(id -u)" -eq 0 ] || sudo="sudo"
echo "setup: installing ${missing[*]}"
$sudo apt-get update -qq
DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}"
