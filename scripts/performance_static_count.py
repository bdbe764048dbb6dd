#!/usr/bin/python3
"""Flops and instructions per element of the packed element loops, counted in the
machine code (docs/performance.md, "Vector kernels"): disassembles the loop that an ISA
runs for a pack of elements (objdump), and counts its instructions and its
floating-point arithmetic, divided by the pack width.

    scripts/performance_static_count.py [BINARY] [--isa x86-64-v3]

BINARY defaults to build/release/bench/element/element_bench. The body of each packed
loop is straight-line code per pack (the kernel is inlined whole, its loops unrolled), so
the static count is the count per pack, apart from the per-lane bookkeeping (energies,
stress stores, the lane-by-lane scatter of packs that are not row packs), which it counts
once per pack instead of once per lane: it slightly undercounts that part. Flops:
add/sub/mul/div = 1 per lane, FMA = 2 per lane. (On x86-64-v2 the counts agree with the
executed counts of scripts/performance_flop_count.py to 2-7 %.)
"""
import argparse
import re
import subprocess

LOOPS = [  # (label, the loop template's name as objdump -C prints it, lanes per ISA)
    ("hex8 axis-aligned", "hex8_parallelepiped_loop<{L}, true>"),
    ("hex8 parallelepiped", "hex8_parallelepiped_loop<{L}, false>"),
    ("hex8 general", "hex8_general_loop<{L}>"),
    ("hex8r parallelepiped", "hex8r_loop<true, {L}>"),
    ("hex8r general", "hex8r_loop<false, {L}>"),
    # The finite-strain loops of linear hardening: every path of the return mapping and
    # of the corner checks (step and inversion) counted once, as if all ran every pack.
    ("hex8r finite plastic", "hex8r_law_loop<exdyn::material::Hardening, true, {L}>"),
    ("hex8 F-bar finite plastic", "hex8_law_loop<exdyn::material::Hardening, true, {L}>"),
]
LANES = {"x86-64-v2": 2, "x86-64-v3": 4, "x86-64-v4": 8}


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("binary", nargs="?", default="build/release/bench/element/element_bench")
    parser.add_argument("--isa", default="x86-64-v3", choices=sorted(LANES))
    args = parser.parse_args()
    lanes = LANES[args.isa]
    text = subprocess.run(["objdump", "-d", "-C", "--no-show-raw-insn", args.binary], check=True,
                          capture_output=True, text=True).stdout
    functions = re.split(r"\n(?=[0-9a-f]+ <)", text)
    wrapper = "loop_" + args.isa.replace("-", "_")
    print(f"{args.binary}, {args.isa}: per element (static count of the pack loop / {lanes})")
    print(f"{'loop':<26} {'instructions':>12} {'fp':>6} {'flops':>7}")
    for label, name in LOOPS:
        target = name.format(L=lanes)
        body = next((f for f in functions if wrapper in f.split("\n", 1)[0] and target in f.split("\n", 1)[0]), None)
        if body is None:
            print(f"{label:<26} not found")
            continue
        instructions = fp = flops = 0
        for line in body.split("\n")[1:]:
            m = re.match(r"\s+[0-9a-f]+:\s+(\S+)\s*(.*)$", line)
            if not m:
                continue
            mnemonic, operands = m.group(1), m.group(2)
            instructions += 1
            width = 8 if "%zmm" in operands else 4 if "%ymm" in operands else 2
            if re.match(r"^v?(add|sub|mul|div)pd$", mnemonic):
                fp, flops = fp + 1, flops + width
            elif re.match(r"^v?(add|sub|mul|div)sd$", mnemonic):
                fp, flops = fp + 1, flops + 1
            elif re.match(r"^vfn?m(add|sub)\d+pd$", mnemonic):
                fp, flops = fp + 1, flops + 2 * width
            elif re.match(r"^vfn?m(add|sub)\d+sd$", mnemonic):
                fp, flops = fp + 1, flops + 2
        print(f"{label:<26} {instructions / lanes:>12.0f} {fp / lanes:>6.0f} {flops / lanes:>7.0f}")


if __name__ == "__main__":
    main()
