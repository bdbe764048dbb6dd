#!/usr/bin/python3
"""Test of scripts/plate_measures.py on synthetic plate impact results with known errors.
Builds, with h5py, a two-plate contact result and a one-plate reference result
in the layout of ../shared/spec/output.md, with a step profile along z = 0 whose plateau
error, front shift, sigma_z error, mirror asymmetry and difference from the reference are
chosen here, and checks that every measure returns them.

    /usr/bin/python3 scripts/test_plate_measures.py
Prints one line per check and `N passed, M failed`; exit status 0 when all passed.
"""

import os
import sys
import tempfile

import h5py
import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import plate_measures as pm  # noqa: E402

N = 50                        # elements per plate side
H = pm.D / N
EPS_PLATEAU = 0.01            # plateau 1 % more compressive than exact
FRONT_ELEMENTS = 26           # elements behind the front (exact: 0.56 N = 28): a 2 h lag
EPS_Z = 0.02                  # sigma_z* = -(1 + EPS_Z) below z = 0.7 d
MIRROR_DEFECT = 0.005         # sigma_zz* of one element of plate B (normalised)
REFERENCE_DEFECT = 0.02       # sigma_xx* of one row element of the reference, s < 0.45 d


def plate_mesh(x0, node_offset):
    """Nodes and VTK-ordered hexahedra of an N x 1 x N box from x0 to x0 + d; elements
    numbered i + N k as exdyn does."""
    xs = x0 + H * np.arange(N + 1)
    ys = np.array([0.0, H])
    zs = H * np.arange(N + 1)
    nodes = np.array([[x, y, z] for z in zs for y in ys for x in xs])

    def nid(i, j, k):
        return node_offset + i + (N + 1) * (j + 2 * k)
    hexes = []
    for k in range(N):
        for i in range(N):
            hexes.append([nid(i, 0, k), nid(i + 1, 0, k), nid(i + 1, 1, k), nid(i, 1, k),
                          nid(i, 0, k + 1), nid(i + 1, 0, k + 1), nid(i + 1, 1, k + 1), nid(i, 1, k + 1)])
    return nodes, np.array(hexes, dtype=np.int64)


def plate_stress(part):
    """Normalised stress (N*N, 6) of a plate, elements i + N k; s from the contact face."""
    stress = np.zeros((N * N, 6))
    for k in range(N):
        for i in range(N):
            m = i if part == 1 else N - 1 - i      # index by distance from the face
            e = i + N * k
            if m < FRONT_ELEMENTS:
                stress[e, pm.XX] = pm.PLATEAU_X * (1 + EPS_PLATEAU)
            z = (k + 0.5) * H
            if z < 0.7 * pm.D:
                stress[e, pm.ZZ] = pm.PLATEAU_Z * (1 + EPS_Z)
            stress[e, pm.XZ] = 0.3 * z / pm.D * (1 if part == 0 else -1)   # mirrored shear
    return stress


def write_result(path, parts, defects=()):
    nodes, hexes, part_ids, stress = [], [], [], []
    offset = 0
    for p in parts:
        n, h = plate_mesh(-pm.D if p == 0 else 0.0, offset)
        nodes.append(n)
        hexes.append(h)
        part_ids.append(np.full(len(h), p, dtype=np.int32))
        stress.append(plate_stress(p))
        offset += len(n)
    stress = np.concatenate(stress)
    for element, component, value in defects:
        stress[element, component] += value
    with h5py.File(path, "w") as f:
        f["/mesh/coordinates"] = np.concatenate(nodes)
        f["/mesh/connectivity"] = np.concatenate(hexes)
        f["/mesh/part"] = np.concatenate(part_ids)
        f["/time"] = np.array([0.0, 2.3255e-7])
        g0 = f.create_group("/steps/000000")
        g0.attrs["time"] = 0.0
        g0["stress"] = np.zeros_like(stress)
        g = f.create_group(f"/steps/{448:06d}")
        g.attrs["time"] = 2.3255e-7
        g["stress"] = stress / pm.STRESS_SCALE      # to Pa


