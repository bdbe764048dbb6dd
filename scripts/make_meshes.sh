#!/usr/bin/env bash
# Meshes the Gmsh scripts of input/meshes/ into the .msh files the decks and tests read
# (committed, so that neither needs the mesher). Needs Debian's gmsh:
#   scripts/install_deps.sh --mesher && scripts/make_meshes.sh
# Format 4.1, ASCII. 20-node hexahedra: -order 2 with Mesh.SecondOrderIncomplete = 1
# (serendipity: no face or body nodes).
set -euo pipefail
cd "$(dirname "$0")/../input/meshes"
command -v gmsh >/dev/null || { echo "make_meshes: no gmsh; run scripts/install_deps.sh --mesher" >&2; exit 2; }
mesh() {  # mesh OUTPUT GEO [gmsh options...]
  local out=$1 geo=$2
  shift 2
  gmsh -3 -format msh41 "$@" "$geo" -o "$out" >/dev/null
  echo "make_meshes: $out ($(wc -c <"$out") bytes)"
}
quadratic=(-order 2 -string "Mesh.SecondOrderIncomplete=1;")
mesh plate_impact_hex8.msh plate_impact.geo -setnumber n 100
mesh plate_impact_hex20.msh plate_impact.geo -setnumber n 50 -setnumber t 5e-5 "${quadratic[@]}"
mesh hertz_ball_hex20.msh hertz_ball.geo "${quadratic[@]}"
mesh hertz_ball_coarse_hex20.msh hertz_ball.geo -setnumber na 8 -setnumber nr 2 "${quadratic[@]}"
mesh weldox_plate_hex8.msh weldox_plate.geo
mesh tube_hex8.msh tube.geo
mesh tube_crush_hex8.msh tube.geo -setnumber ri 9.2e-3 -setnumber L 40e-3 -setnumber z0 0 \
  -setnumber na 24 -setnumber nz 100
mesh u_shape_hex8.msh u_shape.geo
mesh l_shape_hex8.msh u_shape.geo -setnumber right 0
mesh c_slot_hex8.msh c_slot.geo
mesh c_slot_hex20.msh c_slot.geo "${quadratic[@]}"
# The bad-input tests' meshes (tests/mesh/meshes/).
cd ../../tests/mesh/meshes
mesh cube_tets.msh cube.geo
mesh cube_hex27.msh cube.geo -setnumber hexahedra 1 -order 2
