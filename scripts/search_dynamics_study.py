#!/usr/bin/python3
"""The local search study inside dynamics: every method and initial guess on
curved 8-node segments in real runs, the runs where methods fail, and the chart of
accuracy against cost over methods, meshes, formulations and slave points.

    /usr/bin/python3 scripts/search_dynamics_study.py [--jobs 2] [--exdyn PATH]
        [--out results/search_dynamics] [--docs docs] [--hertz-levels coarse,medium,fine]

One command does it all:
1. methods: input/hertz_ball.yaml on its coarse mesh (ball [8, 2], block [6, 6, 5],
   hex20, slave quadrature points), input/cylinders.yaml on its coarse mesh
   (n_around 32), and two plastic scenes of large deformation: input/taylor_rods.yaml
   (the rods' feet mushroom, slave Gauss points slide outward over distorting segments) and
   scripts/decks/ball_dent.yaml (a steel ball's nodes slide over the crater it presses
   into a copper plate); each with every method (newton, lsp, steepest_descent, broyden,
   bfgs, dfp, simplex, hybrid, robust) and initial guess (lsp, center, previous):
   108 runs. From each run's summary (contact.pairs.NAME): projections, mean and largest
   iterations, not converged, saddles, the local search's wall time; from its result:
   F_max and the contact time, and how far they and the stress field (largest
   difference over the written steps, relative to the largest stress) move from the
   robust method's run with the same guess (the plastic scenes: also the final shape,
   relative to the model's size, and the plastic strain);
2. failures: the same methods and guesses where the projection is hard: the cylinders
   at n_around 4 (a quarter circle in four 8-node segments, 22.5 degrees each) meeting
   at +-100 m/s with a soft penalty (scale 0.05), so slave points sink two thirds of an
   element deep into strongly curved master segments (the penetration guard is lifted);
3. the Hertz grid (scripts/hertz_study.py: three meshes, hex8 and hex20, slave nodes
   and quadrature points, BFGS): run or resumed here.
Writes OUT/methods.csv and the tables between the `<!-- batch:dyn_* -->` markers of
DOCS/local-search.md, and the Pareto chart DOCS/figures/results_hertz_pareto.png with
its table in DOCS/results.md (`<!-- batch:hertz_pareto -->`): error against Hertz
(the larger of the F_max and contact time errors) against wall time, every run of
steps 1 and 3 on the ball, the non-dominated ones joined; and for the plastic scenes
the chart DOCS/figures/results_plastic_pareto.png with its fronts in DOCS/local-search.md
(`<!-- batch:plastic_pareto -->`): the final shape's distance from robust's against wall
time (also with --no-hertz). A case whose summary says
`completed` is not run again.
"""

import argparse
import concurrent.futures
import csv
import os
import sys

import h5py
import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.dirname(HERE)
sys.path.insert(0, HERE)
import batch_plate_impact as batch  # noqa: E402
import hertz_study  # noqa: E402

METHODS = ["newton", "lsp", "steepest_descent", "broyden", "bfgs", "dfp", "simplex", "hybrid", "robust"]
GUESSES = ["lsp", "center", "previous"]
BALL_COARSE = ["parts[0].elements=[8, 2]", "parts[1].elements=[6, 6, 5]"]
SCENES = {
    # name: (deck, pair, force factor (quarter or half model), --set overrides)
    "ball": ("hertz_ball.yaml", "impact", 4.0, BALL_COARSE),
    "cylinders": ("cylinders.yaml", "line", 2.0,
                  ["parts[0].elements=[32, 8, 1]", "parts[1].elements=[32, 8, 1]"]),
    "hard_cylinders": ("cylinders.yaml", "line", 2.0,
                       ["parts[0].elements=[4, 2, 1]", "parts[1].elements=[4, 2, 1]",
                        "parts[0].initial_velocity=[0, 0, -100]", "parts[1].initial_velocity=[0, 0, 100]",
                        "contact[0].penalty={scale: 0.05}", "time.end_time=1.5e-5",
                        "guards.max_penetration=10.0"]),
    # Large deformation: the two Taylor rods through contact, their slave Gauss points sliding
    # outward over expanding, distorting master segments (the last step's shape and
    # plastic strain are compared with the robust run's too).
    "taylor_rods": ("taylor_rods.yaml", "impact", 4.0,
                    ["output.fields=[stress, displacement, plastic_strain]", "output.every=100000"]),
    # A steel ball denting a copper plate: the ball's nodes slide over the crater's
    # stretching, tilting segments.
    "ball_dent": ("scripts/decks/ball_dent.yaml", "dent", 4.0,
                  ["output.fields=[stress, displacement, plastic_strain]", "output.every=100000"]),
}
PLASTIC = {"taylor_rods", "ball_dent"}  # the last step's shape and plastic strain compared too


