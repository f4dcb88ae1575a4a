#!/usr/bin/env bash
# Builds the libFuzzer targets (clang, RIPPLE_BUILD_FUZZERS) in a build folder of their own and runs each for
# the given time, one after the other, seeded from fuzz/seeds/<target>/ and, for glTF, the shared sample
# scenes (RIPPLE_DATA_DIR/gltf). Findings land in <build>/fuzz/artifacts/<target>/; the corpus grows in
# <build>/fuzz/corpus/<target>/ and is reused by the next run.
#   scripts/fuzz.sh [seconds per target (60)] [target ...: gltf vtk volume anari]
#   RIPPLE_FUZZ_BUILD_DIR (build-fuzz), RIPPLE_FUZZ_CC / RIPPLE_FUZZ_CXX (clang-14 / clang++-14),
#   RIPPLE_BUILD_JOBS (all cores), RIPPLE_FUZZ_ARGS (more libFuzzer flags, e.g. -jobs=2).
set -euo pipefail
cd "$(dirname "$0")/.."
seconds=${1:-60}
[ $# -gt 0 ] && shift
targets=("$@")
[ ${#targets[@]} -gt 0 ] || targets=(gltf vtk volume anari)
build=${RIPPLE_FUZZ_BUILD_DIR:-build-fuzz}

# Tests off: the fuzz tree builds only what the fuzzers link (its replay tests run in every other tree).
cmake -S . -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release -DCMAKE_C_COMPILER="${RIPPLE_FUZZ_CC:-clang-14}" \
  -DCMAKE_CXX_COMPILER="${RIPPLE_FUZZ_CXX:-clang++-14}" -DRIPPLE_BUILD_FUZZERS=ON -DRIPPLE_BUILD_TESTS=OFF \
  -DRIPPLE_BUILD_BENCH=OFF >/dev/null
cmake --build "$build" --parallel ${RIPPLE_BUILD_JOBS:-} --target "${targets[@]/#/ripple_fuzz_}"
data=$(sed -n 's/^RIPPLE_DATA_DIR:PATH=//p' "$build/CMakeCache.txt")

# As in scripts/sanitize.sh (docs/fuzzing.md), plus verify_asan_link_order=0: clang's -fsanitize=fuzzer puts
# libstdc++ ahead of the shared ASan runtime in the executable's needed list, which ASan refuses by default;
# its interceptors still come before libc's functions in the lookup order, so the order is harmless here.
export ASAN_OPTIONS="detect_leaks=1:strict_string_checks=1:verify_asan_link_order=0${ASAN_OPTIONS:+:$ASAN_OPTIONS}"
export LSAN_OPTIONS="suppressions=$PWD/cmake/lsan-suppressions.txt:print_suppressions=0${LSAN_OPTIONS:+:$LSAN_OPTIONS}"
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1${UBSAN_OPTIONS:+:$UBSAN_OPTIONS}"

status=0
for target in "${targets[@]}"; do
  corpus="$build/fuzz/corpus/$target"
  artifacts="$build/fuzz/artifacts/$target"
  mkdir -p "$corpus" "$artifacts"
  seeds=("fuzz/seeds/$target")
  case $target in
    # Inputs up to 64 KiB: the shared scenes' larger files are cut there, which still exercises their headers.
    gltf) [ -d "$data/gltf" ] && seeds+=("$data/gltf") || echo "fuzz: $data/gltf absent, hand-made seeds only"
          flags=(-max_len=65536 -timeout=20 -rss_limit_mb=3072) ;;
    anari) flags=(-max_len=4096 -timeout=20 -rss_limit_mb=3072) ;;
    vtk) flags=(-max_len=65536 -timeout=20 -rss_limit_mb=3072) ;;
    # NanoVDB buffers are large even for small grids (an upper node's tables): the seed sphere is 306 KiB.
    volume) flags=(-max_len=400000 -timeout=20 -rss_limit_mb=3072) ;;
    *) echo "fuzz: unknown target '$target' (gltf, vtk, volume, anari)"; exit 2 ;;
  esac
  echo "fuzz: $target for $seconds s, corpus $corpus"
  log="$build/fuzz/$target.log"
  "$build/fuzz/ripple_fuzz_$target" "${flags[@]}" -max_total_time="$seconds" -print_final_stats=1 \
    -artifact_prefix="$artifacts/" ${RIPPLE_FUZZ_ARGS:-} "$corpus" "${seeds[@]}" >"$log" 2>&1 || status=$?
  # The last status line carries the totals: executions (#), coverage (cov: edges, ft: features), corpus.
  grep -E '^#[0-9]+' "$log" | tail -1 || true
  grep -E '^stat::number_of_executed_units|^stat::peak_rss_mb' "$log" || true
  echo "fuzz: corpus $(find "$corpus" -type f | wc -l) files; findings: $(find "$artifacts" -type f | wc -l) (log $log)"
done
exit $status
