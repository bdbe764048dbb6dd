#!/usr/bin/python3
"""The crushed tube: input/tube_crush.yaml (a quarter of a thin-walled steel tube
crushed end on by a rigid wall at 10 m/s, one `surface: all` contact) against the
classical concertina theory (docs/verification.md, "The crushed tube").

    /usr/bin/python3 scripts/tube_crush_study.py [--exdyn PATH] [--out DIR] [--docs docs]
        [--threads 2]                                   # the study: table, plot, docs
    /usr/bin/python3 scripts/tube_crush_study.py --check [--quick] [--exdyn PATH]  # the test

Measured from the run (the quarter's figures times 4 for the whole tube):
- the crush force F(d) on the wall against the crush distance d = v t;
- the mean crush force P_m = integral F dd / d over the whole crush;
- the force peaks (one per fold: a new fold starts with a peak) and the crush distance
  between them, against the effective crushing distance of a fold;
- the fold length 2H: the axial distance, in the reference configuration, between
  consecutive outward lobes of the wall at the last step (the outer surface on the
  symmetry plane y = 0), and the number of folds (outward lobes further out than h);
- the largest penetration of the self-contact at every history row, against the wall
  thickness h;
- the energy balance, |E_kin + E_int + E_contact - W_ext| over the external work;
- the self-contact's work: its friction work (the wall has none) and the contact
  force on the folds (nodes more than 2 h below the wall) at the written steps;
- the self-contact's history: the sum of its points' normal force magnitudes
  (/history/contact/folds/normal_force_sum, whole tube), which shows each fold closing
  (its force on the tube, /history/contact/folds/force, cancels within the one body),
  and the points pressed at its peak (the summary's points_in_contact_at_peak).
The study also writes docs/figures/tube_crush_force.png (force against crush distance)
and, with ParaView, docs/figures/tube_crush_folds.png (scripts/paraview/tube_picture.py).
Theory (h the wall thickness, D the mean diameter, sigma_0 the flow stress,
M_0 = 2 sigma_0 h^2 / (4 sqrt 3) the plane-strain fully plastic moment per length):
- Alexander (1960): two straight segments of length H fold outwards about three
  circumferential hinges while the ring between them stretches; the work of one fold,
  crushed by 2H, P 2H = 2 pi D M_0 pi + 2 pi sigma_0 h H^2, is least at
  H = sqrt(pi D h / (2 sqrt 3)) = 0.952 sqrt(D h), where P_m = 5.98 sigma_0 h^1.5 D^0.5;
- Abramowicz and Jones (1984, Int. J. Impact Eng. 2(3) 263-281): the fold partly inside,
  P_m / M_0 = 25.23 sqrt(D / h) + 15.09, over the effective crushing distance
  delta_e / 2H = 0.86 - 0.568 sqrt(h / D) (a fold does not flatten completely):
  P_m^e = P_m 2H / delta_e. This is the estimate the check compares with (25 %).
--check runs the deck to a crush of 10 mm (the first fold closed on itself, the second
begun), --check --quick (the sanitizer build) the first 0.5 mm; both assert the penetration below 5 % of h at every history row,
the energy balance within 1 %, and (the full check) the self-contact at work, the
mean force within 25 % of Abramowicz and Jones and two outward lobes. Prints `N passed, M failed`; exit 0 when all passed.
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
sys.path.insert(0, HERE)
import batch_plate_impact as batch  # noqa: E402  (the document writer, the exdyn path)

DECK = os.path.join(REPO, "input", "tube_crush.yaml")
# The deck's data: radii (m), flow stress (Pa), wall speed (m/s), the quarter model.
R_INNER, R_OUTER, SIGMA_0, SPEED, LENGTH, SYMMETRY = 9.2e-3, 10.0e-3, 3.0e8, 10.0, 40.0e-3, 4
H = R_OUTER - R_INNER
D = R_OUTER + R_INNER  # the mean diameter


def theory():
    """The concertina estimates for the deck's tube (N, m)."""
    m0 = 2.0 * SIGMA_0 * H * H / (4.0 * math.sqrt(3.0))
    half_fold = math.sqrt(math.pi * D * H / (2.0 * math.sqrt(3.0)))
    alexander = 2.0 * math.pi * SIGMA_0 * H * half_fold
    effective = 0.86 - 0.568 * math.sqrt(H / D)
    aj = m0 * (25.23 * math.sqrt(D / H) + 15.09)
    return {"m0": m0, "fold_length": 2.0 * half_fold, "alexander": alexander, "effective": effective,
            "alexander_effective": alexander / effective, "abramowicz_jones": aj,
            "abramowicz_jones_effective": aj / effective, "crush_per_fold": effective * 2.0 * half_fold}


