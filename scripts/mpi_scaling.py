#!/usr/bin/python3
"""Scaling on many ranks (docs/parallel.md), measured on this machine.

Strong scaling: the plate impact at mesh M (2 x M x M elements, the contact included) on
ranks x threads = 1x1, 1x2, 2x1 (and, past the cores, 2x2 and 3x1, marked
oversubscribed). Weak scaling: a fixed block per rank (the plate impact's two plates
100 x 1 x 100 each, stacked R times along z for R ranks, the contact face R times
longer). Each configuration runs --repeat times; the table gives the median
element-cycles per second of the time loop (elements x steps / seconds), the
efficiency against one rank on one thread (strong: speed-up / cores used; weak: rate per
rank), the longest time a rank waited in the exchanges, and the exchange's messages and
bytes per step. Fields written only at the first and last step.

  /usr/bin/python3 scripts/mpi_scaling.py [--exdyn PATH] [--mesh 200] [--repeat 3] [--docs docs]

Writes the table between the markers `batch:mpi_scaling` of docs/parallel.md.
"""
import argparse
import json
import os
import statistics
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.dirname(HERE)
sys.path.insert(0, HERE)
import batch_plate_impact as batch  # noqa: E402

CORES = os.cpu_count() or 1


def run(exdyn, ranks, threads, sets, out, deck="plate_impact"):
    cmd = []
    if ranks > 1:
        cmd = ["mpirun", "-n", str(ranks), "--oversubscribe"] + (["--allow-run-as-root"] if os.geteuid() == 0 else [])
    cmd += [exdyn, "run", os.path.join(REPO, "input", deck + ".yaml"), "--quiet", "--output", out,
            "--threads", str(threads), "--set", "output.every=100000"]
    for s in sets:
        cmd += ["--set", s]
    subprocess.run(cmd, check=True, capture_output=True, text=True)
    with open(os.path.join(out, deck + ".json")) as f:
        return json.load(f)


def measure(exdyn, ranks, threads, sets, repeat, deck="plate_impact"):
    rates, waits, summary = [], [], None
    with tempfile.TemporaryDirectory(prefix="exdyn_scaling_") as out:
        for _ in range(repeat):
            summary = run(exdyn, ranks, threads, sets, out, deck)
            rates.append(summary["element_cycles_per_second"])
            waits.append(summary["mpi"].get("exchange_seconds", 0.0))
    return statistics.median(rates), statistics.median(waits), summary


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--exdyn", default=batch.default_exdyn())
    p.add_argument("--mesh", type=int, default=200)
    p.add_argument("--repeat", type=int, default=3)
    p.add_argument("--docs", default=os.path.join(REPO, "docs"))
    args = p.parse_args()

    m = args.mesh

    def strong_table(deck, sets):
        rows = []
        base = None
        for ranks, threads in [(1, 1), (1, 2), (2, 1), (2, 2), (3, 1)]:
            rate, wait, s = measure(args.exdyn, ranks, threads, sets, args.repeat, deck)
            base = base or rate
            cores = min(ranks * threads, CORES)
            over = ranks * threads > CORES
            rows.append([f"{ranks} x {threads}" + (" (oversubscribed)" if over else ""), s["mesh"]["elements"],
                         s["steps"], f"{rate:.3g}", f"{rate / base:.2f}", f"{rate / base / cores:.2f}",
                         f"{wait:.3f}", s["mpi"].get("messages_per_step", 0),
                         f"{s['mpi'].get('bytes_per_step', 0) / 1e3:.1f}", s["mpi"].get("contact_nodes", 0)])
            print(deck, rows[-1], flush=True)
        return batch.table(["ranks x threads", "elements", "steps", "element-cycles/s", "speed-up",
                            "efficiency per core", "exchange wait (s)", "messages/step", "kB/step",
                            "ghost contact nodes"], rows)

    strong = strong_table("plate_impact", [f"parts[0].elements=[{m}, 1, {m}]", f"parts[1].elements=[{m}, 1, {m}]"])
    # One plate (the reference calculation: no contact), which 2 ranks must cut.
    strong_one = strong_table("plate_impact_reference", [f"parts[0].elements=[{m}, 1, {m}]"])

    rows = []
    base = None
    for ranks in [1, 2, 4]:
        sets = []
        for part in (0, 1):
            sets += [f"parts[{part}].elements=[100, 1, {100 * ranks}]"]
        sets += [f"parts[0].box.max=[0, 2.5e-5, {2.5e-3 * ranks}]",
                 f"parts[1].box.max=[2.5e-3, 2.5e-5, {2.5e-3 * ranks}]"]
        rate, wait, s = measure(args.exdyn, ranks, 1, sets, args.repeat)
        per_rank = rate / ranks
        base = base or per_rank
        over = ranks > CORES
        rows.append([f"{ranks}" + (" (oversubscribed)" if over else ""), s["mesh"]["elements"], s["steps"],
                     f"{rate:.3g}", f"{per_rank:.3g}", f"{per_rank / base:.2f}", f"{wait:.3f}",
                     s["mpi"].get("messages_per_step", 0), f"{s['mpi'].get('bytes_per_step', 0) / 1e3:.1f}",
                     s["mpi"].get("contact_nodes", 0)])
        print(rows[-1], flush=True)
    weak = batch.table(["ranks (1 thread)", "elements", "steps", "element-cycles/s", "per rank",
                        "efficiency", "exchange wait (s)", "messages/step", "kB/step", "ghost contact nodes"],
                       rows)
    text = (f"Written by `/usr/bin/python3 scripts/mpi_scaling.py --mesh {m} --repeat {args.repeat}` on "
            f"{CORES} cores (medians of {args.repeat} runs).\n\nStrong scaling, the plate impact at mesh {m}:\n\n"
            + strong + f"\n\nStrong scaling, one plate (the reference calculation, no contact) at mesh {m}:\n\n"
            + strong_one + "\n\nWeak scaling, two 100 x 1 x 100 plates per rank:\n\n" + weak)
    batch.write_doc(os.path.join(args.docs, "parallel.md"), {"mpi_scaling": text})
    print(f"mpi_scaling: wrote the tables in {os.path.join(args.docs, 'parallel.md')}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
