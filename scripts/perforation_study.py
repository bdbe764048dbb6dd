#!/usr/bin/python3
"""Residual against impact velocity of a projectile through a plate, on three plate
meshes, with a Recht-Ipson fit of each (docs/verification.md, "The punched plate" and
"The perforated plate"). Two decks:

- `--deck punch_through` (input/punch_through.yaml): a hardened elastic rod, radius
  1.5 mm, flat nose, through a 1 mm steel plate whose elements fail at a plastic strain
  of 0.3, a quarter model;
- `--deck perforation` (input/perforation.yaml): the 20 mm blunt projectile of 197 g
  against the 12 mm Weldox 460 E plate of Borvik et al. (2002), Johnson-Cook with its
  damage and `time.erode`; the chart marks the test series' ballistic limit;
- `--deck perforation_fine` (input/perforation_fine.yaml): the same on a round plate
  whose Gmsh mesh is fine where the plug is cut (`--meshes deck`, its only mesh).

    /usr/bin/python3 scripts/perforation_study.py [--deck punch_through|perforation|perforation_fine]
        [--exdyn PATH] [--out DIR] [--threads 2] [--speeds ...] [--meshes ...] [--figure PNG]

Against the test series (Borvik et al. 2002, whose residual velocities were not
reachable here) the chart draws its ballistic limit and the Recht-Ipson plugging curve
through it, a = m_p / (m_p + m_plug), p = 2, and prints each run against that curve.

Each run: the projectile at v_i until it is through and clear of the plate
(punch_through: t = max(15 us, 3.5 mm / v_i); perforation: t = max(200 us, 45 mm /
v_i)). Its residual velocity v_r is the mean z velocity of its nodes at the end
(their masses are equal to within its uniform mesh), 0 where it did not get its nose
through the plate's back face or moves back up. For perforation it must also be free:
a projectile that still presses on the plate at the end with more than 2 % of the
largest contact force, moving down, is undecided (nan, left out of the fit). The fit, Recht and Ipson (1963):

    v_r = a (v_i^p - v_bl^p)^(1/p)   for v_i > v_bl, 0 below,

a, p and the ballistic limit v_bl by least squares over the runs (a grid in v_bl
between the fastest stopped and the slowest perforating speed, and in p; a in closed
form). Prints one table row per run and one per mesh; writes the chart.
"""
import argparse
import json
import os
import subprocess
import sys
import tempfile

import h5py
import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.dirname(HERE)
sys.path.insert(0, HERE)
import batch_plate_impact as batch  # noqa: E402  (the exdyn path)

# Per deck: the file, the plate's back face z (m), the end time of a run at v_i (s), the
# default speeds and meshes (plate bricks across x N and through), the chart's title, and
# the test series' ballistic limit (m/s) where there is one.
DECKS = {
    "punch_through": dict(file="punch_through.yaml", back=-1.0e-3, end=lambda v: max(15.0e-6, 3.5e-3 / v),
                          speeds="60,80,90,100,105,110,125,150,200,250,300,400", meshes="12x4,24x8,36x12",
                          title="input/punch_through.yaml: rod through a 1 mm plate", test_limit=None,
                          must_be_free=False),
    "perforation": dict(file="perforation.yaml", back=-12.0e-3, end=lambda v: max(200.0e-6, 45.0e-3 / v),
                        speeds="200,225,250,275,300,350,400", meshes="20x6,30x9,40x12",
                        title="input/perforation.yaml: 20 mm blunt projectile, 12 mm Weldox 460 E",
                        test_limit=184.5, must_be_free=True),
    # Its plate a Gmsh mesh (input/meshes/weldox_plate.geo): the deck's own, no mesh sizes.
    "perforation_fine": dict(file="perforation_fine.yaml", back=-12.0e-3, end=lambda v: max(200.0e-6, 45.0e-3 / v),
                             speeds="175,190,200,225,250,300", meshes="deck",
                             title="input/perforation_fine.yaml: the round plate, 0.4 mm bricks in the band",
                             test_limit=184.5, must_be_free=True),
}

# The test series' curve where only its ballistic limit was reachable: Recht and Ipson's
# (1963) model of a blunt projectile that shears out a plug, p = 2 and a = m_p / (m_p +
# m_plug), the plug the projectile's diameter through the plate: m_p 197 g, m_plug =
# pi (10 mm)^2 x 12 mm x 7850 kg/m^3 = 29.6 g, so a = 0.869.
PROJECTILE_MASS = 0.197  # kg
PLUG_MASS = np.pi * 10.0e-3 ** 2 * 12.0e-3 * 7850.0  # kg
TEST_A = PROJECTILE_MASS / (PROJECTILE_MASS + PLUG_MASS)


