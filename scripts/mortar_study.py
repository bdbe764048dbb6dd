#!/usr/bin/python3
"""Mortar contact against slave nodes and slave Gauss points: accuracy and cost
(docs/verification.md, "Mortar contact"; ../shared/reference/contact-and-failure.md).

- The dynamic contact patch test (input/contact_patch_mortar.yaml), hex8 and hex20:
  3 x 3 on 4 x 4, 2 x 2 on 5 x 5, 3 x 3 on a graded 4 x 4 (grading 0.5 across the face),
  each with the matching run of the same element heights and the same slave points. Per
  run: the spread of sigma_zz in each interface layer and each layer's mean against the
  matching run's (the larger of the two layers, % of rho c1 v0), and the contact seconds.
- The Hertz ball (input/hertz_ball.yaml): F_max and the contact time against Hertz, and
  the contact pressure along a radius at the written step nearest the peak against
  p0 sqrt(1 - r^2 / a^2): the RMS error inside 0.9 a over p0. The pressure is the L2
  projection of the block face's nodal contact forces on its quad8 shape functions
  (a quad8 corner's consistent area is negative, so force over area does not recover it).
- The local-search methods inside mortar: the patch and Hertz answers of each.
- Speed: contact seconds of a mortar pass and of a 2 x 2 Gauss point pass on the same
  faces (a 60 x 60 on 80 x 80 hex8 patch, and the Hertz ball), one thread.

  /usr/bin/python3 scripts/mortar_study.py [--exdyn PATH] [--docs docs] [--quick]

Writes the tables between the markers `<!-- mortar:NAME -->` of docs/verification.md and
the charts docs/figures/mortar_speed_accuracy.png and mortar_hertz_pressure.png. --quick:
the patch table alone.
"""
import argparse
import json
import math
import os
import subprocess
import sys
import tempfile

import h5py
import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.dirname(HERE)
RHO, C1, V0 = 7800.0, 6020.1841, 1.0
PLATEAU = RHO * C1 * V0
METHODS = ["newton", "lsp", "steepest_descent", "broyden", "bfgs", "dfp", "simplex", "hybrid", "robust"]
POINTS = [("nodes", ["contact[0].slave_points=nodes"]),
          ("Gauss 2 x 2", ["contact[0].slave_points=quadrature", "contact[0].quadrature=2"]),
          ("Gauss 3 x 3", ["contact[0].slave_points=quadrature", "contact[0].quadrature=3"]),
          ("Gauss 4 x 4", ["contact[0].slave_points=quadrature", "contact[0].quadrature=4"]),
          ("mortar", ["contact[0].slave_points=mortar"])]


def run(exdyn, deck, sets, out, threads=1):
    cmd = [exdyn, "run", os.path.join(REPO, "input", deck + ".yaml"), "--quiet", "--output", out,
           "--threads", str(threads)]
    for s in sets:
        cmd += ["--set", s]
    done = subprocess.run(cmd, capture_output=True, text=True)
    if done.returncode != 0:
        raise RuntimeError(" ".join(cmd) + "\n" + done.stdout + done.stderr)
    with open(os.path.join(out, deck + ".json")) as f:
        return json.load(f)


def contact_seconds(summary):
    p = summary["phase_seconds"]
    return (p["contact_global_search"] + p["contact_local_search"] + p["contact_forces"] +
            p.get("contact_segmentation", 0.0))


# ------------------------------------------------------------------ patch test

def patch_run(exdyn, work, label, lower, upper, form, extra):
    sets = [f"parts[0].elements=[{lower[0]}, {lower[1]}, 40]", f"parts[1].elements=[{upper[0]}, {upper[1]}, 40]",
            f"parts[0].formulation={form}", f"parts[1].formulation={form}", "output.fields=[stress]"] + extra
    out = os.path.join(work, label)
    s = run(exdyn, "contact_patch_mortar", sets, out)
    with h5py.File(os.path.join(out, "contact_patch_mortar.h5")) as f:
        last = sorted(f["steps"])[-1]
        szz = f["steps"][last]["stress"][:, 2] / PLATEAU
    n_lower = lower[0] * lower[1] * 40
    low = szz[n_lower - lower[0] * lower[1]:n_lower]
    up = szz[n_lower:n_lower + upper[0] * upper[1]]
    return {"lower": low, "upper": up, "seconds": contact_seconds(s), "summary": s}


