"""Accuracy measures of a plate impact result, against the exact values of
../shared/reference/plate-impact.md. Importable; docs/results.md defines each measure.

A result is read from NAME.h5 (the last written step). Each plate is a structured
N x 1 x N box of cubes of side h; its elements are located by their centroids, so
the element numbering is not assumed. Distances are measured from the contact face:
s = -x for plate_a (part 0, x in [-d, 0]), s = x for plate_b (part 1, x in [0, d]).
Stresses are normalised: sigma* = sigma c1 / (lambda v0).

    /usr/bin/python3 scripts/plate_measures.py RESULT.h5 [--reference REF.h5]   # prints JSON
"""

import json
import math
import sys

import numpy as np

# The case (plate-impact.md): steel, 1 m/s each, half thickness d = 2.5 mm, c1 t / d = 0.56.
E_MODULUS = 2.1e11
POISSON = 0.3
DENSITY = 7800.0
V0 = 1.0
D = 2.5e-3
FRONT_EXACT_OVER_D = 0.56          # the plane dilatational front along z = 0
DIFFRACTED_Z_OVER_D = 0.6081       # sigma_z* = -1 exactly below this along x/d = 0.4
HEAD_WAVE_Z_OVER_D = 0.8988

LAMBDA = E_MODULUS * POISSON / ((1 + POISSON) * (1 - 2 * POISSON))
MU = E_MODULUS / (2 * (1 + POISSON))
M_MODULUS = LAMBDA + 2 * MU
C1 = math.sqrt(M_MODULUS / DENSITY)
STRESS_SCALE = C1 / (LAMBDA * V0)             # sigma* = sigma * STRESS_SCALE
PLATEAU_X = -(1 - POISSON) / POISSON          # -2.3333
PLATEAU_Z = -1.0

# Regions (fractions of d, element centres); docs/results.md states them.
PLATEAU_REGION = (0.05, 0.45)      # behind the front, away from the face and the front (5.5 h .. 44.5 h at N = 100)
PROFILE_WINDOW = 0.75              # the L1 profile error is taken over 0 <= s <= 0.75 d
CONTACT_REF_REGION = 0.45          # contact vs reference along z = 0: elements with s < 0.45 d
SIGMA_Z_LINE = 0.4                 # x/d of the sigma_z* line (Fig. 9)
SIGMA_Z_REGION = 0.6               # sigma_z* is compared with -1 for element centres z/d < 0.6

XX, YY, ZZ, XY, YZ, XZ = range(6)
# Mirroring x -> -x flips the sign of the xy and xz shear stresses.
MIRROR_SIGN = np.array([1, 1, 1, -1, 1, -1], dtype=float)


class Plate:
    """One plate of the last step: stress on an (nz, nx) grid ordered by s (from the
    contact face) and z, with h and the centre coordinates."""

    def __init__(self, centroids, stress, part_index):
        x, z = centroids[:, 0], centroids[:, 2]
        s = -x if part_index == 0 else x
        self.s_sign = -1.0 if part_index == 0 else 1.0
        s_values = np.unique(np.round(s, 12))
        z_values = np.unique(np.round(z, 12))
        self.nx, self.nz = len(s_values), len(z_values)
        self.h = float(s_values[1] - s_values[0]) if self.nx > 1 else 2 * float(s_values[0])
        i = np.rint((s - s_values[0]) / self.h).astype(int)
        k = np.rint((z - z_values[0]) / self.h).astype(int)
        if len(s) != self.nx * self.nz:
            # ny > 1: keep the layer with the smallest y (every layer is the same in plane strain)
            y = centroids[:, 1]
            keep = np.isclose(y, y.min())
            i, k, stress = i[keep], k[keep], stress[keep]
        grid = np.full((self.nz, self.nx, 6), np.nan)
        grid[k, i] = stress
        self.stress = grid * STRESS_SCALE           # normalised, [k, i, component]
        self.s = s_values                           # element centres from the contact face
        self.z = z_values

    def row_sigma_x(self):
        """sigma_x* of the row of elements next to z = 0, ordered by s."""
        return self.stress[0, :, XX]


def read_result(path, step=None):
    """The plates of one result: list of Plate by part index, and the time of the step."""
    import h5py
    with h5py.File(path, "r") as f:
        coords = f["/mesh/coordinates"][...]
        conn = f["/mesh/connectivity"][...]
        part = f["/mesh/part"][...]
        steps = sorted(f["/steps"].keys())
        name = steps[-1] if step is None else f"{step:06d}"
        stress = f[f"/steps/{name}/stress"][...]
        time = float(f[f"/steps/{name}"].attrs.get("time", np.nan))
    centroids = coords[conn].mean(axis=1)
    plates = []
    for p in range(int(part.max()) + 1):
        sel = part == p
        plates.append(Plate(centroids[sel], stress[sel], p))
    return plates, time


def plateau(plate):
    """Mean sigma_x* along z = 0 over centres PLATEAU_REGION (in d), and its relative error
    mean / exact - 1 (positive: more compressive than the exact plateau)."""
    d = D
    sel = (plate.s >= PLATEAU_REGION[0] * d - 1e-12) & (plate.s <= PLATEAU_REGION[1] * d + 1e-12)
    mean = float(np.mean(plate.row_sigma_x()[sel]))
    return mean, mean / PLATEAU_X - 1


