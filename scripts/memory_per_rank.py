#!/usr/bin/python3
"""Model memory per rank against one process (docs/parallel.md, "Memory per rank").

Runs the plate impact for one step on 1, 2 and 4 ranks (one thread each), at a plane
size (each plate NX x 1 x NZ) and a solid one (each plate NX x NY x NZ), and reads
each rank's peak resident memory from the summary (mpi.per_rank.peak_resident_mb).
The program's own memory (its libraries, MPI's buffers) is what the same run of a
small deck (each plate 24 x 1 x 24, 1,152 elements: a chunk per rank on 4 ranks) peaks
at on the same number of ranks; it is taken off every figure. Every run, one process
too, is started by mpirun. The share is a rank's
model memory over one process's:

    share = (peak on the rank - small deck's peak on that rank) /
            (peak of one process - small deck's peak of one process)

1/P is the ideal; on 4 ranks the program aims at <= 0.30.

  /usr/bin/python3 scripts/memory_per_rank.py [--exdyn PATH] [--plane 300,1,300]
                                              [--solid 45,40,50] [--ranks 1,2,4]
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

SMALL = "24,1,24"


def peaks(exdyn, ranks, elements, out):
    """Each rank's peak resident memory (MB) of one step of the plate impact."""
    # One process under mpirun too: started alone, Open MPI's singleton start maps
    # other pages, and the figures are compared launcher to launcher.
    cmd = ["mpirun", "-n", str(ranks), "--oversubscribe"] + (["--allow-run-as-root"] if os.geteuid() == 0 else [])
    cmd += [exdyn, "run", os.path.join(REPO, "input", "plate_impact.yaml"), "--quiet", "--output", out,
            "--threads", "1", "--set", "time.end_time=1e-9", "--set", "output.every=1000"]
    for p in (0, 1):
        cmd += ["--set", f"parts[{p}].elements=[{elements}]"]
    subprocess.run(cmd, check=True, capture_output=True, text=True)
    with open(os.path.join(out, "plate_impact.json")) as f:
        summary = json.load(f)
    return [float(x) for x in summary["mpi"]["per_rank"]["peak_resident_mb"]]


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--exdyn", default=batch.default_exdyn())
    p.add_argument("--plane", default="300,1,300", help="each plate's elements along x, y, z (plane)")
    p.add_argument("--solid", default="45,40,50", help="each plate's elements along x, y, z (solid)")
    p.add_argument("--ranks", default="1,2,4")
    args = p.parse_args()
    ranks = [int(r) for r in args.ranks.split(",")]
    if ranks[0] != 1:
        ranks.insert(0, 1)
    print("| model | elements | ranks | peak per rank, MB | program's own, MB | share per rank |")
    print("|---|---|---|---|---|---|")
    with tempfile.TemporaryDirectory(prefix="exdyn_memory_") as out:
        own = {r: peaks(args.exdyn, r, SMALL, out) for r in ranks}
        for name, elements in (("plane", args.plane), ("solid", args.solid)):
            n = 2
            for v in elements.split(","):
                n *= int(v)
            one = None
            for r in ranks:
                peak = peaks(args.exdyn, r, elements, out)
                model = [x - y for x, y in zip(peak, own[r])]
                if r == 1:
                    one = model[0]
                share = [m / one for m in model]
                print(f"| {name} {elements.replace(',', ' x ')} | {n:,} | {r} | "
                      f"{', '.join(f'{x:.1f}' for x in peak)} | {', '.join(f'{x:.1f}' for x in own[r])} | "
                      f"{', '.join(f'{s:.3f}' for s in share)} |", flush=True)


if __name__ == "__main__":
    main()
