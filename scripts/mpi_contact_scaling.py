#!/usr/bin/python3
"""What each rank holds and sends as the ranks grow (docs/parallel.md, "Per rank").

Counts and bytes, not times: on 1, 2, 4 and 8 ranks (oversubscribed past the cores, one
thread each), short runs of
- the plate impact at mesh M (2 x M x 1 x M elements; default 400),
- the Hertz ball (input/hertz_ball.yaml as it is, and twice as fine each way),
- weak scaling: two 100 x 1 x 100 plates per rank, stacked along z (the contact face
  grows with the ranks, a rank's part of it does not),
read from each run's summary (`mpi.per_rank`, and `mpi.setup`): every rank's peak
resident memory, the
slave points it owns, the segments of its views (own and ghost), its ghost segments
and ghost nodes, the contact's messages and bytes it sends per step, and the force
exchange's. Each row gives the largest over the ranks (and the mean where it differs),
and what the gathered contact (every rank receiving every contact node and every
projection each step: 48 bytes a node, 56 a candidate) would receive per rank.

  /usr/bin/python3 scripts/mpi_contact_scaling.py [--exdyn PATH] [--mesh 400] [--steps 20]
      [--docs docs] [--out DIR]

Writes the tables between the markers `batch:mpi_per_rank` of docs/parallel.md and the
chart docs/figures/mpi_per_rank.png.
"""
import argparse
import json
import os
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.dirname(HERE)
sys.path.insert(0, HERE)
import batch_plate_impact as batch  # noqa: E402

RANKS = [1, 2, 4, 8]


def run(exdyn, deck, ranks, sets, out, steps):
    cmd = []
    if ranks > 1:
        cmd = ["mpirun", "-n", str(ranks), "--oversubscribe"] + (["--allow-run-as-root"] if os.geteuid() == 0 else [])
    cmd += [exdyn, "run", os.path.join(REPO, "input", deck + ".yaml"), "--quiet", "--output", out, "--threads", "1",
            "--set", "output.every=100000", "--set", "output.fields=[displacement]"]
    for s in sets:
        cmd += ["--set", s]
    # A run of `steps` steps: end_time from the first step of a one-step run.
    probe = subprocess.run(cmd + ["--set", "time.end_time=1e-30"], capture_output=True, text=True)
    if probe.returncode != 0:
        raise RuntimeError(probe.stdout + probe.stderr)
    with open(os.path.join(out, deck + ".json")) as f:
        dt = json.load(f)["dt"]
    done = subprocess.run(cmd + ["--set", f"time.end_time={steps * dt * 0.999999}"], capture_output=True, text=True)
    if done.returncode != 0:
        raise RuntimeError(done.stdout + done.stderr)
    with open(os.path.join(out, deck + ".json")) as f:
        return json.load(f)


def row(label, ranks, s, gathered_bytes):
    r = s["mpi"]["per_rank"]
    def largest(key):
        return max(r[key]) if r.get(key) else 0.0
    def mean(key):
        return sum(r[key]) / len(r[key]) if r.get(key) else 0.0
    return {
        "case": label, "ranks": ranks, "setup": s["mpi"].get("setup", "whole"),
        "peak_mb": largest("peak_resident_mb"),
        "points": largest("contact_points"), "points_mean": mean("contact_points"),
        "segments": largest("contact_segments"), "ghost_segments": largest("ghost_segments"),
        "ghost_nodes": largest("ghost_nodes"),
        "contact_messages": largest("contact_messages_per_step"),
        "contact_kb": largest("contact_bytes_per_step") / 1e3,
        "contact_kb_mean": mean("contact_bytes_per_step") / 1e3,
        "force_messages": largest("force_messages_per_step"), "force_kb": largest("force_bytes_per_step") / 1e3,
        "gathered_kb": gathered_bytes / 1e3 if ranks > 1 else 0.0,
    }


def gathered(one):
    """Bytes every rank would receive per step with the contact gathered: 48 per contact
    node and 56 per candidate projected, from the one-rank run (steps 0 .. N: N + 1 passes)."""
    nodes = one["mpi"]["per_rank"]["contact_nodes"][0]
    return 48.0 * nodes + 56.0 * one["contact"]["projections"] / (one["steps"] + 1)


def table(rows):
    return batch.table(
        ["case", "ranks", "setup", "peak resident MB", "slave points (largest / mean)", "segments in view",
         "ghost segments", "ghost nodes", "contact messages/step", "contact kB/step (largest / mean)",
         "gathered contact kB/step", "force messages/step", "force kB/step"],
        [[r["case"], r["ranks"], r["setup"].replace("_", " "), f"{r['peak_mb']:.0f}", f"{r['points']:.0f} / {r['points_mean']:.0f}",
          f"{r['segments']:.0f}", f"{r['ghost_segments']:.0f}", f"{r['ghost_nodes']:.0f}",
          f"{r['contact_messages']:.1f}", f"{r['contact_kb']:.1f} / {r['contact_kb_mean']:.1f}",
          f"{r['gathered_kb']:.1f}", f"{r['force_messages']:.0f}", f"{r['force_kb']:.1f}"] for r in rows])