PATCH_CASES = [("3 x 3 on 4 x 4", (4, 4), (3, 3), [], []),
               ("2 x 2 on 5 x 5", (5, 5), (2, 2), [], []),
               ("3 x 3 on graded 4 x 4", (4, 4), (3, 3), ["parts[0].grading=[0.5, 0.5, 1]"],
                ["parts[0].grading=[0.5, 0.5, 1]", "parts[1].grading=[0.5, 0.5, 1]"])]


def patch_errors(exdyn, work, form, points_label, points_sets, case):
    label, lower, upper, grading, matching_grading = case
    tag = f"{form}_{points_label}_{label}".replace(" ", "_")
    run_ = patch_run(exdyn, work, tag, lower, upper, form, points_sets + grading)
    match = patch_run(exdyn, work, tag + "_match", lower, lower, form, points_sets + matching_grading)
    spread = max(np.ptp(run_["lower"]), np.ptp(run_["upper"]))
    mean = max(abs(run_["lower"].mean() - match["lower"].mean()), abs(run_["upper"].mean() - match["upper"].mean()))
    return 100 * spread, 100 * mean, run_["seconds"], run_["summary"]


def fmt(x):
    return f"{x:.1e}" if x < 0.01 else f"{x:.2f}"


def patch_table(exdyn, work):
    rows, records = [], {}
    for form in ("hex8", "hex20"):
        for points_label, points_sets in POINTS:
            cells = []
            for case in PATCH_CASES:
                spread, mean, seconds, _ = patch_errors(exdyn, work, form, points_label, points_sets, case)
                records[(form, points_label, case[0])] = (spread, mean, seconds)
                cells.append(f"{fmt(spread)} / {fmt(mean)}")
            rows.append(f"| {form} | {points_label} | " + " | ".join(cells) + " |")
    head = ("| elements | slave points | " + " | ".join(c[0] for c in PATCH_CASES) + " |\n"
            "|---|---|" + "---|" * len(PATCH_CASES) + "\n")
    text = ("Spread of sigma_zz in the worse interface layer / its mean against the matching run's, "
            "% of rho c1 v0, half way through (two passes, default penalty):\n\n" + head + "\n".join(rows) + "\n")
    return text, records


# ------------------------------------------------------------------ Hertz

E, NU, R, V = 2.1e11, 0.3, 0.01, 10.0
E_STAR = E / (2 * (1 - NU * NU))


def hertz_theory():
    ball = RHO * 4 / 3 * math.pi * R ** 3
    block = RHO * 0.04 * 0.04 * 0.02
    m = ball * block / (ball + block)
    delta = (15 * m * V * V / (16 * E_STAR * math.sqrt(R))) ** 0.4
    return 4 / 3 * E_STAR * math.sqrt(R) * delta ** 1.5, 2.943 * delta / V


def quad8_shape(xi, eta):
    corners = [(-1, -1), (1, -1), (1, 1), (-1, 1)]
    mids = [(0, -1), (1, 0), (0, 1), (-1, 0)]
    N = [0.25 * (1 + a * xi) * (1 + b * eta) * (a * xi + b * eta - 1) for a, b in corners]
    for a, b in mids:
        N.append(0.5 * (1 - xi * xi) * (1 + b * eta) if a == 0 else 0.5 * (1 + a * xi) * (1 - eta * eta))
    return np.array(N)


