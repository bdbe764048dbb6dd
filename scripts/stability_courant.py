#!/usr/bin/python3
"""The largest stable Courant number of the plate case, by bisection (docs/stability.md).

    /usr/bin/python3 scripts/stability_courant.py [--exdyn PATH] [--mesh N] [--steps S]
                                                  [--tolerance T] [--check]

Runs input/plate_impact_reference.yaml on an N x 1 x N mesh for S steps at a trial
Courant number c (time.end_time = S c dt_rule, dt_rule the step of the formulation's
rule, read from a one-step run) and calls c stable when the run completes: an
unstable run is stopped by the energy guard (exit 1). Bisects on [0.5, 1.5] (hex8,
hex8r) or [0.5, 3.0] (hex20, hex20r: their rule is each element's own 2 / omega_max,
a lower bound of the mesh's, so the limit is at least 1) to the tolerance, and
prints a Markdown table with the
theory (1.0 for the regular cube mesh: the lumped-mass chain's omega_max dt = 2 c) and,
for Courant 1.5, the step at which the guard stopped the run. The theory: 1.0 on an infinite regular
mesh; for hex8 on this finite plate the exact limit from the eigenvalues of M^-1 K
(lower: the free edges' nodes carry half the mass). --check exits 1 unless the hex8
bracket holds the exact limit, each 8-node limit is within 0.01 of 1.0 and each
20-node limit is at least 1.0 (the rule stays below the stable step), and the first
unstable Courant number tried above each limit is caught within 300 steps (1.5 for
the 8-node ones).
"""

import argparse
import json
import math
import os
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
C1 = math.sqrt((1.211538461538e11 + 2 * 8.076923076923e10) / 7800.0)  # m/s, steel of the deck
D = 2.5e-3  # plate side, m


def run(exdyn, out, form, courant, n, steps, rule_step=None):
    """rule_step: the step of the formulation's rule at Courant 1 (s); h / c1 if None."""
    h = D / n
    rule_step = h / C1 if rule_step is None else rule_step
    cmd = [exdyn, "run", os.path.join(ROOT, "input", "plate_impact_reference.yaml"), "--quiet",
           "--output", out, "--set", "name=c",
           "--set", f"parts[0].elements=[{n},1,{n}]",
           "--set", f"parts[0].box={{min: [{-D}, 0, 0], max: [0, {h}, {D}]}}",
           "--set", f"parts[0].formulation={form}",
           "--set", f"time.courant={courant!r}",
           "--set", f"time.end_time={steps * courant * rule_step!r}",
           "--set", "output.every=1000000", "--set", "output.fields=[stress]"]
    proc = subprocess.run(cmd, capture_output=True, text=True, timeout=600)
    if proc.returncode not in (0, 1):
        raise RuntimeError(f"exdyn exit {proc.returncode}: {proc.stdout}{proc.stderr}")
    with open(os.path.join(out, "c.json")) as f:
        s = json.load(f)
    return proc.returncode == 0, s["steps"], s["message"]


def rule_step(exdyn, out, form, n):
    """The step of the formulation's rule at Courant 1 (s), from a one-step run's summary."""
    run(exdyn, out, form, 1.0, n, 1e-6)
    with open(os.path.join(out, "c.json")) as f:
        return json.load(f)["dt"]


def exact_limit_hex8(n, nu=0.3):
    """The largest stable Courant number of the hex8 plate mesh, exactly: central
    differences are stable for dt <= 2 / omega_max, with omega_max^2 the largest
    eigenvalue of M^-1 K. A part one element thick with u_y = 0 is the plane-strain
    four-node quadrilateral with 2 x 2 Gauss points; K and the row-sum lumped M are
    assembled here for the N x N mesh of unit squares with the deck's supports
    (u_x = 0 on the contact face, u_z = 0 on z = 0, the other two edges free).
    Courant number = (2 / omega_max) c1 / h (units cancel: E = 1, rho = 1)."""
    import numpy as np
    lam, mu = nu / ((1 + nu) * (1 - 2 * nu)), 1 / (2 * (1 + nu))
    D = np.array([[lam + 2 * mu, lam, 0], [lam, lam + 2 * mu, 0], [0, 0, mu]])
    corners = [(-1, -1), (1, -1), (1, 1), (-1, 1)]
    g = 1 / math.sqrt(3)
    Ke = np.zeros((8, 8))
    for a, b in [(-g, -g), (g, -g), (g, g), (-g, g)]:
        B = np.zeros((3, 8))
        for i, (s, t) in enumerate(corners):
            dx, dz = s * (1 + t * b) / 2, t * (1 + s * a) / 2  # dN/dx, dN/dz on a unit square
            B[0, 2 * i], B[1, 2 * i + 1], B[2, 2 * i], B[2, 2 * i + 1] = dx, dz, dz, dx
        Ke += B.T @ D @ B / 4
    nodes = (n + 1) * (n + 1)
    K, m = np.zeros((2 * nodes, 2 * nodes)), np.zeros(2 * nodes)
    for i in range(n):
        for j in range(n):
            dofs = [d for (p, q) in [(i, j), (i + 1, j), (i + 1, j + 1), (i, j + 1)]
                    for d in (2 * (p + (n + 1) * q), 2 * (p + (n + 1) * q) + 1)]
            K[np.ix_(dofs, dofs)] += Ke
            m[dofs] += 0.25
    free = [d for q in range(n + 1) for p in range(n + 1)
            for d, held in ((2 * (p + (n + 1) * q), p == n), (2 * (p + (n + 1) * q) + 1, q == 0)) if not held]
    s = 1 / np.sqrt(m[free])
    omega_max = math.sqrt(np.linalg.eigvalsh(K[np.ix_(free, free)] * s[:, None] * s[None, :]).max())
    return 2 / omega_max * math.sqrt(lam + 2 * mu)


