#!/usr/bin/env bash
# Equal-time comparison of Ripple with Blender's Cycles on one glTF scene: each renderer gets the same wall
# time per run, start-up included, and is judged against its own converged reference (rendered with
# another seed, so that no reference shares samples with the image it judges). Prints one table: relMSE
# against each renderer's reference after T seconds, for every T.
#
#   scripts/equal-time.sh [options] SCENE.glb
#
# Options:
#   --size WxH             image size (default 256x256)
#   --max-path-length N    surface interactions per path (default 5; Cycles' bounces = N - 1)
#   --times "T1 T2 ..."    wall-time budgets in seconds (default "2 5 10 20")
#   --reference-spp N      samples of each reference (default 2048)
#   --out DIR              where references, images and logs go (default: a new folder under /tmp)
#   --ripple-render PATH   the ripple-render program (default: build/apps/ripple-render/ripple-render)
#   -h, --help
#
# Needs `blender` (Debian's package: apt-get install blender) for Cycles; scripts/cycles_render.py sets the
# scene up as ripple-render shows it (camera, studio light for unlit scenes, box filter, no denoising, no
# adaptive sampling). Ripple's --time bounds its whole run; Cycles' time limit covers its sampling only, so
# Cycles is started with the budget minus its measured start-up (Blender, the import, the BVH), and both
# processes' wall times are printed beside the budget. relMSE is ripple-imgdiff's (epsilon 0.01).
# Run it on a quiet machine: the two renderers share the CPU cores.
set -euo pipefail

die() { echo "equal-time.sh: $*" >&2; exit 2; }

script_dir=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
repo_dir=$(cd "$script_dir/.." && pwd)
size=256x256
path_length=5
times="2 5 10 20"
reference_spp=2048
out=""
ripple_render="$repo_dir/build/apps/ripple-render/ripple-render"
scene=""

while [ $# -gt 0 ]; do
  case "$1" in
    --size) size=$2; shift 2 ;;
    --max-path-length) path_length=$2; shift 2 ;;
    --times) times=$2; shift 2 ;;
    --reference-spp) reference_spp=$2; shift 2 ;;
    --out) out=$2; shift 2 ;;
    --ripple-render) ripple_render=$2; shift 2 ;;
    -h|--help) sed -n '2,/^set -euo/p' "$0" | sed '$d; s/^# \{0,1\}//'; exit 0 ;;
    -*) die "unknown option $1 (see --help)" ;;
    *) [ -z "$scene" ] || die "one scene only"; scene=$1; shift ;;
  esac
done
[ -n "$scene" ] || die "no scene given (see --help)"
[ -f "$scene" ] || die "$scene: no such file"
[ -x "$ripple_render" ] || die "$ripple_render: not built (cmake --build build)"
imgdiff="$(dirname "$(dirname "$ripple_render")")/ripple-imgdiff/ripple-imgdiff"
[ -x "$imgdiff" ] || die "$imgdiff: not built"
command -v blender >/dev/null || die "blender not found (apt-get install blender)"
[ -n "$out" ] || out=$(mktemp -d "${TMPDIR:-/tmp}/equal-time.XXXXXX")
mkdir -p "$out"

cycles() {  # cycles OUTPUT.exr LOG [cycles_render.py options...]
  local output=$1 log=$2; shift 2
  blender -b --factory-startup --python "$script_dir/cycles_render.py" -- "$scene" "$output" --size "$size" \
    --max-path-length "$path_length" "$@" > "$log" 2>&1 || { tail -20 "$log" >&2; die "Cycles failed (log: $log)"; }
}
now() { date +%s.%N; }
seconds_since() { awk -v a="$1" -v b="$(now)" 'BEGIN { printf "%.2f", b - a }'; }
relmse() { "$imgdiff" "$1" "$2" | awk '/^relMSE/ { print $2 }'; }

echo "scene $scene, $size, path length $path_length, references of $reference_spp spp; output in $out"
# References are kept in --out and reused by a later run with the same scene and settings.
key="$(basename "$scene" .glb)-$size-$path_length-$reference_spp"
ripple_reference="$out/ripple-reference-$key.pfm" cycles_reference="$out/cycles-reference-$key.exr"
if [ ! -f "$ripple_reference" ]; then
  echo "Ripple reference ..."
  "$ripple_render" "$scene" --size "$size" --max-path-length "$path_length" --spp "$reference_spp" --seed 1 \
    --quiet -o "$ripple_reference" > "$out/ripple-reference-$key.log" 2>&1
fi
if [ ! -f "$cycles_reference" ]; then
  echo "Cycles reference ..."
  cycles "$cycles_reference" "$out/cycles-reference-$key.log" --spp "$reference_spp" --seed 1
fi
# Cycles' start-up (Blender, import, scene sync, BVH): one sample's run, minus nothing; subtracted from
# each budget so that the whole process takes about the budget, as Ripple's --time does.
start=$(now)
cycles "$out/cycles-startup.exr" "$out/cycles-startup.log" --spp 1 --seed 3
cycles_startup=$(seconds_since "$start")

printf '\n%8s | %10s %8s %12s | %10s %8s %12s\n' "budget s" "Ripple s" "spp" "relMSE" "Cycles s" "spp" "relMSE"
for t in $times; do
  start=$(now)
  "$ripple_render" "$scene" --size "$size" --max-path-length "$path_length" --time "$t" --seed 2 \
    -o "$out/ripple-$t.pfm" > "$out/ripple-$t.log" 2>&1
  ripple_wall=$(seconds_since "$start")
  ripple_spp=$(sed -n 's/.*rendered [0-9x]*, \([0-9]*\) spp.*/\1/p' "$out/ripple-$t.log" | tail -1)
  limit=$(awk -v t="$t" -v s="$cycles_startup" 'BEGIN { l = t - s; printf "%.2f", (l > 0.1 ? l : 0.1) }')
  start=$(now)
  cycles "$out/cycles-$t.exr" "$out/cycles-$t.log" --time "$limit" --seed 2
  cycles_wall=$(seconds_since "$start")
  cycles_spp=$(grep -o 'Sample [0-9]*' "$out/cycles-$t.log" | awk '{ print $2 }' | sort -n | tail -1)
  printf '%8s | %10s %8s %12s | %10s %8s %12s\n' "$t" "$ripple_wall" "${ripple_spp:-?}" \
    "$(relmse "$out/ripple-$t.pfm" "$ripple_reference")" "$cycles_wall" "${cycles_spp:-?}" \
    "$(relmse "$out/cycles-$t.exr" "$cycles_reference")"
done