def block_face_pressure(h5, step):
    """The L2 projection p_h of the block top face's (z = 0) nodal contact forces on its
    quad8 basis: M p = f_z, M_IJ = integral N_I N_J dA. Returns (x of the nodes on y = 0,
    p there, the total force on the face) for the quarter model."""
    with h5py.File(h5) as f:
        X = f["mesh/coordinates"][...]
        conn = f["mesh/connectivity"][...]
        part = f["mesh/part"][...]
        force = f["steps"][step]["contact_force"][...]
    top = np.abs(X[:, 2]) < 1e-12
    faces = []
    for e in np.where(part == 1)[0]:
        nodes = [n for n in conn[e] if top[n]]
        if len(nodes) == 8:
            faces.append(nodes)
    ids = sorted({n for face in faces for n in face})
    index = {n: k for k, n in enumerate(ids)}
    M = np.zeros((len(ids), len(ids)))
    g = [-math.sqrt(0.6), 0.0, math.sqrt(0.6)]
    w = [5 / 9, 8 / 9, 5 / 9]
    for face in faces:
        xy = X[face, :2]
        x0, x1, y0, y1 = xy[:, 0].min(), xy[:, 0].max(), xy[:, 1].min(), xy[:, 1].max()
        order = []
        for a, b in [(-1, -1), (1, -1), (1, 1), (-1, 1), (0, -1), (1, 0), (0, 1), (-1, 0)]:
            px, py = x0 + (a + 1) / 2 * (x1 - x0), y0 + (b + 1) / 2 * (y1 - y0)
            order.append(face[int(np.argmin(np.hypot(xy[:, 0] - px, xy[:, 1] - py)))])
        jac = (x1 - x0) * (y1 - y0) / 4
        k = [index[n] for n in order]
        for i in range(3):
            for j in range(3):
                N = quad8_shape(g[i], g[j])
                M[np.ix_(k, k)] += w[i] * w[j] * jac * np.outer(N, N)
    fz = force[ids, 2]
    p = np.linalg.solve(M, fz)
    on_axis = [k for k, n in enumerate(ids) if abs(X[n, 1]) < 1e-12]
    on_axis.sort(key=lambda k: X[ids[k], 0])
    return X[[ids[k] for k in on_axis], 0], p[on_axis], fz.sum()


def hertz_run(exdyn, work, label, sets):
    out = os.path.join(work, "hertz_" + label.replace(" ", "_"))
    s = run(exdyn, "hertz_ball", sets + ["output.every=10", "output.fields=[contact_force]", "output.history_every=1"],
            out)
    h5 = os.path.join(out, "hertz_ball.h5")
    with h5py.File(h5) as f:
        t = f["/history/time"][...]
        F = 4 * f["/history/contact/impact/force"][:, 2]
        steps = sorted(f["steps"], key=int)
        dt = s["dt"]
    peak = F.max()
    on = t[F > 1e-3 * peak]
    F_exact, t_exact = hertz_theory()
    # The written step nearest the peak.
    peak_step = int(round(t[int(np.argmax(F))] / dt))
    step = min(steps, key=lambda k: abs(int(k) - peak_step))
    x, p, total = block_face_pressure(h5, step)
    load = 4 * abs(total)  # the whole ball's
    a = (3 * load * R / (4 * E_STAR)) ** (1 / 3)
    p0 = 3 * load / (2 * math.pi * a * a)
    inside = x < 0.9 * a
    exact = p0 * np.sqrt(np.clip(1 - (x / a) ** 2, 0, None))
    rms = math.sqrt(np.mean(((np.abs(p) - exact)[inside] / p0) ** 2))
    return {"F": 100 * (peak / F_exact - 1), "t": 100 * ((on[-1] - on[0]) / t_exact - 1), "rms": 100 * rms,
            "seconds": contact_seconds(s), "wall": s["wall_seconds"], "projections": s["contact"]["projections"],
            "points_inside": int(inside.sum()), "penetration": s["contact"]["max_penetration_over_h"],
            "profile": (x / a, np.abs(p) / p0)}


HERTZ_CASES = [("nodes (two passes, scale 1)", ["contact[0].slave_points=nodes", "contact[0].two_pass=true",
                                                "contact[0].penalty={scale: 1.0}"]),
               ("Gauss 2 x 2", ["contact[0].slave_points=quadrature", "contact[0].quadrature=2"]),
               ("Gauss 3 x 3 (the deck)", []),
               ("mortar, scale 4 (the deck's)", ["contact[0].slave_points=mortar"]),
               ("mortar, scale 1", ["contact[0].slave_points=mortar", "contact[0].penalty={scale: 1.0}"]),
               ("mortar, scale 0.75", ["contact[0].slave_points=mortar", "contact[0].penalty={scale: 0.75}"])]


def hertz_table(exdyn, work):
    rows, records = [], {}
    for label, sets in HERTZ_CASES:
        r = hertz_run(exdyn, work, label, sets)
        records[label] = r
        rows.append(f"| {label} | {r['F']:+.2f} | {r['t']:+.2f} | {r['rms']:.1f} | {r['penetration']:.4f} | "
                    f"{r['projections']:,} | {r['seconds']:.2f} |")
    text = ("| slave points | F_max vs Hertz, % | contact time, % | pressure RMS inside 0.9 a, % of p0 | "
            "largest penetration / h | projections | contact s |\n|---|---|---|---|---|---|---|\n" +
            "\n".join(rows) + f"\n\n({records[HERTZ_CASES[0][0]]['points_inside']} nodes of the block's face lie "
            "on the radius inside 0.9 a.)\n")
    return text, records


