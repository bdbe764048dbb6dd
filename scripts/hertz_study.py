#!/usr/bin/python3
"""The Hertz impact study: input/hertz_ball.yaml over three meshes, 8- and
20-node bricks, slave nodes and slave quadrature points, against Hertz theory.

    /usr/bin/python3 scripts/hertz_study.py [--jobs 2] [--levels coarse,medium,fine]
        [--exdyn PATH] [--out results/hertz] [--docs docs]

Each case is one `exdyn run` of the deck with --set overrides: the ball's
[n_around, n_radius] and the block's [nx, ny, nz] (coarse 8 x 2 on 6 x 6 x 5, medium
16 x 4 on 12 x 12 x 10 (the deck), fine 24 x 6 on 18 x 18 x 15), the formulation of both
parts and the slave points (slave nodes: two passes at penalty scale 1; quadrature
points: the deck's one pass at scale 4). From /history/contact/impact/force (the quarter model's
force on the ball, times 4) it takes the peak force and the contact time (the first to
the last history row with a force above 1e-3 of the peak) and compares them with
Hertz theory with the reduced mass (the deck's comment). Writes OUT/hertz.csv,
DOCS/figures/hertz_force.png (F(t) of the cases over the Hertz curve) and the table
between the `<!-- batch:hertz_table -->` markers of DOCS/verification.md. A case whose
summary says `completed` is not run again. Needs python3-numpy, -h5py, -matplotlib.
"""

import argparse
import concurrent.futures
import csv
import json
import math
import os
import subprocess
import sys

import h5py
import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.dirname(HERE)
sys.path.insert(0, HERE)
import batch_plate_impact as batch  # noqa: E402  (the document writer)

DECK = os.path.join(REPO, "input", "hertz_ball.yaml")
LEVELS = {"coarse": ([8, 2], [6, 6, 5]), "medium": ([16, 4], [12, 12, 10]), "fine": ([24, 6], [18, 18, 15])}
FORMULATIONS = ["hex8", "hex20"]
SLAVE_POINTS = ["nodes", "quadrature"]

# The deck's data.
E, NU, RHO, R, V = 2.1e11, 0.3, 7800.0, 0.01, 10.0
BLOCK_VOLUME = 0.04 * 0.04 * 0.02


def hertz():
    """delta_max (m), F_max (N), contact time (s), and the force history F(t) of Hertz
    theory: m delta'' = -K delta^(3/2), K = 4/3 E* sqrt(R), delta(0) = 0, delta'(0) = v."""
    e_star = E / (2 * (1 - NU * NU))
    ball = RHO * 4 / 3 * math.pi * R ** 3
    block = RHO * BLOCK_VOLUME
    m = ball * block / (ball + block)
    k = 4 / 3 * e_star * math.sqrt(R)
    delta = (15 * m * V * V / (16 * e_star * math.sqrt(R))) ** 0.4
    t_contact = 2.943 * delta / V
    dt = t_contact / 20000
    d, v, t = 0.0, V, 0.0
    times, forces = [0.0], [0.0]
    accel = lambda x: -k * max(x, 0.0) ** 1.5 / m  # noqa: E731
    while True:   # RK4 until the ball leaves
        k1 = (v, accel(d))
        k2 = (v + 0.5 * dt * k1[1], accel(d + 0.5 * dt * k1[0]))
        k3 = (v + 0.5 * dt * k2[1], accel(d + 0.5 * dt * k2[0]))
        k4 = (v + dt * k3[1], accel(d + dt * k3[0]))
        d += dt / 6 * (k1[0] + 2 * k2[0] + 2 * k3[0] + k4[0])
        v += dt / 6 * (k1[1] + 2 * k2[1] + 2 * k3[1] + k4[1])
        t += dt
        if d <= 0.0:
            break
        times.append(t)
        forces.append(k * d ** 1.5)
    return delta, k * delta ** 1.5, t_contact, np.array(times), np.array(forces)


