#!/usr/bin/python3
"""The local contact search study of issue 3: writes docs/local-search.md and
docs/figures/local_search_*.png from runs of `exdyn project`.

    /usr/bin/python3 scripts/local_search_study.py [--exdyn PATH] [--out DIR] [--seed N]
    /usr/bin/python3 scripts/local_search_study.py --quick --out /tmp/x   # seconds; a test
    /usr/bin/python3 scripts/local_search_study.py --self-test            # no binary needed

Needs Debian's python3-numpy and python3-matplotlib (run with /usr/bin/python3).
The truth (closest point of each segment) is computed here in numpy, independently of
the C++ library: a 201 x 201 grid of f over [-1,1]^2, then projected Newton with an
active set on the bounds from the lowest grid minima. Numbers in the document are
written only between the `<!-- study:NAME -->` markers, from the run itself.
Exit status: 0 success, 1 a check failed, 2 bad usage.
"""

import argparse
import datetime
import os
import platform
import subprocess
import sys
import tempfile
import time

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import local_search_cases as lc  # noqa: E402
import local_search_geometry as geo  # noqa: E402
import local_search_plots as plots  # noqa: E402

REPO = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))

# --- Table 1 segment: a distorted quad8 bowl (published in the document) -----------------
TABLE1_NODES = np.array([
    [-0.87, -0.88, 0.59],
    [1.06, -0.95, 0.57],
    [1.07, 1.02, 0.57],
    [-0.91, 1.0, 0.56],
    [-0.08, -1.12, 0.06],
    [1.12, 0.08, 0.46],
    [-0.1, 1.1, 0.06],
    [-1.06, 0.04, 0.53],
])  # z = 0.5 x^2 + 0.1 y^2 at the nodes (as T2), then every node moved by up to 0.15
TABLE1_POINT = np.array([0.0, -0.07, 1.26])  # above the bowl, beyond its radius of curvature in x
TABLE1_TOLERANCE = "1e-10"     # the paper's test ||x^k - x^(k-1)|| <= 1e-10
TABLE1_MAX_ITERATIONS = "20000"  # the paper's slowest run took 14900

# The seed paper's Table 1 (../shared/reference/local-search-tests.md): iterations, saddles.
PAPER_TABLE1 = {
    "newton": ("5-28", "3 of 6"),
    "lsp": ("116-137", "0"),
    "steepest_descent": ("14-1543", "0"),
    "broyden": ("9-14900", "0"),
    "bfgs": ("7-23", "0"),
    "dfp": ("7-26", "0"),
    "simplex": ("184-210", "0 (never)"),
}

ROBUSTNESS_MAX_ITERATIONS = "1000"  # so that "not converged" means stuck, not only slow
SEGMENT_TYPES = (4, 8)
LEVELS = (0.1, 0.25, 0.4)
POSITIONS = ("above", "below", "beside")
GUESSES = ("lsp", "center")

# Sizes: every row of `exdyn project` is timed for >= 1 ms, which bounds what fits in minutes.
FULL = dict(per_cell=200, basin_grid=41, basin_grid_untimed=81, table1_repeats=5)
QUICK = dict(per_cell=4, basin_grid=9, basin_grid_untimed=9, table1_repeats=1)


def log(msg):
    print(f"[{time.strftime('%H:%M:%S')}] {msg}", file=sys.stderr, flush=True)


# =============================================================================
# Self-test of the truth against the reference page