# ------------------------------------------------------------------ methods and speed

def methods_table(exdyn, work):
    rows, records = [], {}
    case = PATCH_CASES[0]
    for method in METHODS:
        sets = ["contact[0].slave_points=mortar", f"contact[0].local_search.method={method}",
                "contact[0].local_search.fallback=none"]
        spread, mean, seconds, s = patch_errors(exdyn, work, "hex8", "mortar_" + method, sets, case)
        h = hertz_run(exdyn, work, "mortar_" + method, sets + ["contact[0].penalty={scale: 1.0}"])
        records[method] = (spread, mean, seconds, h)
        c = s["contact"]
        rows.append(f"| {method} | {fmt(spread)} / {fmt(mean)} | {c['mean_iterations']:.2f} | {h['F']:+.3f} | "
                    f"{h['t']:+.3f} | {h['seconds']:.2f} |")
    text = ("Mortar with each local-search method: the hex8 patch 3 x 3 on 4 x 4 (spread / mean, %; its mean "
            "iterations) and the Hertz ball at penalty scale 1 (F_max, contact time, %; contact seconds):\n\n"
            "| method | patch | iterations | Hertz F_max | contact time | Hertz contact s |\n"
            "|---|---|---|---|---|---|\n" + "\n".join(rows) + "\n")
    return text, records


def speed_table(exdyn, work):
    """Contact seconds per step of a mortar pass against a 2 x 2 Gauss point pass on the
    same faces, one thread."""
    rows = []
    ratios = {}
    cases = [("hex8 patch 60 x 60 on 80 x 80", "contact_patch_mortar",
              ["parts[0].elements=[80, 80, 4]", "parts[1].elements=[60, 60, 4]",
               "parts[0].box={min: [0, 0, -5.0e-5], max: [1.0e-3, 1.0e-3, 0]}",
               "parts[1].box={min: [0, 0, 0], max: [1.0e-3, 1.0e-3, 5.0e-5]}", "time.end_time=2.0e-8",
               "output.fields=[stress]"]),
             ("Hertz ball (hex20)", "hertz_ball", ["output.fields=[stress]"])]
    for label, deck, sets in cases:
        per = {}
        for name, points in [("nodes", ["contact[0].slave_points=nodes"]),
                             ("Gauss 2 x 2", ["contact[0].slave_points=quadrature", "contact[0].quadrature=2"]),
                             ("mortar", ["contact[0].slave_points=mortar"])]:
            best = None
            for repeat in range(3):
                s = run(exdyn, deck, sets + points, os.path.join(work, f"speed_{deck}_{name[:4]}_{repeat}"))
                seconds = contact_seconds(s) / s["steps"]
                if best is None or seconds < best[0]:
                    best = (seconds, s)
            per[name] = best
            s = best[1]
            p = s["phase_seconds"]
            rows.append(f"| {label} | {name} | {s['contact']['projections'] / s['steps']:,.0f} | "
                        f"{1e3 * p['contact_global_search'] / s['steps']:.3f} | "
                        f"{1e3 * p.get('contact_segmentation', 0.0) / s['steps']:.3f} | "
                        f"{1e3 * p['contact_local_search'] / s['steps']:.3f} | "
                        f"{1e3 * p['contact_forces'] / s['steps']:.3f} | {1e3 * best[0]:.3f} | "
                        f"{s['element_cycles_per_second']:.3g} |")
        ratios[label] = per["mortar"][0] / per["Gauss 2 x 2"][0]
        rows.append(f"| {label} | mortar / Gauss 2 x 2 | | | | | | **{ratios[label]:.2f}** | |")
        rows.append(f"| {label} | mortar / nodes | | | | | | {per['mortar'][0] / per['nodes'][0]:.2f} | |")
    text = ("Per step, one thread, the least of 3 runs (ms; element-cycles/s of the whole run):\n\n"
            "| faces | slave points | projections | global search | segmentation | local search | forces | "
            "contact | element-cycles/s |\n|---|---|---|---|---|---|---|---|---|\n" + "\n".join(rows) + "\n")
    return text, ratios


