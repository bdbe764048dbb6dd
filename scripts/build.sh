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
  asan)    flags=(-DCMAKE_BUILD_TYPE=Debug -DEXDYN_SANITIZE=ON -DEXDYN_BUILD_BENCHMARKS=OFF) ;;
  *) echo "usage: scripts/build.sh [release|asan]" >&2; exit 2 ;;
esac
cmake -S "$root" -B "$root/build/$kind" "${flags[@]}" >/dev/null
cmake --build "$root/build/$kind" -j "$jobs"