def self_test():
    """Asserts the reference page's exact answers come out of the numpy truth."""
    refs = lc.reference_segments()
    expected = {  # name: (xi or None, distance, interior)
        "T1": ((0.3, -0.2), 0.5, True),
        "T2": ((0.7071068, 0.0), 1.2247449, True),
        "T2b": ((0.0, 0.0), 0.8, True),
        "T2c": ((1.0, 1.0), 5.5821143, False),
        "T3": ((0.1610826, 0.2774013), 0.5629727, True),
        "T4": ((1.0, 0.2), 0.5830952, False),
        "T4b": ((1.0, 1.0), 0.5385165, False),
        "T5": ((-0.6228027, -0.8114014), 0.2, True),
    }
    names = list(expected)
    nodes = [refs[k][0] for k in names]
    failures = []
    for k, nd in zip(names, nodes):
        t = geo.closest_point(nd[None], refs[k][1][None])
        xi_exp, d_exp, interior = expected[k]
        xi = t["xi"][0]
        if k in ("T2", "T2c"):  # symmetric twins: compare |xi|
            xi = np.abs(xi)
        if np.abs(xi - xi_exp).max() > 1e-6 or abs(t["distance"][0] - d_exp) > 1e-6 or t["interior"][0] != interior:
            failures.append(f"{k}: got xi {t['xi'][0]}, distance {t['distance'][0]:.7f}, interior {t['interior'][0]}")
    # Stationary points named on the page, found by plain Newton and classified.
    checks = [
        ("T2", (0.0, 0.0), (0.0, 0.0), 1.25, "saddle"),
        ("T2c", (0.0, 0.0), (0.0, 0.0), 6.0, "maximum"),
        ("T2c", (3.0, 0.1), (3.16227766, 0.0), None, "minimum"),
        ("T5", (-1.3, -1.2), (-1.3548, -1.1774), 0.2, "minimum"),
        ("T5", (4.9, 2.0), (4.978, 1.989), 0.2, "minimum"),
    ]
    for k, start, xi_exp, d_exp, kind in checks:
        nd, p = refs[k]
        xi, d, gn, kinds = geo.newton_unconstrained(nd[None], p[None], np.array([start]))
        tol = 1e-3 if k == "T5" else 1e-6  # the page gives T5's outside points to 4 digits
        if (np.abs(xi[0] - xi_exp).max() > tol or gn[0] > 1e-10 or kinds[0] != kind
                or (d_exp is not None and abs(d[0] - d_exp) > 1e-7)):
            failures.append(f"{k} stationary point near {xi_exp}: got {xi[0]}, distance {d[0]}, {kinds[0]}")
    # Shape functions: partition of unity and interpolation at the nodes.
    for n in (4, 8):
        if np.abs(geo.shape(n, geo.NODE_XI[:n, 0], geo.NODE_XI[:n, 1]) - np.eye(n)).max() > 1e-14:
            failures.append(f"quad{n} shape functions do not interpolate the nodes")
        s = np.linspace(-1, 1, 7)
        if np.abs(geo.shape(n, s, s[::-1]).sum(-1) - 1).max() > 1e-14:
            failures.append(f"quad{n} shape functions do not sum to one")
    # Classification on made-up rows for T2 (truth inside) and T4 (truth on the boundary).
    nd = np.stack([refs["T2"][0], refs["T4"][0]])
    pt = np.stack([refs["T2"][1], refs["T4"][1]])
    truth = geo.closest_point(nd, pt)
    rows = {
        "id": np.array([0, 0, 0, 0, 0, 1, 1, 1]),
        "xi1": np.array([-0.70710678118, 0.0, 0.7071067811865, 2.0, 0.3, 1.5, 1.0, 0.5]),
        "xi2": np.array([0.0, 0.0, 0.0, 0.0, 0.1, 0.2, 0.2, 0.2]),
        "converged": np.array([1, 1, 1, 1, 0, 1, 1, 1]),
        "inside": np.array([1, 1, 1, 0, 1, 0, 1, 1]),
        "stationary": np.array(["minimum", "saddle", "minimum", "minimum", "none", "minimum", "none", "none"],
                               dtype=object),
    }
    want = ["true closest point", "saddle", "true closest point", "wrong minimum", "not converged",
            "true closest point", "true closest point", "wrong minimum"]
    got, _ = lc.classify(rows, truth, nd, pt)
    if list(got) != want:
        failures.append(f"classification: got {list(got)}, want {want}")
    return failures


# =============================================================================
# Running the command and checking what it prints


class Runner:
    """Writes cases files, runs `exdyn project --method all` on them and checks the rows."""

    def __init__(self, exdyn, workdir, methods):
        self.exdyn = exdyn
        self.workdir = workdir
        self.methods = methods
        self.count = 0
        self.seconds = 0.0
        help_text = subprocess.run([exdyn, "project", "--help"], capture_output=True, text=True).stdout
        # Timing every projection for at least 1 ms dominates the study's run time; where the
        # command lets us, the basins (which need no time) are run untimed.
        self.untimed = ["--timing-seconds", "0"] if "--timing-seconds" in help_text else None

    def run(self, nodes, points, initial_guess=None, guesses_per_case=1, starts=None, extra=(), method=None):
        return self.run_parallel([(nodes, points, initial_guess, guesses_per_case, starts, extra)], method)[0]

    def run_parallel(self, jobs, method=None):
        """jobs: (nodes, points, initial_guess, guesses_per_case, starts, extra); all run at once.
        Every method (`--method all`) unless `method` names one."""
        commands = []
        for nodes, points, initial_guess, _, starts, extra in jobs:
            self.count += 1
            path = os.path.join(self.workdir, f"cases_{self.count:03d}.yaml")
            lc.write_cases(path, nodes, points, np.arange(len(nodes)), starts)
            commands.append(lc.project_command(self.exdyn, path, method or "all", initial_guess, extra))
        t0 = time.time()
        results = lc.run_project_parallel(commands)
        self.seconds += time.time() - t0
        for cmd, rows, (nodes, points, _, guesses_per_case, _, _) in zip(commands, results, jobs):
            os.remove(cmd[2])
            check_rows(rows, len(nodes), [method] if method else self.methods, guesses_per_case, nodes, points)
        return results