def run(exdyn, out, threads, extra=()):
    os.makedirs(out, exist_ok=True)
    cmd = [exdyn, "run", DECK, "--quiet", "--output", out, "--threads", str(threads)]
    for s in extra:
        cmd += ["--set", s]
    proc = subprocess.run(cmd, capture_output=True, text=True)
    if proc.returncode != 0:
        raise RuntimeError(f"exdyn failed ({proc.returncode}): {proc.stderr[-600:]}")
    with open(os.path.join(out, "tube_crush.json")) as f:
        return json.load(f)


def peaks(d, force, spacing):
    """Crush distances of the force's local maxima, each the largest within +-spacing/2
    and above the mean of that window (the peaks that start folds, not the ringing)."""
    found = []
    for i in range(1, len(force) - 1):
        window = np.abs(d - d[i]) <= 0.5 * spacing
        if force[i] >= force[window].max() and force[i] > 1.2 * force[window].mean():
            found.append(float(d[i]))
    return found


def lobes(z_ref, r, threshold):
    """Reference heights of the outward lobes: local maxima of r(z_ref) beyond threshold."""
    order = np.argsort(z_ref)
    z, rr = z_ref[order], r[order]
    return [float(z[i]) for i in range(1, len(z) - 1) if rr[i] >= rr[i - 1] and rr[i] > rr[i + 1]
            and rr[i] > threshold]


def measure(out, summary):
    with h5py.File(os.path.join(out, "tube_crush.h5"), "r") as f:
        t = f["history/time"][:]
        force = -SYMMETRY * f["history/wall/crusher/force"][:, 2]
        penetration = f["history/contact/folds/max_penetration"][:]
        kinetic, internal = f["history/kinetic_energy"][:], f["history/internal_energy"][:]
        contact, external = f["history/contact_energy"][:], f["history/external_work"][:]
        friction = f["history/friction_work"][:]
        self_contact = SYMMETRY * f["history/contact/folds/normal_force_sum"][:]
        x_ref = f["mesh/coordinates"][:]
        steps = sorted(f["steps"].keys())
        last = f["steps"][steps[-1]]
        u = last["displacement"][:]
        fold_force = []
        for name in steps:
            step = f["steps"][name]
            if "contact_force" not in step:
                continue
            z = x_ref[:, 2] + step["displacement"][:, 2]
            wall_z = LENGTH - SPEED * float(f["time"][steps.index(name)])
            below = z < wall_z - 2.0 * H
            fold_force.append(float(np.abs(step["contact_force"][:][below]).sum()))
    d = SPEED * t
    mean_force = float(np.trapz(force, d) / d[-1]) if d[-1] > 0 else 0.0
    energy_error = float(np.max(np.abs(kinetic + internal + contact - external)) / max(external[-1], 1e-30))
    x = x_ref + u
    # The outer surface on the symmetry plane y = 0 (a generator of the tube).
    generator = (np.abs(x_ref[:, 1]) < 1e-9) & (np.abs(x_ref[:, 0] - R_OUTER) < 1e-6 * R_OUTER)
    r = np.hypot(x[generator, 0], x[generator, 1])
    outward = lobes(x_ref[generator, 2], r, R_OUTER + H)
    fold_lengths = np.diff(outward)
    th = theory()
    crush_peaks = peaks(d, force, 0.5 * th["crush_per_fold"])
    return {
        "elements": summary["mesh"]["elements"], "steps": summary["steps"],
        "wall_seconds": summary["wall_seconds"], "crush": float(d[-1]), "mean_force": mean_force,
        "peak_force": float(force.max()), "force_peaks": crush_peaks,
        "crush_per_fold": float(np.mean(np.diff(crush_peaks))) if len(crush_peaks) > 1 else float("nan"),
        "lobes": outward, "folds": len(outward),
        "fold_length": float(np.mean(fold_lengths)) if len(fold_lengths) else float("nan"),
        "max_penetration": float(penetration.max()), "penetration_over_h": float(penetration.max() / H),
        "energy_error": energy_error, "friction_work": float(friction[-1]),
        "external_work": float(external[-1]), "fold_contact_force": max(fold_force) if fold_force else 0.0,
        "contact_share": contact_share(summary),
        "not_converged": summary["contact"]["not_converged"],
        "fallbacks": summary["contact"].get("fallbacks", 0),
        "self_contact_peak": float(self_contact.max()),
        "self_contact_first": float(d[np.argmax(self_contact > 0)]) if self_contact.max() > 0 else float("nan"),
        "points_at_peak": summary["contact"]["pairs"]["folds"].get("points_in_contact_at_peak", 0),
        "history": {"d": d, "force": force, "self_contact": self_contact},
    }