def bisect(exdyn, out, form, n, steps, tolerance, step, top):
    stable, unstable = 0.5, top
    runs = 0
    while unstable - stable > tolerance:
        trial = 0.5 * (stable + unstable)
        ok, _, _ = run(exdyn, out, form, trial, n, steps, step)
        runs += 1
        if ok:
            stable = trial
        else:
            unstable = trial
    return stable, unstable, runs


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--exdyn", default=os.path.join(ROOT, "build", "release", "src", "app", "exdyn"))
    parser.add_argument("--mesh", type=int, default=25)
    parser.add_argument("--steps", type=int, default=2000)
    parser.add_argument("--tolerance", type=float, default=1e-3)
    parser.add_argument("--check", action="store_true")
    args = parser.parse_args()
    failures = []
    print(f"plate reference, {args.mesh} x 1 x {args.mesh} cubes, {args.steps} steps per trial, "
          f"bisection on [0.5, 1.5] to {args.tolerance}\n")
    exact = exact_limit_hex8(args.mesh)
    print(f"hex8 exact limit of this mesh (eigenvalues of M^-1 K): {exact:.5f}\n")
    print("| formulation | largest stable Courant (bisection) | first unstable | theory | runs | "
          "an unstable run: stopped at step | message |")
    print("|---|---|---|---|---|---|---|")
    with tempfile.TemporaryDirectory(prefix="stability_courant_") as out:
        for form in ("hex8", "hex8r", "hex20", "hex20r"):
            quadratic = form.startswith("hex20")
            step = rule_step(args.exdyn, out, form, args.mesh)
            top = 3.0 if quadratic else 1.5
            stable, unstable, runs = bisect(args.exdyn, out, form, args.mesh, args.steps, args.tolerance, step, top)
            trial = 1.5 if not quadratic else min(top, unstable + 0.1)
            ok, caught, message = run(args.exdyn, out, form, trial, args.mesh, args.steps, step)
            if form == "hex8":
                theory = f"{exact:.5f} (exact)"
            elif form == "hex8r":
                theory = "1.0 (infinite mesh)"
            else:
                theory = f">= 1 (rule: element eigenvalue, {step * C1 / (D / args.mesh):.4f} h / c1)"
            print(f"| {form} | {stable:.4f} | {unstable:.4f} | {theory} | {runs} | "
                  f"Courant {trial:.3f}: {caught} | {message[:90]} |")
            if form == "hex8" and not stable <= exact <= unstable:
                failures.append(f"hex8: the bisection bracket [{stable:.4f}, {unstable:.4f}] misses the exact {exact:.5f}")
            if not quadratic and abs(stable - 1.0) > 0.01:
                failures.append(f"{form}: largest stable Courant {stable:.4f}, more than 0.01 from 1.0")
            if quadratic and stable < 1.0:
                failures.append(f"{form}: largest stable Courant {stable:.4f} below 1: the rule allows an unstable step")
            if ok or caught > 300:
                failures.append(f"{form}: Courant {trial:.3f} not caught within 300 steps")
    for f in failures:
        print("FAIL " + f, file=sys.stderr)
    if args.check:
        print(f"{9 - len(failures)} passed, {len(failures)} failed")
        return 1 if failures else 0
    return 0


if __name__ == "__main__":
    sys.exit(main())
