#!/usr/bin/env bash
# Installs what is missing, builds, and runs every test:
#   1. the Release build's GoogleTest suite (ctest), every deck of input/ included;
#   2. ParaView opening the plate reference result (scripts/check_paraview.sh);
#   3. the suite again in the AddressSanitizer + UBSan Debug build
#      (skip with EXDYN_SKIP_ASAN=1 for a quick local run);
#   4. libFuzzer on the deck, cases and mesh readers, 60 s each (scripts/fuzz.sh, clang 14).
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$root"
# Each phase's wall time, so that a CI log shows where its minutes go.
phase() {  # phase NAME COMMAND...
  local name=$1 start=$SECONDS
  shift
  "$@"
  echo "test.sh: $name took $((SECONDS - start)) s (total $SECONDS s)"
}
phase install scripts/install_deps.sh --test
phase "release build" scripts/build.sh release
phase "release tests" bash -c 'cd build/release && ctest --output-on-failure -j "$(nproc)"'
phase paraview scripts/check_paraview.sh
if [ "${EXDYN_SKIP_ASAN:-0}" != "1" ]; then
  phase "sanitizer build" scripts/build.sh asan
  phase "sanitizer tests" bash -c 'cd build/asan && ctest --output-on-failure -j "$(nproc)"'
fi
phase fuzz scripts/fuzz.sh 60
echo "test.sh: all tests passed"