def contact_share(summary):
    """The contact phases' share of the step (the self-contact and the wall)."""
    phases = summary["phase_seconds"]
    contact = sum(v for k, v in phases.items() if k.startswith("contact_"))
    return contact / max(sum(phases.values()), 1e-30)


def report(m):
    th = theory()
    print(f"crush {m['crush'] * 1e3:.1f} mm, {m['elements']} bricks, {m['steps']} steps, "
          f"{m['wall_seconds']:.0f} s: mean force {m['mean_force'] / 1e3:.2f} kN "
          f"(Abramowicz-Jones {th['abramowicz_jones_effective'] / 1e3:.2f}, Alexander "
          f"{th['alexander'] / 1e3:.2f}), peak {m['peak_force'] / 1e3:.2f} kN; folds {m['folds']}, "
          f"fold length {m['fold_length'] * 1e3:.2f} mm (Alexander {th['fold_length'] * 1e3:.2f}); "
          f"crush per fold {m['crush_per_fold'] * 1e3:.2f} mm (A-J {th['crush_per_fold'] * 1e3:.2f}); "
          f"penetration {100 * m['penetration_over_h']:.2f} % of h; energy {100 * m['energy_error']:.3f} %; "
          f"friction work {m['friction_work']:.3f} J; contact share {100 * m['contact_share']:.0f} %; "
          f"self-contact: first pressed at {m['self_contact_first'] * 1e3:.2f} mm, peak sum of normal forces "
          f"{m['self_contact_peak'] / 1e3:.2f} kN with {m['points_at_peak']} points pressed (a quarter); "
          f"{m['fallbacks']} searches settled by the fallback",
          flush=True)


