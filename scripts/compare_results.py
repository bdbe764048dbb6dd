#!/usr/bin/python3
"""Compares two exdyn results (NAME.h5) dataset by dataset: the mesh, every step's
fields and the history. Prints, per dataset kind, the largest difference relative to
the largest value of the reference (max |a - b| / max |b|) and whether all are bitwise
equal. Exit 0 when every relative difference is at most --tolerance (default 1e-12),
1 otherwise (or when the files differ in structure).

  scripts/compare_results.py REFERENCE.h5 OTHER.h5 [--tolerance T]
"""
import argparse
import sys

import h5py
import numpy as np


def datasets(group, prefix=""):
    out = {}
    for name, item in group.items():
        path = prefix + "/" + name
        if isinstance(item, h5py.Group):
            out.update(datasets(item, path))
        else:
            out[path] = item[()]
    return out


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("reference")
    parser.add_argument("other")
    parser.add_argument("--tolerance", type=float, default=1e-12)
    args = parser.parse_args()
    with h5py.File(args.reference, "r") as a, h5py.File(args.other, "r") as b:
        ref, oth = datasets(a), datasets(b)
    if set(ref) != set(oth):
        print("different datasets: only in reference", sorted(set(ref) - set(oth))[:5],
              "only in other", sorted(set(oth) - set(ref))[:5])
        return 1
    worst = {}
    bitwise = True
    for path in sorted(ref):
        x, y = np.asarray(ref[path]), np.asarray(oth[path])
        if x.shape != y.shape:
            print(f"{path}: shape {x.shape} vs {y.shape}")
            return 1
        kind = path.split("/")[-1] if path.startswith("/steps/") else path
        if not np.array_equal(x, y):
            bitwise = False
        scale = float(np.max(np.abs(x))) if x.size else 0.0
        diff = float(np.max(np.abs(x.astype(float) - y.astype(float)))) if x.size else 0.0
        relative = diff / scale if scale > 0 else diff
        worst[kind] = max(worst.get(kind, 0.0), relative)
    for kind in sorted(worst):
        print(f"{kind:40s} {worst[kind]:.3e}")
    largest = max(worst.values())
    print(f"steps {len([p for p in ref if p.endswith('/displacement')])}, largest relative difference "
          f"{largest:.3e}, bitwise equal: {'yes' if bitwise else 'no'}")
    return 0 if largest <= args.tolerance else 1


if __name__ == "__main__":
    sys.exit(main())