class Case:
    def __init__(self, level, formulation, points, out):
        self.level, self.formulation, self.points = level, formulation, points
        self.name = f"{level}_{formulation}_{points}"
        self.dir = os.path.join(out, "cases", self.name)

    def sets(self):
        ball, block = LEVELS[self.level]
        sets = [f"parts[0].elements={ball}", f"parts[1].elements={block}",
                f"parts[0].formulation={self.formulation}", f"parts[1].formulation={self.formulation}",
                f"contact[0].slave_points={self.points}", "output.every=1000000", "output.fields=[stress]"]
        # Slave nodes: two passes, the automatic penalty at scale 1. In one pass the ball's
        # coarse nodes press on the block's fine corner, whose small masses cap the spring so
        # low that the pole node sinks in and the energy guard stops the run; the deck's
        # scale 4 (for quadrature points) is above the nodes' stable bound.
        return sets + (["contact[0].penalty={scale: 1.0}", "contact[0].two_pass=true"]
                       if self.points == "nodes" else [])

    def summary(self):
        return read_summary(os.path.join(self.dir, "hertz_ball.json"))


def read_summary(path):
    """A run's NAME.json, or None when it is missing or unreadable."""
    try:
        with open(path) as f:
            return json.load(f)
    except (OSError, ValueError):
        return None


def run_deck(exdyn, deck, directory, sets, summary_path):
    """One `exdyn run` of the deck with --set overrides on one thread, unless the
    summary there already says `completed` (a study resumes)."""
    if (read_summary(summary_path) or {}).get("status") == "completed":
        return "skipped"
    os.makedirs(directory, exist_ok=True)
    cmd = [exdyn, "run", deck, "--quiet", "--threads", "1", "--output", directory]
    for s in sets:
        cmd += ["--set", s]
    proc = subprocess.run(cmd, capture_output=True, text=True)
    return "ran" if proc.returncode == 0 else f"exit {proc.returncode}: {proc.stderr.strip()[-300:]}"


def run(case, exdyn):
    return run_deck(exdyn, DECK, case.dir, case.sets(), os.path.join(case.dir, "hertz_ball.json"))


def measure(case):
    with h5py.File(os.path.join(case.dir, "hertz_ball.h5"), "r") as f:
        t = f["history/time"][...]
        force = 4.0 * f["history/contact/impact/force"][...][:, 2]
    peak = force.max()
    on = np.where(force > 1e-3 * peak)[0]
    return t, force, peak, t[on[0]], t[on[-1]]