def check(args):
    results = []

    def expect(ok, what):
        results.append(ok)
        print(f"{'ok  ' if ok else 'FAIL'} {what}", flush=True)

    th = theory()
    end = 5.0e-5 if args.quick else 1.0e-3
    with tempfile.TemporaryDirectory(prefix="exdyn_tube_") as out:
        summary = run(args.exdyn, out, args.threads, [f"time.end_time={end}", "output.every=4000"])
        m = measure(out, summary)
        report(m)
        expect(m["penetration_over_h"] < 0.05,
               f"largest penetration {100 * m['penetration_over_h']:.2f} % of h at every history row (5 %)")
        expect(m["energy_error"] < 0.01, f"energy balance {100 * m['energy_error']:.3f} % of the work (1 %)")
        expect(m["not_converged"] == 0, f"{m['not_converged']} projections did not converge")
        if not args.quick:
            expect(m["friction_work"] > 0.0 and m["fold_contact_force"] > 0.0,
                   f"the folds touch: friction work {m['friction_work']:.3f} J, "
                   f"{m['fold_contact_force']:.0f} N on the folds")
            sums = m["history"]["self_contact"]
            expect(sums[0] == 0.0 and m["self_contact_peak"] > 0.0 and m["points_at_peak"] > 0,
                   f"the self-contact's history shows the folds: nothing at the start, from "
                   f"{m['self_contact_first'] * 1e3:.2f} mm of crush a sum of normal forces up to "
                   f"{m['self_contact_peak'] / 1e3:.2f} kN, {m['points_at_peak']} points pressed at its peak")
            error = m["mean_force"] / th["abramowicz_jones_effective"] - 1.0
            expect(abs(error) <= 0.25, f"mean force {m['mean_force'] / 1e3:.2f} kN, {100 * error:+.1f} % "
                   f"from Abramowicz and Jones (25 %)")
            expect(m["folds"] >= 2, f"{m['folds']} outward lobes (the first fold and the second begun), "
                   f"{m['fold_length'] * 1e3:.2f} mm apart (Alexander's 2H: {th['fold_length'] * 1e3:.2f} mm)")
    failed = results.count(False)
    print(f"{len(results) - failed} passed, {failed} failed")
    return 1 if failed else 0


def plot(m, path):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    th = theory()
    h = m["history"]
    fig, ax = plt.subplots(figsize=(7.5, 4.2))
    ax.plot(1e3 * h["d"], 1e-3 * h["force"], lw=0.8, color="k", label="exdyn, wall force (whole tube)")
    ax.axhline(1e-3 * m["mean_force"], color="k", ls="--", lw=1.0,
               label=f"exdyn, mean {m['mean_force'] / 1e3:.2f} kN")
    ax.axhline(1e-3 * th["abramowicz_jones_effective"], color="tab:red", lw=1.0,
               label=f"Abramowicz-Jones (1984), effective distance: {th['abramowicz_jones_effective'] / 1e3:.2f} kN")
    ax.axhline(1e-3 * th["alexander"], color="tab:blue", lw=1.0,
               label=f"Alexander (1960): {th['alexander'] / 1e3:.2f} kN")
    ax.plot(1e3 * h["d"], 1e-3 * h["self_contact"], lw=0.8, color="tab:green",
            label="exdyn, self-contact: sum of its points' normal forces (whole tube)")
    ax.set_xlabel("crush distance (mm)")
    ax.set_ylabel("crush force (kN)")
    ax.set_ylim(bottom=0)
    ax.set_title(f"Steel tube D/h = {D / H:.0f}, crushed at {SPEED:.0f} m/s, one `surface: all`")
    ax.legend(fontsize=8, loc="upper right")
    fig.tight_layout()
    fig.savefig(path, dpi=120)


def picture(xmf, png):
    """The folded tube from ParaView (scripts/paraview/tube_picture.py), or why not."""
    if not os.path.exists(batch.PVPYTHON_RUNNER):
        return f"no picture: {batch.PVPYTHON_RUNNER} not found"
    script = os.path.join(HERE, "paraview", "tube_picture.py")
    for attempt in range(4):  # xvfb-run -a can lose a race for a display number
        proc = subprocess.run(batch.pvpython(script, xmf, "--out", png), capture_output=True, text=True)
        if '"ok": true' in proc.stdout:
            return f"wrote {png}"
        if "X server" not in proc.stderr:
            break
    return f"no picture: {proc.stderr[-300:]}"