def pressure_chart(hertz, path):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(figsize=(6, 4))
    r = np.linspace(0, 1, 200)
    ax.plot(r, np.sqrt(1 - r * r), "k-", label="Hertz")
    for label, h in hertz.items():
        x, p = h["profile"]
        keep = x < 1.3
        ax.plot(x[keep], p[keep], "o-", ms=4, label=f"{label} (RMS {h['rms']:.1f} %)")
    ax.set_xlabel("r / a")
    ax.set_ylabel("p / p0")
    ax.set_title("Hertz ball: contact pressure on the block at the peak")
    ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(path, dpi=110)


def chart(patch, hertz, methods, path):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, axes = plt.subplots(1, 2, figsize=(11, 4.2))
    colours = {"nodes": "tab:red", "Gauss 2 x 2": "tab:orange", "Gauss 3 x 3": "tab:olive",
               "Gauss 4 x 4": "tab:brown", "mortar": "tab:blue"}
    ax = axes[0]
    for (form, points, case), (spread, mean, seconds) in patch.items():
        if case != PATCH_CASES[0][0]:
            continue
        ax.scatter(seconds, max(spread, 1e-14), color=colours[points], marker="o" if form == "hex8" else "s",
                   label=f"{points} ({form})")
    for method, (spread, mean, seconds, h) in methods.items():
        ax.scatter(seconds, max(spread, 1e-14), color="tab:blue", marker="x", s=18)
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("contact wall time of the run, s")
    ax.set_ylabel("patch test: spread in a layer, % of rho c1 v0")
    ax.set_title("Patch test 3 x 3 on 4 x 4 (x: mortar, each method)")
    ax.legend(fontsize=7)
    ax = axes[1]
    for label, r in hertz.items():
        key = "mortar" if label.startswith("mortar") else label.split(" (")[0]
        ax.scatter(r["seconds"], abs(r["F"]), color=colours.get(key, "tab:gray"),
                   marker="^" if label.startswith("mortar, scale 1") else "o", label=label)
    for method, (spread, mean, seconds, h) in methods.items():
        ax.scatter(h["seconds"], abs(h["F"]), color="tab:blue", marker="x", s=18)
    ax.set_xscale("log")
    ax.set_xlabel("contact wall time of the run, s")
    ax.set_ylabel("Hertz ball: |F_max error|, %")
    ax.set_title("Hertz ball (x: mortar, each method)")
    ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(path, dpi=110)


def replace_block(text, name, body):
    open_m, close_m = f"<!-- mortar:{name} -->", f"<!-- /mortar:{name} -->"
    a, b = text.find(open_m), text.find(close_m)
    if a < 0 or b < a:
        raise SystemExit(f"docs/verification.md has no markers {open_m} ... {close_m}")
    return text[:a + len(open_m)] + "\n" + body.rstrip("\n") + "\n" + text[b:]


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--exdyn", default=os.path.join(REPO, "build", "release", "src", "app", "exdyn"))
    parser.add_argument("--docs", default=os.path.join(REPO, "docs"))
    parser.add_argument("--quick", action="store_true")
    args = parser.parse_args()
    with tempfile.TemporaryDirectory(prefix="exdyn_mortar_") as work:
        blocks = {}
        blocks["patch"], patch = patch_table(args.exdyn, work)
        print(blocks["patch"], flush=True)
        if not args.quick:
            blocks["hertz"], hertz = hertz_table(args.exdyn, work)
            print(blocks["hertz"], flush=True)
            blocks["methods"], methods = methods_table(args.exdyn, work)
            print(blocks["methods"], flush=True)
            blocks["speed"], ratios = speed_table(args.exdyn, work)
            print(blocks["speed"], flush=True)
            chart(patch, hertz, methods, os.path.join(args.docs, "figures", "mortar_speed_accuracy.png"))
            pressure_chart(hertz, os.path.join(args.docs, "figures", "mortar_hertz_pressure.png"))
    path = os.path.join(args.docs, "verification.md")
    with open(path) as f:
        text = f.read()
    for name, body in blocks.items():
        text = replace_block(text, name, body)
    with open(path, "w") as f:
        f.write(text)
    print(f"wrote {path}")


if __name__ == "__main__":
    main()