def check_rows(rows, n_cases, methods, guesses_per_case, nodes, points):
    got = set(rows["method"])
    if got != set(methods):
        raise lc.StudyError(f"--method all gave methods {sorted(got)}, expected {sorted(methods)}")
    want = n_cases * len(methods) * guesses_per_case
    if len(rows["id"]) != want:
        raise lc.StudyError(f"{len(rows['id'])} CSV rows, expected {want}")
    if set(rows["id"]) != set(range(n_cases)):
        raise lc.StudyError("CSV ids do not match the cases file")
    xi = np.stack([rows["xi1"], rows["xi2"]], axis=-1)
    finite = np.isfinite(xi).all(axis=1)
    f = np.full(len(xi), np.nan)
    with np.errstate(all="ignore"):  # a diverged method may return a huge xi
        f[finite] = geo.evaluate(nodes[rows["id"][finite]], points[rows["id"][finite]], xi[finite])[0]
        d = np.sqrt(f)
        # far outside the segment (a diverged run) the two evaluations differ by round-off only
        moderate = finite & (np.abs(xi).max(axis=1) < 1e3)
        bad = moderate & (np.abs(d - rows["distance"]) > 1e-9 * np.maximum(d, 1.0))
    if bad.any():
        k = np.flatnonzero(bad)[0]
        raise lc.StudyError(f"distance {rows['distance'][k]} of case {rows['id'][k]} ({rows['method'][k]}) "
                            f"differs from |ys - y(xi)| = {d[k]} computed here: shape functions or node order")
    m = np.abs(xi).max(axis=1)
    wrong_inside = finite & (((m < 1 - 1e-6) & (rows["inside"] != 1)) | ((m > 1 + 1e-6) & (rows["inside"] != 0)))
    if wrong_inside.any():
        k = np.flatnonzero(wrong_inside)[0]
        raise lc.StudyError(f"case {rows['id'][k]} ({rows['method'][k]}): inside={rows['inside'][k]} at xi {xi[k]}")
    kinds = {"minimum", "saddle", "maximum", "none"}
    if not set(rows["stationary"]) <= kinds:
        raise lc.StudyError(f"stationary column has {set(rows['stationary']) - kinds}")
    if not np.all(rows["nanoseconds"] > 0):
        raise lc.StudyError("nanoseconds column has values <= 0")


# =============================================================================
# 1. Table 1 again


def study_table1(runner, repeats):
    nodes, point = TABLE1_NODES[None], TABLE1_POINT[None]
    truth = geo.closest_point(nodes, point)
    extra = ["--tolerance", TABLE1_TOLERANCE, "--max-iterations", TABLE1_MAX_ITERATIONS]
    runs = [runner.run(nodes, point, "all", 6, extra=extra) for _ in range(repeats)]
    rows = runs[0]
    for r in runs[1:]:  # the same deterministic runs; only the times differ
        if not np.array_equal(r["iterations"], rows["iterations"]):
            raise lc.StudyError("Table 1: iterations differ between repeated runs")
    ns = np.median(np.stack([r["nanoseconds"] for r in runs]), axis=0)
    outcome, _ = lc.classify(rows, truth, nodes, point)
    guesses = list(dict.fromkeys(rows["initial_guess"]))
    ref = np.flatnonzero((rows["method"] == "newton") & (rows["initial_guess"] == guesses[0]))[0]
    # stationary points of this f, to say where saddles are
    s = np.linspace(-4.0, 4.0, 81)
    S1, S2 = np.meshgrid(s, s, indexing="ij")
    starts = np.stack([S1.ravel(), S2.ravel()], -1)
    sxi, sd, sgn, skind = geo.newton_unconstrained(np.repeat(nodes, len(starts), 0), np.repeat(point, len(starts), 0),
                                                   starts, iterations=60)
    stat = cluster_stationary(sxi, sd, sgn, skind, box=4.0)
    # LSP (Gauss-Newton) near the answer: e_new = A^-1 (r.y_,ab) e, A_ab = a_a.a_b, so it converges
    # linearly with the spectral radius of that matrix as its rate.
    xi = truth["xi"]
    _, _, H, r = geo.evaluate(nodes, point, xi)
    a1, a2 = geo.tangents(nodes, xi)
    A = np.array([[a1[0] @ a1[0], a1[0] @ a2[0]], [a1[0] @ a2[0], a2[0] @ a2[0]]])
    M = A - H[0] / 2  # = r.y_,ab
    lsp_rate = np.abs(np.linalg.eigvals(np.linalg.solve(A, M))).max()
    # the Hessian at each start: where it is indefinite a first Newton step (and B0 = H^-1) heads for a saddle
    a1, a2 = geo.tangents(nodes, np.zeros((1, 2)))
    r0 = point - geo.position(nodes, np.zeros((1, 2)))
    A0 = np.array([[a1[0] @ a1[0], a1[0] @ a2[0]], [a1[0] @ a2[0], a2[0] @ a2[0]]])
    start_xi = {"lsp": np.linalg.solve(A0, [r0[0] @ a1[0], r0[0] @ a2[0]]), "center": np.zeros(2)}
    start_xi.update({f"corner{i + 1}": geo.NODE_XI[i] for i in range(4)})
    starts_h = {}
    for g in guesses:
        if g in start_xi:
            H0 = geo.evaluate(nodes, point, start_xi[g][None])[2]
            starts_h[g] = (start_xi[g], geo.stationary_kind(H0)[0], np.linalg.eigvalsh(H0[0]))
    return dict(rows=rows, ns=ns, ref_ns=ns[ref], outcome=outcome, guesses=guesses, truth=truth,
                stationary=stat, repeats=repeats, lsp_rate=lsp_rate, starts_h=starts_h)


def cluster_stationary(xi, d, gn, kind, box):
    """Distinct stationary points with |xi| <= box, from many Newton runs."""
    keep = (gn < 1e-9) & np.all(np.abs(xi) <= box + 1e-9, axis=1) & np.isfinite(xi).all(axis=1)
    found = []
    for x, dd, k in zip(xi[keep], d[keep], kind[keep]):
        if not any(np.linalg.norm(x - y[0]) < 1e-6 for y in found):
            found.append((x, dd, k))
    found.sort(key=lambda t: t[1])
    return found


