#!/usr/bin/env bash
# Runs the plate decks and opens their results with a real ParaView (all three
# XDMF readers, every array compared with the HDF5 file). Fails if ParaView
# cannot read a result or a field is missing.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
exdyn="${EXDYN:-$root/build/release/src/app/exdyn}"
checker="$root/../shared/tools/paraview/run_pvpython.sh"
[ -x "$checker" ] || { echo "check_paraview: $checker not found (../shared must sit beside the repo)" >&2; exit 1; }
out="$(mktemp -d)"
trap 'rm -rf "$out"' EXIT

check() {  # deck points cells steps fields
  local name=$1 points=$2 cells=$3 steps=$4 fields=$5
  "$exdyn" run "$root/input/$name.yaml" --output "$out" --quiet
  if ! "$checker" check_xdmf.py "$out/$name.xmf" --fields "$fields" \
      --expect-points "$points" --expect-cells "$cells" --expect-steps "$steps" --expect-cell-type hexahedron \
      --strict --compact > "$out/$name.check.json"; then
    cat "$out/$name.check.json"
    echo "check_paraview: ParaView cannot read $name (see above)" >&2
    exit 1
  fi
  echo "check_paraview: ParaView 5.11 reads $name ($points points, $cells hexahedra, $steps steps; $fields): ok"
}

check plate_impact_reference 20402 10000 8 displacement:point:3,velocity:point:3,stress:cell:6,von_mises:cell:1
check plate_impact 40804 20000 8 \
  displacement:point:3,velocity:point:3,stress:cell:6,von_mises:cell:1,contact_force:point:3,gap:point:1
