#!/usr/bin/python3
"""The Taylor impact study: input/taylor_bar.yaml (a quarter copper rod on a rigid wall
at 227 m/s) on three meshes for each formulation, against the range the codes and
papers report (../shared/reference/large-deformation-and-friction.md, section 2).

    /usr/bin/python3 scripts/taylor_study.py [--jobs 2] [--exdyn PATH] [--out results/taylor]
        [--docs docs] [--cases hex8,hex8r,hex8r_fb,hex20r,hex8_plain] [--check]

Cases, each one `exdyn run` with --set overrides of the deck:
  hex8        F-bar (the deck), meshes [4,2,27] (324 bricks), [8,4,54] (2,592: the deck
              and CalculiX's mesh), [12,6,81] (8,748);
  hex8r       one point at its default hourglass control (assumed strain, perfectly
              plastic modes: docs/theory.md, "One point with hourglass stiffness"),
              the same meshes;
  hex8r_fb    one point, Flanagan-Belytschko hourglass stiffness 0.01, the same meshes;
  hex20r      20-node, 2 x 2 x 2 points, [2,2,14], [4,2,27], [6,3,40];
  hex8_plain  the 2 x 2 x 2 brick without F-bar on the deck's mesh (the locking).
Measured from the last step: the final length (the highest node), the mushroom radius
(the largest radius of the impact face's nodes), the largest element-mean equivalent
plastic strain, the energy error (|E_total(end) - E_total(0)| / K_0), the hourglass
energy over the internal energy, steps, the smallest step and the wall time. Writes
OUT/taylor.csv and the table between the `<!-- taylor_table -->` markers of
DOCS/verification.md. A case already run (its summary exists, also a failed one) is not run
again. --check exits 1 unless every F-bar, hex8r, hex8r_fb and hex20r case lies in
the range (length 21.3-21.7 mm, radius 6.9-7.2 mm, plastic strain 2.5-3.3), except the
coarsest hex8r_fb mesh, which the table shows outside it.
"""

import argparse
import concurrent.futures
import csv
import json
import os
import subprocess
import sys

import h5py
import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.dirname(HERE)
DECK = os.path.join(REPO, "input", "taylor_bar.yaml")
RANGE = {"length": (21.3, 21.7), "radius": (6.9, 7.2), "eps_p": (2.5, 3.3)}
CASES = {
    "hex8": [("hex8", m, []) for m in ([4, 2, 27], [8, 4, 54], [12, 6, 81])],
    "hex8r": [("hex8r", m, []) for m in ([4, 2, 27], [8, 4, 54], [12, 6, 81])],
    "hex8r_fb": [("hex8r", m, ["parts[0].hourglass.coefficient=0.01"]) for m in ([4, 2, 27], [8, 4, 54], [12, 6, 81])],
    "hex20r": [("hex20r", m, []) for m in ([2, 2, 14], [4, 2, 27], [6, 3, 40])],
    "hex8_plain": [("hex8", [8, 4, 54], ["parts[0].f_bar=false"])],
}


def case_name(kind, formulation, mesh):
    return "%s_%s" % (kind, "x".join(str(n) for n in mesh))


def run_case(exdyn, out, kind, formulation, mesh, extra):
    name = case_name(kind, formulation, mesh)
    directory = os.path.join(out, name)
    summary_path = os.path.join(directory, "taylor_bar.json")
    if os.path.exists(summary_path):  # run before (a failed run's file says why)
        return name, directory
    sets = ["parts[0].formulation=" + formulation, "parts[0].elements=[%d,%d,%d]" % tuple(mesh),
            "output.every=1000000"] + extra
    command = [exdyn, "run", DECK, "--output", directory, "--quiet", "--threads", "1"]
    for s in sets:
        command += ["--set", s]
    subprocess.run(command, check=False, stderr=subprocess.DEVNULL)
    return name, directory


