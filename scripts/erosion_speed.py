#!/usr/bin/python3
"""The cost of following erosion before anything erodes (docs/performance.md,
"Contact on opened faces: its cost").

Runs input/punch_through.yaml with the rod at 100 m/s (its first element fails at step
174) to step 165, with the plate's `failure` and without it, alternately, REPEATS times
each, and prints the median element-cycle rate of the time loop (the summary's
element_cycles_per_second), the median wall time of the whole run (setup included) and
their ratios. With `failure` the contact surface holds every face the plate's bricks
share (dead until exposed) and the damage pass runs; without it, neither.

  /usr/bin/python3 scripts/erosion_speed.py [--exdyn PATH] [--repeats 9] [--threads 2]
"""
import argparse
import json
import os
import statistics
import subprocess
import sys
import tempfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.dirname(HERE)
sys.path.insert(0, HERE)
import batch_plate_impact as batch  # noqa: E402

DECK = os.path.join(REPO, "input", "punch_through.yaml")
END_TIME = "1.7e-6"  # 165 steps of 1.0414e-8 s


def run(exdyn, deck, out, threads):
    """(element-cycles/s of the time loop, wall seconds of the whole run, steps)."""
    cmd = [exdyn, "run", deck, "--quiet", "--output", out, "--threads", str(threads),
           "--set", "parts[0].initial_velocity=[0, 0, -100]", "--set", f"time.end_time={END_TIME}",
           "--set", "output.every=100000"]
    start = time.perf_counter()
    subprocess.run(cmd, check=True, capture_output=True, text=True)
    wall = time.perf_counter() - start
    with open(os.path.join(out, "punch_through.json")) as f:
        summary = json.load(f)
    if summary["energy"]["eroded_elements"] != 0:
        raise SystemExit("an element failed before the end: the comparison is up to the first erosion")
    return summary["element_cycles_per_second"], wall, summary["steps"]


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--exdyn", default=batch.default_exdyn())
    p.add_argument("--repeats", type=int, default=9)
    p.add_argument("--threads", type=int, default=2)
    args = p.parse_args()
    rates = {True: [], False: []}
    walls = {True: [], False: []}
    with tempfile.TemporaryDirectory() as work:
        # The same deck with the plate's material never failing: its `failure` line gone.
        with open(DECK) as f:
            lines = f.readlines()
        kept = [line for line in lines if not line.strip().startswith("failure:")]
        assert len(kept) == len(lines) - 1, "the deck has one failure line"
        decks = {True: DECK, False: os.path.join(work, "punch_through.yaml")}
        with open(decks[False], "w") as f:
            f.writelines(kept)
        for _ in range(args.repeats):
            for failing in (True, False):
                rate, wall, steps = run(args.exdyn, decks[failing], os.path.join(work, str(failing)), args.threads)
                rates[failing].append(rate)
                walls[failing].append(wall)
    print(f"punch_through.yaml at 100 m/s to step {steps}, {args.threads} threads, {args.repeats} runs each:")
    for failing in (True, False):
        print(f"  {'failure' if failing else 'no failure':10s}: {statistics.median(rates[failing]):.4g} "
              f"element-cycles/s (time loop, median; {min(rates[failing]):.4g} to {max(rates[failing]):.4g}), "
              f"{statistics.median(walls[failing]):.3f} s whole run (median)")
    print(f"  rate ratio failure / none: {statistics.median(rates[True]) / statistics.median(rates[False]):.3f}; "
          f"wall ratio: {statistics.median(walls[True]) / statistics.median(walls[False]):.3f}")


if __name__ == "__main__":
    main()
