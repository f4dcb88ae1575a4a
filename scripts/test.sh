#!/usr/bin/env bash
# Sets up, builds and runs every test suite: the README's test command and what CI runs.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh
build=${RIPPLE_BUILD_DIR:-build}
cmake -S . -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release
cmake --build "$build" --parallel
ctest --test-dir "$build" --output-on-failure --timeout 900 --parallel "$(nproc)"
# The unit, light-transport and robustness suites and the fuzz regressions again under ASan + UBSan
# (docs/fuzzing.md), in a build folder of their own and without the Vulkan validation layer (the Release
# run above has it; tests/CMakeLists.txt): the whole suite under the sanitizers would not fit CI's time.
RIPPLE_SANITIZE_BUILD_DIR="$build-asan" \
  RIPPLE_SANITIZE_TARGETS="ripple_unit_tests ripple_light_transport_tests ripple_robustness_tests ripple_fuzz_gltf_replay ripple_fuzz_vtk_replay ripple_fuzz_volume_replay ripple_fuzz_anari_replay" \
  scripts/sanitize.sh -R '^(unit|light_transport|robustness|fuzz_regressions_.*)$'