def fmt_xi(x, digits=4):
    return "(" + ", ".join(f"{v:.{digits}f}".replace("-0." + "0" * digits, "0." + "0" * digits) for v in x) + ")"


def table1_markdown(t1, methods):
    rows, ns, ref_ns = t1["rows"], t1["ns"], t1["ref_ns"]
    guesses = t1["guesses"]
    mark = {"saddle": " **sp**", "not converged": " nc", "wrong minimum": " wm", "true closest point": ""}
    out = []
    out.append("Segment (quad8; corners counter-clockwise, then mid-sides) and slave point:\n")
    out.append("| node | x | y | z |\n|---|---|---|---|")
    labels = ["(-1,-1)", "(1,-1)", "(1,1)", "(-1,1)", "(0,-1)", "(1,0)", "(0,1)", "(-1,0)"]
    for lab, p in zip(labels, TABLE1_NODES):
        out.append(f"| {lab} | {p[0]:g} | {p[1]:g} | {p[2]:g} |")
    p = TABLE1_POINT
    out.append(f"| slave point | {p[0]:g} | {p[1]:g} | {p[2]:g} |\n")
    tr = t1["truth"]
    out.append(f"Closest point (numpy truth): xi = {fmt_xi(tr['xi'][0], 7)}, distance {tr['distance'][0]:.7f}. "
               "Stationary points of f with |xi_a| <= 4 (plain Newton from an 81 x 81 grid of starts): "
               + "; ".join(f"{k} at {fmt_xi(x)} ({'inside' if np.all(np.abs(x) <= 1) else 'outside'}, "
                           f"distance {d:.4f})" for x, d, k in t1["stationary"]) + ".\n")
    definite = {"minimum": "positive definite", "saddle": "indefinite", "maximum": "negative definite"}
    out.append("Hessian of f at the six starts (eigenvalues): " + "; ".join(
        f"`{g}` {fmt_xi(x, 3)}: {definite.get(k, k)} ({ev[0]:.3f}, {ev[1]:.3f})"
        for g, (x, k, ev) in t1["starts_h"].items()) + ".\n")
    rate = t1["lsp_rate"]
    out.append(f"LSP's linear rate at the closest point (spectral radius of A^-1 (r.y_,ab), A_ab = a_a.a_b): "
               f"{rate:.3f}, so each iteration divides the error by {1 / rate:.3f} and reaching 1e-10 from an error "
               f"of 1 takes about {np.log(1e-10) / np.log(rate):.0f} iterations.\n")
    out.append(f"Each cell: iterations / time normalised to Newton from the LSP guess "
               f"({ref_ns:.0f} ns, median of {t1['repeats']} runs). Marks: **sp** converged on a saddle, "
               f"wm converged elsewhere than the closest point, nc not converged. "
               f"`--tolerance {TABLE1_TOLERANCE} --max-iterations {TABLE1_MAX_ITERATIONS}`.\n")
    corner_xi = {f"corner{i + 1}": f" ({x:+.0f},{y:+.0f})" for i, (x, y) in enumerate(geo.NODE_XI[:4])}
    out.append("| method | " + " | ".join(f"`{g}`{corner_xi.get(g, '')}" for g in guesses)
               + " | iterations (ours) | paper |")
    out.append("|---|" + "---|" * (len(guesses) + 2))
    summary = []
    for m in methods:
        cells = []
        its = []
        nsp = 0
        for g in guesses:
            k = np.flatnonzero((rows["method"] == m) & (rows["initial_guess"] == g))[0]
            o = t1["outcome"][k]
            nsp += o == "saddle"
            its.append(rows["iterations"][k])
            cells.append(f"{rows['iterations'][k]} / {ns[k] / ref_ns:.2f}{mark[o]}")
        ours = f"{min(its)}-{max(its)}" + (f", {nsp} sp" if nsp else "")
        paper = PAPER_TABLE1.get(m)
        if paper is None:
            paper_txt = "not in the paper"
        else:
            paper_txt = paper[0] + (f", {paper[1]} sp" if paper[1] not in ("0", "0 (never)") else "")
        out.append(f"| {m} | " + " | ".join(cells) + f" | {ours} | {paper_txt} |")
        summary.append((m, min(its), max(its), nsp, sum(t1["outcome"][k] == "not converged" for k in
                        np.flatnonzero(rows["method"] == m)), paper))
    out.append("\nOur iteration ranges against the paper's (generated from the table above):\n")
    for m, lo, hi, nsp, nnc, paper in summary:
        if paper is None:
            out.append(f"- {m}: {lo}-{hi} iterations, {nsp} saddles, {nnc} not converged; not in the paper.")
            continue
        plo, phi = (int(v) for v in paper[0].split("-"))
        if lo >= plo and hi <= phi:
            where = "inside the paper's range"
        elif hi < plo:
            where = "below the paper's range"
        elif lo > phi:
            where = "above the paper's range"
        else:
            where = "overlapping the paper's range"
        out.append(f"- {m}: {lo}-{hi} iterations against {paper[0]} ({where}); {nsp} of {len(guesses)} runs "
                   f"on saddles against {paper[1]}; {nnc} not converged.")
    return "\n".join(out)


