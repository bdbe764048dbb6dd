#!/usr/bin/python3
"""The plate impact's rate against its size (docs/performance.md, "The large plate"):
input/plate_impact.yaml refined to m x 1 x m bricks a plate (m = 100 is the deck as
shipped, 20,000 bricks; 800 is 1.28 M), about 200 steps each (the end time scaled with
h), output at the first and last steps only. The sizes run in turn, `--repeat` rounds, so
that a drift of the host's speed touches them alike. Prints, per size, the median
element-cycles/s of the time loop and each phase's time per element-cycle (ns): where the
larger model loses its rate.

    /usr/bin/python3 scripts/plate_size_rates.py [--exdyn PATH] [--threads 1] [--repeat 3]
                                                 [--meshes 100,200,400,800]
"""
import argparse
import json
import os
import statistics
import subprocess
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
PHASES = ("element_forces", "contact", "time_integration", "other")


def run(exdyn, mesh, threads, out):
    h = 2.5e-3 / mesh  # one brick through the thickness (y), as shipped
    command = [exdyn, "run", os.path.join(ROOT, "input", "plate_impact.yaml"), "--quiet", "--threads",
               str(threads), "--output", out, "--set", "output.every=1000000",
               "--set", f"parts[0].elements=[{mesh},1,{mesh}]", "--set", f"parts[1].elements=[{mesh},1,{mesh}]",
               "--set", f"parts[0].box.max=[0,{h},2.5e-3]", "--set", f"parts[1].box.max=[2.5e-3,{h},2.5e-3]",
               "--set", f"time.end_time={1.04e-5 / mesh}"]
    subprocess.run(command, check=True)
    with open(os.path.join(out, "plate_impact.json")) as f:
        summary = json.load(f)
    cycles = summary["steps"] * summary["mesh"]["elements"]
    phase = summary["phase_seconds"]
    contact = sum(phase[k] for k in ("contact_global_search", "contact_local_search", "contact_forces"))
    loop = cycles / summary["element_cycles_per_second"]  # the time loop's seconds
    ns = {"element_forces": phase["element_forces"], "contact": contact,
          "time_integration": phase["time_integration"]}
    ns["other"] = loop - sum(ns.values())
    return summary["element_cycles_per_second"], {k: 1e9 * v / cycles for k, v in ns.items()}, summary["mesh"]


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--exdyn", default=os.path.join(ROOT, "build", "release", "src", "app", "exdyn"))
    parser.add_argument("--threads", type=int, default=1)
    parser.add_argument("--repeat", type=int, default=3)
    parser.add_argument("--meshes", default="100,200,400,800")
    args = parser.parse_args()
    meshes = [int(m) for m in args.meshes.split(",")]
    rates = {m: [] for m in meshes}
    phases = {m: {p: [] for p in PHASES} for m in meshes}
    sizes = {}
    with tempfile.TemporaryDirectory() as out:
        for _ in range(args.repeat):
            for m in meshes:
                rate, ns, mesh = run(args.exdyn, m, args.threads, out)
                rates[m].append(rate)
                for p in PHASES:
                    phases[m][p].append(ns[p])
                sizes[m] = mesh
    print(f"plate impact, {args.threads} thread(s), median of {args.repeat} (ns per element-cycle)")
    print(f"{'mesh':>5} {'elements':>10} {'nodes':>10} {'rate':>10} {'vs first':>8} "
          + " ".join(f"{p:>16}" for p in PHASES))
    first = statistics.median(rates[meshes[0]])
    for m in meshes:
        rate = statistics.median(rates[m])
        print(f"{m:>5} {sizes[m]['elements']:>10} {sizes[m]['nodes']:>10} {rate:>10.3e} {rate / first:>8.2f} "
              + " ".join(f"{statistics.median(phases[m][p]):>16.2f}" for p in PHASES))


if __name__ == "__main__":
    main()