def front_position(plate):
    """Where sigma_x* along z = 0 crosses half the exact plateau, by linear interpolation
    between element centres, scanning from the far end toward the face (the first
    element whose |sigma_x*| reaches half the plateau is behind the front). In metres."""
    row = plate.row_sigma_x()
    half = 0.5 * PLATEAU_X
    idx = np.nonzero(row <= half)[0]
    if len(idx) == 0:
        return float("nan")
    j = idx[-1]
    if j + 1 >= len(row):
        return float(plate.s[j])
    a, b = row[j], row[j + 1]
    t = (half - a) / (b - a)
    return float(plate.s[j] + t * (plate.s[j + 1] - plate.s[j]))


def profile_error(plate):
    """L1 distance of the z = 0 profile from the exact step over 0 <= s <= PROFILE_WINDOW d,
    as a fraction of the plateau: sum_e h |sigma*_e - exact(s_e)| / (|plateau| PROFILE_WINDOW d).
    The exact value is taken at each element centre (a centre exactly on the front counts as 0.5 of the step)."""
    row = plate.row_sigma_x()
    sel = plate.s <= PROFILE_WINDOW * D + 1e-12
    exact = np.where(plate.s < FRONT_EXACT_OVER_D * D, PLATEAU_X, 0.0)
    exact = np.where(np.isclose(plate.s, FRONT_EXACT_OVER_D * D), 0.5 * PLATEAU_X, exact)
    return float(np.sum(plate.h * np.abs(row[sel] - exact[sel])) / (abs(PLATEAU_X) * PROFILE_WINDOW * D))


def sigma_z_line(plate):
    """sigma_z* along x/d = SIGMA_Z_LINE: linear interpolation in s between the two element
    columns whose centres bracket it. Returns (z centres, values)."""
    target = SIGMA_Z_LINE * D
    j = int(np.searchsorted(plate.s, target)) - 1
    j = min(max(j, 0), plate.nx - 2)
    t = (target - plate.s[j]) / (plate.s[j + 1] - plate.s[j])
    values = (1 - t) * plate.stress[:, j, ZZ] + t * plate.stress[:, j + 1, ZZ]
    return plate.z, values


def sigma_z_error(plate):
    """Mean and largest |sigma_z* - (-1)| along x/d = 0.4 over element centres z/d < SIGMA_Z_REGION."""
    z, values = sigma_z_line(plate)
    sel = z < SIGMA_Z_REGION * D
    dev = np.abs(values[sel] - PLATEAU_Z)
    return float(np.mean(values[sel]) - PLATEAU_Z), float(dev.max())


def mirrored(plate_b_stress):
    """Plate B's stress on plate A's grid orientation: same (k, i by s), shear signs flipped."""
    return plate_b_stress * MIRROR_SIGN


def mirror_symmetry(plate_a, plate_b):
    """Largest difference between plate A and mirrored plate B over every element and
    every stress component, as a fraction of the sigma_x plateau."""
    diff = np.abs(plate_a.stress - mirrored(plate_b.stress))
    return float(np.nanmax(diff) / abs(PLATEAU_X))


def contact_vs_reference(contact_plates, reference_plate):
    """Largest difference between each contact plate and the reference plate:
    (along z = 0, sigma_x*, elements with s < CONTACT_REF_REGION d; every element and
    component), both as fractions of the sigma_x plateau, worst of the two plates."""
    sel = reference_plate.s < CONTACT_REF_REGION * D
    row_worst, all_worst = 0.0, 0.0
    for p in contact_plates:
        stress = p.stress if p.s_sign == reference_plate.s_sign else mirrored(p.stress)
        row = np.abs(stress[0, sel, XX] - reference_plate.stress[0, sel, XX])
        row_worst = max(row_worst, float(row.max()))
        all_worst = max(all_worst, float(np.nanmax(np.abs(stress - reference_plate.stress))))
    return row_worst / abs(PLATEAU_X), all_worst / abs(PLATEAU_X)


def measures(result_path, reference_path=None):
    """Every measure of one result as a flat dict (the CSV columns). The profile measures
    are those of plate A; plate B enters through the mirror symmetry and the reference difference."""
    plates, time = read_result(result_path)
    a = plates[0]
    mean, err = plateau(a)
    front = front_position(a)
    sz_mean, sz_max = sigma_z_error(a)
    out = {
        "h": a.h,
        "time": time,
        "plateau_mean": mean,
        "plateau_error": err,
        "front_over_h": front / a.h,
        "front_over_d": front / D,
        "front_error_over_h": (front - FRONT_EXACT_OVER_D * D) / a.h,
        "profile_error": profile_error(a),
        "sigma_z_mean_error": sz_mean,
        "sigma_z_max_error": sz_max,
        "mirror_symmetry": mirror_symmetry(a, plates[1]) if len(plates) > 1 else float("nan"),
        "contact_vs_reference_row": float("nan"),
        "contact_vs_reference_all": float("nan"),
    }
    if reference_path is not None:
        ref_plates, _ = read_result(reference_path)
        row, every = contact_vs_reference(plates, ref_plates[0])
        out["contact_vs_reference_row"] = row
        out["contact_vs_reference_all"] = every
    return out


def main(argv):
    import argparse
    parser = argparse.ArgumentParser(description="accuracy measures of a plate impact result")
    parser.add_argument("result")
    parser.add_argument("--reference")
    args = parser.parse_args(argv)
    print(json.dumps(measures(args.result, args.reference), indent=2))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