# =============================================================================
# 2. Robustness


def study_robustness(runner, rng, per_cell):
    """Random segments, their truth, every method from the lsp guess and Newton from the centre."""
    batches = []
    redraw_total = 0
    for n_nodes in SEGMENT_TYPES:
        for level in LEVELS:
            nodes, points, where = [], [], []
            for pos in POSITIONS:
                nd, pt, redraws = lc.random_cases(rng, n_nodes, level, pos, per_cell)
                redraw_total += redraws
                nodes.append(nd)
                points.append(pt)
                where += [pos] * per_cell
            nodes = np.concatenate(nodes)
            points = np.concatenate(points)
            t0 = time.time()
            truth = geo.closest_point(nodes, points)
            log(f"quad{n_nodes} level {level}: truth of {len(nodes)} cases in {time.time() - t0:.1f} s")
            if truth["gradnorm"].max() > 1e-8:
                raise lc.StudyError(f"truth not converged: projected gradient {truth['gradnorm'].max():.2e}")
            for guess in GUESSES:  # every method from lsp; Newton also from the centre (the reference page's runs)
                rows = runner.run(nodes, points, guess, extra=["--max-iterations", ROBUSTNESS_MAX_ITERATIONS],
                                  method=None if guess == "lsp" else "newton")
                outcome, _ = lc.classify(rows, truth, nodes, points)
                batches.append(dict(n_nodes=n_nodes, level=level, guess=guess, rows=rows, outcome=outcome,
                                    where=np.array(where, dtype=object)[rows["id"]],
                                    interior=truth["interior"][rows["id"]],
                                    true_distance=truth["distance"][rows["id"]], true_xi=truth["xi"][rows["id"]]))
    # one flat table
    cat = {k: np.concatenate([b["rows"][k] for b in batches]) for k in batches[0]["rows"]}
    cat["outcome"] = np.concatenate([b["outcome"] for b in batches])
    cat["where"] = np.concatenate([b["where"] for b in batches])
    cat["interior"] = np.concatenate([b["interior"] for b in batches])
    cat["true_distance"] = np.concatenate([b["true_distance"] for b in batches])
    cat["true_xi"] = np.concatenate([b["true_xi"] for b in batches])
    cat["n_nodes"] = np.concatenate([np.full(len(b["outcome"]), b["n_nodes"]) for b in batches])
    cat["level"] = np.concatenate([np.full(len(b["outcome"]), b["level"]) for b in batches])
    cat["guess"] = np.concatenate([np.full(len(b["outcome"]), b["guess"], dtype=object) for b in batches])
    return dict(rows=cat, per_cell=per_cell, redraws=redraw_total,
                cases=len(SEGMENT_TYPES) * len(LEVELS) * len(POSITIONS) * per_cell)


def pct(x):
    return f"{100.0 * x:.1f}"


def robustness_runs(r, methods):
    """(label, row mask) of each line of the robustness tables."""
    runs = [(f"{m}", (r["method"] == m) & (r["guess"] == "lsp")) for m in methods]
    runs.append(("newton from the centre", (r["method"] == "newton") & (r["guess"] == "center")))
    return runs


