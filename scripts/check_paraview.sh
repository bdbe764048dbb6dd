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

check() {  # deck points cells steps fields [cell type]
  local name=$1 points=$2 cells=$3 steps=$4 fields=$5 type=${6:-hexahedron}
  "$exdyn" run "$root/input/$name.yaml" --output "$out" --quiet
  if ! "$checker" check_xdmf.py "$out/$name.xmf" --fields "$fields" \
      --expect-points "$points" --expect-cells "$cells" --expect-steps "$steps" --expect-cell-type "$type" \
      --strict --compact > "$out/$name.check.json"; then
    cat "$out/$name.check.json"
    echo "check_paraview: ParaView cannot read $name (see above)" >&2
    exit 1
  fi
  echo "check_paraview: ParaView 5.11 reads $name ($points points, $cells cells of type $type, $steps steps; $fields): ok"
}

check plate_impact_reference 20402 10000 8 displacement:point:3,velocity:point:3,stress:cell:6,von_mises:cell:1
check plate_impact 40804 20000 8 \
  displacement:point:3,velocity:point:3,stress:cell:6,von_mises:cell:1,contact_force:point:3,gap:point:1
check plate_impact_hex20 36006 5000 8 \
  displacement:point:3,velocity:point:3,stress:cell:6,von_mises:cell:1,contact_force:point:3,gap:point:1 \
  quadratichexahedron
check plastic_wave 1604 400 3 \
  displacement:point:3,velocity:point:3,stress:cell:6,von_mises:cell:1,plastic_strain:cell:1

# A deck that mixes 8- and 20-node parts: plate A as 100 x 2 x 100 hex8, plate B
# hex20. Its .xmf uses XDMF's "Mixed" topology (/mesh/mixed_topology,
# docs/output.md). The harness's linter does not follow a Mixed topology (it takes
# the flat list's length for the cell count), so here every ParaView reader must
# open it with the right cells of each type and arrays equal to the HDF5 file, and
# the only lint findings allowed are those about that length.
"$exdyn" run "$root/input/plate_impact_hex20.yaml" --output "$out/mixed" --quiet \
  --set parts[0].formulation=hex8 --set 'parts[0].elements=[100,2,100]'
"$checker" check_xdmf.py "$out/mixed/plate_impact_hex20.xmf" \
  --fields displacement:point:3,velocity:point:3,stress:cell:6,von_mises:cell:1,contact_force:point:3,gap:point:1 \
  --expect-steps 8 --compact > "$out/mixed.check.json" || true
/usr/bin/python3 - "$out/mixed.check.json" <<'PYTHON'
import json, sys
result = json.load(open(sys.argv[1]))
problems = []
for name, reader in result["readers"].items():
    if reader.get("status") != "ok":
        problems.append("%s: %s" % (name, reader.get("status")))
    if reader.get("cell_types") != {"hexahedron": 20000, "quadratichexahedron": 2500}:
        problems.append("%s: cell types %s" % (name, reader.get("cell_types")))
    if reader.get("hdf5_compare", {}).get("mismatches"):
        problems.append("%s: arrays differ from the HDF5 file" % name)
for error in result["errors"]:
    if not ("Topology: NumberOfElements=22500 but connectivity has" in error
            or "Center=Cell but leading dimension 22500 !=" in error):
        problems.append(error)
if problems:
    print(json.dumps(result)[:4000])
    sys.exit("check_paraview: ParaView cannot read the mixed 8/20-node result: " + "; ".join(problems))
print("check_paraview: ParaView 5.11 reads a mixed deck (20000 hexahedra, 2500 quadratic hexahedra, 8 steps, "
      "every field, 3 readers): ok")
PYTHON