def test_curve(v_i, v_bl):
    """The Recht-Ipson plugging curve through the test's ballistic limit, m/s."""
    return TEST_A * np.sqrt(np.maximum(np.asarray(v_i, dtype=float) ** 2 - v_bl ** 2, 0.0))


def run(exdyn, deck, out, speed, mesh, threads, read_only=False):
    """(v_r in m/s, nose z at the end, the summary) of one run; None with --read-only
    where the run is not there."""
    end = deck["end"](speed)
    name = os.path.splitext(deck["file"])[0]
    cmd = [exdyn, "run", os.path.join(REPO, "input", deck["file"]), "--quiet", "--output", out, "--threads", str(threads),
           "--set", f"parts[0].initial_velocity=[0, 0, {-speed}]", "--set", f"time.end_time={end}",
           "--set", "output.every=1000000", "--set", "output.fields=[displacement, velocity, status]"]
    if mesh is not None:  # (bricks across x and y, through); None: the deck's own mesh
        cmd += ["--set", f"parts[1].elements=[{mesh[0]}, {mesh[0]}, {mesh[1]}]"]
    summary_path = os.path.join(out, name + ".json")
    done = os.path.exists(summary_path) and json.load(open(summary_path)).get("status") == "completed"
    if not done and read_only:
        return None
    if not done:  # a run with --out that completed before is read again, not run
        subprocess.run(cmd, capture_output=True, text=True)
    with open(summary_path) as f:
        summary = json.load(f)
    if summary.get("status") != "completed":
        return None, None, summary
    with h5py.File(os.path.join(out, name + ".h5"), "r") as f:
        x = f["/mesh/coordinates"][:]
        part = f["/mesh/part"][:].ravel()
        cells = f["/mesh/connectivity"][:]
        last = sorted(f["/steps"].keys())[-1]
        u = f[f"/steps/{last}/displacement"][:]
        v = f[f"/steps/{last}/velocity"][:]
        force = np.abs(f["/history/contact/all/force"][:, 2]) if "/history/contact/all/force" in f else None
    rod = np.unique(cells[part == 0].ravel())
    nose = float(np.min(x[rod, 2] + u[rod, 2]))
    residual = max(float(-np.mean(v[rod, 2])), 0.0) if nose < deck["back"] else 0.0
    # Through means free: at the end the plate pushes on the projectile with under 2 % of
    # the largest force it saw (a projectile still pressing a bulging plate is not through).
    pressed = force is not None and force[-1] > 0.02 * force.max()
    if deck["must_be_free"] and pressed:
        residual = 0.0 if residual == 0.0 else float("nan")  # still being stopped: undecided
    return residual, nose, summary


