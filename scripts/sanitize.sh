#!/usr/bin/env bash
# Builds Ripple with AddressSanitizer + UndefinedBehaviorSanitizer (RIPPLE_SANITIZE) in a build folder of its
# own and runs the test suite under them. Arguments go to ctest, e.g. scripts/sanitize.sh -R '^(unit|robustness)$'.
#   RIPPLE_SANITIZE_BUILD_DIR  build folder (build-asan)     RIPPLE_BUILD_JOBS  parallel build jobs (all cores)
#   RIPPLE_SANITIZE_TARGETS    build only these targets (space-separated; default: all), for a partial run
# The options below are explained in docs/fuzzing.md.
set -euo pipefail
cd "$(dirname "$0")/.."
build=${RIPPLE_SANITIZE_BUILD_DIR:-build-asan}
# Warnings are not errors here (the Release tree gates them): GCC 12's object-size analysis of
# sanitizer-instrumented code reports impossible bounds (-Wstringop-overflow on a vector resize in
# tests/unit/sampler_tables_test.cpp), which the sanitizers themselves check at run time.
cmake -S . -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release -DRIPPLE_SANITIZE=ON -DRIPPLE_BUILD_BENCH=OFF -DRIPPLE_WERROR=OFF
targets=()
for t in ${RIPPLE_SANITIZE_TARGETS:-}; do targets+=(--target "$t"); done
cmake --build "$build" --parallel ${RIPPLE_BUILD_JOBS:-} "${targets[@]}"

# No leak check in the Vulkan and MPI suites: the Vulkan loader unloads the driver and layers, and Open MPI
# its components, before LeakSanitizer looks at exit, so their allocations kept until exit are reported
# from unknown modules that no suppression can name. The fuzz replay tests (no Vulkan) turn it back on
# (fuzz/CMakeLists.txt). UB ends the process (the build sets -fno-sanitize-recover) with a stack.
export ASAN_OPTIONS="detect_leaks=0:strict_string_checks=1:check_initialization_order=1${ASAN_OPTIONS:+:$ASAN_OPTIONS}"
export LSAN_OPTIONS="suppressions=$PWD/cmake/lsan-suppressions.txt:print_suppressions=0${LSAN_OPTIONS:+:$LSAN_OPTIONS}"
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1${UBSAN_OPTIONS:+:$UBSAN_OPTIONS}"
start=$(date +%s)
status=0
ctest --test-dir "$build" --output-on-failure --timeout 1800 --parallel "$(nproc)" "$@" || status=$?
echo "sanitize: ctest took $(( $(date +%s) - start )) s"
exit $status
