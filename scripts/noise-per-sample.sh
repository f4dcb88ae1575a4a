#!/usr/bin/env bash
# Noise per sample of one renderer on one glTF scene, without a converged reference: K images of N samples
# each, with seeds 1..K (independent samples), give each pixel's variance at N spp; the noise per sample is
#   relMSE x spp = N * mean over pixels and channels of s^2 / (m^2 + 0.01),
# s^2 the pixel's unbiased variance across the K images, m the median of the K images (robust to the
# fireflies that the variance measures) and 0.01 ripple-imgdiff's epsilon. Lower is better; for
# independent samples it does not depend on N (Ripple stratifies its pixel jitter and first bounce over the
# frames, so its figure falls a little as N grows: compare renderers at the same N). Also printed: the same
# without the 10 pixels of largest error, and those 10 pixels' share of it (how much fireflies dominate),
# and the same without the worst 1% of the pixels (the steadiest figure when a few glints decide the
# rest). One line of text, one of JSON.
#
#   scripts/noise-per-sample.sh [options] SCENE.glb
#   scripts/noise-per-sample.sh [options] --demo NAME   (a built-in scene of ripple-render, e.g. default)
#
# Options:
#   --renderer ripple|cycles  ripple-render (default) or Blender's Cycles set up as ripple-render shows the
#                          scene (scripts/cycles_render.py: same camera, studio light, path length)
#   --images K             independent images (default 16)
#   --spp N                samples per image (default 16)
#   --size WxH             image size (default 256x256)
#   --max-path-length L    surface interactions per path (default 5)
#   --out DIR              where the images go (default: a new folder under /tmp); images already there for
#                          the same renderer, scene, size, spp, path length and seed are reused
#   --map FILE.png         also write a heat map of each pixel's relMSE x spp (log10, -3 black to 1 white)
#   --ripple-render PATH   the ripple-render program (default: build/apps/ripple-render/ripple-render)
#   --demo NAME            ripple-render's built-in scene NAME instead of a file (--renderer ripple only)
#   -h, --help
#
# Needs python3 with numpy (Debian: python3-numpy), and `blender` for --renderer cycles.
set -euo pipefail

die() { echo "noise-per-sample.sh: $*" >&2; exit 2; }

script_dir=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
repo_dir=$(cd "$script_dir/.." && pwd)
renderer=ripple
images=16
spp=16
size=256x256
path_length=5
out=""
map=""
ripple_render="$repo_dir/build/apps/ripple-render/ripple-render"
scene=""
demo=""

while [ $# -gt 0 ]; do
  case "$1" in
    --renderer) renderer=$2; shift 2 ;;
    --images) images=$2; shift 2 ;;
    --spp) spp=$2; shift 2 ;;
    --size) size=$2; shift 2 ;;
    --max-path-length) path_length=$2; shift 2 ;;
    --out) out=$2; shift 2 ;;
    --map) map=$2; shift 2 ;;
    --ripple-render) ripple_render=$2; shift 2 ;;
    --demo) demo=$2; shift 2 ;;
    -h|--help) sed -n '2,/^set -euo/p' "$0" | sed '$d; s/^# \{0,1\}//'; exit 0 ;;
    -*) die "unknown option $1 (see --help)" ;;
    *) [ -z "$scene" ] || die "one scene only"; scene=$1; shift ;;
  esac
done
if [ -n "$demo" ]; then
  [ -z "$scene" ] || die "a scene file or --demo, not both"
  [ "$renderer" = ripple ] || die "--demo needs --renderer ripple"
  scene_args=(--demo "$demo")
  name=demo-$demo
else
  [ -n "$scene" ] || die "no scene given (see --help)"
  [ -f "$scene" ] || die "$scene: no such file"
  scene_args=("$scene")
  name=$(basename "$scene"); name=${name%.*}
fi
case "$renderer" in
  ripple) [ -x "$ripple_render" ] || die "$ripple_render: not built (cmake --build build)" ;;
  cycles) command -v blender >/dev/null || die "blender not found (apt-get install blender)" ;;
  *) die "--renderer must be ripple or cycles" ;;
esac
[[ "$images" =~ ^[0-9]+$ ]] && [ "$images" -ge 2 ] || die "--images must be an integer >= 2"
[[ "$spp" =~ ^[0-9]+$ ]] && [ "$spp" -ge 1 ] || die "--spp must be a positive integer"
python3 -c "import numpy" 2>/dev/null || die "python3 with numpy is needed (apt-get install python3-numpy)"
[ -n "$out" ] || out=$(mktemp -d "${TMPDIR:-/tmp}/noise.XXXXXX")
mkdir -p "$out"