def study(args):
    out = os.path.join(args.out, "full")
    summary_path = os.path.join(out, "tube_crush.json")
    if os.path.exists(summary_path):  # run before
        with open(summary_path) as f:
            summary = json.load(f)
    else:
        summary = run(args.exdyn, out, args.threads)
    m = measure(out, summary)
    report(m)
    th = theory()
    figure = os.path.join(args.docs, "figures", "tube_crush_force.png")
    plot(m, figure)
    print("tube_crush_study:", picture(os.path.join(out, "tube_crush.xmf"),
                                       os.path.join(args.docs, "figures", "tube_crush_folds.png")))
    rows = [
        ["mean crush force P_m (kN)", f"{m['mean_force'] / 1e3:.2f}",
         f"{th['abramowicz_jones_effective'] / 1e3:.2f} (Abramowicz-Jones, delta_e)",
         f"{100 * (m['mean_force'] / th['abramowicz_jones_effective'] - 1):+.1f} %"],
        ["", "", f"{th['alexander'] / 1e3:.2f} (Alexander)",
         f"{100 * (m['mean_force'] / th['alexander'] - 1):+.1f} %"],
        ["", "", f"{th['alexander_effective'] / 1e3:.2f} (Alexander, delta_e)",
         f"{100 * (m['mean_force'] / th['alexander_effective'] - 1):+.1f} %"],
        ["fold length 2H (mm)", f"{m['fold_length'] * 1e3:.2f}", f"{th['fold_length'] * 1e3:.2f} (Alexander)",
         f"{100 * (m['fold_length'] / th['fold_length'] - 1):+.1f} %"],
        ["crush per fold (mm)", f"{m['crush_per_fold'] * 1e3:.2f}",
         f"{th['crush_per_fold'] * 1e3:.2f} (delta_e of Alexander's 2H)",
         f"{100 * (m['crush_per_fold'] / th['crush_per_fold'] - 1):+.1f} %"],
        ["folds (outward lobes) / crush (mm)", f"{m['folds']} / {m['crush'] * 1e3:.1f}", "", ""],
        ["first peak force (kN)", f"{m['peak_force'] / 1e3:.2f}", "", ""],
        ["largest penetration / h (every history row)", f"{100 * m['penetration_over_h']:.2f} %", "< 5 %", ""],
        ["energy balance / external work", f"{100 * m['energy_error']:.3f} %", "< 1 %", ""],
        ["friction work of the folds (J, quarter)", f"{m['friction_work']:.3f}", "", ""],
        ["self-contact: first pressed at (mm of crush)", f"{m['self_contact_first'] * 1e3:.2f}", "", ""],
        ["self-contact: peak sum of normal forces (kN, whole tube); points pressed then (quarter)",
         f"{m['self_contact_peak'] / 1e3:.2f}; {m['points_at_peak']}", "", ""],
        ["contact's share of the step", f"{100 * m['contact_share']:.0f} %", "", ""],
        ["bricks, steps, wall time", f"{m['elements']}, {m['steps']}, {m['wall_seconds']:.0f} s "
         f"({summary['threads']} threads)", "", ""],
    ]
    table = batch.table(["quantity", "exdyn", "theory", "difference"], rows)
    text = (f"Written by `/usr/bin/python3 scripts/tube_crush_study.py` (input/tube_crush.yaml, "
            f"{summary['threads']} threads).\n\n" + table)
    batch.write_doc(os.path.join(args.docs, "verification.md"), {"tube_crush_table": text})
    with open(os.path.join(args.out, "tube_crush.json"), "w") as f:
        json.dump({k: v for k, v in m.items() if k != "history"}, f, indent=1)
    print(f"tube_crush_study: wrote {figure} and the table in {os.path.join(args.docs, 'verification.md')}")
    return 0


def main(argv):
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--exdyn", default=batch.default_exdyn())
    p.add_argument("--check", action="store_true")
    p.add_argument("--quick", action="store_true", help="with --check: the sanitizer build's short variant")
    p.add_argument("--threads", type=int, default=2)
    p.add_argument("--out", default=os.path.join(REPO, "results", "tube_crush"))
    p.add_argument("--docs", default=os.path.join(REPO, "docs"))
    args = p.parse_args(argv)
    return check(args) if args.check else study(args)


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
