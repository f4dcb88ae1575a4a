#!/usr/bin/env bash
# Measures data-parallel rendering and compositing at 1..N ranks on this machine (mpirun --oversubscribe)
# and writes one JSON file per run into a folder, for scripts/scaling_model.py (docs/scaling.md):
#   ripple-boxes --bench for each partition (random, slabs) and exchange (ring, bounds), and
#   ripple-composite-bench (1080p) for each compositing method that fits the rank count.
# Usage: scripts/dp-scaling.sh [--ranks N] [--out DIR] [--build DIR]   (defaults: 8, scaling-runs, build)
set -euo pipefail
ranks=8 out=scaling-runs build=build
while [[ $# -gt 0 ]]; do
  case "$1" in
    --ranks) ranks="$2"; shift 2 ;;
    --out) out="$2"; shift 2 ;;
    --build) build="$2"; shift 2 ;;
    -h|--help) sed -n '2,7p' "$0"; exit 0 ;;
    *) echo "dp-scaling.sh: unknown argument $1" >&2; exit 2 ;;
  esac
done
boxes="$build/apps/ripple-boxes/ripple-boxes"
composite="$build/bench/ripple-composite-bench/ripple-composite-bench"
for tool in "$boxes" "$composite"; do
  [[ -x "$tool" ]] || { echo "dp-scaling.sh: $tool not built" >&2; exit 1; }
done
mkdir -p "$out"
mpirun=(mpirun --oversubscribe)
[[ "$(id -u)" == 0 ]] && mpirun+=(--allow-run-as-root)
# The boxes at 196,610 triangles (tessellation 16), 256x256, 4 spp, paths of 3; one rank uses every core,
# several ranks one lavapipe thread each.
scene=(--bench --size 256x256 --spp 4 --frames 4 --tessellation 16)
for partition in random slabs; do
  "$boxes" "${scene[@]}" --partition "$partition" --json "$out/boxes-$partition-1.json" -o "$out/boxes-$partition-1.png" \
    | grep "per frame"
  for exchange in ring bounds; do
    for ((n = 2; n <= ranks; ++n)); do
      "${mpirun[@]}" -np "$n" -x LP_NUM_THREADS=1 "$boxes" "${scene[@]}" --partition "$partition" --exchange "$exchange" \
        --json "$out/boxes-$partition-$exchange-$n.json" -o "$out/boxes-$partition-$exchange-$n.png" | grep "per frame"
    done
  done
done
for ((n = 1; n <= ranks; ++n)); do
  methods=(auto)
  (( n > 1 && (n & (n - 1)) == 0 )) && methods+=(binarySwap)
  for method in "${methods[@]}"; do
    "${mpirun[@]}" -np "$n" "$composite" --pattern blocks --method "$method" --json "$out/composite-$method-$n.json" \
      | grep "per composite"
  done
done
echo "wrote $out/"
