#!/usr/bin/python3
"""The Taylor impact side by side with CalculiX (Debian's calculix-ccx 2.20): the same
quarter-rod mesh of input/taylor_bar.yaml (2,592 bricks), one thread each.

    /usr/bin/python3 scripts/calculix_taylor.py [--exdyn PATH] [--ccx ccx] [--out results/calculix]
        [--increment 4e-9] [--docs docs] [--elements 8,4,54]

exdyn runs the deck twice, hex8r (hourglass coefficient 0.01) and hex8 with F-bar, and
its mesh (/mesh of the result) is written as a CalculiX deck: C3D8R and C3D8 (the VTK
and the Abaqus/CalculiX 8-node orders are the same), the symmetry planes and the wall
as *BOUNDARY, the copper as *ELASTIC, *DENSITY and a two-row *PLASTIC table (linear
hardening, H = 100 MPa), *INITIAL CONDITIONS of velocity, and one *STEP, NLGEOM with
*DYNAMIC, EXPLICIT whose largest increment is capped. ccx 2.20 keeps its first stable
increment (about 1.1e-8 s on this mesh) while the foot crushes, and diverges; the cap is
--increment (default 4e-9 s, about exdyn's smallest step on this mesh). (DIRECT, a fixed
increment, makes ccx 2.20 select an increment of 0.)
From the .dat file's last *NODE PRINT (U) and *EL PRINT (PEEQ) it takes the final
length, the mushroom radius and the largest plastic strain, and prints them beside
exdyn's with the wall time of each (OMP_NUM_THREADS=1 for ccx, --threads 1 for exdyn).
Writes the table between the `<!-- calculix_table -->` markers of DOCS/verification.md.
"""

import argparse
import os
import re
import subprocess
import sys
import time

import h5py
import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.dirname(HERE)
sys.path.insert(0, HERE)
from taylor_study import write_between_markers  # noqa: E402

DECK = os.path.join(REPO, "input", "taylor_bar.yaml")


def run_exdyn(exdyn, out, formulation, elements, extra):
    directory = os.path.join(out, "exdyn_" + formulation)
    command = [exdyn, "run", DECK, "--output", directory, "--quiet", "--threads", "1",
               "--set", "parts[0].formulation=" + formulation, "--set", "parts[0].elements=[%s]" % elements,
               "--set", "output.every=1000000"] + extra
    start = time.monotonic()
    subprocess.run(command, check=True)
    wall = time.monotonic() - start
    with h5py.File(os.path.join(directory, "taylor_bar.h5"), "r") as f:
        x0 = f["mesh/coordinates"][:]
        connectivity = f["mesh/connectivity"][:]
        last = sorted(f["steps"].keys())[-1]
        x = x0 + f["steps"][last]["displacement"][:]
        eps = f["steps"][last]["plastic_strain"][:]
    return x0, connectivity, measure(x0, x) + (float(eps.max()), wall)


def measure(x0, x):
    face = np.abs(x0[:, 2]) < 1e-12
    return 1e3 * x[:, 2].max(), 1e3 * np.hypot(x[face, 0], x[face, 1]).max()


def write_inp(path, x0, connectivity, element_type, increment):
    tol = 1e-12
    increments = int(1.2 * 8.0e-5 / increment) + 10
    lines = ["** The Taylor impact, quarter rod (scripts/calculix_taylor.py)", "*NODE, NSET=NALL"]
    lines += ["%d, %.17g, %.17g, %.17g" % (i + 1, *p) for i, p in enumerate(x0)]
    lines.append("*ELEMENT, TYPE=%s, ELSET=EALL" % element_type)
    lines += ["%d, %s" % (e + 1, ", ".join(str(n + 1) for n in nodes)) for e, nodes in enumerate(connectivity)]

    def node_set(name, mask):
        ids = [str(i + 1) for i in np.nonzero(mask)[0]]
        out = ["*NSET, NSET=%s" % name]
        out += [", ".join(ids[k:k + 16]) for k in range(0, len(ids), 16)]
        return out

    lines += node_set("XSYM", np.abs(x0[:, 0]) < tol)
    lines += node_set("YSYM", np.abs(x0[:, 1]) < tol)
    lines += node_set("WALL", np.abs(x0[:, 2]) < tol)
    lines += [
        "*BOUNDARY", "XSYM, 1", "YSYM, 2", "WALL, 3",
        "*MATERIAL, NAME=COPPER", "*ELASTIC", "1.17e11, 0.35", "*DENSITY", "8930.",
        "*PLASTIC", "4.0e8, 0.", "1.4e9, 10.",  # sigma_y = 400 MPa + 100 MPa eps_p
        "*SOLID SECTION, ELSET=EALL, MATERIAL=COPPER",
        "*INITIAL CONDITIONS, TYPE=VELOCITY", "NALL, 3, -227.",
        # INC: enough for the step (ccx 2.20 sizes memory by it: 1e7 ran for hours).
        "*STEP, NLGEOM, INC=%d" % increments,
        # The fourth entry caps the increment; DIRECT selects an increment of 0 in ccx 2.20.
        "*DYNAMIC, EXPLICIT", "%.6g, 8.0e-5, 1.0e-12, %.6g" % (increment, increment),
        "*NODE PRINT, NSET=NALL, FREQUENCY=%d" % increments, "U",
        "*EL PRINT, ELSET=EALL, FREQUENCY=%d" % increments, "PEEQ",
        "*END STEP",
    ]
    open(path, "w").write("\n".join(lines) + "\n")


