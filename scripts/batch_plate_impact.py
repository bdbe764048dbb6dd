#!/usr/bin/python3
"""Batch study of the plate impact: runs input/plate_impact.yaml (two plates,
contact) and input/plate_impact_reference.yaml (one plate, face held) over a grid of
meshes, element formulations and local search methods, measures each result against
the exact values (scripts/plate_measures.py), and writes the CSV, the charts
(docs/figures/results_*.png) and the tables of docs/results.md.

    /usr/bin/python3 scripts/batch_plate_impact.py                 # the default grid
    /usr/bin/python3 scripts/batch_plate_impact.py --meshes 25,50 --methods bfgs,dfp \\
        --formulations hex8 --out /tmp/b --docs /tmp/b/docs --jobs 2

Grid: --meshes (node intervals per plate side, h = d / mesh: elements per side for
8-node formulations, half as many for 20-node ones, so every formulation of a mesh
has the same node spacing; the y thickness follows so the elements stay cubes),
--formulations (hex8, hex8r, hex20, hex20r), --slave-points (nodes, quadrature),
--methods (or `all`); one reference run per mesh and formulation (no contact, so no
method and no slave points). Cases run in parallel (--jobs, default the
cores), one `exdyn run` process each; a case whose summary JSON exists with status
`completed` is not run again (resume). Writes OUT/cases/CASE/{NAME.h5,NAME.xmf,NAME.json},
OUT/batch.csv (one row per case), DOCS/figures/results_*.png and the generated parts
of DOCS/results.md (between `<!-- batch:KEY -->` markers; the prose outside them is kept).
Needs Debian's python3-numpy, python3-h5py, python3-matplotlib (/usr/bin/python3);
the ParaView pictures need pvpython and xvfb (../shared/tools/paraview/run_pvpython.sh).

--study formulations runs the other study of the page: every formulation (hex8, hex8r,
hex20, hex20r) and both slave points at equal node counts, one method (--figure-method,
bfgs), results in results/formulations; it writes docs/figures/results_formulations.png
and only the `formulations_*` sections of results.md, so the method study's figures stay:

    /usr/bin/python3 scripts/batch_plate_impact.py --study formulations --jobs 1

Exit status: 0 every case completed, 1 some case failed, 2 bad usage.
"""

import argparse
import concurrent.futures
import csv
import datetime
import json
import math
import os
import platform
import re
import shutil
import subprocess
import sys
import time

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import plate_measures as pm  # noqa: E402

REPO = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
CONTACT_DECK = os.path.join(REPO, "input", "plate_impact.yaml")
REFERENCE_DECK = os.path.join(REPO, "input", "plate_impact_reference.yaml")
PVPYTHON_RUNNER = os.path.join(os.path.dirname(REPO), "shared", "tools", "paraview", "run_pvpython.sh")
# Two `xvfb-run -a` started at once can pick the same display: each ParaView run holds
# this lock (flock, util-linux) for its own seconds, so that the tests that render run
# beside each other and lock nothing else.
XVFB_LOCK = os.path.join("/tmp", "exdyn-xvfb.lock")


def pvpython(*args):
    """The command that runs ../shared/tools/paraview/run_pvpython.sh with args, one
    ParaView at a time on the machine."""
    return ["flock", XVFB_LOCK, PVPYTHON_RUNNER, *args]
PICTURES_SCRIPT = os.path.join(REPO, "scripts", "paraview", "plate_pictures.py")

ALL_METHODS = ["newton", "lsp", "steepest_descent", "broyden", "bfgs", "dfp", "simplex", "hybrid", "robust"]
ALL_FORMULATIONS = ["hex8", "hex8r", "hex20", "hex20r"]
DEFAULT_FORMULATIONS = ["hex8", "hex8r"]
ALL_SLAVE_POINTS = ["nodes", "quadrature"]
DEFAULT_MESHES = [25, 50, 100, 200]
FORMULATION_MESHES = [20, 50, 100, 200]
FIGURE_MESH = 100          # the paper's mesh: Fig. 8, Fig. 9 and the ParaView pictures
FIGURE_METHOD = "bfgs"     # the deck's method
PHASES = ["element_forces", "contact_global_search", "contact_local_search", "contact_forces",
          "time_integration", "output"]
CONTACT_PHASES = ["contact_global_search", "contact_local_search", "contact_forces"]
MEASURES = ["plateau_mean", "plateau_error", "front_over_h", "front_over_d", "front_error_over_h",
            "profile_error", "sigma_z_mean_error", "sigma_z_max_error", "contact_vs_reference_row",
            "contact_vs_reference_all", "mirror_symmetry"]
COLUMNS = (["case", "kind", "mesh", "h", "formulation", "slave_points", "method", "status", "elements", "steps", "dt",
            "wall_seconds", "process_seconds", "element_cycles_per_second", "energy_max_relative_error",
            "contact_projections", "contact_mean_iterations", "contact_max_iterations",
            "contact_not_converged", "contact_saddle_points", "contact_max_penetration_over_h",
            "contact_penalty_stiffness"]
           + ["phase_" + p for p in PHASES] + ["contact_share"] + MEASURES)


def log(msg):
    print(msg, flush=True)


# =============================================================================
# The grid


