#!/usr/bin/env bash
# Runs the plate reference deck and opens the result with a real ParaView
# (all three XDMF readers, every array compared with the HDF5 file).
# Fails if ParaView cannot read it or a field is missing.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
exdyn="${EXDYN:-$root/build/release/src/app/exdyn}"
checker="$root/../shared/tools/paraview/run_pvpython.sh"
[ -x "$checker" ] || { echo "check_paraview: $checker not found (../shared must sit beside the repo)" >&2; exit 1; }
out="$(mktemp -d)"
trap 'rm -rf "$out"' EXIT
"$exdyn" run "$root/input/plate_impact_reference.yaml" --output "$out" --quiet
"$checker" check_xdmf.py "$out/plate_impact_reference.xmf" \
  --fields displacement:point:3,velocity:point:3,stress:cell:6,von_mises:cell:1 \
  --expect-points 20402 --expect-cells 10000 --expect-steps 8 --expect-cell-type hexahedron \
  --strict --compact > "$out/check.json" || { cat "$out/check.json"; echo "check_paraview: FAILED" >&2; exit 1; }
echo "check_paraview: ParaView 5.11 reads the plate reference result (3 readers, 8 steps, 4 fields): ok"