def chart(rows, path):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, (left, right) = plt.subplots(1, 2, figsize=(11, 4.2))
    for k, case in enumerate(sorted({r["case"] for r in rows})):
        rs = [r for r in rows if r["case"] == case and r["ranks"] > 1]
        if not rs:
            continue
        p = [r["ranks"] for r in rs]
        left.plot(p, [r["contact_kb"] for r in rs], "o-", color=f"C{k}", label=f"{case}: sent, largest rank")
        left.plot(p, [r["gathered_kb"] for r in rs], "x--", color=f"C{k}", alpha=0.6, label=f"{case}: gathered")
        right.plot(p, [r["peak_mb"] for r in rs], "o-", color=f"C{k}", label=case)
    ideal = [2, 4, 8]
    for ax in (left, right):
        ax.set_xscale("log", base=2)
        ax.set_yscale("log")
        ax.set_xticks(ideal)
        ax.set_xticklabels([str(i) for i in ideal])
        ax.set_xlabel("ranks")
        ax.grid(True, which="both", alpha=0.3)
    left.set_ylabel("contact kB per step and rank")
    left.set_title("Contact traffic per rank")
    right.set_ylabel("peak resident MB per rank")
    right.set_title("Memory per rank")
    left.legend(fontsize=7)
    right.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(path, dpi=110)


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--exdyn", default=batch.default_exdyn())
    p.add_argument("--mesh", type=int, default=400)
    p.add_argument("--steps", type=int, default=20)
    p.add_argument("--docs", default=os.path.join(REPO, "docs"))
    p.add_argument("--out", default=None)
    args = p.parse_args()
    m = args.mesh
    cases = [(f"plate impact, mesh {m}", "plate_impact", [f"parts[0].elements=[{m}, 1, {m}]",
                                                          f"parts[1].elements=[{m}, 1, {m}]"]),
             ("Hertz ball", "hertz_ball", []),
             # twice as fine each way: 20,480 ball and 11,520 block elements, 8 times the model
             ("Hertz ball x2", "hertz_ball", ["parts[0].elements=[32, 8]", "parts[1].elements=[24, 24, 20]"])]
    rows = []
    with tempfile.TemporaryDirectory(prefix="exdyn_per_rank_") as work:
        out = args.out or work
        for label, deck, sets in cases:
            one = None
            for ranks in RANKS:
                s = run(args.exdyn, deck, ranks, sets, os.path.join(out, f"{deck}_{ranks}"), args.steps)
                one = one or s
                rows.append(row(label, ranks, s, gathered(one)))
                print(rows[-1], flush=True)
        weak = []
        for ranks in RANKS:
            sets = [f"parts[{k}].elements=[100, 1, {100 * ranks}]" for k in (0, 1)]
            sets += [f"parts[0].box.max=[0, 2.5e-5, {2.5e-3 * ranks}]",
                     f"parts[1].box.max=[2.5e-3, 2.5e-5, {2.5e-3 * ranks}]"]
            s = run(args.exdyn, "plate_impact", ranks, sets, os.path.join(out, f"weak_{ranks}"), args.steps)
            # the gathered contact of this size, from its run on one rank
            one = s if ranks == 1 else run(args.exdyn, "plate_impact", 1, sets,
                                           os.path.join(out, f"weak_{ranks}_one"), args.steps)
            weak.append(row("weak: 2 x 100 x 1 x 100 per rank", ranks, s, gathered(one)))
            print(weak[-1], flush=True)
    os.makedirs(os.path.join(args.docs, "figures"), exist_ok=True)
    chart(rows + weak, os.path.join(args.docs, "figures", "mpi_per_rank.png"))
    text = (f"Written by `/usr/bin/python3 scripts/mpi_contact_scaling.py --mesh {m} --steps {args.steps}` "
            f"(one thread a rank, oversubscribed past {os.cpu_count()} cores; largest over the ranks):\n\n"
            + table(rows) + "\n\nWeak scaling (the contact face grows with the ranks):\n\n" + table(weak))
    batch.write_doc(os.path.join(args.docs, "parallel.md"), {"mpi_per_rank": text})
    print("mpi_contact_scaling: wrote the tables in docs/parallel.md and docs/figures/mpi_per_rank.png")
    return 0


if __name__ == "__main__":
    sys.exit(main())