def robustness_markdown(rb, methods):
    r = rb["rows"]
    runs = robustness_runs(r, methods)
    success = r["outcome"] == "true closest point"
    first = runs[0][1]
    out = []
    out.append(f"{rb['cases']} random cases: quad4 and quad8 x distortion levels {', '.join(map(str, LEVELS))} x "
               f"slave points {', '.join(POSITIONS)}, {rb['per_cell']} of each, so {rb['cases'] // len(LEVELS)} "
               f"per level ({rb['redraws']} segments were drawn again because their in-plane Jacobian was not "
               f"positive). The closest point of the segment lies on its boundary in "
               f"{pct(1 - r['interior'][first].mean())} % of the cases "
               f"({pct(1 - r['interior'][first & (r['where'] == 'beside')].mean())} % of the `beside` ones). "
               f"Runs: `--method all --initial-guess lsp`, and `--method newton --initial-guess center` (the runs "
               f"of the reference page), with `--max-iterations {ROBUSTNESS_MAX_ITERATIONS}` and the default "
               "tolerance.\n")
    out.append(f"**Outcomes** (% of the {rb['cases']} runs of each line):\n")
    out.append("| method | " + " | ".join(lc.OUTCOMES) + " | wrong minima outside the segment |")
    out.append("|---|" + "---|" * (len(lc.OUTCOMES) + 1))
    for label, sel in runs:
        wrong = sel & (r["outcome"] == "wrong minimum")
        out.append(f"| {label} | " + " | ".join(pct((r["outcome"][sel] == o).mean()) for o in lc.OUTCOMES)
                   + f" | {(wrong & (r['inside'] == 0)).sum()} of {wrong.sum()} |")
    out.append("")
    out.append("**True closest point by segment and distortion level** (% of "
               f"{rb['per_cell'] * len(POSITIONS)} runs per cell):\n")
    cols = [(n, lv) for n in SEGMENT_TYPES for lv in LEVELS]
    out.append("| method | " + " | ".join(f"quad{n} {lv}" for n, lv in cols) + " |")
    out.append("|---|" + "---|" * len(cols))
    for label, sel in runs:
        cells = [pct(success[sel & (r["n_nodes"] == n) & (r["level"] == lv)].mean()) for n, lv in cols]
        out.append(f"| {label} | " + " | ".join(cells) + " |")
    out.append("")
    out.append("**Outcomes by slave point position** (% of "
               f"{rb['per_cell'] * len(LEVELS) * len(SEGMENT_TYPES)} runs per cell: true closest point / saddle / "
               "wrong minimum / not converged):\n")
    out.append("| method | " + " | ".join(POSITIONS) + " |")
    out.append("|---|" + "---|" * len(POSITIONS))
    for label, sel in runs:
        cells = []
        for pos in POSITIONS:
            m = sel & (r["where"] == pos)
            cells.append(" / ".join(pct((r["outcome"][m] == o).mean()) for o in lc.OUTCOMES))
        out.append(f"| {label} | " + " | ".join(cells) + " |")
    out.append("")
    if "robust" in methods:
        miss = np.flatnonzero((r["method"] == "robust") & (r["guess"] == "lsp") & ~success)
        out.append(f"Runs of `robust` not on the true closest point: {len(miss)} of {rb['cases']}"
                   + (":" if len(miss) else ".") + "\n")
        for k in miss[:10]:
            out.append(f"- quad{r['n_nodes'][k]}, level {r['level'][k]}, slave point {r['where'][k]} (case "
                       f"{r['id'][k]} of its batch): {r['outcome'][k]} at xi = {fmt_xi((r['xi1'][k], r['xi2'][k]))}, "
                       f"distance {r['distance'][k]:.6f}; the closest point is at xi = {fmt_xi(r['true_xi'][k])} "
                       f"({'inside' if r['interior'][k] else 'on the boundary'}), "
                       f"distance {r['true_distance'][k]:.6f}.")
        if len(miss):
            out.append("")
    vals = [pct(success[runs[-1][1] & (r["n_nodes"] == 8) & (r["level"] == lv)].mean()) for lv in LEVELS]
    out.append(f"Newton from the centre on quad8 at levels {', '.join(map(str, LEVELS))}: "
               f"{' %, '.join(vals)} % on the true closest point; the reference page quotes roughly 80, 72 and "
               "64 % on its own random quad8 segments, whose distortion and slave points it does not specify.")
    return "\n".join(out)


# =============================================================================
# 3. Basins


def study_basins(runner, grid):
    """Every method from each point of a grid x grid of starts on [-1,1]^2, for T2 and T5."""
    s = np.linspace(-1.0, 1.0, grid)
    S1, S2 = np.meshgrid(s, s, indexing="ij")
    starts = np.stack([S1.ravel(), S2.ravel()], -1)  # case id k = i * grid + j
    n = len(starts)
    names = ("T2", "T5")
    jobs = []
    for name in names:
        nodes, point = lc.reference_segments()[name]
        jobs.append((np.repeat(nodes[None], n, 0), np.repeat(point[None], n, 0), None, 1, starts,
                     ["--max-iterations", ROBUSTNESS_MAX_ITERATIONS] + (runner.untimed or [])))
    results = runner.run_parallel(jobs)  # the times are not used: the two runs may share the CPU
    res = {}
    for name, rows, job in zip(names, results, jobs):
        nodes, point = job[0][0], job[1][0]
        truth = geo.closest_point(nodes[None], point[None])
        # every stationary point of f, wherever it lies (T5's outside minima too)
        w = np.linspace(-6, 6, 61)
        W1, W2 = np.meshgrid(w, w, indexing="ij")
        ws = np.stack([W1.ravel(), W2.ravel()], -1)
        sxi, sd, sgn, skind = geo.newton_unconstrained(np.repeat(nodes[None], len(ws), 0),
                                                       np.repeat(point[None], len(ws), 0), ws, iterations=80)
        stat = cluster_stationary(sxi, sd, sgn, skind, box=1e3)
        labels, label_names = label_endpoints(rows, stat, truth)
        closest = [x for x, d, k in stat if k == "minimum" and np.all(np.abs(x) <= 1)
                   and abs(d - truth["distance"][0]) < 1e-9] or [truth["xi"][0]]
        res[name] = dict(rows=rows, grid=grid, s=s, labels=labels, label_names=label_names, stationary=stat,
                         truth=truth, closest=closest)
    return res


