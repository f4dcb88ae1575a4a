#!/usr/bin/env bash
# One command for a machine with a GPU (NVIDIA, AMD or Intel; also runs on lavapipe as a dry run): brings the
# Vulkan loader where the machine lacks it, builds unless a build is already there, runs the API, render and
# MPI suites on the GPU, the main job, ripple-bench and a fixed set of renders, and writes one JSON file with
# the device, driver, timings and image checksums. docs/gpu.md says how to run it and what it checks.
#
#   scripts/gpu-check.sh [--out DIR] [--build DIR] [--debs DIR] [--skip-suites]
#
#   --out DIR     where the JSON (gpu-check.json), the log and the images go (default: gpu-check)
#   --build DIR   build folder (default: build); built with scripts/setup.sh and CMake when it holds no
#                 ripple-render, so a machine without network needs a build carried to it
#   --debs DIR    Debian packages (.deb) to unpack into / first, for a machine that can reach no package
#                 archive: libvulkan1 at least, vulkan-validationlayers for the validated suites
#   --skip-suites the renders and the benchmark only
set -uo pipefail
cd "$(dirname "$0")/.."

out=gpu-check
build=build
debs=""
suites=1
while [ $# -gt 0 ]; do
  case "$1" in
    --out) out=$2; shift 2 ;;
    --build) build=$2; shift 2 ;;
    --debs) debs=$2; shift 2 ;;
    --skip-suites) suites=0; shift ;;
    -h|--help) sed -n '2,16p' "$0"; exit 0 ;;
    *) echo "gpu-check: unknown option $1 (see --help)" >&2; exit 2 ;;
  esac
done
mkdir -p "$out"
log="$out/gpu-check.log"
: >"$log"
say() { echo "[gpu-check] $*" | tee -a "$log"; }
started=$(date +%s)

# 1. The Vulkan loader (and the validation layer the suites use), from packages given or from the archive.
if [ -n "$debs" ]; then
  for f in "$debs"/*.deb; do dpkg -x "$f" / && say "unpacked $(basename "$f")"; done
  ldconfig
fi
if ! ldconfig -p | grep -q 'libvulkan\.so\.1'; then
  say "no Vulkan loader: installing libvulkan1"
  if ! { apt-get update -qq && apt-get install -y -qq libvulkan1 vulkan-validationlayers; } >>"$log" 2>&1; then
    say "ERROR: no Vulkan loader, and none could be installed (give --debs DIR with libvulkan1)"; exit 1
  fi
fi
# NVIDIA's driver may keep its ICD file outside the loader's search path.
if [ -z "${VK_DRIVER_FILES:-}" ] && [ -f /usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json ] &&
   ! ls /usr/share/vulkan/icd.d/nvidia* /etc/vulkan/icd.d/nvidia* >/dev/null 2>&1; then
  export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
fi

# 2. The build, unless one is there.
render="$build/apps/ripple-render/ripple-render"
if [ ! -x "$render" ]; then
  say "building in $build"
  { scripts/setup.sh && cmake -S . -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release && cmake --build "$build" --parallel; } \
    >>"$log" 2>&1 || { say "ERROR: the build failed (see $log)"; exit 1; }
fi

# 3. The device Ripple takes, as its start-up line names it ("Vulkan device 0 of 1: NAME (...), driver DRIVER").
probe=$("$render" --size 8x8 --spp 1 -o "$out/probe.png" 2>&1)
device_line=$(echo "$probe" | grep -m1 'Vulkan device' | sed 's/^ripple: //' || true)
say "${device_line:-no Vulkan device line: $probe}"
[ -n "$device_line" ] || exit 1
devices=$("$render" --list-devices 2>&1)
say "devices: $devices"
gpu=1
case "$device_line" in *llvmpipe*|*"(CPU)"*) gpu=0; say "this is a CPU device: a dry run of the script, not a GPU check" ;; esac

json_escape() { python3 -c 'import json,sys; print(json.dumps(sys.stdin.read().strip()))'; }
seconds_since() { python3 -c "import time,sys; print(round(time.time()-float(sys.argv[1]),3))" "$1"; }

# 4. The suites: API, renders, light transport, ray queries where the device has them, MPI at 2 ranks.
suite_status=skipped
suite_seconds=0
if [ $suites = 1 ]; then
  t=$(date +%s.%N)
  if ctest --test-dir "$build" --output-on-failure --timeout 300 \
       -R '^(unit|light_transport|ray_query|anari_api|anari_render|mpi_equivalence_2|mpi_render_cornell_2)$' >>"$log" 2>&1; then
    suite_status=passed
  else
    suite_status=failed
  fi
  suite_seconds=$(seconds_since "$t")
  say "suites: $suite_status in ${suite_seconds} s"
fi

# 5. The main job, then a fixed set of renders: seconds and the checksum of the linear float pixels (PFM).
renders="["
render_one() {  # name, arguments
  local name=$1; shift
  local t; t=$(date +%s.%N)
  if "$render" -q "$@" -o "$out/$name.pfm" >>"$log" 2>&1; then
    local s; s=$(seconds_since "$t")
    local sum; sum=$(md5sum "$out/$name.pfm" | cut -d' ' -f1)
    say "render $name: $s s, md5 $sum"
    renders+="{\"name\": \"$name\", \"arguments\": $(echo "$*" | json_escape), \"seconds\": $s, \"md5\": \"$sum\"},"
  elif [[ " $* " == *" rayQuery "* ]] && tail -n 3 "$log" | grep -qi 'ray quer'; then
    say "render $name: skipped, the device has no ray queries"
    renders+="{\"name\": \"$name\", \"arguments\": $(echo "$*" | json_escape), \"skipped\": \"no ray queries\"},"
  else
    say "render $name: FAILED"
    renders+="{\"name\": \"$name\", \"arguments\": $(echo "$*" | json_escape), \"failed\": true},"
  fi
}
# A CPU device (the dry run) renders them small; their checksums are then not the GPU's to compare.
large="--size 1920x1080 --spp 64" medium="--size 512x512 --spp 64" bench_size=1920x1080
[ $gpu = 1 ] || { large="--size 320x180 --spp 4"; medium="--size 128x128 --spp 4"; bench_size=256x192; }
render_one main-job
render_one default-large $large
render_one cornell --demo cornell $medium
render_one volume --demo volume $medium
render_one isosurface --demo isosurface $medium
render_one default-ray-query --traversal rayQuery $medium
renders="${renders%,}]"

# 6. ripple-bench on its built-in scene (no data files travel), Ripple only.
bench_status=failed
if "$build/bench/ripple-bench/ripple-bench" --scenes builtin --no-embree --size $bench_size --repeat 3 \
     --json "$out/ripple-bench.json" >>"$log" 2>&1; then
  bench_status=passed
fi
say "ripple-bench: $bench_status"

total=$(( $(date +%s) - started ))
cat >"$out/gpu-check.json" <<EOF
{
  "device": $(echo "$device_line" | json_escape),
  "devices": $(echo "$devices" | json_escape),
  "gpu": $([ $gpu = 1 ] && echo true || echo false),
  "driverFiles": $(echo "${VK_DRIVER_FILES:-}" | json_escape),
  "host": $(uname -a | json_escape),
  "suites": {"status": "$suite_status", "seconds": $suite_seconds},
  "renders": $renders,
  "bench": {"status": "$bench_status", "json": "ripple-bench.json"},
  "seconds": $total
}
EOF
say "wrote $out/gpu-check.json ($total s)"
[ "$suite_status" != failed ] && [ "$bench_status" = passed ] && ! grep -q '"failed": true' "$out/gpu-check.json"