def measure(directory):
    summary = json.load(open(os.path.join(directory, "taylor_bar.json")))
    with h5py.File(os.path.join(directory, "taylor_bar.h5"), "r") as f:
        x0 = f["mesh/coordinates"][:]
        last = sorted(f["steps"].keys())[-1]
        x = x0 + f["steps"][last]["displacement"][:]
        eps = f["steps"][last]["plastic_strain"][:]
        h = f["history"]
        kinetic0 = h["kinetic_energy"][0]
        total = h["total_energy"][:]
        internal = h["internal_energy"][-1]
        hourglass = h["hourglass_energy"][-1]
    face = np.abs(x0[:, 2]) < 1e-12
    return {
        "status": summary["status"],
        "length": 1e3 * x[:, 2].max(),
        "radius": 1e3 * np.hypot(x[face, 0], x[face, 1]).max(),
        "eps_p": float(eps.max()),
        "energy_error": abs(total[-1] - total[0]) / kinetic0,
        "hourglass_share": hourglass / internal if internal > 0 else 0.0,
        "elements": summary["mesh"]["elements"],
        "steps": summary["steps"],
        "dt_min": summary.get("dt_min", summary["dt"]),
        "wall": summary["wall_seconds"],
    }


def write_between_markers(path, name, text):
    """Replaces what stands between `<!-- NAME -->` and `<!-- /NAME -->` in the file."""
    document = open(path).read()
    begin, end = "<!-- %s -->" % name, "<!-- /%s -->" % name
    i, j = document.index(begin) + len(begin), document.index(end)
    open(path, "w").write(document[:i] + "\n" + text + "\n" + document[j:])


def in_range(row):
    return all(RANGE[k][0] <= row[k] <= RANGE[k][1] for k in RANGE)


def main(argv):
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--jobs", type=int, default=2)
    parser.add_argument("--exdyn", default=os.path.join(REPO, "build", "release", "src", "app", "exdyn"))
    parser.add_argument("--out", default=os.path.join("results", "taylor"))
    parser.add_argument("--docs", default=None, help="write the table into DOCS/verification.md")
    parser.add_argument("--cases", default=",".join(CASES))
    parser.add_argument("--check", action="store_true")
    args = parser.parse_args(argv)
    jobs = []
    for kind in args.cases.split(","):
        for formulation, mesh, extra in CASES[kind]:
            jobs.append((kind, formulation, mesh, extra))
    rows = []
    with concurrent.futures.ThreadPoolExecutor(max_workers=args.jobs) as pool:
        futures = [pool.submit(run_case, args.exdyn, args.out, *job) for job in jobs]
        for job, future in zip(jobs, futures):
            name, directory = future.result()
            row = {"case": name, "kind": job[0], "mesh": "[%d, %d, %d]" % tuple(job[2])}
            row.update(measure(directory))
            rows.append(row)
    os.makedirs(args.out, exist_ok=True)
    with open(os.path.join(args.out, "taylor.csv"), "w", newline="") as f:
        writer = csv.DictWriter(f, fieldnames=list(rows[0].keys()))
        writer.writeheader()
        writer.writerows(rows)
    header = ("| case | mesh | bricks | run | final length, mm | mushroom radius, mm | largest eps_p "
              "| energy error / K0 | hourglass / internal | steps | smallest dt, s | wall, s |")
    lines = [header, "|" + "---|" * 12]
    for r in rows:
        lines.append("| %s | %s | %d | %s | %.2f | %.2f | %.2f | %.2e | %.2f %% | %d | %.3g | %.1f |" % (
            r["kind"], r["mesh"], r["elements"], r["status"], r["length"], r["radius"], r["eps_p"],
            r["energy_error"], 100 * r["hourglass_share"], r["steps"], r["dt_min"], r["wall"]))
    table = "\n".join(lines)
    print(table)
    if args.docs:
        write_between_markers(os.path.join(args.docs, "verification.md"), "taylor_table", table)
    if args.check:
        bad = [r["case"] for r in rows if r["kind"] in ("hex8", "hex8r", "hex8r_fb", "hex20r") and not in_range(r)
               and not (r["kind"] == "hex8r_fb" and r["elements"] < 500)]
        bad += [r["case"] for r in rows if r["status"] != "completed" or r["energy_error"] > 0.01
                or r["hourglass_share"] > 0.05]
        if bad:
            print("taylor_study: outside the range or failed:", ", ".join(bad))
            return 1
        print("taylor_study: every case in the literature range")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
