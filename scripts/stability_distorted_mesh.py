#!/usr/bin/python3
"""Stability on distorted meshes (docs/stability.md, "Distorted meshes"): runs the plate
impact (input/plate_impact.yaml, two plates, contact) and its one-plate reference
(input/plate_impact_reference.yaml) with the interior nodes of each plate moved at random
by at most a fraction of h (parts[i].perturbation), for each element
formulation, and prints a Markdown table of how the result degrades.

    /usr/bin/python3 scripts/stability_distorted_mesh.py [--exdyn build/release/src/app/exdyn]
        [--fractions 0,0.1,0.2,0.3] [--formulations hex8,hex8r] [--seeds 1,2] [--keep DIR]

plate_a is perturbed with the first seed in both runs (the same mesh), plate_b with the
second. Columns (stress measures as fractions of the sigma_x plateau, docs/results.md):
- steps: the stable step follows the shortest element, so a distorted mesh takes more;
- min det J / det J0: the smallest corner Jacobian of the distorted elements, as a
  fraction of the regular element's;
- plateau error, profile error, contact - reference (worst of the two plates): from
  scripts/plate_measures.py; "plate_a": contact - reference for plate_a alone, meshed
  alike in both runs, so the difference is the contact's alone;
- reference sigma_x* change: the one-plate reference's sigma_x* against its value on
  the regular mesh, element by element (rms and largest): the noise the distortion adds;
- max penetration / h and the energy error (max relative): from NAME.json.
plate_measures.py locates elements by their centroids on the regular grid, so each
result is measured on a copy whose /mesh/coordinates are those of the regular mesh
(fraction 0 is always run): each element is measured as its grid cell. A fraction whose
draw inverts an element is refused by exdyn (exit 2; docs/input.md) and shown as such.
Needs Debian's python3-numpy and python3-h5py.
Exit status: 0 every case ran to the end, 1 some case was refused or failed, 2 bad usage.
"""

import argparse
import datetime
import json
import os
import platform
import shutil
import subprocess
import sys
import tempfile

import h5py
import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import plate_measures as pm  # noqa: E402  (its constants and per-plate measures)

REPO = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
CONTACT_DECK = os.path.join(REPO, "input", "plate_impact.yaml")
REFERENCE_DECK = os.path.join(REPO, "input", "plate_impact_reference.yaml")
MEASURES_SCRIPT = os.path.join(REPO, "scripts", "plate_measures.py")

# VTK hexahedron: the neighbours of each corner along +xi, +eta, +zeta, and the sign
# that orients the three edges that way (as element_block.hpp's inversion check).
CORNER_NEIGHBOURS = np.array([[1, 3, 4], [0, 2, 5], [3, 1, 6], [2, 0, 7],
                              [5, 7, 0], [4, 6, 1], [7, 5, 2], [6, 4, 3]])
CORNER_ORIENTATION = np.array([1.0, -1.0, 1.0, -1.0, -1.0, 1.0, -1.0, 1.0])


def corner_jacobians(coordinates, connectivity):
    """det[e_xi, e_eta, e_zeta] at the 8 corners of every element, (elements, 8), m^3."""
    x = coordinates[connectivity]                                   # (elements, 8, 3)
    a = x[:, CORNER_NEIGHBOURS[:, 0]] - x
    b = x[:, CORNER_NEIGHBOURS[:, 1]] - x
    c = x[:, CORNER_NEIGHBOURS[:, 2]] - x
    return CORNER_ORIENTATION * np.einsum("eci,eci->ec", a, np.cross(b, c))


def smallest_relative_jacobian(result, regular):
    """min over elements and corners of det J / det J of the same element unperturbed."""
    with h5py.File(result, "r") as f, h5py.File(regular, "r") as g:
        conn = f["/mesh/connectivity"][...]
        distorted = corner_jacobians(f["/mesh/coordinates"][...], conn)
        undistorted = corner_jacobians(g["/mesh/coordinates"][...], conn)
    return float(np.min(distorted / undistorted))


def on_the_grid(result, regular, copy):
    """A copy of result whose mesh coordinates are those of the regular grid."""
    shutil.copyfile(result, copy)
    with h5py.File(regular, "r") as g:
        grid = g["/mesh/coordinates"][...]
    with h5py.File(copy, "r+") as f:
        f["/mesh/coordinates"][...] = grid
    return copy


