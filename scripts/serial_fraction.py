#!/usr/bin/python3
"""The serial fraction of exdyn's time loop, measured: samples of the call stacks (Linux
perf, DWARF unwinding) of one run, each sample inside the time loop (TimeLoop::run on
its stack) counted as threaded when an OpenMP region's body (GCC's outlined
"._omp_fn." functions) or exdyn's one_thread_loop (common/parallel.hpp: what
parallel_for_static runs in place of a region on one thread) is on its stack, and as serial otherwise. Run on one thread,
the serial share is what Amdahl's law charges: the speed-up on p threads is at most
1 / (s + (1 - s) / p). Prints the share, that bound for 2 and 16 threads, and where
the serial samples fall (the innermost exdyn function of each, by samples).

    scripts/serial_fraction.py [--exdyn PATH] [--frequency HZ] -- run DECK [exdyn options...]

The run's own options follow `--` (give `--threads 1` for the figure Amdahl reads).
Needs perf (scripts/install_deps.sh --perf: Debian's linux-perf), a kernel that lets
this user sample it (kernel.perf_event_paranoid <= 2) and exdyn's symbol table (the
Release build keeps it).
"""
import argparse
import collections
import os
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def perf_script(perf_data):
    """The samples' call stacks as perf script prints them (addresses, mangled names)."""
    return subprocess.run(["perf", "script", "-i", perf_data, "-F", "ip,sym", "--no-demangle"],
                          capture_output=True, text=True, check=True).stdout


def stacks(text):
    """Each sample's frames (symbol names, innermost first), from perf script's text."""
    frames = []
    for line in text.splitlines():
        line = line.strip()
        if not line:
            if frames:
                yield frames
            frames = []
            continue
        # "  ffff... name (inlined)" or "name+0x..": the name without the offset
        parts = line.split(None, 1)
        name = parts[1] if len(parts) > 1 and all(c in "0123456789abcdef" for c in parts[0]) else line
        frames.append(name.replace(" (inlined)", ""))
    if frames:
        yield frames


def classify(text):
    """Samples inside the time loop, those of them threaded, and the serial ones by the
    innermost exdyn function (mangled)."""
    loop = threaded = 0
    serial_at = collections.Counter()
    for frames in stacks(text):
        if not any("8TimeLoop3runEv" in f for f in frames):  # exdyn::solver::TimeLoop::run()
            continue
        loop += 1
        if any("._omp_fn." in f or "one_thread_loop" in f for f in frames):
            threaded += 1
            continue
        serial_at[next((f for f in frames if "5exdyn" in f), frames[0])] += 1
    return loop, threaded, serial_at


def demangled(names):
    text = subprocess.run(["c++filt"], input="\n".join(names), capture_output=True, text=True).stdout
    return [line.replace("(anonymous namespace)", "{anon}").split("(")[0][:110] for line in text.splitlines()]


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--exdyn", default=os.path.join(ROOT, "build/release/src/app/exdyn"))
    parser.add_argument("--frequency", type=int, default=4000, help="samples per second (default 4000)")
    parser.add_argument("run", nargs=argparse.REMAINDER, help="-- run DECK [options]")
    args = parser.parse_args()
    command = [a for a in args.run if a != "--"]
    if not command:
        parser.error("give the run after --, e.g. -- run input/taylor_bar.yaml --threads 1")
    with tempfile.TemporaryDirectory() as scratch:
        data = os.path.join(scratch, "perf.data")
        if "--output" not in command:
            command += ["--output", scratch]
        subprocess.run(["perf", "record", "-q", "--call-graph", "dwarf,32768", "-F", str(args.frequency), "-o",
                        data, args.exdyn] + command + ["--quiet"], check=True, stdout=subprocess.DEVNULL)
        loop, threaded, serial_at = classify(perf_script(data))
    if loop == 0:
        sys.exit("no sample inside TimeLoop::run: is the build's symbol table there (not stripped)?")
    serial = (loop - threaded) / loop
    amdahl = lambda p: 1.0 / (serial + (1.0 - serial) / p)
    print(f"time loop samples {loop}: threaded {threaded}, serial {loop - threaded} = {100 * serial:.2f} %")
    print(f"Amdahl's bound: {amdahl(2):.2f}x on 2 threads, {amdahl(16):.1f}x on 16")
    top = serial_at.most_common(12)
    for (_, count), name in zip(top, demangled([n for n, _ in top])):
        print(f"  {100 * count / loop:6.2f} %  {name}")


if __name__ == "__main__":
    main()