class Case:
    def __init__(self, kind, mesh, formulation, method, out_root, pictures=False, slave_points="nodes"):
        self.kind, self.mesh, self.formulation, self.method = kind, mesh, formulation, method
        self.slave_points = slave_points if kind == "contact" else ""
        self.pictures = pictures    # writes every field at 8 steps, for ParaView
        # The default slave points keep the names of the cases run before the axis existed.
        points = "" if self.slave_points in ("", "nodes") else "_" + self.slave_points
        self.name = (f"contact_{formulation}_n{mesh}_{method}{points}" if kind == "contact"
                     else f"reference_{formulation}_n{mesh}")
        self.dir = os.path.join(out_root, "cases", self.name)
        self.deck = CONTACT_DECK if kind == "contact" else REFERENCE_DECK
        self.run_name = "plate_impact" if kind == "contact" else "plate_impact_reference"
        self.h = pm.D / mesh

    @property
    def json_path(self):
        return os.path.join(self.dir, self.run_name + ".json")

    @property
    def h5_path(self):
        return os.path.join(self.dir, self.run_name + ".h5")

    @property
    def xmf_path(self):
        return os.path.join(self.dir, self.run_name + ".xmf")

    def settings(self):
        """The --set values: the deck values this case varies."""
        n, h, d = self.mesh, self.h, pm.D
        if self.formulation.startswith("hex20"):   # elements of 2h: nodes every h
            if n % 2:
                raise ValueError(f"mesh {n}: a 20-node mesh needs an even number of node intervals")
            n, h = n // 2, 2 * h
        sets = [f"parts[0].elements=[{n},1,{n}]",
                f"parts[0].box={{min: [{-d!r}, 0, 0], max: [0, {h!r}, {d!r}]}}",
                f"parts[0].formulation={self.formulation}"]
        if self.kind == "contact":
            sets += [f"parts[1].elements=[{n},1,{n}]",
                     f"parts[1].box={{min: [0, 0, 0], max: [{d!r}, {h!r}, {d!r}]}}",
                     f"parts[1].formulation={self.formulation}",
                     f"contact[0].local_search.method={self.method}", "contact[0].local_search.fallback=none",
                     f"contact[0].slave_points={self.slave_points}"]
        if self.pictures:
            every = max(1, round(64 * n / 100))       # 8 outputs over the run (448 steps at n = 100)
            fields = ("[displacement, velocity, stress, von_mises, contact_force, gap]" if self.kind == "contact"
                      else "[displacement, velocity, stress, von_mises]")
        else:
            every, fields = 100000, "[stress]"          # the last step only: all the measures need
        sets += [f"output.every={every}", f"output.fields={fields}"]
        return sets

    def summary(self):
        try:
            with open(self.json_path) as f:
                return json.load(f)
        except (OSError, ValueError):
            return None

    def done(self):
        s = self.summary()
        return s is not None and s.get("status") == "completed" and os.path.exists(self.h5_path)


def build_grid(args):
    cases = []
    for n in args.meshes:
        for form in args.formulations:
            cases.append(Case("reference", n, form, "", args.out))
            for m in args.methods:
                for points in args.slave_points:
                    pictures = (getattr(args, "study", "methods") == "methods"
                                and n == args.figure_mesh and form == args.formulations[0]
                                and m == args.figure_method and points == args.slave_points[0])
                    cases.append(Case("contact", n, form, m, args.out, pictures, points))
    return cases


# =============================================================================
# Running


def run_case(case, exdyn):
    os.makedirs(case.dir, exist_ok=True)
    cmd = [exdyn, "run", case.deck, "--output", case.dir, "--quiet", "--threads", "1"]
    for s in case.settings():
        cmd += ["--set", s]
    with open(os.path.join(case.dir, "command.txt"), "w") as f:
        f.write(" ".join(_quote(c) for c in cmd) + "\n")
    t0 = time.perf_counter()
    proc = subprocess.run(cmd, capture_output=True, text=True)
    seconds = time.perf_counter() - t0
    with open(os.path.join(case.dir, "process.json"), "w") as f:
        json.dump({"returncode": proc.returncode, "process_seconds": seconds,
                   "stderr": proc.stderr[-4000:], "stdout": proc.stdout[-4000:]}, f, indent=1)
    return proc.returncode, seconds, proc.stderr.strip()


def _quote(s):
    return s if re.fullmatch(r"[\w./=,\[\]:-]+", s) else "'" + s.replace("'", "'\\''") + "'"


def run_grid(cases, args):
    todo = [c for c in cases if not c.done()]
    skipped = len(cases) - len(todo)
    log(f"batch: {len(cases)} cases, {skipped} already done, {len(todo)} to run on {args.jobs} job(s)")
    failures = 0
    load_start = os.getloadavg()[0]
    t0 = time.perf_counter()
    with concurrent.futures.ThreadPoolExecutor(max_workers=args.jobs) as pool:
        futures = {pool.submit(run_case, c, args.exdyn): c for c in todo}
        for i, fut in enumerate(concurrent.futures.as_completed(futures), 1):
            c = futures[fut]
            rc, seconds, err = fut.result()
            s = c.summary() or {}
            status = s.get("status", "no summary")
            if rc != 0 or status != "completed":
                failures += 1
                log(f"[{i}/{len(todo)}] {c.name}: FAILED (exit {rc}, {status}) {err[-300:]}")
            else:
                log(f"[{i}/{len(todo)}] {c.name}: {seconds:.1f} s (exdyn wall {s['wall_seconds']:.2f} s, "
                    f"{s['element_cycles_per_second'] / 1e6:.2f} M element-cycles/s)")
    total = time.perf_counter() - t0
    log(f"batch: ran {len(todo)} cases, skipped {skipped}, {failures} failed, {total:.1f} s")
    if todo:   # the invocations that ran cases, for the document
        with open(os.path.join(args.out, "invocations.jsonl"), "a") as f:
            f.write(json.dumps({"finished": datetime.datetime.now(datetime.timezone.utc).strftime("%Y-%m-%d %H:%M UTC"),
                                "command": args.command, "jobs": args.jobs, "ran": len(todo), "skipped": skipped,
                                "failed": failures, "seconds": round(total, 1), "exdyn": args.exdyn_label,
                                "repository": git_commit(),
                                "load_average": [round(load_start, 2), round(os.getloadavg()[0], 2)]}) + "\n")
    return len(todo), skipped, failures, total


# =============================================================================
# Rows


