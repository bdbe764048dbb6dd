#!/usr/bin/python3
"""Test of scripts/serial_fraction.py's reading of call stacks, on perf script text
written here: samples outside the time loop are not counted, a sample under an OpenMP
region's body or one_thread_loop is threaded, any other sample in the loop is serial
and named by its innermost exdyn function.

    /usr/bin/python3 scripts/test_serial_fraction.py
Exit status 0 when every check holds.
"""
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import serial_fraction as sf  # noqa: E402

LOOP = "_ZN5exdyn6solver12_GLOBAL__N_18TimeLoop3runEv"
SAMPLES = [
    # setup: outside the loop
    ["_ZN5exdyn4mesh15add_mapped_partEv", "_ZN5exdyn6solver14run_simulationEv", "main"],
    # the element pass on the threads
    ["_ZN5exdyn7element14loop_x86_64_v4Ev", "_ZN5exdyn7element16add_chunk_forcesEv._omp_fn.0",
     "GOMP_parallel", LOOP, "main"],
    # the same pass on one thread, through one_thread_loop
    ["_ZN5exdyn7element14loop_x86_64_v4Ev", "_ZN5exdyn15one_thread_loopIZNS_7elementEvEEvlRT_", LOOP, "main"],
    # serial: the output staging (twice) and libgomp starting a region
    ["__memset_avx512", "_ZN5exdyn6output12ResultWriter4Impl10fill_frameEv", LOOP, "main"],
    ["_ZN5exdyn6output12ResultWriter4Impl10fill_frameEv", LOOP, "main"],
    ["[unknown]", "_ZN5exdyn7element19add_internal_forcesEv", LOOP, "main"],
]


def perf_text(samples):
    """perf script -F ip,sym: a header-less block of "address name" lines per sample."""
    blocks = []
    for frames in samples:
        blocks.append("\n".join(f"\t{0x1000 + 16 * i:16x} {name}" for i, name in enumerate(frames)))
    return "\n\n".join(blocks) + "\n"


def main():
    loop, threaded, serial_at = sf.classify(perf_text(SAMPLES))
    names = dict(zip(serial_at, sf.demangled(list(serial_at))))
    checks = [
        ("five samples in the loop", loop == 5),
        ("two threaded (a region's body, one_thread_loop)", threaded == 2),
        ("fill_frame serial twice", serial_at["_ZN5exdyn6output12ResultWriter4Impl10fill_frameEv"] == 2),
        ("a region's start named by its caller",
         serial_at["_ZN5exdyn7element19add_internal_forcesEv"] == 1),
        ("names demangled", "exdyn::output::ResultWriter::Impl::fill_frame" in names.values()),
    ]
    failed = [name for name, ok in checks if not ok]
    for name, ok in checks:
        print(("ok   " if ok else "FAIL ") + name)
    print(f"{len(checks) - len(failed)} passed, {len(failed)} failed")
    sys.exit(1 if failed else 0)


if __name__ == "__main__":
    main()