def run_exdyn(exdyn, deck, out, settings, threads):
    """Runs one deck; returns (exit status, the last line of its output)."""
    command = [exdyn, "run", deck, "--quiet", "--output", out]
    for setting in settings:
        command += ["--set", setting]
    if threads:
        command += ["--threads", str(threads)]
    done = subprocess.run(command, capture_output=True, text=True, check=False)
    text = (done.stdout + done.stderr).strip()
    return done.returncode, text.splitlines()[-1] if text else ""


def run_case(args, work, formulation, fraction):
    """Both runs of one (formulation, fraction); a dict of what the table shows."""
    seed_a, seed_b = args.seeds
    tag = f"{formulation}-{fraction:g}"
    common = [f"parts[0].formulation={formulation}",
              f"parts[0].perturbation={{fraction: {fraction!r}, seed: {seed_a}}}"]
    contact_settings = common + [f"parts[1].formulation={formulation}",
                                 f"parts[1].perturbation={{fraction: {fraction!r}, seed: {seed_b}}}"]
    case = {"formulation": formulation, "fraction": fraction, "status": "completed",
            "reference_dir": os.path.join(work, tag, "reference"),
            "contact_dir": os.path.join(work, tag, "contact")}
    for kind, deck, settings in (("reference", REFERENCE_DECK, common), ("contact", CONTACT_DECK, contact_settings)):
        status, last_line = run_exdyn(args.exdyn, deck, case[f"{kind}_dir"], settings, args.threads)
        if status != 0:
            print(f"{tag} {kind}: exit {status}: {last_line}", file=sys.stderr)
            if status == 2 and "the distortion inverts" in last_line:  # the mesh's own check (mesh.cpp)
                detail = last_line[last_line.index("the distortion inverts"):].split(":")[0]
                case["status"] = f"refused (exit 2): {detail}"
            else:
                case["status"] = f"{'refused' if status == 2 else 'failed'} ({kind}, exit {status}): {last_line}"
            return case
    with open(os.path.join(case["contact_dir"], "plate_impact.json")) as f:
        summary = json.load(f)
    case["steps"] = summary["steps"]
    case["dt"] = summary["dt"]
    case["wall_seconds"] = summary["wall_seconds"]
    case["energy_error"] = summary["energy"]["max_relative_error"]
    case["max_penetration_over_h"] = summary["contact"]["max_penetration_over_h"]
    return case


def measure(case, regular):
    """Adds plate_measures.py's measures (on grid copies), the same measure of contact -
    reference for plate_a alone (the plate meshed alike in both runs), how far the
    reference plate's sigma_x* moves from its value on the regular mesh, and the
    smallest Jacobian."""
    contact_h5 = os.path.join(case["contact_dir"], "plate_impact.h5")
    reference_h5 = os.path.join(case["reference_dir"], "plate_impact_reference.h5")
    case["min_jacobian"] = smallest_relative_jacobian(contact_h5, regular["contact"])
    contact_grid = on_the_grid(contact_h5, regular["contact"], contact_h5 + ".grid.h5")
    reference_grid = on_the_grid(reference_h5, regular["reference"], reference_h5 + ".grid.h5")
    done = subprocess.run([sys.executable, MEASURES_SCRIPT, contact_grid, "--reference", reference_grid],
                          capture_output=True, text=True, check=True)
    case.update(json.loads(done.stdout))
    contact_plates, _ = pm.read_result(contact_grid)
    reference_plate = pm.read_result(reference_grid)[0][0]
    case["plate_a_vs_reference_row"], case["plate_a_vs_reference_all"] = pm.contact_vs_reference(
        contact_plates[:1], reference_plate)
    regular_plate = pm.read_result(regular["reference"])[0][0]
    change = np.abs(reference_plate.stress[:, :, pm.XX] - regular_plate.stress[:, :, pm.XX]) / abs(pm.PLATEAU_X)
    case["mesh_change_rms"] = float(np.sqrt(np.mean(change ** 2)))
    case["mesh_change_max"] = float(change.max())


def percent(value, digits=2):
    return f"{100 * value:.{digits}f} %"


COLUMNS = [
    "formulation", "fraction", "steps", "min det J / det J0", "plateau error", "profile error",
    "contact - reference, z = 0 row: worst plate / plate_a", "contact - reference, all: worst plate / plate_a",
    "reference sigma_x* change from the regular mesh: rms / max", "max penetration / h", "energy error"]