class Case:
    def __init__(self, scene, method, guess, out):
        self.scene, self.method, self.guess = scene, method, guess
        self.deck, self.pair, self.factor, self.sets = SCENES[scene]
        self.name = f"{scene}_{method}_{guess}"
        self.dir = os.path.join(out, "cases", self.name)
        self.stem = os.path.splitext(os.path.basename(self.deck))[0]

    def summary(self):
        return hertz_study.read_summary(os.path.join(self.dir, self.stem + ".json"))


def run(case, exdyn):
    # The methods bare (no fallback): the study measures each method's own failures.
    sets = [f"contact[0].local_search.method={case.method}", f"contact[0].local_search.initial_guess={case.guess}",
            "contact[0].local_search.fallback=none", "output.every=200", "output.fields=[stress]"] + case.sets
    deck = os.path.join(REPO, case.deck) if "/" in case.deck else os.path.join(REPO, "input", case.deck)
    return hertz_study.run_deck(exdyn, deck, case.dir, sets,
                                os.path.join(case.dir, case.stem + ".json"))


def history(case):
    with h5py.File(os.path.join(case.dir, case.stem + ".h5"), "r") as f:
        t = f["history/time"][...]
        force = case.factor * np.abs(f[f"history/contact/{case.pair}/force"][...][:, 2])
        stress = {k: f["steps"][k]["stress"][...] for k in f["steps"]}
    peak = force.max()
    on = np.where(force > 1e-3 * peak)[0] if peak > 0 else np.array([0])
    return peak, t[on[-1]] - t[on[0]], stress


def last_shape(case):
    """The last step's displacement and plastic strain, or None where not written."""
    with h5py.File(os.path.join(case.dir, case.stem + ".h5"), "r") as f:
        last = f["steps"][sorted(f["steps"].keys())[-1]]
        if "displacement" not in last:
            return None
        return last["displacement"][...], last["plastic_strain"][...], f["mesh/coordinates"][...]


def row(case, reference):
    s = case.summary() or {}
    pair = (s.get("contact") or {}).get("pairs", {}).get(case.pair, {})
    r = {"scene": case.scene, "method": case.method, "guess": case.guess, "status": s.get("status", "not run"),
         "message": (s.get("message") or "")[:120], "wall_seconds": s.get("wall_seconds", float("nan")),
         "steps": s.get("steps", 0), "projections": pair.get("projections", 0),
         "mean_iterations": pair.get("mean_iterations", float("nan")),
         "max_iterations": pair.get("max_iterations", 0), "not_converged": pair.get("not_converged", 0),
         "saddle_points": pair.get("saddle_points", 0),
         "local_search_seconds": pair.get("local_search_seconds", float("nan")),
         "f_max": float("nan"), "contact_time": float("nan"), "f_max_vs_robust": float("nan"),
         "time_vs_robust": float("nan"), "stress_vs_robust": float("nan"), "shape_vs_robust": float("nan"),
         "plastic_strain_vs_robust": float("nan")}
    if not s or not os.path.exists(os.path.join(case.dir, case.stem + ".h5")):
        return r
    r["f_max"], r["contact_time"], stress = history(case)
    if reference is not None and reference.summary() and reference.summary().get("status") == "completed":
        f0, t0, s0 = history(reference)
        r["f_max_vs_robust"] = r["f_max"] / f0 - 1
        r["time_vs_robust"] = r["contact_time"] / t0 - 1
        common = [k for k in stress if k in s0]
        scale = max(np.abs(s0[k]).max() for k in common)
        r["stress_vs_robust"] = max(np.abs(stress[k] - s0[k]).max() for k in common) / scale
        mine, theirs = last_shape(case), last_shape(reference)
        # Both at end_time (a step that follows the mesh lands on it, in however many steps).
        if mine is not None and theirs is not None and r["status"] == "completed":
            size = np.ptp(theirs[2], axis=0).max()  # the model's largest extent
            r["shape_vs_robust"] = np.abs(mine[0] - theirs[0]).max() / size
            r["plastic_strain_vs_robust"] = np.abs(mine[1] - theirs[1]).max() / max(np.abs(theirs[1]).max(), 1e-300)
    return r


