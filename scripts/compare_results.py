#!/usr/bin/python3
"""Compares two exdyn results whose meshes number nodes and elements differently.

    scripts/compare_results.py A.h5 B.h5

Matches nodes by part and position and elements by part and centroid (to 1e-9 of the
model's size), then prints, for every field of every step both files wrote, the largest
difference over the field's largest absolute value in A. Exit 1 when the meshes do not
match (a node or element of A has no partner in B).
"""
import sys

import h5py
import numpy as np


def keys(points, part, scale):
    """One hashable key per row: the part and the position rounded to 1e-9 of the size."""
    rounded = np.round(points / (1e-9 * scale)).astype(np.int64)
    return [(int(p),) + tuple(r) for p, r in zip(part, rounded)]


def matching(a, b, scale):
    """Indices into b of each row of a, or None where a row has no partner."""
    index = {k: i for i, k in enumerate(b)}
    return [index.get(k) for k in a]


def mesh_keys(f, scale):
    x = f["/mesh/coordinates"][...]
    conn = f["/mesh/connectivity"][...]
    element_part = f["/mesh/part"][...]
    node_part = np.full(len(x), -1)
    for e, nodes in enumerate(conn):
        node_part[nodes] = element_part[e]
    centroid = x[conn[:, :8]].mean(axis=1)
    return keys(x, node_part, scale), keys(centroid, element_part, scale), len(x), len(conn)


def main():
    if len(sys.argv) != 3:
        print(__doc__, file=sys.stderr)
        return 2
    with h5py.File(sys.argv[1], "r") as fa, h5py.File(sys.argv[2], "r") as fb:
        x = fa["/mesh/coordinates"][...]
        scale = float(np.max(x.max(axis=0) - x.min(axis=0)))
        nodes_a, elements_a, n_nodes, n_elements = mesh_keys(fa, scale)
        nodes_b, elements_b, _, _ = mesh_keys(fb, scale)
        node_map = matching(nodes_a, nodes_b, scale)
        element_map = matching(elements_a, elements_b, scale)
        if None in node_map or None in element_map:
            print("the meshes do not match: %d of %d nodes and %d of %d elements have no partner"
                  % (node_map.count(None), n_nodes, element_map.count(None), n_elements))
            return 1
        node_map, element_map = np.array(node_map), np.array(element_map)
        worst = 0.0
        for step in sorted(set(fa["/steps"]) & set(fb["/steps"])):
            for field in sorted(set(fa["/steps"][step]) & set(fb["/steps"][step])):
                va = fa["/steps"][step][field][...]
                vb = fb["/steps"][step][field][...]
                order = node_map if len(va) == n_nodes else element_map
                vb = vb[order]
                largest = float(np.max(np.abs(va)))
                difference = float(np.max(np.abs(va - vb)))
                relative = difference / largest if largest > 0 else difference
                worst = max(worst, relative)
                print("%s %-14s largest %.6e  difference %.3e  relative %.3e" % (step, field, largest,
                                                                               difference, relative))
        print("worst relative difference %.3e" % worst)
    return 0


if __name__ == "__main__":
    sys.exit(main())