def case_row(case, reference):
    row = {k: "" for k in COLUMNS}
    row.update(case=case.name, kind=case.kind, mesh=case.mesh, h=case.h, formulation=case.formulation,
               slave_points=case.slave_points,
               method=case.method)
    s = case.summary()
    if s is None:
        row["status"] = "not run"
        return row
    row["status"] = s.get("status", "")
    try:
        with open(os.path.join(case.dir, "process.json")) as f:
            row["process_seconds"] = json.load(f)["process_seconds"]
    except (OSError, ValueError, KeyError):
        pass
    row.update(elements=s["mesh"]["elements"], steps=s["steps"], dt=s["dt"], wall_seconds=s["wall_seconds"],
               element_cycles_per_second=s["element_cycles_per_second"],
               energy_max_relative_error=s["energy"]["max_relative_error"])
    phases = s.get("phase_seconds", {})
    for p in PHASES:
        row["phase_" + p] = phases.get(p, 0.0)
    total = sum(phases.get(p, 0.0) for p in PHASES)
    row["contact_share"] = sum(phases.get(p, 0.0) for p in CONTACT_PHASES) / total if total > 0 else 0.0
    if case.kind == "contact":
        c = s["contact"]
        row.update(contact_projections=c["projections"], contact_mean_iterations=c["mean_iterations"],
                   contact_max_iterations=c["max_iterations"], contact_not_converged=c["not_converged"],
                   contact_saddle_points=c["saddle_points"],
                   contact_max_penetration_over_h=c["max_penetration_over_h"],
                   contact_penalty_stiffness=c["penalty_stiffness"])
    if row["status"] == "completed" and os.path.exists(case.h5_path):
        ref = reference.h5_path if (reference is not None and reference.done()) else None
        m = pm.measures(case.h5_path, ref if case.kind == "contact" else None)
        for k in MEASURES:
            row[k] = m[k]
    return row


def write_csv(rows, path):
    with open(path, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=COLUMNS)
        w.writeheader()
        for r in rows:
            w.writerow({k: (repr(v) if isinstance(v, float) else v) for k, v in r.items()})


def num(v):
    try:
        return float(v)
    except (TypeError, ValueError):
        return float("nan")


def pareto(rows):
    """Cases no other case beats in both wall time and profile error (smaller is better). Errors
    that agree to 1e-9 (relative) are equal: the methods give the same answer to round-off."""
    pts = sorted((num(r["wall_seconds"]), num(r["profile_error"]), i) for i, r in enumerate(rows)
                 if math.isfinite(num(r["profile_error"])))
    front, best = [], float("inf")
    for t, e, i in pts:
        if e < best * (1 - 1e-9):
            front.append(i)
            best = e
    return [rows[i] for i in front]


# =============================================================================
# Charts

FORMULATION_COLOUR = {"hex8": "C0", "hex8r": "C3", "hex20": "C2", "hex20r": "C1"}
POINTS_MARKER = {"nodes": "o", "quadrature": "s"}
METHOD_MARKER = dict(zip(ALL_METHODS, ["o", "s", "v", "^", "D", "P", "X", "*", "h"]))


def profiles(path):
    plates, _ = pm.read_result(path)
    return plates


def chart_fig8(contact_plates, reference_plate, title, ax):
    a, b = contact_plates[0], contact_plates[1]
    ax.plot(-a.s / pm.D, a.row_sigma_x(), "-", color="C0", lw=1.1, label="contact (plates A, B)")
    ax.plot(b.s / pm.D, b.row_sigma_x(), "-", color="C0", lw=1.1)
    r = reference_plate.row_sigma_x()
    ax.plot(-reference_plate.s / pm.D, r, "o", color="C1", ms=2.2, label="reference (and mirrored)")
    ax.plot(reference_plate.s / pm.D, r, "o", color="C1", ms=2.2)
    f = pm.FRONT_EXACT_OVER_D
    ax.plot([-1, -f, -f, f, f, 1], [0, 0, pm.PLATEAU_X, pm.PLATEAU_X, 0, 0], "k--", lw=1, label="exact")
    ax.set_xlabel("x / d   (z = 0: the row of elements next to the symmetry plane)")
    ax.set_ylabel(r"$\sigma_x^*$")
    ax.set_title(title, fontsize=10)
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8, loc="upper center")


def chart_fig9(contact_plate, reference_plate, title, ax):
    z, v = pm.sigma_z_line(contact_plate)
    ax.plot(z / pm.D, v, "-", color="C0", lw=1.2, label="contact (plate A)")
    z, v = pm.sigma_z_line(reference_plate)
    ax.plot(z / pm.D, v, "o", color="C1", ms=2.2, label="reference")
    ax.plot([0, pm.DIFFRACTED_Z_OVER_D], [pm.PLATEAU_Z] * 2, "k--", lw=1, label="exact, z/d < 0.6081")
    ax.axvline(pm.DIFFRACTED_Z_OVER_D, color="0.5", lw=0.8, ls=":", label="diffracted wave arrives")
    ax.axvline(pm.HEAD_WAVE_Z_OVER_D, color="0.5", lw=0.8, ls="-.", label="head wave arrives")
    ax.set_xlabel("z / d   (x / d = 0.4)")
    ax.set_ylabel(r"$\sigma_z^*$")
    ax.set_title(title, fontsize=10)
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8, loc="upper left")


