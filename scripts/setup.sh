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
  zlib1g-dev                                                                   # gzip-encoded NRRD volumes
  libpugixml-dev                                                               # VTK XML files
  libnanovdb-dev                                                               # NanoVDB grids (PNanoVDB.h in the kernels)
  libopenvdb-dev libblosc-dev libboost-iostreams-dev                           # OpenVDB files (.vdb), blosc-compressed .nvdb
  python3-meshio                                                               # an independent VTK reader for the tests
  libopenmpi-dev openmpi-bin                                                   # data-parallel rendering
  clang-14 libclang-rt-14-dev                                                  # libFuzzer (scripts/fuzz.sh)
  libglfw3-dev libimgui-dev libgl1-mesa-dri                                    # ripple-view: window, panels, GL (llvmpipe)
  xvfb xauth                                                                   # ripple-view's test: a virtual X server (xvfb-run)
  pybind11-dev python3-dev python3-numpy python3-pytest python3-mpi4py          # the pynari Python module and its tests
  python3-pil                                                                  # pynari's samples save their images with it
)

sudo=""
[ "$(id -u)" -eq 0 ] || sudo="sudo"

# Debian 12 ships Mesa 22.3, whose lavapipe runs Ripple's kernels 3-5x slower than Mesa 25 and has no ray
# queries. On Debian 12, take mesa-vulkan-drivers (and the libdrm it needs) from bookworm-backports, pinned
# so that nothing else comes from there. The backports source uses the machine's own Debian mirror.
# Debian 13 and newer have Mesa 25 already. RIPPLE_SYSTEM_MESA=1 keeps the distribution's Mesa.
backports_list=/etc/apt/sources.list.d/ripple-bookworm-backports.sources
backports_pin=/etc/apt/preferences.d/ripple-bookworm-backports
debian_mirror() {
  # The first http(s) Debian archive (not the security archive) named in the apt sources, either format.
  grep -rhoE '(URIs:|^deb)[[:space:]]+(\[[^]]*\][[:space:]]+)?https?://[^[:space:]]+' \
       /etc/apt/sources.list /etc/apt/sources.list.d/ 2>/dev/null |
    grep -oE 'https?://[^[:space:]]+' | grep -v -- '-security' | grep -E '/debian/?$' | head -n 1 || true
}
want_backports_mesa=0
if [ "${RIPPLE_SYSTEM_MESA:-0}" != 1 ] && grep -q '^VERSION_CODENAME=bookworm$' /etc/os-release 2>/dev/null; then
  want_backports_mesa=1
fi
if [ $want_backports_mesa = 1 ] && [ ! -f "$backports_list" ]; then
  mirror=$(debian_mirror)
  if [ -z "$mirror" ]; then
    echo "setup: no Debian mirror found in the apt sources; keeping Debian 12's Mesa 22.3 (slower, no ray queries)" >&2
    want_backports_mesa=0
  else
    echo "setup: adding bookworm-backports from $mirror for mesa-vulkan-drivers (Mesa 25)"
    printf 'Types: deb\nURIs: %s\nSuites: bookworm-backports\nComponents: main\nSigned-By: /usr/share/keyrings/debian-archive-keyring.gpg\n' \
      "$mirror" | $sudo tee "$backports_list" >/dev/null
    # Backports default to priority 100 (never chosen over bookworm); these packages only are raised.
    printf 'Package: mesa-vulkan-drivers libdrm*\nPin: release n=bookworm-backports\nPin-Priority: 990\n' |
      $sudo tee "$backports_pin" >/dev/null
    $sudo apt-get update -qq
  fi
fi

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
# An installed Mesa older than the backports candidate counts as missing.
if [ $want_backports_mesa = 1 ] && [ -f "$backports_list" ]; then
  installed=$(dpkg-query -W -f='${Version}' mesa-vulkan-drivers 2>/dev/null || true)
  candidate=$(apt-cache policy mesa-vulkan-drivers 2>/dev/null | awk '/Candidate:/ {print $2}')
  if [ -n "$installed" ] && [ -n "$candidate" ] && [ "$candidate" != "(none)" ] &&
     dpkg --compare-versions "$installed" lt "$candidate"; then
    missing+=(mesa-vulkan-drivers)
  fi
fi
if [ ${#missing[@]} -eq 0 ]; then
  echo "setup: all ${#packages[@]} packages present"
  exit 0
fi

echo "setup: installing ${missing[*]}"
$sudo apt-get update -qq
DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}"
