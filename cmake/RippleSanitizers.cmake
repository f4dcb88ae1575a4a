# Sanitizer and fuzzer builds: RIPPLE_SANITIZE puts AddressSanitizer + UndefinedBehaviorSanitizer on every
# target of the tree (included before any target exists); RIPPLE_BUILD_FUZZERS adds the libFuzzer targets of
# fuzz/. scripts/sanitize.sh and scripts/fuzz.sh configure such a tree in a build folder of its own.
option(RIPPLE_SANITIZE "Build everything with AddressSanitizer and UndefinedBehaviorSanitizer" OFF)
option(RIPPLE_BUILD_FUZZERS "Build the libFuzzer targets of fuzz/ (clang only; implies RIPPLE_SANITIZE)" OFF)

if(RIPPLE_BUILD_FUZZERS)
  if(NOT CMAKE_CXX_COMPILER_ID STREQUAL "Clang")
    message(FATAL_ERROR "RIPPLE_BUILD_FUZZERS needs clang (libFuzzer); configure with -DCMAKE_CXX_COMPILER=clang++-14 "
                        "-DCMAKE_C_COMPILER=clang-14 (Debian: clang-14 libclang-rt-14-dev)")
  endif()
  set(RIPPLE_SANITIZE ON CACHE BOOL "Build everything with AddressSanitizer and UndefinedBehaviorSanitizer" FORCE)
endif()

if(RIPPLE_SANITIZE)
  # A UB report ends the process, so a test that triggers one fails instead of printing and passing.
  set(ripple_sanitize_flags -fsanitize=address,undefined -fno-sanitize-recover=undefined -fno-omit-frame-pointer)
  if(CMAKE_CXX_COMPILER_ID STREQUAL "Clang")
    # The device libraries link with --no-undefined, and clang links its static runtime into executables
    # only: with the shared runtime (as gcc does by default) a .so resolves the __asan_* symbols itself.
    # The runtime is not on the loader's path, hence the rpath.
    list(APPEND ripple_sanitize_flags -shared-libsan)
    execute_process(COMMAND ${CMAKE_CXX_COMPILER} -print-file-name=libclang_rt.asan-x86_64.so
                    OUTPUT_VARIABLE ripple_asan_runtime OUTPUT_STRIP_TRAILING_WHITESPACE)
    get_filename_component(ripple_asan_runtime_dir "${ripple_asan_runtime}" DIRECTORY)
    add_link_options("-Wl,-rpath,${ripple_asan_runtime_dir}")
    set(ripple_debug_lines -gline-tables-only)
  else()
    set(ripple_debug_lines -g1)
  endif()
  # Line tables only: file:line in the reports at a fraction of full debug info's build time.
  add_compile_options(${ripple_sanitize_flags} ${ripple_debug_lines})
  add_link_options(${ripple_sanitize_flags})
  message(STATUS "Sanitizers: address,undefined (${CMAKE_CXX_COMPILER_ID}); run the tests with scripts/sanitize.sh")
endif()