results = []


def check(name, got, want, tol):
    ok = abs(got - want) <= tol
    results.append(ok)
    print(f"{'ok  ' if ok else 'FAIL'} {name}: got {got:.10g}, want {want:.10g} (tol {tol:g})")


def main():
    tmp = tempfile.mkdtemp(prefix="plate_measures_")
    contact, reference = os.path.join(tmp, "contact.h5"), os.path.join(tmp, "reference.h5")
    # Plate B (part 1) elements follow plate A's N*N; the defect is in plate B at i = 10, k = 20.
    write_result(contact, [0, 1], defects=[(N * N + 10 + N * 20, pm.ZZ, MIRROR_DEFECT)])
    # The reference plate (plate A's position): one row element at s = 9.5 h (i = N - 10).
    write_result(reference, [0], defects=[(N - 10, pm.XX, REFERENCE_DEFECT)])

    m = pm.measures(contact, reference)
    p = abs(pm.PLATEAU_X)
    check("material: sigma_x* plateau", pm.PLATEAU_X, -7.0 / 3.0, 1e-12)
    check("material: lambda", pm.LAMBDA, 1.211538e11, 1e5)
    check("material: c1", pm.C1, 6020.18, 0.01)
    check("plateau mean", m["plateau_mean"], pm.PLATEAU_X * (1 + EPS_PLATEAU), 1e-12)
    check("plateau error", m["plateau_error"], EPS_PLATEAU, 1e-12)
    # Half-plateau crossing: between the last plateau centre (25.5 h) and the next (26.5 h),
    # linear: t = (0.5 - (1 + eps)) / (0 - (1 + eps)).
    t = 1 - 0.5 / (1 + EPS_PLATEAU)
    front_h = FRONT_ELEMENTS - 0.5 + t
    check("front x/h", m["front_over_h"], front_h, 1e-9)
    check("front - 0.56 d, in h", m["front_error_over_h"], front_h - 0.56 * N, 1e-9)
    check("front x/d", m["front_over_d"], front_h / N, 1e-11)
    # L1: 26 elements off by eps |P|, 2 (centres 26.5 h, 27.5 h < 28 h) off by |P|, over 0.75 d.
    check("profile error", m["profile_error"], (FRONT_ELEMENTS * EPS_PLATEAU + 2) / (0.75 * N), 1e-12)
    check("sigma_z* mean + 1", m["sigma_z_mean_error"], -EPS_Z, 1e-12)
    check("max |sigma_z* + 1|", m["sigma_z_max_error"], EPS_Z, 1e-12)
    check("mirror symmetry", m["mirror_symmetry"], MIRROR_DEFECT / p, 1e-12)
    check("contact - reference along z = 0", m["contact_vs_reference_row"], REFERENCE_DEFECT / p, 1e-12)
    check("contact - reference, every element", m["contact_vs_reference_all"], REFERENCE_DEFECT / p, 1e-12)

    # Without defects the mirror and reference measures are zero (shear sign handled).
    clean = os.path.join(tmp, "clean.h5")
    write_result(clean, [0, 1])
    write_result(reference, [0])
    m = pm.measures(clean, reference)
    check("mirror symmetry, no defect", m["mirror_symmetry"], 0.0, 1e-15)
    check("contact - reference, no defect", m["contact_vs_reference_all"], 0.0, 1e-15)

    # The reference alone: no mirror, no reference difference.
    m = pm.measures(reference)
    results.append(np.isnan(m["mirror_symmetry"]) and np.isnan(m["contact_vs_reference_row"]))
    print(f"{'ok  ' if results[-1] else 'FAIL'} one plate: mirror and reference measures are NaN")

    failed = results.count(False)
    print(f"{len(results) - failed} passed, {failed} failed")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