def recht_ipson(points):
    """(a, p, v_bl, rms) of the fit to [(v_i, v_r)], or None with fewer than 3 perforations."""
    pts = sorted(points)
    through = [(vi, vr) for vi, vr in pts if vr > 0.0]
    stopped = [vi for vi, vr in pts if vr == 0.0]
    if len(through) < 3:
        return None
    lo = max(stopped) if stopped else 0.0
    hi = min(vi for vi, _ in through)
    vi = np.array([p[0] for p in pts])
    vr = np.array([p[1] for p in pts])
    best = None
    for v_bl in np.linspace(lo, hi, 401)[:-1]:
        for p in np.linspace(1.2, 4.0, 141):
            g = np.where(vi > v_bl, np.maximum(vi ** p - v_bl ** p, 0.0) ** (1.0 / p), 0.0)
            a = float(np.dot(vr, g) / np.dot(g, g))
            rms = float(np.sqrt(np.mean((vr - a * g) ** 2)))
            if best is None or rms < best[3]:
                best = (a, float(p), float(v_bl), rms)
    return best


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--deck", choices=sorted(DECKS), default="punch_through")
    p.add_argument("--exdyn", default=batch.default_exdyn())
    p.add_argument("--out", default=None,
                   help="keep the runs here, and read again those that completed (default: a temporary directory)")
    p.add_argument("--threads", type=int, default=2)
    p.add_argument("--speeds", default=None, help="m/s, comma-separated (default: the deck's)")
    p.add_argument("--meshes", default=None, help="the plate's bricks across x N and through (default: the deck's)")
    p.add_argument("--figure", default=None, help="default: docs/figures/<deck>_study.png")
    p.add_argument("--read-only", action="store_true",
                   help="with --out: tabulate and chart the runs that completed there, run none")
    args = p.parse_args()
    deck = DECKS[args.deck]
    args.speeds = args.speeds or deck["speeds"]
    args.meshes = args.meshes or deck["meshes"]
    study = {"punch_through": "perforation_study", "perforation": "weldox_study"}.get(args.deck, args.deck + "_study")
    args.figure = args.figure or os.path.join(REPO, "docs", "figures", study + ".png")
    speeds = [float(s) for s in args.speeds.split(",")]
    meshes = [None if m == "deck" else tuple(int(k) for k in m.split("x")) for m in args.meshes.split(",")]

    def label_of(mesh):
        return "the deck's" if mesh is None else f"{mesh[0]} x {mesh[0]} x {mesh[1]}"
    work = args.out or tempfile.mkdtemp(prefix="exdyn_" + args.deck + "_")
    results = {}
    print("| plate bricks | v_i (m/s) | v_r (m/s) | nose z (mm) | eroded | steps | wall (s) |")
    print("|---|---|---|---|---|---|---|")
    for mesh in meshes:
        for speed in speeds:
            out = os.path.join(work, ("deck" if mesh is None else f"{mesh[0]}x{mesh[1]}") + f"_{int(speed)}")
            ran = run(args.exdyn, deck, out, speed, mesh, args.threads, args.read_only)
            if ran is None:
                continue
            residual, nose, summary = ran
            label = label_of(mesh)
            if residual is None:
                print(f"| {label} | {speed:g} | run {summary['status']}: {summary.get('message', '')[:80]} "
                      f"| | | {summary['steps']} | {summary['wall_seconds']:.1f} |", flush=True)
                continue
            if residual == residual:  # not undecided
                results.setdefault(mesh, []).append((speed, residual))
            print(f"| {label} | {speed:g} | {residual:.1f} | {1e3 * nose:.2f} | "
                  f"{summary['energy']['eroded_elements']} | {summary['steps']} | "
                  f"{summary['wall_seconds']:.1f} |", flush=True)
    print()
    print("| plate bricks | v_bl (m/s) | a | p | rms (m/s) |")
    print("|---|---|---|---|---|")
    fits = {}
    for mesh, points in results.items():
        fit = recht_ipson(points)
        fits[mesh] = fit
        label = label_of(mesh)
        if fit is None:
            print(f"| {label} | fewer than 3 perforations | | | |")
        else:
            print(f"| {label} | {fit[2]:.1f} | {fit[0]:.3f} | {fit[1]:.2f} | {fit[3]:.2f} |")

    if deck["test_limit"] is not None:
        print()
        print(f"| plate bricks | v_i (m/s) | v_r (m/s) | Recht-Ipson through the test's {deck['test_limit']:g} m/s (m/s) | difference (m/s) |")
        print("|---|---|---|---|---|")
        for mesh, points in results.items():
            for vi, vr in sorted(points):
                ref = float(test_curve(vi, deck["test_limit"]))
                print(f"| {label_of(mesh)} | {vi:g} | {vr:.1f} | {ref:.1f} | {vr - ref:+.1f} |")

    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(figsize=(6.4, 4.4), dpi=100)
    for k, (mesh, points) in enumerate(sorted(results.items(), key=lambda item: item[0] or (0, 0))):
        colour = f"C{k}"
        vi, vr = zip(*sorted(points))
        ax.plot(vi, vr, "o", color=colour, label="the deck's plate" if mesh is None else "plate " + label_of(mesh))
        fit = fits[mesh]
        if fit is not None:
            a, power, v_bl, _ = fit
            grid = np.linspace(0.0, max(speeds) * 1.05, 400)
            ax.plot(grid, np.where(grid > v_bl, a * np.maximum(grid ** power - v_bl ** power, 0.0) ** (1 / power),
                                   0.0), "-", color=colour, lw=1,
                    label=f"Recht-Ipson: v_bl {v_bl:.0f} m/s, a {a:.2f}, p {power:.2f}")
    ax.plot([0, max(speeds)], [0, max(speeds)], "k:", lw=0.8, label="v_r = v_i")
    if deck["test_limit"] is not None:
        ax.axvline(deck["test_limit"], color="k", lw=1.2, ls="--",
                   label=f"test series' ballistic limit {deck['test_limit']:g} m/s (Borvik et al. 2002)")
        grid = np.linspace(deck["test_limit"], max(speeds) * 1.05, 200)
        ax.plot(grid, test_curve(grid, deck["test_limit"]), "k-", lw=1.6, alpha=0.5,
                label=f"Recht-Ipson through it: a = m_p/(m_p+m_plug) = {TEST_A:.3f}, p = 2")
    ax.set_xlabel("impact velocity v_i (m/s)")
    ax.set_ylabel("residual velocity v_r (m/s)")
    ax.set_title(deck["title"], fontsize=10)
    ax.grid(alpha=0.3)
    ax.legend(fontsize=7)
    fig.tight_layout()
    os.makedirs(os.path.dirname(os.path.abspath(args.figure)), exist_ok=True)
    fig.savefig(args.figure)
    print(f"\nchart: {args.figure}; runs in {work}")


if __name__ == "__main__":
    main()