def main(argv):
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--levels", default="coarse,medium,fine")
    p.add_argument("--jobs", type=int, default=os.cpu_count() or 1)
    p.add_argument("--exdyn", default=batch.default_exdyn())
    p.add_argument("--out", default=os.path.join(REPO, "results", "hertz"))
    p.add_argument("--docs", default=os.path.join(REPO, "docs"))
    args = p.parse_args(argv)
    levels = args.levels.split(",")
    if any(level not in LEVELS for level in levels) or args.jobs < 1:
        print(f"hertz_study: levels among {', '.join(LEVELS)}; --jobs >= 1", file=sys.stderr)
        return 2
    cases = [Case(level, form, points, args.out) for level in levels for form in FORMULATIONS
             for points in SLAVE_POINTS]
    with concurrent.futures.ThreadPoolExecutor(max_workers=args.jobs) as pool:
        for case, status in zip(cases, pool.map(lambda c: run(c, args.exdyn), cases)):
            print(f"{case.name}: {status}", flush=True)
    delta, f_max, t_contact, ht, hf = hertz()
    print(f"Hertz: delta_max {delta * 1e3:.4f} mm, F_max {f_max:.1f} N, contact time {t_contact * 1e6:.2f} us")

    rows, curves, failed = [], {}, []
    for case in cases:
        s = case.summary()
        if not s or s.get("status") != "completed":
            failed.append([f"{case.level}: {LEVELS[case.level][0]} / {LEVELS[case.level][1]}", case.formulation,
                           case.points, (s or {}).get("message", "not run").split(":")[0][:90]])
            continue
        t, force, peak, first, last = measure(case)
        curves[case.name] = (t - first, force)
        c = s["contact"]
        rows.append({"level": case.level, "formulation": case.formulation, "slave_points": case.points,
                     "elements": s["mesh"]["elements"], "steps": s["steps"], "wall_seconds": s["wall_seconds"],
                     "f_max": peak, "f_max_error": peak / f_max - 1, "contact_time": last - first,
                     "contact_time_error": (last - first) / t_contact - 1,
                     "energy_error": s["energy"]["max_relative_error"], "projections": c["projections"],
                     "mean_iterations": c["mean_iterations"], "not_converged": c["not_converged"]})
    os.makedirs(args.out, exist_ok=True)
    with open(os.path.join(args.out, "hertz.csv"), "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0]) if rows else ["level"])
        w.writeheader()
        w.writerows(rows)

    table = batch.table(
        ["mesh (ball / block)", "form.", "slave points", "elements", "steps", "wall (s)", "F_max (kN)",
         "F_max err.", "contact time (us)", "time err.", "energy err.", "mean it."],
        [[f"{r['level']}: {LEVELS[r['level']][0]} / {LEVELS[r['level']][1]}", r["formulation"], r["slave_points"],
          r["elements"], r["steps"], f"{r['wall_seconds']:.1f}", f"{r['f_max'] / 1e3:.2f}",
          f"{100 * r['f_max_error']:+.2f} %", f"{1e6 * r['contact_time']:.2f}",
          f"{100 * r['contact_time_error']:+.2f} %", f"{r['energy_error']:.1e}", f"{r['mean_iterations']:.2f}"]
         for r in rows])
    if failed:
        table += "\n\nRuns that did not complete (the guard's message):\n\n" + batch.table(
            ["mesh (ball / block)", "form.", "slave points", "stopped by"], failed)
    text = (f"Hertz: delta_max {delta * 1e3:.4f} mm, F_max {f_max / 1e3:.2f} kN, contact time "
            f"{t_contact * 1e6:.2f} us. Written by `/usr/bin/python3 scripts/hertz_study.py "
            f"--levels {','.join(levels)}`, one thread per case.\n\n" + table)
    for r in rows:
        print(f"{r['level']:7s} {r['formulation']:6s} {r['slave_points']:10s} F_max {100 * r['f_max_error']:+.2f} % "
              f"time {100 * r['contact_time_error']:+.2f} % wall {r['wall_seconds']:.1f} s")

    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    # Left: the runs that follow Hertz; right: hex20 with slave nodes, whose corner
    # nodes carry no share of a uniform pressure (docs/contact.md) and ring.
    fig, axes = plt.subplots(1, 2, figsize=(11, 4.5))
    colours = {"hex8": "C0", "hex20": "C2"}
    for ax in axes:
        ax.plot(ht * 1e6, hf / 1e3, "k-", lw=2.5, alpha=0.4, label="Hertz")
    for case in cases:
        if case.name in curves and case.level == levels[-1]:
            t, force = curves[case.name]
            ax = axes[1] if (case.formulation, case.points) == ("hex20", "nodes") else axes[0]
            ax.plot(t * 1e6, force / 1e3, "-" if case.points == "quadrature" else "--",
                    color=colours[case.formulation], lw=0.8 if ax is axes[1] else 1.1,
                    label=f"{case.formulation}, slave {case.points}")
    for ax, title in zip(axes, [f"the {levels[-1]} mesh against Hertz",
                                f"hex20 with slave nodes, the {levels[-1]} mesh"]):
        ax.set_xlabel("time from first contact (us)")
        ax.set_ylabel("contact force, whole ball (kN)")
        ax.set_title(f"Hertz impact, R = 10 mm at 10 m/s: {title}", fontsize=9)
        ax.grid(alpha=0.3)
        ax.legend(fontsize=8)
    os.makedirs(os.path.join(args.docs, "figures"), exist_ok=True)
    fig.tight_layout()
    fig.savefig(os.path.join(args.docs, "figures", "hertz_force.png"), dpi=100)
    batch.write_doc(os.path.join(args.docs, "verification.md"), {"hertz_table": text})
    print(f"hertz_study: wrote {os.path.join(args.docs, 'figures', 'hertz_force.png')} and the table")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
