#!/usr/bin/python3
"""What a restart checkpoint costs against one field output (docs/performance.md,
"Checkpoints"): its size and wall time, for the plate impact at 20,000 and at 1.28 M
bricks and for the punch-through.

    /usr/bin/python3 scripts/checkpoint_cost.py --exdyn PATH [--threads N] [--ranks R] [--repeats R] [--cases a,b]

Each case runs a few steps with a checkpoint and a field output every K steps (the
output written on the time loop's thread, output.background: false, so its time is the
write's); the checkpoint's time and size come from NAME.json (`checkpoints`), the field
output's from `phase_seconds.output` over the steps written and the size of one step
group of NAME.h5. Prints a Markdown table; the overhead of a checkpoint every 10 minutes
is its time over 600 s. --ranks R: under `mpirun -n R` (each rank --threads threads; the
checkpoint gathered to rank 0, which writes it).
"""

import argparse
import json
import os
import shutil
import statistics
import subprocess
import sys
import tempfile

import h5py

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))

CASES = {
    "plate_20k": ("plate_impact", ["time.end_time=2.6e-8", "output.every=20", "checkpoint.every=20"]),
    "plate_1.28M": ("plate_impact", ["parts[0].elements=[800,1,800]", "parts[1].elements=[800,1,800]",
                                     "time.end_time=3.0e-9", "output.every=10", "checkpoint.every=10"]),
    "punch_through": ("punch_through", ["time.end_time=2.0e-6", "output.every=100", "checkpoint.every=100"]),
}


def one_run(exdyn, deck, sets, threads, work, ranks=0):
    out = tempfile.mkdtemp(dir=work)
    cmd = []
    if ranks > 0:
        cmd = ["mpirun", "-n", str(ranks), "--oversubscribe"] + (["--allow-run-as-root"] if os.geteuid() == 0 else [])
    cmd += [exdyn, "run", os.path.join(ROOT, "input", deck + ".yaml"), "--quiet", "--output", out, "--threads",
           str(threads), "--set", "output.background=false", "--set", "checkpoint.keep=1"]
    for s in sets:
        cmd += ["--set", s]
    subprocess.run(cmd, check=True, capture_output=True, text=True)
    with open(os.path.join(out, deck + ".json")) as f:
        summary = json.load(f)
    with h5py.File(os.path.join(out, deck + ".h5"), "r") as f:
        groups = list(f["steps"])
        step_bytes = sum(d.nbytes for d in f["steps"][groups[-1]].values())
    c = summary["checkpoints"]
    shutil.rmtree(out)
    return {
        "elements": summary["mesh"]["elements"],
        "checkpoint_seconds": c["seconds"] / c["written"],
        "checkpoint_largest": c["largest_seconds"],
        "checkpoint_bytes": c["bytes"],
        "output_seconds": summary["phase_seconds"]["output"] / len(groups),
        "output_bytes": step_bytes,
        "step_seconds": summary["wall_seconds"] / max(summary["steps"], 1),
    }


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--exdyn", required=True)
    parser.add_argument("--threads", type=int, default=2)
    parser.add_argument("--ranks", type=int, default=0)
    parser.add_argument("--repeats", type=int, default=3)
    parser.add_argument("--cases", default=",".join(CASES))
    args = parser.parse_args()
    work = tempfile.mkdtemp(prefix="exdyn_checkpoint_cost_")
    print("| case | bricks | checkpoint MB | checkpoint s (median of runs) | field output MB | field output s "
          "| checkpoint / output time | every 10 min costs |")
    print("|---|---|---|---|---|---|---|---|")
    try:
        for name in args.cases.split(","):
            deck, sets = CASES[name]
            runs = [one_run(args.exdyn, deck, sets, args.threads, work, args.ranks) for _ in range(args.repeats)]
            m = {k: statistics.median(r[k] for r in runs) for k in runs[0]}
            print(f"| {name} | {m['elements']:,.0f} | {m['checkpoint_bytes'] / 1e6:.1f} | "
                  f"{m['checkpoint_seconds']:.3f} ({min(r['checkpoint_seconds'] for r in runs):.3f}-"
                  f"{max(r['checkpoint_seconds'] for r in runs):.3f}) | {m['output_bytes'] / 1e6:.1f} | "
                  f"{m['output_seconds']:.3f} | {m['checkpoint_seconds'] / m['output_seconds']:.2f} | "
                  f"{100 * m['checkpoint_seconds'] / 600:.2f} % |", flush=True)
    finally:
        shutil.rmtree(work, ignore_errors=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