def label_endpoints(rows, stat, truth):
    """Label index of each run and the label names.

    Each minimum of f gets its own label (the closest point first); saddles and maxima
    share one label each; then "converged elsewhere" and "not converged".
    """
    xi = np.stack([rows["xi1"], rows["xi2"]], -1)
    conv = rows["converged"] == 1
    t_xi, t_d = truth["xi"][0], truth["distance"][0]
    kind_of = np.full(len(xi), "", dtype=object)
    which = np.full(len(xi), -1)
    for j, (x, d, k) in enumerate(stat):
        hit = conv & (np.linalg.norm(xi - x, axis=1) < 1e-5) & (which < 0)
        which[hit] = j
        kind_of[hit] = k
    # a method that keeps xi in the segment may stop on the truth when it is on the boundary
    on_truth = conv & (which < 0) & (np.linalg.norm(xi - t_xi, axis=1) < 1e-6)
    names, labels = [], np.full(len(xi), -1)

    def add(name, mask):
        if mask.any():
            names.append(name)
            labels[mask] = len(names) - 1

    minima = [j for j, (x, d, k) in enumerate(stat) if k == "minimum"]
    minima.sort(key=lambda j: (not (np.all(np.abs(stat[j][0]) <= 1) and abs(stat[j][1] - t_d) < 1e-9), stat[j][1]))
    for j in minima:
        x, d, _ = stat[j]
        inside = np.all(np.abs(x) <= 1)
        tag = "closest point" if inside and abs(d - t_d) < 1e-9 else ("minimum inside" if inside else "minimum outside")
        add(f"{tag} {fmt_xi(x + 0.0, 2)}, d = {d:.3f}", which == j)
    add("closest point on the boundary", on_truth)
    add("saddle", np.isin(kind_of, ["saddle", "degenerate"]))
    add("maximum", kind_of == "maximum")
    add("converged elsewhere", conv & (labels < 0))
    add("not converged", ~conv)
    return labels, names


def basins_markdown(bs, methods, figure_names):
    out = []
    for name in ("T2", "T5"):
        b = bs[name]
        r = b["rows"]
        out.append(f"**{name}**: {b['grid']} x {b['grid']} starting points on [-1,1]^2, "
                   f"`--max-iterations {ROBUSTNESS_MAX_ITERATIONS}`, "
                   f"![basins of {name}](figures/{figure_names[name]})\n")
        out.append("Share of starting points (%) ending on each point:\n")
        out.append("| method | " + " | ".join(b["label_names"]) + " |")
        out.append("|---|" + "---|" * len(b["label_names"]))
        for m in methods:
            sel = r["method"] == m
            shares = [pct((b["labels"][sel] == j).mean()) for j in range(len(b["label_names"]))]
            out.append(f"| {m} | " + " | ".join(shares) + " |")
        out.append("")
    return "\n".join(out)


# =============================================================================
# 4. Speed against accuracy


def speed_table(rb, methods):
    r = rb["rows"]
    out = []
    for m in methods:
        sel = (r["method"] == m) & (r["guess"] == "lsp")
        out.append(dict(method=m, mean_ns=r["nanoseconds"][sel].mean(), median_ns=np.median(r["nanoseconds"][sel]),
                        success=(r["outcome"][sel] == "true closest point").mean(),
                        iterations=r["iterations"][sel].mean(), evaluations=r["evaluations"][sel].mean()))
    return out


def speed_markdown(sp, figure_name, cases):
    out = [f"All {cases} random cases, initial guess `lsp`. ![speed against accuracy](figures/{figure_name})\n",
           "| method | success % | mean ns | median ns | mean iterations | mean evaluations |",
           "|---|---|---|---|---|---|"]
    for s in sorted(sp, key=lambda s: s["mean_ns"]):
        out.append(f"| {s['method']} | {pct(s['success'])} | {s['mean_ns']:.0f} | {s['median_ns']:.0f} | "
                   f"{s['iterations']:.1f} | {s['evaluations']:.1f} |")
    # the methods no other method beats on both counts
    front = [a for a in sp if not any(b["mean_ns"] <= a["mean_ns"] and b["success"] >= a["success"]
                                      and (b["mean_ns"] < a["mean_ns"] or b["success"] > a["success"]) for b in sp)]
    front.sort(key=lambda s: s["mean_ns"])
    fastest = front[0]
    out.append("\nNo other method is both faster and more often right than: "
               + ", ".join(f"{a['method']} ({a['mean_ns']:.0f} ns, {pct(a['success'])} %)" for a in front) + ". "
               + "Mean time relative to " + fastest["method"] + ": "
               + ", ".join(f"{a['method']} {a['mean_ns'] / fastest['mean_ns']:.1f}x"
                           for a in sorted(sp, key=lambda s: s["mean_ns"]) if a is not fastest) + ".")
    return "\n".join(out)


# =============================================================================
# The document


MY_SECTIONS = [  # (heading, marker names) in document order; library sections in between
    ("## Table 1 again", ["table1"]),
    ("## Robustness", ["robustness"]),
    ("## Basins of attraction", ["basins"]),
    ("## Speed against accuracy", ["speed"]),
    ("## How to reproduce", ["stamp"]),
]
LIBRARY_SECTIONS = ["## Methods as implemented", "## The robust method"]


def skeleton():
    parts = ["# Local contact search\n",
             "The local search finds, for a slave node and a master segment, the point of the segment "
             "closest to the node (docs of issue 3).\n"]
    for h in LIBRARY_SECTIONS:
        parts.append(f"{h}\n\n(see the library section below)\n")
    for h, markers in MY_SECTIONS:
        parts.append(f"{h}\n")
        for mk in markers:
            parts.append(f"<!-- study:{mk} -->\n<!-- /study:{mk} -->\n")
    return "\n".join(parts)


