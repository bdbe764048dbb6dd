"""Cases for the local search study: the reference cases, random distorted segments,
the YAML cases file of `exdyn project` (../shared/spec/cli.md), running the command,
reading its CSV and classifying each run against the numpy truth."""

import csv
import io
import re
import subprocess

import numpy as np

import local_search_geometry as geo

CSV_COLUMNS = ["id", "method", "initial_guess", "xi1", "xi2", "converged", "iterations", "evaluations",
               "stationary", "inside", "distance", "gap", "nanoseconds"]

# Used only when src/contact/search_names.hpp cannot be read.
FALLBACK_METHODS = ["newton", "lsp", "steepest_descent", "broyden", "bfgs", "dfp", "simplex", "hybrid", "robust"]

OUTCOMES = ["true closest point", "saddle", "wrong minimum", "not converged"]


def methods_from_header(repo_root):
    """The method names of `--method all`, read from the library's own name table."""
    try:
        text = open(f"{repo_root}/src/contact/search_names.hpp").read()
    except OSError:
        return list(FALLBACK_METHODS)
    names = re.findall(r'\{SearchMethod::\w+,\s*"(\w+)"\}', text)
    return names or list(FALLBACK_METHODS)


# ---------------------------------------------------------------------------
# Reference cases (../shared/reference/local-search-tests.md)


def flat_q8():
    return np.array([[x, y, 0.0] for x, y in geo.NODE_XI])


def reference_segments():
    """name -> (nodes (n, 3), slave point (3,))."""
    flat = flat_q8()
    t2 = np.array([[x, y, 0.5 * x * x + 0.1 * y * y] for x, y in geo.NODE_XI])
    t3 = np.array([[-1, -1, 0], [1, -1, 0.5], [1, 1, 0], [-1, 1, 0.5]], dtype=float)
    t5 = flat.copy()
    t5[4] = [-0.5, -1, 0]
    t5[7] = [-1, -0.5, 0]
    return {
        "T1": (flat, np.array([0.3, -0.2, 0.5])),
        "T2": (t2, np.array([0.0, 0.0, 1.25])),
        "T2b": (t2, np.array([0.0, 0.0, 0.8])),
        "T2c": (t2, np.array([0.0, 0.0, 6.0])),
        "T3": (t3, np.array([0.2, 0.3, 0.8])),
        "T4": (flat, np.array([1.5, 0.2, 0.3])),
        "T4b": (flat, np.array([1.4, 1.3, 0.2])),
        "T5": (t5, np.array([-0.9, -0.95, 0.2])),
    }


# ---------------------------------------------------------------------------
# Random distorted segments


def _jacobian_positive(nodes, samples=9):
    """True when the in-plane Jacobian det(dx/dxi, dy/dxi) > 0 on a samples^2 grid."""
    s = np.linspace(-1, 1, samples)
    X1, X2 = np.meshgrid(s, s, indexing="ij")
    n = nodes.shape[0]
    d1 = geo.shape(n, X1.ravel(), X2.ravel(), 1, 0) @ nodes
    d2 = geo.shape(n, X1.ravel(), X2.ravel(), 0, 1) @ nodes
    det = d1[:, 0] * d2[:, 1] - d1[:, 1] * d2[:, 0]
    return bool(np.all(det > 0.05))


def random_segment(rng, n_nodes, level):
    """One distorted segment on the square [-1,1]^2 (half side 1).

    Every node moves by U(-level, level) in x, y and z; for quad8 each mid-side node gets
    a further out-of-plane offset U(-2 level, 2 level), which curves the edges.
    Segments whose in-plane Jacobian is not clearly positive are redrawn.
    Returns (nodes, redraws)."""
    redraws = 0
    while True:
        nodes = np.concatenate([geo.NODE_XI[:n_nodes], np.zeros((n_nodes, 1))], axis=1)
        nodes += rng.uniform(-level, level, size=nodes.shape)
        if n_nodes == 8:
            nodes[4:, 2] += rng.uniform(-2 * level, 2 * level, size=4)
        if _jacobian_positive(nodes):
            return nodes, redraws
        redraws += 1