start=$(date +%s.%N)
files=()
rendered=0
for seed in $(seq 1 "$images"); do
  image="$out/$renderer-$name-$size-${spp}spp-L$path_length-$seed.pfm"
  files+=("$image")
  [ -f "$image" ] && continue
  rendered=$((rendered + 1))
  log="${image%.pfm}.log"
  if [ "$renderer" = ripple ]; then
    "$ripple_render" "${scene_args[@]}" --size "$size" --spp "$spp" --max-path-length "$path_length" --seed "$seed" -q \
      -o "$image" > "$log" 2>&1 || die "ripple-render failed: $log"
  else
    blender -b --factory-startup --python "$script_dir/cycles_render.py" -- "$scene" "$image" --size "$size" \
      --max-path-length "$path_length" --spp "$spp" --seed "$seed" > "$log" 2>&1 || die "blender failed: $log"
  fi
done
# Seconds per image rendered now (-1 when every image was reused).
seconds=$(python3 -c "import sys; n = int(sys.argv[3]); print('%.1f' % ((float(sys.argv[2]) - float(sys.argv[1])) / n) if n else -1)" \
  "$start" "$(date +%s.%N)" "$rendered")

python3 - "$renderer" "$name" "$spp" "$seconds" "$map" "${files[@]}" <<'PY'
import json, struct, sys, zlib
import numpy as np

def read_pfm(path):
    with open(path, "rb") as f:
        kind = f.readline().strip()
        width, height = map(int, f.readline().split())
        scale = float(f.readline())
        data = np.fromfile(f, "<f4" if scale < 0 else ">f4")
    return data.reshape(height, width, 3 if kind == b"PF" else 1)

def write_heat_map(path, values):
    """log10 of values from -3 (black) through red and yellow to 1 (white), as an 8-bit RGB PNG."""
    t = np.clip((np.log10(np.maximum(values, 1e-30)) + 3.0) / 4.0, 0.0, 1.0)
    rgb = np.stack([np.clip(3 * t, 0, 1), np.clip(3 * t - 1, 0, 1), np.clip(3 * t - 2, 0, 1)], axis=2)
    rows = (rgb[::-1] * 255 + 0.5).astype(np.uint8)  # PFM rows run bottom to top, PNG's top to bottom
    raw = b"".join(b"\0" + row.tobytes() for row in rows)
    def chunk(kind, data):
        return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data) & 0xFFFFFFFF)
    height, width = values.shape
    with open(path, "wb") as f:
        f.write(b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", width, height, 8, 2, 0, 0, 0)) +
                chunk(b"IDAT", zlib.compress(raw, 9)) + chunk(b"IEND", b""))

renderer, scene, spp, seconds, heat_map = sys.argv[1], sys.argv[2], int(sys.argv[3]), float(sys.argv[4]), sys.argv[5]
stack = np.stack([read_pfm(p).astype(np.float64) for p in sys.argv[6:]])
if not np.isfinite(stack).all():
    sys.exit("noise-per-sample.sh: an image holds NaN or Inf")
median = np.median(stack, axis=0)
error = (stack.var(axis=0, ddof=1) / (median ** 2 + 0.01)).mean(axis=2)  # per pixel, at spp samples
if heat_map:
    write_heat_map(heat_map, error * spp)
ranked = np.sort(error.ravel())[::-1]
total = ranked.sum()
result = {
    "renderer": renderer, "scene": scene, "images": len(stack), "spp": spp,
    "seconds_per_image": seconds if seconds >= 0 else None,
    "relmse_x_spp": float(error.mean() * spp),
    "relmse_x_spp_without_top10": float(ranked[10:].sum() / error.size * spp),
    "top10_share": float(ranked[:10].sum() / total) if total > 0 else 0.0,
    "relmse_x_spp_without_top1pct": float(ranked[error.size // 100:].sum() / error.size * spp),
}
print("%s %s: relMSE x spp %.4g (without the 10 worst pixels %.4g; they hold %.0f%%; without the worst 1%% %.4g), "
      "%d images of %d spp%s"
      % (renderer, scene, result["relmse_x_spp"], result["relmse_x_spp_without_top10"], 100 * result["top10_share"],
         result["relmse_x_spp_without_top1pct"], len(stack), spp,
         ", %.1f s each" % seconds if seconds >= 0 else " (reused)"))
print(json.dumps(result))
PY
