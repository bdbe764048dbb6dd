#!/usr/bin/env bash
# The two partitions of the chunks over MPI ranks side by side (docs/parallel.md,
# "Partitions"): recursive coordinate bisection and METIS, on 2 and 3 ranks (one thread
# each, oversubscribed where the machine has fewer cores), for the imported decks.
# Prints the chunk graph's edge cut, the shared nodes, the force messages and bytes of
# a step, the wall time of the run, and whether every field is the one-rank result bit
# for bit.
#   scripts/partition_figures.sh [DECK ...]   (default: the Gmsh decks of input/)
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$root"
scripts/build.sh release >/dev/null
exdyn=$root/build/release/src/app/exdyn
out="$(mktemp -d)"
trap 'rm -rf "$out"' EXIT
decks=("$@")
[ ${#decks[@]} -gt 0 ] || decks=(input/hertz_ball_gmsh.yaml input/plate_impact_gmsh.yaml)
mpi=(mpirun --oversubscribe)
[ "$(id -u)" -eq 0 ] && mpi+=(--allow-run-as-root)
printf '%-22s %-10s %5s %9s %7s %9s %11s %8s  %s\n' deck partition ranks edge_cut shared messages bytes/step wall_s "fields = 1 rank"
for deck in "${decks[@]}"; do
  name=$(basename "$deck" .yaml)
  "$exdyn" run "$deck" --quiet --threads 1 --output "$out/1" --set output.every=1000000
  for ranks in 2 3; do
    for partition in bisection metis; do
      "${mpi[@]}" -n $ranks "$exdyn" run "$deck" --quiet --threads 1 --output "$out/${ranks}_$partition" \
        --partition $partition --set output.every=1000000
      /usr/bin/python3 - "$out/1/$name.h5" "$out/${ranks}_$partition/$name" "$name" "$partition" "$ranks" <<'PY'
import json, sys
import h5py, numpy as np
one, many, name, partition, ranks = sys.argv[1:6]
s = json.load(open(many + ".json"))
same = True
with h5py.File(one, "r") as a, h5py.File(many + ".h5", "r") as b:
    for step in a["steps"]:
        for field in a["steps"][step]:
            same = same and np.array_equal(a["steps"][step][field][...], b["steps"][step][field][...])
m = s["mpi"]
print(f"{name:<22} {partition:<10} {ranks:>5} {m['edge_cut']:>9} {m['shared_nodes']:>7} {m['messages_per_step']:>9} "
      f"{m['bytes_per_step']:>11.0f} {s['wall_seconds']:>8.2f}  {'bit for bit' if same else 'DIFFERENT'}")
PY
    done
  done
done