def rel(x):
    return "" if not np.isfinite(x) else ("0" if x == 0 else f"{x:+.1e}")


def methods_table(rows, scene):
    body = []
    for r in rows:
        if r["scene"] != scene:
            continue
        state = "completed" if r["status"] == "completed" else f"**{r['status']}**: {r['message']}"
        body.append([r["method"], r["guess"], r["projections"], f"{r['mean_iterations']:.2f}", r["max_iterations"],
                     r["not_converged"], r["saddle_points"], f"{r['local_search_seconds']:.2f}",
                     f"{r['wall_seconds']:.1f}", f"{r['f_max'] / 1e3:.3f}", rel(r["f_max_vs_robust"]),
                     f"{r['contact_time'] * 1e6:.2f}", rel(r["time_vs_robust"]),
                     "" if not np.isfinite(r["stress_vs_robust"]) else f"{r['stress_vs_robust']:.1e}"]
                    + ([rel(r["shape_vs_robust"]), rel(r["plastic_strain_vs_robust"])] if scene in PLASTIC else [])
                    + [state])
    shape = ["final shape vs robust", "eps_p vs robust"] if scene in PLASTIC else []
    return batch.table(["method", "guess", "projections", "mean it.", "max it.", "not conv.", "saddles",
                        "local search (s)", "wall (s)", "F_max (kN)", "vs robust", "contact (us)", "vs robust",
                        "stress vs robust"] + shape + ["run"], body)


def pareto_front(points):
    """The non-dominated (wall, error, ...) points, cheapest first; equal errors (the same
    answer to round-off) are one point."""
    front, best = [], float("inf")
    for p in sorted(points):
        if p[1] < best * (1.0 - 1e-6):
            front.append(p)
            best = p[1]
    return front


def save_chart(fig, ax, ylabel, title, path):
    """Log-log axes against the wall time, the labels, the legend, and the file."""
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("wall time of the run, one thread (s)")
    ax.set_ylabel(ylabel)
    ax.set_title(title, fontsize=9)
    ax.grid(alpha=0.3, which="both")
    ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(path, dpi=100)


def pareto_chart(method_rows, hertz_rows, docs):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    _, f_exact, t_exact, _, _ = hertz_study.hertz()
    points = []   # (wall, error, label, group)
    for r in method_rows:
        if r["scene"] == "ball" and r["status"] == "completed":
            err = max(abs(r["f_max"] / f_exact - 1), abs(r["contact_time"] / t_exact - 1))
            points.append((r["wall_seconds"], err, f"coarse hex20 quadrature, {r['method']} / {r['guess']}",
                           "methods (coarse hex20, quadrature)"))
    for r in hertz_rows:
        err = max(abs(float(r["f_max_error"])), abs(float(r["contact_time_error"])))
        points.append((float(r["wall_seconds"]), err, f"{r['level']} {r['formulation']} {r['slave_points']}, bfgs",
                       f"{r['formulation']}, slave {r['slave_points']}"))
    front = pareto_front(points)
    fig, ax = plt.subplots(figsize=(8, 5))
    groups = sorted({p[3] for p in points})
    for k, g in enumerate(groups):
        sel = [p for p in points if p[3] == g]
        ax.scatter([p[0] for p in sel], [100 * p[1] for p in sel], s=22, color=f"C{k}", label=g, alpha=0.8)
    ax.plot([p[0] for p in front], [100 * p[1] for p in front], "k-", lw=1, alpha=0.6, label="Pareto front")
    save_chart(fig, ax, "error against Hertz: max(|F_max err.|, |contact time err.|) (%)",
               "Hertz impact: accuracy against cost over methods, meshes, formulations, slave points",
               os.path.join(docs, "figures", "results_hertz_pareto.png"))
    return batch.table(["case", "wall (s)", "error against Hertz"],
                       [[p[2], f"{p[0]:.1f}", f"{100 * p[1]:.2f} %"] for p in front])