def read_dat(path, x0):
    """The last displacement block and the last PEEQ block of a .dat file."""
    text = open(path).read()
    u_blocks = re.split(r"displacements \(vx,vy,vz\) for set NALL and time\s+\S+", text)
    peeq_blocks = re.split(r"equivalent plastic strain \(elem, integ\.pnt\.,pe\)for set EALL and time\s+\S+", text)
    if len(u_blocks) < 2 or len(peeq_blocks) < 2:
        raise RuntimeError("no *NODE PRINT / *EL PRINT output in " + path)
    u = np.zeros_like(x0)
    for line in u_blocks[-1].strip().splitlines():
        parts = line.split()
        if len(parts) != 4:
            break
        u[int(parts[0]) - 1] = [float(v) for v in parts[1:]]
    peeq = []
    for line in peeq_blocks[-1].strip().splitlines():
        parts = line.split()
        if len(parts) != 3:
            break
        peeq.append(float(parts[2]))
    return x0 + u, max(peeq)


def run_ccx(ccx, out, x0, connectivity, element_type, increment):
    job = os.path.join(out, "taylor_" + element_type.lower())
    write_inp(job + ".inp", x0, connectivity, element_type, increment)
    env = dict(os.environ, OMP_NUM_THREADS="1", CCX_NPROC_EQUATION_SOLVER="1")
    start = time.monotonic()
    result = subprocess.run([ccx, "-i", os.path.basename(job)], cwd=out, env=env, capture_output=True, text=True,
                            stdin=subprocess.DEVNULL)
    wall = time.monotonic() - start
    if result.returncode != 0 or "Job finished" not in result.stdout:
        tail = "\n".join(result.stdout.splitlines()[-5:])
        return None, wall, tail
    x, peeq = read_dat(job + ".dat", x0)
    return measure(x0, x) + (peeq, wall), wall, ""


def main(argv):
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--exdyn", default=os.path.join(REPO, "build", "release", "src", "app", "exdyn"))
    parser.add_argument("--ccx", default="ccx")
    parser.add_argument("--out", default=os.path.join("results", "calculix"))
    parser.add_argument("--increment", type=float, default=4e-9)
    parser.add_argument("--elements", default="8,4,54")
    parser.add_argument("--docs", default=None)
    args = parser.parse_args(argv)
    out = os.path.abspath(args.out)
    os.makedirs(out, exist_ok=True)
    rows = []
    x0, connectivity, hex8r = run_exdyn(args.exdyn, out, "hex8r", args.elements,
                                        ["--set", "parts[0].hourglass.coefficient=0.01"])
    rows.append(("exdyn hex8r (hourglass 0.01)",) + hex8r)
    _, _, hex8 = run_exdyn(args.exdyn, out, "hex8", args.elements, [])
    rows.append(("exdyn hex8, F-bar",) + hex8)
    for element_type in ("C3D8R", "C3D8"):
        figures, wall, failure = run_ccx(args.ccx, out, x0, connectivity, element_type, args.increment)
        if figures is None:
            print("ccx %s failed after %.1f s:\n%s" % (element_type, wall, failure))
            continue
        rows.append(("CalculiX %s, increment %.3g s" % (element_type, args.increment),) + figures)
    lines = ["| run | final length, mm | mushroom radius, mm | largest eps_p | wall, s (one thread) |",
             "|---|---|---|---|---|"]
    for name, length, radius, eps, wall in rows:
        lines.append("| %s | %.2f | %.2f | %.2f | %.1f |" % (name, length, radius, eps, wall))
    table = "\n".join(lines)
    print(table)
    by_name = {r[0].split(",")[0].split(" (")[0]: r for r in rows}
    if "CalculiX C3D8R" in by_name:
        print("CalculiX C3D8R / exdyn hex8r wall time: %.1f" % (by_name["CalculiX C3D8R"][4] / hex8r[3]))
    if args.docs:
        write_between_markers(os.path.join(args.docs, "verification.md"), "calculix_table", table)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
