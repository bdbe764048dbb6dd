#!/usr/bin/env bash
# Speed of exdyn on this machine (a benchmark, not a test: the machine is shared,
# so run it when it is quiet and read the numbers as such).
#   scripts/bench.sh            the decks below + the kernel benchmarks
#   scripts/bench.sh --quick    small sizes only
# Prints element-cycles per second (elements x steps / wall seconds of the time
# loop) for hex8 and hex8r on 1 and 2 threads, the speed-up, and the share of each
# phase of the step; then the kernel benchmarks.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$root"
scripts/install_deps.sh >/dev/null
scripts/build.sh release >/dev/null
exdyn=build/release/src/app/exdyn
out="$(mktemp -d)"
trap 'rm -rf "$out"' EXIT
quick=0; [ "${1:-}" = "--quick" ] && quick=1

echo "machine: $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ //'), $(nproc) cores; $(date -u +%Y-%m-%dT%H:%MZ)"
echo "exdyn $($exdyn --version | head -1 | cut -d' ' -f2), kernels $($exdyn --version | sed -n 's/.*a run uses \([^ ;]*\).*/\1/p'); load average at the start: $(cut -d' ' -f1-3 /proc/loadavg)"
printf '%-34s %-6s %3s %10s %7s %12s %8s  %s\n' case form thr elements steps "Mcycles/s" speedup \
  "phase shares (element forces / integration / output / contact: global + local + forces)"
echo "(on 2 threads with contact the element and contact passes run side by side, each timing itself: their shares overlap)"

run_case() {  # label formulation deck overrides... (each at 1 thread, then 2)
  local label=$1 form=$2 deck=$3; shift 3
  local name="bench_$$"
  for threads in 1 2; do
    "$exdyn" run "$deck" --quiet --threads $threads --output "$out" --set name=${name}_$threads \
      --set "parts[0].formulation=$form" "$@"
  done
  /usr/bin/python3 - "$out/${name}_1.json" "$out/${name}_2.json" "$label" "$form" <<'PY'
import json, sys
one = json.load(open(sys.argv[1]))
for path in sys.argv[1:3]:
    s = json.load(open(path))
    p = s["phase_seconds"]; total = sum(p.values()) or 1.0
    share = lambda k: 100.0 * p.get(k, 0.0) / total
    speedup = s["element_cycles_per_second"] / one["element_cycles_per_second"]
    print(f"{sys.argv[3]:<34} {sys.argv[4]:<6} {s['threads']:>3} {s['mesh']['elements']:>10} {s['steps']:>7} "
          f"{s['element_cycles_per_second'] / 1e6:>12.2f} {speedup:>8.2f}  "
          f"{share('element_forces'):.0f} % / {share('time_integration'):.0f} % / {share('output'):.0f} % / "
          f"{share('contact_global_search'):.1f} + {share('contact_local_search'):.1f} + {share('contact_forces'):.1f} %")
PY
}

for form in hex8 hex8r; do
  run_case "plate reference 100x100x1" $form input/plate_impact_reference.yaml
  run_case "plate impact (contact, bfgs)" $form input/plate_impact.yaml --set "parts[1].formulation=$form"
  if [ $quick = 0 ]; then
    run_case "plate 400x400x1, 400 steps" $form input/plate_impact_reference.yaml \
      --set "parts[0].elements=[400,1,400]" --set "parts[0].box={min: [-2.5e-3, 0, 0], max: [0, 6.25e-6, 2.5e-3]}" \
      --set time.end_time=1.3e-7 --set output.every=100000
    run_case "block 22x22x22 (10^4), 200 steps" $form input/hourglass_block.yaml \
      --set "parts[0].elements=[22,22,22]" --set time.end_time=1.3e-5 --set output.every=100000 \
      --set "output.fields=[stress]"
    run_case "block 46x46x46 (10^5), 60 steps" $form input/hourglass_block.yaml \
      --set "parts[0].elements=[46,46,46]" --set time.end_time=1.9e-6 --set output.every=100000 \
      --set "output.fields=[stress]"
    run_case "block 100x100x100 (10^6), 20 steps" $form input/hourglass_block.yaml \
      --set "parts[0].elements=[100,100,100]" --set time.end_time=3.0e-7 --set output.every=100000 \
      --set "output.fields=[stress]"
  fi
done

# Large deformation (docs/performance.md, "Finite strain and plasticity"): the Taylor
# rod of 2,592 bricks to 80 us on one thread, hex8r (hourglass 0.01) and hex8 with F-bar;
# the rate is elements x steps over the time loop's seconds, the step following the
# crushing elements (so the steps differ by formulation).
echo; echo "== finite strain, plasticity: the Taylor rod (1 thread, 2,592 bricks; best of 3)"
for form in hex8r hex8; do
  best=0
  for run in 1 2 3; do
    "$exdyn" run input/taylor_bar.yaml --quiet --threads 1 --output "$out" --set name=taylor_$form \
      --set "parts[0].formulation=$form" --set "parts[0].hourglass.coefficient=0.01" --set output.every=1000000
    rate=$(/usr/bin/python3 -c "import json,sys; print(json.load(open(sys.argv[1]))['element_cycles_per_second'])" \
      "$out/taylor_$form.json")
    best=$(/usr/bin/python3 -c "print(max($best, $rate))")
  done
  printf '%-10s %-32s %12.3e element-cycles/s\n' $form "taylor_bar, finite, plastic" $best
done

# The instruction sets (docs/performance.md, "Vector kernels"): the element loops and
# two whole runs on every ISA this CPU runs, one thread, the best of 3 runs each.
echo; echo "== instruction sets (1 thread; whole runs: best of 3, element-cycles/s of the time loop)"
for isa in x86-64-v2 x86-64-v3 x86-64-v4; do
  "$exdyn" run input/wave_bar.yaml --isa $isa --quiet --output "$out" --set name=isa_probe \
    --set time.end_time=1e-7 >/dev/null 2>&1 || { echo "$isa: not on this CPU"; continue; }
  for deck in plate_impact plate_impact_hex20; do
    best=0
    for run in 1 2 3; do
      "$exdyn" run input/$deck.yaml --isa $isa --quiet --threads 1 --output "$out" --set name=isa_$deck
      rate=$(/usr/bin/python3 -c "import json,sys; print(json.load(open(sys.argv[1]))['element_cycles_per_second'])" \
        "$out/isa_$deck.json")
      best=$(/usr/bin/python3 -c "print(max($best, $rate))")
    done
    printf '%-10s %-20s %12.3e element-cycles/s\n' $isa $deck $best
  done
  EXDYN_ISA=$isa build/release/bench/element/element_bench --benchmark_filter='threads:1' \
    --benchmark_min_time=$([ $quick = 1 ] && echo 0.05 || echo 0.3) 2>/dev/null | grep -E '^hex' | \
    sed "s/^/$isa /"
done

for b in build/release/bench/element/element_bench build/release/bench/contact/contact_local_search_bench \
         build/release/bench/global_search/bench_global_search build/release/bench/setup/setup_bench; do
  if [ -x "$b" ]; then
    echo; echo "== $(basename "$b")"
    "$b" --benchmark_min_time=$([ $quick = 1 ] && echo 0.05 || echo 0.5)
  fi
done
