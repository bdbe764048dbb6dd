#!/usr/bin/env bash
# Fuzzes the input readers (decks, cases, meshes, restart checkpoints) with libFuzzer
# (tests/fuzz/, docs/stability.md):
#   1. installs what is missing (clang 14, libFuzzer) and builds build/fuzz with clang,
#      ASan and UBSan;
#   2. replays every file of tests/fuzz/regressions/{deck,cases,mesh,checkpoint}/ (past findings);
#   3. fuzzes each target for SECONDS (default 60) from a seed corpus copied to a
#      temporary directory: the decks of input/ and tests/input/, the cases of
#      tests/contact/, tests/fuzz/seeds/ and the regressions.
#   scripts/fuzz.sh [SECONDS]
# Exit status 0: no finding. 1: a finding; its input is kept under build/fuzz/findings/
# (printed). Fix the reader, then add the input to tests/fuzz/regressions/TARGET/.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$root"
seconds="${1:-60}"
[[ "$seconds" =~ ^[0-9]+$ ]] || { echo "usage: scripts/fuzz.sh [SECONDS]" >&2; exit 2; }
jobs="${EXDYN_JOBS:-$(nproc)}"
build="$root/build/fuzz"

scripts/install_deps.sh --fuzz
# Only the readers', the mesh and the output libraries and the four targets are built (the rest is configured, not compiled).
# Debug with -O1: assertions on, every sanitizer check, fast enough to fuzz; -g1: line
# tables for the findings' stack traces. Warnings are not
# errors: the project's warning set is GCC's (-Wno-restrict), and -Werror is the GCC build's job.
CC=clang-14 CXX=clang++-14 cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE=Debug "-DCMAKE_CXX_FLAGS_DEBUG=-g1 -O1" \
  -DEXDYN_BUILD_FUZZ=ON -DEXDYN_BUILD_TESTS=OFF -DEXDYN_BUILD_BENCHMARKS=OFF -DEXDYN_WERROR=OFF >/dev/null
cmake --build "$build" -j "$jobs" --target fuzz_deck fuzz_cases fuzz_mesh fuzz_checkpoint

# Stack traces of findings with file and line.
if [ -z "${ASAN_SYMBOLIZER_PATH:-}" ] && [ -x /usr/lib/llvm-14/bin/llvm-symbolizer ]; then
  export ASAN_SYMBOLIZER_PATH=/usr/lib/llvm-14/bin/llvm-symbolizer
fi

corpus="$(mktemp -d "${TMPDIR:-/tmp}/exdyn_fuzz.XXXXXX")"
trap 'rm -rf "$corpus"' EXIT
mkdir -p "$build/logs"
status=0

# The common options: a run longer than 10 s is a hang, more than 2 GB of memory
# (or one allocation that large) a runaway allocation.
limits=(-timeout=10 -rss_limit_mb=2048)

# fuzz TARGET MAX_LEN SEED_SOURCE...: replays the regressions, then fuzzes.
fuzz() {
  local target="$1" max_len="$2"
  shift 2
  local binary="$build/tests/fuzz/fuzz_$target"
  local findings="$build/findings/$target"
  local log="$build/logs/$target.log"
  mkdir -p "$findings" "$corpus/$target"

  local regressions=("$root"/tests/fuzz/regressions/"$target"/*)
  if [ -e "${regressions[0]}" ]; then
    if ! "$binary" "${limits[@]}" -artifact_prefix="$findings/" "${regressions[@]}" >"$log" 2>&1; then
      tail -n 40 "$log"
      echo "fuzz.sh: $target: a regression input of tests/fuzz/regressions/$target/ fails again (log: $log)"
      return 1
    fi
    echo "fuzz.sh: $target: ${#regressions[@]} regression inputs pass"
  fi

  # Seeds under unique names (several folders hold a plate_impact.yaml).
  local source file
  for source in "$@"; do
    for file in "$root/$source"/*; do
      if [ -f "$file" ]; then cp "$file" "$corpus/$target/$(echo "${source}_$(basename "$file")" | tr '/' '_')"; fi
    done
  done
  local seeds
  seeds=$(find "$corpus/$target" -type f | wc -l)

  if "$binary" "${limits[@]}" -max_len="$max_len" -max_total_time="$seconds" -print_final_stats=1 \
      -dict="$root/tests/fuzz/yaml.dict" -artifact_prefix="$findings/" "$corpus/$target" >"$log" 2>&1; then
    local runs rate rss
    runs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$log")
    rate=$(sed -n 's/^stat::average_exec_per_sec: *//p' "$log")
    rss=$(sed -n 's/^stat::peak_rss_mb: *//p' "$log")
    echo "fuzz.sh: $target: ${runs} executions in ${seconds} s (${rate} exec/s, peak RSS ${rss} MB)" \
         "from ${seeds} seeds, corpus $(find "$corpus/$target" -type f | wc -l) inputs: no finding"
  else
    grep -v '^"' "$log" | tail -n 40
    local saved
    saved=$(sed -n 's/.*Test unit written to \(.*\)$/\1/p' "$log" | tail -n 1)
    echo "fuzz.sh: $target: FINDING after fuzzing; the input is saved as ${saved:-"(see $log)"}"
    echo "fuzz.sh: reproduce with $binary ${saved:-INPUT}; after the fix, copy it to tests/fuzz/regressions/$target/"
    return 1
  fi
}

# libFuzzer runs on one core: with two or more, the deck and cases targets fuzz side by
# side, each still for SECONDS on a core of its own.
if [ "$jobs" -ge 2 ]; then
  fuzz deck 8192 input tests/input/decks tests/input/bad_decks tests/fuzz/seeds/deck tests/fuzz/regressions/deck &
  deck_fuzzer=$!
else
  fuzz deck 8192 input tests/input/decks tests/input/bad_decks tests/fuzz/seeds/deck tests/fuzz/regressions/deck ||
    status=1
fi
fuzz cases 4096 tests/contact/cases tests/contact/bad_cases tests/fuzz/seeds/cases tests/fuzz/regressions/cases ||
  status=1
if [ -n "${deck_fuzzer:-}" ]; then wait "$deck_fuzzer" || status=1; fi
# The mesh and checkpoint targets side by side too.
if [ "$jobs" -ge 2 ]; then
  fuzz mesh 256 tests/fuzz/seeds/mesh tests/fuzz/regressions/mesh &
  mesh_fuzzer=$!
else
  fuzz mesh 256 tests/fuzz/seeds/mesh tests/fuzz/regressions/mesh || status=1
fi
fuzz checkpoint 16384 tests/fuzz/seeds/checkpoint tests/fuzz/regressions/checkpoint || status=1
if [ -n "${mesh_fuzzer:-}" ]; then wait "$mesh_fuzzer" || status=1; fi

if [ "$status" -ne 0 ]; then
  echo "fuzz.sh: FAILED (logs in $build/logs/)"
  exit 1
fi
echo "fuzz.sh: no finding in ${seconds} s per target"
