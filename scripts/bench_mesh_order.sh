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
run() {  # label deck overrides...
  local label=$1 deck=$2; shift 2
  for r in $(seq "$runs"); do
    "$exdyn" run "$deck" --quiet --threads 1 --output "$out" --set name=run_$r \
      --set time.end_time="$end" --set output.every=100000 "$@"
  done
  /usr/bin/python3 - "$label" "$out" "$runs" <<'PY'
import json, statistics, sys
label, out, runs = sys.argv[1], sys.argv[2], int(sys.argv[3])
rates = [json.load(open(f"{out}/run_{r}.json"))["element_cycles_per_second"] for r in range(1, runs + 1)]
rate = statistics.median(rates)
with open(f"{out}/rates.txt", "a") as f:
    f.write(f"{label} {rate}\n")
base = float(open(f"{out}/rates.txt").readline().split()[1])
print(f"{label:<16} {rate / 1e6:8.2f} Mcycles/s   {100 * (rate / base - 1):+6.1f} % against built-in   "
      f"(runs {', '.join(f'{r / 1e6:.2f}' for r in rates)})")
PY
}
mesh_set() {  # the plate_impact_gmsh deck on FILE, reordered or not
  echo --set "parts[0].mesh.file=$1" --set "parts[1].mesh.file=$1" \
       --set "parts[0].mesh.reorder=$2" --set "parts[1].mesh.reorder=$2"
}
run built-in input/plate_impact.yaml --set "parts[0].elements=[$n,1,$n]" --set "parts[1].elements=[$n,1,$n]"
# shellcheck disable=SC2046
run gmsh input/plate_impact_gmsh.yaml $(mesh_set "$out/plate.msh" true)
# shellcheck disable=SC2046
run shuffled input/plate_impact_gmsh.yaml $(mesh_set "$out/shuffled.msh" false)
# shellcheck disable=SC2046
run shuffled+order input/plate_impact_gmsh.yaml $(mesh_set "$out/shuffled.msh" true)