def replace_block(text, name, body):
    open_m, close_m = f"<!-- study:{name} -->", f"<!-- /study:{name} -->"
    a = text.find(open_m)
    b = text.find(close_m)
    if a < 0 or b < a:
        # the heading of the block's section exists? put the markers right under it
        heading = next(h for h, ms in MY_SECTIONS if name in ms)
        h = text.find(heading + "\n")
        if h < 0:
            text = text.rstrip("\n") + f"\n\n{heading}\n\n{open_m}\n{close_m}\n"
        else:
            e = h + len(heading) + 1
            text = text[:e] + f"\n{open_m}\n{close_m}\n" + text[e:]
        a = text.find(open_m)
        b = text.find(close_m)
    return text[:a + len(open_m)] + "\n" + body.rstrip("\n") + "\n" + text[b:]


def cpu_model():
    try:
        for line in open("/proc/cpuinfo"):
            if line.startswith("model name"):
                return line.split(":", 1)[1].strip()
    except OSError:
        pass
    return platform.processor() or "unknown CPU"


def stamp_markdown(args, seconds, runner, exdyn):
    try:
        version = subprocess.run([exdyn, "--version"], capture_output=True, text=True).stdout.strip().splitlines()[0]
    except OSError:
        version = "?"
    load = os.getloadavg()
    shown = os.path.relpath(exdyn, REPO) if exdyn.startswith(REPO + os.sep) else exdyn
    return (f"Numbers above: run of {datetime.datetime.now(datetime.timezone.utc):%Y-%m-%d %H:%M} UTC, "
            f"`{version}` (`{shown}`), on {cpu_model()} ({os.cpu_count()} logical CPUs, load average "
            f"{load[0]:.1f} at the end of the run), seed {args.seed}"
            f"{', --quick sizes' if args.quick else ''}; {runner.count} runs of `exdyn project` took "
            f"{runner.seconds:.0f} s of the study's {seconds:.0f} s.")


# =============================================================================


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--exdyn", default=os.path.join(REPO, "build/release/src/app/exdyn"),
                    help="the exdyn executable (default: build/release/src/app/exdyn in the repository)")
    ap.add_argument("--out", default=os.path.join(REPO, "docs"),
                    help="where local-search.md and figures/ are written (default: docs/)")
    ap.add_argument("--quick", action="store_true", help="small sizes: a test that the study runs (seconds)")
    ap.add_argument("--seed", type=int, default=1, help="seed of the random segments (default 1)")
    ap.add_argument("--self-test", action="store_true", help="check the numpy truth on the reference cases, then stop")
    args = ap.parse_args()

    t_start = time.time()
    failures = self_test()
    if failures:
        for f in failures:
            print(f"self-test FAILED: {f}", file=sys.stderr)
        return 1
    log("self-test passed: T1-T5 answers of ../shared/reference/local-search-tests.md reproduced")
    if args.self_test:
        return 0

    exdyn = os.path.abspath(args.exdyn)
    if not os.access(exdyn, os.X_OK):
        print(f"error: no executable at {exdyn} (build it, or pass --exdyn)", file=sys.stderr)
        return 1
    sizes = QUICK if args.quick else FULL
    methods = lc.methods_from_header(REPO)
    out_dir = os.path.abspath(args.out)
    fig_dir = os.path.join(out_dir, "figures")
    os.makedirs(fig_dir, exist_ok=True)
    doc_path = os.path.join(out_dir, "local-search.md")

    rng = np.random.default_rng(args.seed)
    with tempfile.TemporaryDirectory(prefix="local_search_study_") as work:
        runner = Runner(exdyn, work, methods)
        try:
            log("Table 1")
            t1 = study_table1(runner, sizes["table1_repeats"])
            log("robustness")
            rb = study_robustness(runner, rng, sizes["per_cell"])
            log("basins")
            bs = study_basins(runner, sizes["basin_grid_untimed" if runner.untimed else "basin_grid"])
        except lc.StudyError as e:
            print(f"study FAILED: {e}", file=sys.stderr)
            return 1

    figs = {"T2": "local_search_basins_t2.png", "T5": "local_search_basins_t5.png"}
    for name in ("T2", "T5"):
        plots.basins(bs[name], methods, os.path.join(fig_dir, figs[name]), name)
    sp = speed_table(rb, methods)
    speed_fig = "local_search_speed_accuracy.png"
    plots.speed_accuracy(sp, os.path.join(fig_dir, speed_fig), rb["cases"])
    for name in list(figs.values()) + [speed_fig]:
        size = os.path.getsize(os.path.join(fig_dir, name))
        if size > 200_000:
            print(f"check FAILED: {name} is {size} bytes (> 200 KB)", file=sys.stderr)
            return 1

    text = open(doc_path).read() if os.path.exists(doc_path) else skeleton()
    text = replace_block(text, "table1", table1_markdown(t1, methods))
    text = replace_block(text, "robustness", robustness_markdown(rb, methods))
    text = replace_block(text, "basins", basins_markdown(bs, methods, figs))
    text = replace_block(text, "speed", speed_markdown(sp, speed_fig, rb["cases"]))
    text = replace_block(text, "stamp", stamp_markdown(args, time.time() - t_start, runner, exdyn))
    with open(doc_path, "w") as fh:
        fh.write(text)
    log(f"wrote {doc_path} and {len(figs) + 1} figures in {fig_dir} ({time.time() - t_start:.0f} s)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