def make_charts(cases, rows, args, figdir):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    written = []
    by_name = {c.name: c for c in cases}
    row_of = {r["case"]: r for r in rows}

    def ok(c):
        return c is not None and row_of.get(c.name, {}).get("status") == "completed"

    def save(fig, name):
        path = os.path.join(figdir, name)
        fig.tight_layout()
        fig.savefig(path, dpi=100)
        plt.close(fig)
        written.append(path)

    method = args.figure_method
    forms = [f for f in args.formulations]
    # Fig. 8 and Fig. 9 on the figure mesh, one panel per formulation.
    fig_mesh = args.figure_mesh if args.figure_mesh in args.meshes else max(args.meshes)
    pairs = []
    for form in forms:
        c = by_name.get(f"contact_{form}_n{fig_mesh}_{method}")
        r = by_name.get(f"reference_{form}_n{fig_mesh}")
        if ok(c) and ok(r):
            pairs.append((form, profiles(c.h5_path), profiles(r.h5_path)[0]))
    if pairs:
        fig, axes = plt.subplots(1, len(pairs), figsize=(6.2 * len(pairs), 3.8), squeeze=False)
        for ax, (form, cp, rp) in zip(axes[0], pairs):
            chart_fig8(cp, rp, f"Fig. 8: {fig_mesh} x {fig_mesh} per plate, {form}, {method}, c1 t/d = 0.56", ax)
        save(fig, "results_fig8.png")
        fig, axes = plt.subplots(1, len(pairs), figsize=(6.2 * len(pairs), 3.8), squeeze=False)
        for ax, (form, cp, rp) in zip(axes[0], pairs):
            chart_fig9(cp[0], rp, f"Fig. 9: {fig_mesh} x {fig_mesh} per plate, {form}, {method}", ax)
        save(fig, "results_fig9.png")

    # Convergence: every mesh on one chart (contact, plate A), the first formulation (the
    # others agree with it to round-off along z = 0: see the summary).
    fig, axes = plt.subplots(1, 2, figsize=(12, 3.8), squeeze=False)
    cmap = plt.get_cmap("viridis")
    for fi, form in enumerate(forms[:1]):
        meshes = [n for n in args.meshes if ok(by_name.get(f"contact_{form}_n{n}_{method}"))]
        for mi, n in enumerate(meshes):
            col = cmap(mi / max(1, len(meshes) - 1) * 0.85)
            a = profiles(by_name[f"contact_{form}_n{n}_{method}"].h5_path)[0]
            axes[fi, 0].plot(a.s / pm.D, a.row_sigma_x(), "-", color=col, lw=1.0, label=f"{n} x {n}")
            z, v = pm.sigma_z_line(a)
            axes[fi, 1].plot(z / pm.D, v, "-", color=col, lw=1.0, label=f"{n} x {n}")
        f = pm.FRONT_EXACT_OVER_D
        axes[fi, 0].plot([0, f, f, 1], [pm.PLATEAU_X, pm.PLATEAU_X, 0, 0], "k--", lw=1, label="exact")
        axes[fi, 0].set_xlabel("distance from the contact face s / d, z = 0")
        axes[fi, 0].set_ylabel(r"$\sigma_x^*$")
        axes[fi, 0].set_title(f"Fig. 8, every mesh: contact, {form}, {method}", fontsize=10)
        axes[fi, 1].plot([0, pm.DIFFRACTED_Z_OVER_D], [pm.PLATEAU_Z] * 2, "k--", lw=1, label="exact")
        axes[fi, 1].axvline(pm.DIFFRACTED_Z_OVER_D, color="0.5", lw=0.8, ls=":")
        axes[fi, 1].set_xlabel("z / d, x / d = 0.4")
        axes[fi, 1].set_ylabel(r"$\sigma_z^*$")
        axes[fi, 1].set_title(f"Fig. 9, every mesh: contact, {form}, {method}", fontsize=10)
        for ax in axes[fi]:
            ax.grid(alpha=0.3)
        axes[fi, 0].legend(fontsize=8, loc="center right")
        axes[fi, 1].legend(fontsize=8, loc="upper left")
    save(fig, "results_convergence.png")

    # Speed against accuracy.
    contact = [r for r in rows if r["kind"] == "contact" and r["status"] == "completed"]
    if contact:
        fig, ax = plt.subplots(figsize=(7.5, 5.0))
        for r in contact:
            ax.loglog(num(r["wall_seconds"]), num(r["profile_error"]), linestyle="none",
                      marker=METHOD_MARKER.get(r["method"], "o"), color=FORMULATION_COLOUR.get(r["formulation"], "k"),
                      ms=6, alpha=0.75, mfc="none" if r["formulation"] == "hex8r" else None)
        front = pareto(contact)
        ax.loglog([num(r["wall_seconds"]) for r in front], [num(r["profile_error"]) for r in front],
                  "k-", lw=1, drawstyle="steps-post", label="Pareto front")
        for n in args.meshes:
            sel = [r for r in contact if int(r["mesh"]) == n]
            if sel:
                t = min(num(r["wall_seconds"]) for r in sel)
                e = max(num(r["profile_error"]) for r in sel)
                ax.annotate(f"{n} x {n}", (t, e), textcoords="offset points", xytext=(-10, 8), fontsize=8)
        from matplotlib.lines import Line2D
        handles = [Line2D([], [], color=FORMULATION_COLOUR.get(f, "k"), marker="o", ls="none",
                          mfc="none" if f == "hex8r" else None, label=f) for f in forms]
        handles += [Line2D([], [], color="0.3", marker=METHOD_MARKER.get(m, "o"), ls="none", label=m)
                    for m in args.methods]
        handles += [Line2D([], [], color="k", lw=1, label="Pareto front")]
        ax.legend(handles=handles, fontsize=7, ncol=2, loc="upper right")
        ax.set_xlabel("wall time of the run (s)")
        ax.set_ylabel("profile error of $\\sigma_x^*$ along z = 0 (L1, fraction of the plateau)")
        ax.set_title("Speed against accuracy: one point per contact case", fontsize=10)
        ax.grid(alpha=0.3, which="both")
        save(fig, "results_speed_accuracy.png")

        # Contact cost share per local search method.
        fig, axes = plt.subplots(1, len(forms), figsize=(6.2 * len(forms), 3.8), squeeze=False, sharey=True)
        width = 0.8 / max(1, len(args.meshes))
        for ax, form in zip(axes[0], forms):
            for mi, n in enumerate(args.meshes):
                vals = []
                for m in args.methods:
                    r = row_of.get(f"contact_{form}_n{n}_{m}")
                    vals.append(100 * num(r["contact_share"]) if r and r["status"] == "completed" else np.nan)
                ax.bar(np.arange(len(args.methods)) + (mi - (len(args.meshes) - 1) / 2) * width, vals, width,
                       color=cmap(mi / max(1, len(args.meshes) - 1) * 0.85), label=f"{n} x {n}")
            ax.set_xticks(np.arange(len(args.methods)))
            ax.set_xticklabels(args.methods, rotation=30, ha="right", fontsize=8)
            ax.set_title(f"contact share of the run time, {form}", fontsize=10)
            ax.grid(alpha=0.3, axis="y")
            ax.legend(fontsize=8)
        axes[0, 0].set_ylabel("contact phases / all phases (%)")
        save(fig, "results_contact_share.png")
    return written