def table(cases):
    """The Markdown table; every stress measure is a fraction of the sigma_x plateau."""
    lines = ["| " + " | ".join(COLUMNS) + " |", "|" + "---|" * len(COLUMNS)]
    for c in cases:
        head = f"| {c['formulation']} | {c['fraction']:g} |"
        if c["status"] != "completed":
            lines.append(head + f" {c['status']} |" + " |" * (len(COLUMNS) - 3))
            continue
        lines.append(head + f" {c['steps']} | {c['min_jacobian']:.3f} | {percent(c['plateau_error'])} "
                     f"| {percent(c['profile_error'])} "
                     f"| {percent(c['contact_vs_reference_row'])} / {percent(c['plate_a_vs_reference_row'])} "
                     f"| {percent(c['contact_vs_reference_all'])} / {percent(c['plate_a_vs_reference_all'])} "
                     f"| {percent(c['mesh_change_rms'])} / {percent(c['mesh_change_max'])} "
                     f"| {c['max_penetration_over_h']:.2e} | {c['energy_error']:.1e} |")
    return "\n".join(lines)


def machine():
    model = platform.machine()
    try:
        with open("/proc/cpuinfo") as f:
            model = next(line.split(":", 1)[1].strip() for line in f if line.startswith("model name"))
    except (OSError, StopIteration):
        pass
    return f"{platform.node()} ({model}, {os.cpu_count()} cores)"


def number_list(text, kind):
    try:
        return [kind(item) for item in text.split(",") if item.strip()]
    except ValueError:
        raise argparse.ArgumentTypeError(f"expected a comma-separated list, got '{text}'")


def main(argv):
    parser = argparse.ArgumentParser(description="the plate impact on randomly distorted meshes")
    parser.add_argument("--exdyn", default=os.path.join(REPO, "build", "release", "src", "app", "exdyn"),
                        help="the exdyn executable (default: build/release/src/app/exdyn)")
    parser.add_argument("--fractions", type=lambda t: number_list(t, float), default=[0.0, 0.1, 0.2, 0.3],
                        help="perturbation fractions of h (default 0,0.1,0.2,0.3; 0 is always run)")
    parser.add_argument("--formulations", type=lambda t: number_list(t, str), default=["hex8", "hex8r"])
    parser.add_argument("--seeds", type=lambda t: number_list(t, int), default=[1, 2],
                        help="the seeds of plate_a and plate_b (default 1,2)")
    parser.add_argument("--threads", type=int, default=0, help="passed to exdyn run --threads")
    parser.add_argument("--keep", help="write the runs here and keep them (default: a temporary directory)")
    args = parser.parse_args(argv)
    if len(args.seeds) != 2:
        parser.error("--seeds takes two seeds: plate_a's and plate_b's")
    if not os.access(args.exdyn, os.X_OK):
        parser.error(f"no exdyn executable at {args.exdyn} (give --exdyn)")
    fractions = sorted(set([0.0] + args.fractions))

    work = args.keep or tempfile.mkdtemp(prefix="exdyn-distorted-")
    os.makedirs(work, exist_ok=True)
    cases = []
    try:
        for formulation in args.formulations:
            regular = None
            for fraction in fractions:
                case = run_case(args, work, formulation, fraction)
                if case["status"] == "completed" and fraction == 0.0:  # fractions are sorted: 0 comes first
                    regular = {"contact": os.path.join(case["contact_dir"], "plate_impact.h5"),
                               "reference": os.path.join(case["reference_dir"], "plate_impact_reference.h5")}
                if case["status"] == "completed":
                    if regular is None:
                        case["status"] = "not measured: the unperturbed run failed"
                    else:
                        measure(case, regular)
                cases.append(case)
    finally:
        if not args.keep:
            shutil.rmtree(work, ignore_errors=True)

    print(f"input/plate_impact.yaml and input/plate_impact_reference.yaml, seeds {args.seeds[0]} (plate_a) "
          f"and {args.seeds[1]} (plate_b); {datetime.date.today().isoformat()}, {machine()}; {args.exdyn}\n")
    print(table(cases))
    return 0 if all(c["status"] == "completed" for c in cases) else 1


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