def plastic_chart(rows, docs):
    """Wall time against the final shape's distance from robust's (the closest point proven,
    a fraction of the model's extent) for every method and guess of the plastic scenes."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    floor = 1e-17  # robust itself, and runs that end on robust's bits
    fig, ax = plt.subplots(figsize=(8, 5))
    fronts = []
    for k, scene in enumerate(sorted({r["scene"] for r in rows} & PLASTIC)):
        points = sorted((r["wall_seconds"], max(abs(r["shape_vs_robust"]), floor), f"{r['method']} / {r['guess']}")
                        for r in rows if r["scene"] == scene and r["status"] == "completed"
                        and np.isfinite(r["shape_vs_robust"]))
        ax.scatter([p[0] for p in points], [p[1] for p in points], s=22, color=f"C{k}", label=scene, alpha=0.8)
        front = pareto_front(points)
        ax.plot([p[0] for p in front], [p[1] for p in front], "-", color=f"C{k}", lw=1, alpha=0.6)
        fronts += [[scene, p[2], f"{p[0]:.2f}", "0" if p[1] <= floor else f"{p[1]:.1e}"] for p in front]
    save_chart(fig, ax, "final shape's largest distance from robust's / model extent",
               "Plastic scenes: cost against the departure from the proven closest point (lines: fronts)",
               os.path.join(docs, "figures", "results_plastic_pareto.png"))
    return batch.table(["scene", "method / guess", "wall (s)", "final shape vs robust"], fronts)


def main(argv):
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--jobs", type=int, default=os.cpu_count() or 1)
    p.add_argument("--exdyn", default=batch.default_exdyn())
    p.add_argument("--out", default=os.path.join(REPO, "results", "search_dynamics"))
    p.add_argument("--docs", default=os.path.join(REPO, "docs"))
    p.add_argument("--hertz-out", default=os.path.join(REPO, "results", "hertz"))
    p.add_argument("--hertz-levels", default="coarse,medium,fine")
    p.add_argument("--scenes", default=",".join(SCENES))
    p.add_argument("--no-hertz", action="store_true", help="only the method tables (no Hertz grid, no chart)")
    args = p.parse_args(argv)
    scenes = args.scenes.split(",")
    cases = [Case(s, m, g, args.out) for s in scenes for g in GUESSES for m in METHODS]
    with concurrent.futures.ThreadPoolExecutor(max_workers=args.jobs) as pool:
        for case, status in zip(cases, pool.map(lambda c: run(c, args.exdyn), cases)):
            print(f"{case.name}: {status}", flush=True)
    by_name = {c.name: c for c in cases}
    rows = [row(c, by_name.get(f"{c.scene}_robust_{c.guess}")) for c in cases]
    os.makedirs(args.out, exist_ok=True)
    with open(os.path.join(args.out, "methods.csv"), "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0]))
        w.writeheader()
        w.writerows(rows)
    sections = {f"dyn_{s}": methods_table(rows, s) for s in scenes}
    if PLASTIC & set(scenes):
        sections["plastic_pareto"] = plastic_chart(rows, args.docs)
    batch.write_doc(os.path.join(args.docs, "local-search.md"), sections)
    if args.no_hertz:
        return 0

    if hertz_study.main(["--levels", args.hertz_levels, "--jobs", str(args.jobs), "--exdyn", args.exdyn,
                         "--out", args.hertz_out, "--docs", args.docs]) != 0:
        return 1
    with open(os.path.join(args.hertz_out, "hertz.csv")) as f:
        hertz_rows = list(csv.DictReader(f))
    front = pareto_chart(rows, hertz_rows, args.docs)
    batch.write_doc(os.path.join(args.docs, "results.md"), {"hertz_pareto": front})
    print(f"search_dynamics_study: wrote {args.out}/methods.csv, the tables and the Pareto chart")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
