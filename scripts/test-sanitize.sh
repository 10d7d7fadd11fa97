#!/usr/bin/env bash
# Builds Tessera with AddressSanitizer and UndefinedBehaviorSanitizer (TESSERA_SANITIZE=ON,
# RelWithDebInfo at -O1 -g1) in build-asan/ and runs the test suite there, minus the 4096x4096 accuracy
# case (minutes under ASan; the plain suite runs it). Any report fails its test: ASan and UBSan
# abort, LeakSanitizer exits non-zero. Leaks inside Mesa's lavapipe and LLVM are suppressed
# by scripts/lsan-suppressions.txt (see there why); Tessera's own allocations stay checked.
set -euo pipefail
cd "$(dirname "$0")/.."
# ccache caches the tests' precompiled-header compilations only with this (tests/CMakeLists.txt).
export CCACHE_SLOPPINESS=${CCACHE_SLOPPINESS:-pch_defines,time_macros}
scripts/setup.sh
jobs=$(nproc 2>/dev/null || echo 2)
# A cache without the generator's file is a configure that was cut short (Ctrl+C, or another
# configure at the same moment): configure again rather than build nothing.
if [[ ! -f build-asan/CMakeCache.txt || ! ( -f build-asan/Makefile || -f build-asan/build.ninja ) ]]; then
  launcher=()
  command -v ccache >/dev/null && launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
  # -O1 -g1: AddressSanitizer's documentation asks for -O1 or higher for reasonable speed; it
  # compiles much faster than RelWithDebInfo's -O2 -g (the sanitizer build was the largest step
  # of .ci/run, docs/development.md); -g1 keeps the line numbers a report needs.
  cmake -S . -B build-asan -DCMAKE_BUILD_TYPE=RelWithDebInfo -DTESSERA_SANITIZE=ON \
    -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g1 -DNDEBUG" \
    -DTESSERA_BUILD_BENCH=OFF "${launcher[@]}" "$@" >/dev/null
fi
cmake --build build-asan -j "$jobs"
export XDG_RUNTIME_DIR=${XDG_RUNTIME_DIR:-$(mktemp -d)}
# The Vulkan loader unloads the validation layer and lavapipe when an instance is destroyed.
# After that, blocks that lavapipe's globals still point to look leaked, and LeakSanitizer can
# only say "<unknown module>" for frames in either library. Preloading keeps both mapped:
# lavapipe's blocks stay reachable, and the layer's leaks can be suppressed by name
# (scripts/lsan-suppressions.txt). verify_asan_link_order=0: the ASan runtime is then not the
# first library, harmless as neither defines an allocator.
layer=$(find /usr/lib -name libVkLayer_khronos_validation.so -print -quit)
lavapipe=$(find /usr/lib -name libvulkan_lvp.so -print -quit)
export LD_PRELOAD=$layer:$lavapipe
export ASAN_OPTIONS=detect_leaks=1:verify_asan_link_order=0:strict_string_checks=1
export LSAN_OPTIONS=suppressions=$PWD/scripts/lsan-suppressions.txt:print_suppressions=0
export UBSAN_OPTIONS=print_stacktrace=1
# The tests' own lavapipe context without the validation layer: the plain suite (scripts/test.sh)
# has run every test under it, and nothing the sanitizers change reaches Vulkan, while under
# ASan's allocator the layer slowed in-process tests by a quarter (tests/vulkan_fixture.cpp).
# The tool's --validate runs keep it.
export TESSERA_TEST_VALIDATION=0
cd build-asan
# View.*: the viewer's GLFW finds no Vulkan loader while the validation layer and lavapipe are
# preloaded (which ASan needs for their interposition), so the window tests run in the plain
# suite (scripts/test.sh, with validation) only.
# --timeout 1500: since tests share processes (tests/suite_tests.cmake) the longest, from
# Accuracy to Cli, took 667 s under ASan on the 2-core VM while a build ran beside it.
ctest --output-on-failure -j "$jobs" --timeout 1500 -E 'AccuracySizes\.DefaultScene/4096x4096|^View$'