def chart_formulations(rows, args, figdir):
    """Error against wall time at equal node counts: one line per formulation and slave
    points through the meshes (finer to the right), the Pareto front in black."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    contact = [r for r in rows if r["kind"] == "contact" and r["status"] == "completed"]
    if not contact:
        return []
    fig, ax = plt.subplots(figsize=(7.5, 5.0))
    for form in args.formulations:
        for points in args.slave_points:
            sel = sorted((r for r in contact if r["formulation"] == form and r["slave_points"] == points),
                         key=lambda r: int(r["mesh"]))
            if not sel:
                continue
            ax.loglog([num(r["wall_seconds"]) for r in sel], [num(r["profile_error"]) for r in sel],
                      "-" if points == "nodes" else "--", marker=POINTS_MARKER.get(points, "o"),
                      color=FORMULATION_COLOUR.get(form, "k"), ms=5, lw=1.0,
                      mfc="none" if form.endswith("r") else None, label=f"{form}, slave {points}")
    front = pareto(contact)
    ax.loglog([num(r["wall_seconds"]) for r in front], [num(r["profile_error"]) for r in front],
              "k-", lw=0.8, alpha=0.6, drawstyle="steps-post", label="Pareto front")
    for n in args.meshes:
        sel = [r for r in contact if int(r["mesh"]) == n]
        if sel:
            t = min(num(r["wall_seconds"]) for r in sel)
            e = min(num(r["profile_error"]) for r in sel)
            ax.annotate(f"h = d/{n}", (t, e), textcoords="offset points", xytext=(-12, -12), fontsize=8)
    ax.legend(fontsize=7, ncol=2, loc="upper right")
    ax.set_xlabel("wall time of the run, one thread (s)")
    ax.set_ylabel("profile error of $\\sigma_x^*$ along z = 0 (L1, fraction of the plateau)")
    ax.set_title(f"Formulations at equal node counts, two plates with contact, {args.figure_method}",
                 fontsize=10)
    ax.grid(alpha=0.3, which="both")
    path = os.path.join(figdir, "results_formulations.png")
    fig.tight_layout()
    fig.savefig(path, dpi=100)
    plt.close(fig)
    return [path]


def formulation_sections(cases, rows, args, stats, command):
    """The `formulations_*` sections of results.md: the run and the table of every case."""
    ran, skipped, failures, _ = stats
    completed = [r for r in rows if r["status"] == "completed"]
    now = datetime.datetime.now(datetime.timezone.utc).strftime("%Y-%m-%d %H:%M UTC")
    sec = {"formulations_run": "\n".join(
        [f"- machine: {cpu_model()}, {os.cpu_count()} cores visible; written {now} by `{command}` (ran {ran} "
         f"cases, skipped {skipped}, {failures} failed); {len(cases)} cases, {len(completed)} completed; "
         f"meshes {', '.join(str(n) for n in args.meshes)} node intervals per plate side; method "
         f"{args.figure_method};"]
        + [f"- {i['finished']}: ran {i['ran']} cases with {i['jobs']} job(s) in {i['seconds']:.0f} s; 1-minute "
           f"load average {i['load_average'][0]:.1f} at the start, {i['load_average'][1]:.1f} at the end; "
           f"{i.get('exdyn', '')}; repository at {i.get('repository', '')}" for i in invocations(args.out)])}
    refs = {(r["mesh"], r["formulation"]): r for r in rows if r["kind"] == "reference"}
    lines = []
    for r in rows:
        if r["kind"] != "contact":
            continue
        if r["status"] != "completed":
            lines.append([r["mesh"], r["formulation"], r["slave_points"], r["status"]] + [""] * 10)
            continue
        ref = refs.get((r["mesh"], r["formulation"]), {})
        lines.append([r["mesh"], r["formulation"], r["slave_points"], r["elements"], r["steps"],
                      fmt(r["wall_seconds"], ".2f"), fmt(num(r["element_cycles_per_second"]) / 1e6, ".2f"),
                      fmt(r["profile_error"], ".4f"), fmt(r["plateau_mean"], ".4f"),
                      fmt(r["front_over_d"], ".4f"), fmt(100 * num(r["contact_vs_reference_row"]), ".3f"),
                      fmt(r["mirror_symmetry"], ".1e"), fmt(r["energy_max_relative_error"], ".1e"),
                      fmt(ref.get("profile_error"), ".4f")])
    sec["formulations"] = table(["nodes/side", "form.", "slave points", "elements", "steps", "wall (s)",
                                 "M el.-cycles/s", "profile err.", "plateau mean", "front x/d",
                                 "contact - ref., z = 0 (%)", "mirror", "energy err.", "ref. profile err."],
                                lines)
    front = pareto([r for r in completed if r["kind"] == "contact"])
    sec["formulations_pareto"] = table(["nodes/side", "form.", "slave points", "wall (s)", "profile err."],
                                       [[r["mesh"], r["formulation"], r["slave_points"],
                                         fmt(r["wall_seconds"], ".2f"), fmt(r["profile_error"], ".4f")]
                                        for r in front])
    return sec


# =============================================================================
# ParaView


def make_pictures(cases, args, figdir):
    c = next((c for c in cases if c.pictures), None)
    if c is None or not c.done():
        log("paraview: no picture case in the grid (mesh %d, %s, %s): skipped"
            % (args.figure_mesh, args.formulations[0], args.figure_method))
        return []
    if not os.path.exists(PVPYTHON_RUNNER):
        log(f"paraview: {PVPYTHON_RUNNER} not found: skipped")
        return []
    t0 = time.perf_counter()
    # xvfb-run -a can lose a race for a display number to another xvfb-run on the machine
    # (pvpython then aborts: "bad X server connection"): try again.
    # The script's JSON line is what counts: xvfb-run can fail to clean up after a good run.
    for attempt in range(4):
        proc = subprocess.run(pvpython(PICTURES_SCRIPT, c.xmf_path, "--out-dir", figdir, "--prefix", "results_pv"),
                              capture_output=True, text=True)
        ok = '"ok": true' in proc.stdout
        if ok or "X server" not in proc.stderr:
            break
        log(f"paraview: no X display (attempt {attempt + 1}), trying again")
        time.sleep(2 + 3 * attempt)
    if not ok:
        log(f"paraview: FAILED (exit {proc.returncode}): {proc.stderr[-500:]}")
        return []
    csv_path = os.path.join(figdir, "results_pv_line.csv")
    if os.path.exists(csv_path):       # the samples are data, not a figure: keep them with the cases
        os.replace(csv_path, os.path.join(c.dir, "results_pv_line.csv"))
    log(f"paraview: pictures of {c.name} in {time.perf_counter() - t0:.1f} s")
    return [os.path.join(figdir, "results_pv_sigma_xx.png"), os.path.join(figdir, "results_pv_line.png")]


# =============================================================================
# The document


def cpu_model():
    try:
        with open("/proc/cpuinfo") as f:
            for line in f:
                if line.startswith("model name"):
                    return line.split(":", 1)[1].strip()
    except OSError:
        pass
    return platform.processor() or "unknown CPU"


def git_commit():
    try:
        out = subprocess.run(["git", "-C", REPO, "rev-parse", "--short", "HEAD"], capture_output=True, text=True)
        dirty = subprocess.run(["git", "-C", REPO, "status", "--porcelain", "--untracked-files=no"],
                               capture_output=True, text=True).stdout.strip()
        return out.stdout.strip() + (" (with uncommitted changes)" if dirty else "")
    except OSError:
        return "unknown"


def invocations(out):
    try:
        with open(os.path.join(out, "invocations.jsonl")) as f:
            return [json.loads(line) for line in f if line.strip()]
    except (OSError, ValueError):
        return []


def fmt(v, spec):
    x = num(v)
    return "" if not math.isfinite(x) else format(x, spec)


def table(header, rows):
    lines = ["| " + " | ".join(header) + " |", "|" + "---|" * len(header)]
    lines += ["| " + " | ".join(str(c) for c in r) + " |" for r in rows]
    return "\n".join(lines)


def doc_sections(cases, rows, args, stats, command, exdyn_version):
    ran, skipped, failures, total = stats
    row_of = {r["case"]: r for r in rows}
    completed = [r for r in rows if r["status"] == "completed"]
    wall_sum = sum(num(r["wall_seconds"]) for r in completed)
    proc_sum = sum(num(r["process_seconds"]) for r in completed if math.isfinite(num(r["process_seconds"])))
    now = datetime.datetime.now(datetime.timezone.utc).strftime("%Y-%m-%d %H:%M UTC")
    sec = {}
    sec["run"] = "\n".join([
        f"- machine: {cpu_model()}, {os.cpu_count()} cores visible, {platform.system()} {platform.release()}; "
        f"page written {now}; the cases were measured by the invocations below;",
        f"- grid: meshes {', '.join(str(n) for n in args.meshes)} elements per plate side; formulations "
        f"{', '.join(args.formulations)}; local search methods {', '.join(args.methods)}; "
        f"{len(cases)} cases ({sum(c.kind == 'contact' for c in cases)} contact, "
        f"{sum(c.kind == 'reference' for c in cases)} reference), {len(completed)} completed;",
        f"- the invocations that ran cases (from `{os.path.join(os.path.basename(args.out), 'invocations.jsonl')}`):"]
        + [f"  - {i['finished']}: `{i['command']}`: ran {i['ran']} cases ({i['failed']} failed), skipped "
           f"{i['skipped']}, {i['seconds']:.0f} s with {i['jobs']} job(s); 1-minute load average "
           f"{i['load_average'][0]:.1f} at the start, {i['load_average'][1]:.1f} at the end; "
           f"{i.get('exdyn', 'exdyn not recorded')}; repository at {i.get('repository', 'not recorded')}"
           for i in invocations(args.out)]
        + [f"- the completed cases' exdyn wall times add up to {wall_sum:.0f} s (processes: {proc_sum:.0f} s); "
           "each case runs on one thread, and on a machine shared with other work the wall times include "
           "waiting for a core;",
           f"- this page was written by `{command}` (ran {ran} cases, skipped {skipped}, {failures} failed)."])

    # Accuracy per mesh and formulation (the figure method and the reference).
    acc = []
    for n in args.meshes:
        for form in args.formulations:
            c = row_of.get(f"contact_{form}_n{n}_{args.figure_method}")
            r = row_of.get(f"reference_{form}_n{n}")
            if not c or c["status"] != "completed":
                continue
            acc.append([n, form, fmt(c["plateau_mean"], ".4f"), fmt(100 * num(c["plateau_error"]), "+.3f"),
                        fmt(c["front_over_h"], ".2f"), fmt(c["front_over_d"], ".4f"),
                        fmt(c["front_error_over_h"], "+.2f"), fmt(c["profile_error"], ".4f"),
                        fmt(c["sigma_z_mean_error"], "+.4f"), fmt(c["sigma_z_max_error"], ".4f"),
                        fmt(100 * num(c["contact_vs_reference_row"]), ".3f"),
                        fmt(100 * num(c["contact_vs_reference_all"]), ".2f"),
                        fmt(c["mirror_symmetry"], ".1e"),
                        fmt(r["plateau_mean"], ".4f") if r else "", fmt(r["front_over_h"], ".2f") if r else ""])
    sec["accuracy"] = (f"Contact cases with `{args.figure_method}`, and the reference of the same mesh and "
                       "formulation (last two columns). Exact: plateau -2.3333, front 0.56 d.\n\n" + table(
        ["mesh", "form.", "plateau mean", "plateau err. %", "front x/h", "front x/d", "front - 0.56 d (h)",
         "profile err.", "sigma_z* mean + 1", "max abs(sigma_z* + 1)", "contact - ref., z = 0 (%)",
         "contact - ref., all (%)", "mirror", "ref. plateau", "ref. front x/h"], acc))

    # Every contact case.
    allrows = []
    for r in rows:
        if r["kind"] != "contact":
            continue
        if r["status"] != "completed":
            allrows.append([r["mesh"], r["formulation"], r["method"], r["status"]] + [""] * 10)
            continue
        allrows.append([r["mesh"], r["formulation"], r["method"], fmt(r["wall_seconds"], ".2f"),
                        fmt(num(r["element_cycles_per_second"]) / 1e6, ".2f"),
                        fmt(100 * num(r["contact_share"]), ".1f"),
                        fmt(r["contact_mean_iterations"], ".2f"), r["contact_max_iterations"],
                        r["contact_not_converged"], r["contact_saddle_points"],
                        fmt(r["contact_max_penetration_over_h"], ".1e"),
                        fmt(r["energy_max_relative_error"], ".1e"), fmt(r["profile_error"], ".4f"),
                        fmt(100 * num(r["contact_vs_reference_row"]), ".3f")])
    sec["cases"] = table(["mesh", "form.", "method", "wall (s)", "M el.-cycles/s", "contact share %",
                          "mean it.", "max it.", "not conv.", "saddles", "max pen. / h", "energy err.",
                          "profile err.", "contact - ref., z = 0 (%)"], allrows)

    refrows = [[r["mesh"], r["formulation"], fmt(r["wall_seconds"], ".2f"),
                fmt(num(r["element_cycles_per_second"]) / 1e6, ".2f"), fmt(r["plateau_mean"], ".4f"),
                fmt(r["front_over_h"], ".2f"), fmt(r["profile_error"], ".4f"), fmt(r["sigma_z_max_error"], ".4f"),
                fmt(r["energy_max_relative_error"], ".1e")]
               for r in rows if r["kind"] == "reference" and r["status"] == "completed"]
    sec["reference"] = table(["mesh", "form.", "wall (s)", "M el.-cycles/s", "plateau mean", "front x/h",
                              "profile err.", "max abs(sigma_z* + 1)", "energy err."], refrows)

    contact = [r for r in completed if r["kind"] == "contact"]
    sec["summary"] = summary_lines(args, row_of, contact)
    front = pareto(contact)
    sec["pareto"] = table(["mesh", "form.", "method", "wall (s)", "profile err."],
                          [[r["mesh"], r["formulation"], r["method"], fmt(r["wall_seconds"], ".2f"),
                            fmt(r["profile_error"], ".4f")] for r in front])

    share = []
    for m in args.methods:
        line = [m]
        for form in args.formulations:
            for n in args.meshes:
                r = row_of.get(f"contact_{form}_n{n}_{m}")
                line.append(fmt(100 * num(r["contact_share"]), ".1f") if r and r["status"] == "completed" else "")
        share.append(line)
    sec["share"] = ("Contact phases (global search + local search + forces) as % of all phases of the run.\n\n"
                    + table(["method"] + [f"{f} {n}" for f in args.formulations for n in args.meshes], share))
    return sec


def summary_lines(args, row_of, contact):
    """Sentences with the key numbers, written from the rows."""
    lines = []
    m = args.figure_method
    for form in args.formulations:
        meshes = [n for n in args.meshes
                  if row_of.get(f"contact_{form}_n{n}_{m}", {}).get("status") == "completed"]
        if not meshes:
            continue
        c = {n: row_of[f"contact_{form}_n{n}_{m}"] for n in meshes}
        lines.append(f"- {form}, `{m}`: front - 0.56 d, in elements: "
                     + ", ".join(f"{fmt(c[n]['front_error_over_h'], '+.2f')} h (N = {n})" for n in meshes)
                     + "; in d: " + ", ".join(fmt(num(c[n]["front_over_d"]) - pm.FRONT_EXACT_OVER_D, "+.4f")
                                               for n in meshes) + ".")
        lag = [pm.FRONT_EXACT_OVER_D - num(c[n]["front_over_d"]) for n in meshes]
        rates = [math.log(lag[i] / lag[i + 1]) / math.log(meshes[i + 1] / meshes[i])
                 for i in range(len(meshes) - 1) if lag[i] > 0 and lag[i + 1] > 0]
        if rates:
            lines.append(f"- {form}, `{m}`: the front lag in d falls like h^p with observed p = "
                         + ", ".join(fmt(r, ".2f") for r in rates) + " between successive meshes.")
        errs = [num(c[n]["profile_error"]) for n in meshes]
        orders = [math.log(errs[i] / errs[i + 1]) / math.log(meshes[i + 1] / meshes[i])
                  for i in range(len(meshes) - 1) if errs[i + 1] > 0]
        lines.append(f"- {form}, `{m}`: profile error " + ", ".join(fmt(e, ".4f") for e in errs)
                     + (" (observed order " + ", ".join(fmt(o, ".2f") for o in orders) + ")" if orders else "")
                     + "; plateau error " + ", ".join(fmt(100 * num(c[n]["plateau_error"]), "+.3f") + " %"
                                                     for n in meshes)
                     + "; contact - reference along z = 0 " + ", ".join(
                         fmt(100 * num(c[n]["contact_vs_reference_row"]), ".3f") + " %" for n in meshes)
                     + "; mirror " + ", ".join(fmt(c[n]["mirror_symmetry"], ".1e") for n in meshes) + ".")
    spread = 0.0
    for n in args.meshes:
        for form in args.formulations:
            e = [num(r["profile_error"]) for r in contact if int(r["mesh"]) == n and r["formulation"] == form]
            if len(e) > 1:
                spread = max(spread, (max(e) - min(e)) / min(e))
    lines.append(f"- Across the local search methods the profile error of one mesh and formulation differs by "
                 f"at most {spread:.1e} (relative).")
    if len(args.formulations) > 1:
        a, b = args.formulations[:2]
        diffs = []
        for n in args.meshes:
            ra, rb = row_of.get(f"contact_{a}_n{n}_{m}"), row_of.get(f"contact_{b}_n{n}_{m}")
            if ra and rb and ra["status"] == rb["status"] == "completed":
                diffs.append(abs(num(ra["profile_error"]) - num(rb["profile_error"])))
        if diffs:
            lines.append(f"- {a} against {b} (`{m}`): the profile errors differ by at most {max(diffs):.1e}.")
    return "\n".join(lines)


DOC_TEMPLATE = """# Results: the plate impact, batch study