_EDGES = [((-1, -1), (1, -1)), ((1, -1), (1, 1)), ((1, 1), (-1, 1)), ((-1, 1), (-1, -1))]


def random_slave_point(rng, nodes, where):
    """A slave point above (gap > 0), below (penetrated) or beside (outside an edge)."""
    one = nodes[None]
    if where in ("above", "below"):
        xi = rng.uniform(-0.95, 0.95, size=(1, 2))
        h = rng.uniform(0.02, 1.5) if where == "above" else -rng.uniform(0.01, 0.5)
        return geo.position(one, xi)[0] + h * geo.unit_normal(one, xi)[0]
    # beside: from a point of an edge, outward in the tangent plane, plus a normal offset
    (a1, b1), (a2, b2) = _EDGES[rng.integers(4)]
    t = rng.uniform(0.05, 0.95)
    xi = np.array([[a1 + t * (a2 - a1), b1 + t * (b2 - b1)]])
    edge_dir = np.array([a2 - a1, b2 - b1], dtype=float)
    ta1, ta2 = geo.tangents(one, xi)
    along = edge_dir[0] * ta1[0] + edge_dir[1] * ta2[0]
    normal = geo.unit_normal(one, xi)[0]
    outward = np.cross(along, normal)  # counter-clockwise edges: along x n points out
    outward /= np.linalg.norm(outward)
    s = rng.uniform(0.05, 0.8)
    h = rng.uniform(-0.3, 0.6)
    return geo.position(one, xi)[0] + s * outward + h * normal


def random_cases(rng, n_nodes, level, where, count):
    nodes = np.empty((count, n_nodes, 3))
    points = np.empty((count, 3))
    redraws = 0
    for k in range(count):
        nodes[k], r = random_segment(rng, n_nodes, level)
        redraws += r
        points[k] = random_slave_point(rng, nodes[k], where)
    return nodes, points, redraws


# ---------------------------------------------------------------------------
# The cases file and the command


def _num(x):
    return repr(float(x))


def write_cases(path, nodes, points, ids, initial_guesses=None):
    """Writes the YAML cases file by hand (flow sequences, round-trip float repr)."""
    out = ["cases:"]
    for k in range(len(ids)):
        n = nodes[k]
        out.append(f"  - id: {int(ids[k])}")
        out.append(f"    segment: {'quad4' if len(n) == 4 else 'quad8'}")
        out.append("    nodes: [" + ", ".join("[" + ", ".join(_num(c) for c in p) + "]" for p in n) + "]")
        out.append("    point: [" + ", ".join(_num(c) for c in points[k]) + "]")
        if initial_guesses is not None:
            out.append("    initial_guess: [" + ", ".join(_num(c) for c in initial_guesses[k]) + "]")
    with open(path, "w") as fh:
        fh.write("\n".join(out) + "\n")


class StudyError(RuntimeError):
    pass


def project_command(exdyn, cases_path, methods="all", initial_guess=None, extra=()):
    cmd = [exdyn, "project", cases_path, "--method", methods]
    if initial_guess is not None:
        cmd += ["--initial-guess", initial_guess]
    return cmd + list(extra)


def run_project(exdyn, cases_path, methods="all", initial_guess=None, extra=()):
    """Runs `exdyn project` and returns its rows as a dict of numpy arrays."""
    return run_project_parallel([project_command(exdyn, cases_path, methods, initial_guess, extra)])[0]


