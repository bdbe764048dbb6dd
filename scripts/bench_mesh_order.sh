#!/usr/bin/env bash
# What the import's element order buys (a benchmark, not a test: run it on a quiet
# machine). The plate impact at n x 1 x n bricks per plate, one thread, four ways:
#   built-in       the built-in box mesher's lattice order
#   gmsh           the Gmsh mesh of input/meshes/plate_impact.geo, reordered on import
#   shuffled       its elements in a random order (bench/mesh/shuffle_mesh), kept so
#   shuffled+order the same shuffled file, reordered on import (the default)
# Prints element-cycles per second (the median of RUNS runs) and each against built-in.
#   scripts/bench_mesh_order.sh [n=200] [runs=3]
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$root"
n=${1:-200}
runs=${2:-3}
scripts/install_deps.sh --mesher >/dev/null
scripts/build.sh release >/dev/null
exdyn=build/release/src/app/exdyn
out="$(mktemp -d)"
trap 'rm -rf "$out"' EXIT
gmsh -3 -format msh41 -setnumber n "$n" input/meshes/plate_impact.geo -o "$out/plate.msh" >/dev/null
build/release/bench/mesh/shuffle_mesh "$out/plate.msh" "$out/shuffled.msh" 7
steps=200
h=$(/usr/bin/python3 -c "print(2.5e-3 / $n)")
end=$(/usr/bin/python3 -c "import math; c=math.sqrt(2.1e11*0.7/(1.3*0.4*7800)); print(0.125*$h/c*$steps*(1-1e-9))")
echo "machine: $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ //'); load $(cut -d' ' -f1-3 /proc/loadavg)"
echo "plate impact, $n x 1 x $n bricks per plate, $steps steps, 1 thread, median of $runs runs"
# The cases take turns (built-in, gmsh, shuffled, shuffled+order, then again), so that a
# drift of the machine's speed touches them alike.
labels=(built-in gmsh shuffled shuffled+order)
case_args() {  # the deck and overrides of case $1
  local mesh reorder
  case $1 in
    built-in) echo input/plate_impact.yaml --set "parts[0].elements=[$n,1,$n]" --set "parts[1].elements=[$n,1,$n]"
              return ;;
    gmsh) mesh=$out/plate.msh reorder=true ;;
    shuffled) mesh=$out/shuffled.msh reorder=false ;;
    shuffled+order) mesh=$out/shuffled.msh reorder=true ;;
  esac
  echo input/plate_impact_gmsh.yaml --set "parts[0].mesh.file=$mesh" --set "parts[1].mesh.file=$mesh" \
       --set "parts[0].mesh.reorder=$reorder" --set "parts[1].mesh.reorder=$reorder"
}
for r in $(seq "$runs"); do
  for label in "${labels[@]}"; do
    # shellcheck disable=SC2046
    "$exdyn" run $(case_args "$label") --quiet --threads 1 --output "$out" --set "name=${label//+/_}_$r" \
      --set time.end_time="$end" --set output.every=100000
  done
done
/usr/bin/python3 - "$out" "$runs" "${labels[@]}" <<'PY'
import json, statistics, sys
out, runs, labels = sys.argv[1], int(sys.argv[2]), sys.argv[3:]
rate = {}
for label in labels:
    rates = [json.load(open(f"{out}/{label.replace('+', '_')}_{r}.json"))["element_cycles_per_second"]
             for r in range(1, runs + 1)]
    rate[label] = statistics.median(rates)
    print(f"{label:<16} {rate[label] / 1e6:8.2f} Mcycles/s   {100 * (rate[label] / rate[labels[0]] - 1):+6.1f} % "
          f"against built-in   (runs {', '.join(f'{x / 1e6:.2f}' for x in rates)})")
PY