Generated by `scripts/batch_plate_impact.py`. Everything between
`<!-- batch:... -->` markers is written by the script from its last run; the
text outside the markers is kept when the script runs again.

## The run

<!-- batch:run -->
<!-- /batch:run -->

## Accuracy

<!-- batch:accuracy -->
<!-- /batch:accuracy -->

<!-- batch:summary -->
<!-- /batch:summary -->

### Reference calculations

<!-- batch:reference -->
<!-- /batch:reference -->

## Every contact case

<!-- batch:cases -->
<!-- /batch:cases -->

## Speed against accuracy: the Pareto front

<!-- batch:pareto -->
<!-- /batch:pareto -->

## Contact cost share per local search method

<!-- batch:share -->
<!-- /batch:share -->
"""


def write_doc(path, sections):
    text = open(path).read() if os.path.exists(path) else DOC_TEMPLATE
    for key, body in sections.items():
        pattern = re.compile(r"(<!-- batch:%s -->\n).*?(<!-- /batch:%s -->)" % (key, key), re.S)
        if not pattern.search(text):
            text += f"\n<!-- batch:{key} -->\n<!-- /batch:{key} -->\n"
        text = pattern.sub(lambda m: m.group(1) + body.rstrip() + "\n" + m.group(2), text)
    with open(path + ".tmp", "w") as f:
        f.write(text)
    os.replace(path + ".tmp", path)


# =============================================================================


def parse_list(text, allowed=None, kind=str):
    items = [kind(x) for x in text.split(",") if x.strip()]
    if allowed is not None:
        bad = [x for x in items if x not in allowed]
        if bad:
            raise argparse.ArgumentTypeError(f"unknown {bad}; choose from {allowed}")
    return items


def default_exdyn():
    for sub in ("release", "lead", "batch"):
        p = os.path.join(REPO, "build", sub, "src", "app", "exdyn")
        if os.path.exists(p):
            return p
    return "exdyn"


def main(argv):
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--meshes", default=",".join(map(str, DEFAULT_MESHES)),
                   help="node intervals per plate side (elements for 8-node formulations), comma "
                        "separated (default %(default)s)")
    p.add_argument("--formulations", default=",".join(DEFAULT_FORMULATIONS),
                   help="comma separated among " + ", ".join(ALL_FORMULATIONS) + ", or all")
    p.add_argument("--slave-points", default="nodes",
                   help="contact slave points, comma separated among nodes, quadrature, or all")
    p.add_argument("--methods", default="all", help="local search methods, comma separated, or all")
    p.add_argument("--jobs", type=int, default=os.cpu_count() or 1, help="cases run at once (default: cores)")
    p.add_argument("--out", default=None,
                   help="results directory (default results/batch, or results/formulations for that study)")
    p.add_argument("--docs", default=os.path.join(REPO, "docs"),
                   help="where results.md and figures/results_*.png go (default: the repository's docs)")
    p.add_argument("--exdyn", default=default_exdyn())
    p.add_argument("--figure-mesh", type=int, default=FIGURE_MESH)
    p.add_argument("--figure-method", default=FIGURE_METHOD)
    p.add_argument("--study", choices=["methods", "formulations"], default="methods",
                   help="methods (default): the grid options below; formulations: every formulation and "
                        "slave points at equal node counts, one method, its own sections of results.md")
    p.add_argument("--no-plots", action="store_true", help="no charts, no document")
    p.add_argument("--skip-paraview", action="store_true")
    try:
        args = p.parse_args(argv)
        args.meshes = parse_list(args.meshes, kind=int)
        args.formulations = (ALL_FORMULATIONS if args.formulations == "all"
                             else parse_list(args.formulations, ALL_FORMULATIONS))
        args.slave_points = (ALL_SLAVE_POINTS if args.slave_points == "all"
                             else parse_list(args.slave_points, ALL_SLAVE_POINTS))
        args.methods = ALL_METHODS if args.methods == "all" else parse_list(args.methods, ALL_METHODS)
        if args.study == "formulations":
            if "--formulations" not in argv:
                args.formulations = ALL_FORMULATIONS
            if "--slave-points" not in argv:
                args.slave_points = ALL_SLAVE_POINTS
            if "--meshes" not in argv:   # even: the 20-node meshes take half as many elements
                args.meshes = FORMULATION_MESHES
            args.methods = [args.figure_method]
    except (argparse.ArgumentTypeError, ValueError) as e:
        print(f"batch_plate_impact: {e}", file=sys.stderr)
        return 2
    if any(f.startswith("hex20") for f in args.formulations) and any(n % 2 for n in args.meshes):
        print("batch_plate_impact: 20-node formulations need even meshes (node intervals per side)",
              file=sys.stderr)
        return 2
    if not args.meshes or not args.formulations or not args.slave_points or not args.methods or args.jobs < 1:
        print("batch_plate_impact: empty grid or --jobs < 1", file=sys.stderr)
        return 2
    if args.figure_method not in args.methods:
        args.figure_method = args.methods[0]
    args.command = "/usr/bin/python3 scripts/batch_plate_impact.py " + " ".join(_quote(a) for a in argv)
    args.out = os.path.abspath(args.out or os.path.join(REPO, "results",
                                                         "formulations" if args.study == "formulations" else "batch"))
    args.exdyn = os.path.abspath(args.exdyn) if os.path.exists(args.exdyn) else args.exdyn
    try:
        exdyn_version = subprocess.run([args.exdyn, "--version"], capture_output=True, text=True).stdout.strip().splitlines()[0]
        built = datetime.datetime.fromtimestamp(os.path.getmtime(shutil.which(args.exdyn) or args.exdyn),
                                                datetime.timezone.utc).strftime("%Y-%m-%d %H:%M UTC")
        args.exdyn_label = f"{exdyn_version} ({args.exdyn}, built {built})"
    except OSError:
        print(f"batch_plate_impact: cannot run {args.exdyn}", file=sys.stderr)
        return 2
    os.makedirs(args.out, exist_ok=True)

    cases = build_grid(args)
    stats = run_grid(cases, args)
    refs = {(c.mesh, c.formulation): c for c in cases if c.kind == "reference"}
    rows = [case_row(c, refs.get((c.mesh, c.formulation))) for c in cases]
    csv_path = os.path.join(args.out, "batch.csv")
    write_csv(rows, csv_path)
    log(f"batch: wrote {csv_path} ({len(rows)} rows)")

    if not args.no_plots and args.study == "formulations":
        figdir = os.path.join(args.docs, "figures")
        os.makedirs(figdir, exist_ok=True)
        for w in chart_formulations(rows, args, figdir):
            log(f"batch: wrote {w} ({os.path.getsize(w) // 1024} kB)")
        doc = os.path.join(args.docs, "results.md")
        write_doc(doc, formulation_sections(cases, rows, args, stats, args.command.strip()))
        log(f"batch: wrote {doc}")
    elif not args.no_plots:
        figdir = os.path.join(args.docs, "figures")
        os.makedirs(figdir, exist_ok=True)
        written = make_charts(cases, rows, args, figdir)
        if not args.skip_paraview:
            written += make_pictures(cases, args, figdir)
        for w in written:
            log(f"batch: wrote {w} ({os.path.getsize(w) // 1024} kB)")
        doc = os.path.join(args.docs, "results.md")
        write_doc(doc, doc_sections(cases, rows, args, stats, args.command.strip(), exdyn_version))
        log(f"batch: wrote {doc}")
    return 1 if stats[2] else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