def run_project_parallel(commands):
    """Runs several `exdyn project` commands at once; returns their parsed rows in order."""
    procs = [subprocess.Popen(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True) for cmd in commands]
    outs = [p.communicate() for p in procs]
    results = []
    for cmd, p, (out, err) in zip(commands, procs, outs):
        if p.returncode != 0:
            raise StudyError(f"{' '.join(cmd)} exited {p.returncode}: {err.strip()[:2000]}")
        results.append(parse_csv(out, " ".join(cmd)))
    return results


def parse_csv(text, source="CSV"):
    reader = csv.reader(io.StringIO(text))
    try:
        header = next(reader)
    except StopIteration:
        raise StudyError(f"{source}: empty output")
    header = [h.strip() for h in header]
    missing = [c for c in CSV_COLUMNS if c not in header]
    if missing:
        raise StudyError(f"{source}: CSV lacks columns {missing} (header: {header})")
    col = {c: header.index(c) for c in CSV_COLUMNS}
    rows = [r for r in reader if r]
    bad = [k for k, r in enumerate(rows) if len(r) != len(header)]
    if bad:
        raise StudyError(f"{source}: CSV row {bad[0] + 2} has {len(rows[bad[0]])} fields, header {len(header)}")
    data = {}
    for c in CSV_COLUMNS:
        vals = [r[col[c]].strip() for r in rows]
        try:
            if c in ("method", "initial_guess", "stationary"):
                data[c] = np.array(vals, dtype=object)
            elif c in ("id", "converged", "iterations", "evaluations", "inside"):
                data[c] = np.array([int(v) for v in vals], dtype=np.int64)
            else:
                data[c] = np.array([float(v) for v in vals])
        except ValueError as e:
            raise StudyError(f"{source}: column {c}: {e}")
    return data


# ---------------------------------------------------------------------------
# Classification


def classify(rows, truth, nodes, points, xi_tol=1e-6, dist_rtol=1e-9):
    """Outcome of each CSV row against the truth of its case.

    rows: parsed CSV; truth: closest_point() output indexed by case id; nodes/points by id.
    Returns (outcome array of OUTCOMES strings, distance recomputed from xi by numpy).

    - true closest point: converged and
        * the truth is inside the segment: inside, and xi within xi_tol of the truth or the
          distance within dist_rtol * max(distance, 1) of the true distance (an equally
          close twin, e.g. the two minima of T2, counts);
        * the truth is on the boundary: either the same test (methods that keep xi in the
          segment), or the run ends outside [-1,1]^2 on a minimum: it then tells the
          contact search, correctly, that the closest point is not inside this segment.
    - saddle: converged, not the above, and the Hessian there is indefinite (the program's
      `stationary` says saddle) or negative definite (maximum).
    - wrong minimum: converged anywhere else: a minimum that is not the closest point, a
      point outside the segment when the truth is inside, a point where the gradient is
      not zero.
    - not converged: the method's stopping test was not met.
    """
    ids = rows["id"]
    xi = np.stack([rows["xi1"], rows["xi2"]], axis=-1)
    with np.errstate(all="ignore"):  # a diverged method may return a huge or non-finite xi
        f, _, _, _ = geo.evaluate(nodes[ids], points[ids], xi)
    dist_np = np.sqrt(f)
    t_xi = truth["xi"][ids]
    t_d = truth["distance"][ids]
    interior = truth["interior"][ids]
    conv = rows["converged"] == 1
    inside = rows["inside"] == 1
    close = (np.linalg.norm(xi - t_xi, axis=-1) <= xi_tol) | (
        np.abs(dist_np - t_d) <= dist_rtol * np.maximum(t_d, 1.0))
    stationary = rows["stationary"]
    on_truth = inside & close
    outside_ok = ~interior & ~inside & (stationary == "minimum")
    is_true = conv & (on_truth | outside_ok)
    is_saddle = conv & ~is_true & np.isin(stationary, ["saddle", "maximum"])
    out = np.where(~conv, "not converged",
                   np.where(is_true, "true closest point", np.where(is_saddle, "saddle", "wrong minimum")))
    return out.astype(object), dist_np
