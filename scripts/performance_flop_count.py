#!/usr/bin/python3
"""Floating-point operations and instructions per element-cycle of each element
kernel, counted by the machine (docs/performance.md): runs one call of
add_internal_forces of bench/element/element_bench under valgrind's callgrind
(instruction-level counts, collection only inside add_internal_forces), maps every
executed instruction to its mnemonic with objdump and counts the arithmetic
instructions by kind and width.

    scripts/performance_flop_count.py [BUILD_DIR] [--n 22] [--json OUT.json]

BUILD_DIR defaults to build/h-perf. Flops: add/sub/mul/div = 1 per lane,
FMA = 2 per lane (xmm: 2 lanes, ymm: 4, zmm: 8; scalar sd: 1). Compares, min/max,
and/or/xor (abs, negation) are counted apart, not as flops.
"""
import argparse
import json
import os
import re
import subprocess
import sys
import tempfile

BENCHMARKS = [  # (label, benchmark name)
    ("hex8 parallelepiped", "hex8_box"),
    ("hex8 general", "hex8_distorted"),
    ("hex8r parallelepiped", "hex8r_box"),
    ("hex8r general", "hex8r_distorted"),
]
TOGGLE = "exdyn::element::add_internal_forces(exdyn::element::ElementBlock const&, exdyn::NodalVectors const&*"

ARITH = re.compile(r"^v?(add|sub|mul|div|sqrt)(p|s)d$")
FMA = re.compile(r"^vf(n?)m(add|sub)(132|213|231)(p|s)d$")
OTHER = re.compile(r"^v?(max|min|cmp[a-z]*|and|andn|or|xor)(p|s)d$")
SHUFFLE = re.compile(r"^v?(unpck[lh]p[ds]|shufp[ds]|movhlps|movlhps|movddup|pshufd|blendp[ds]|permilp[ds]|perm2f128|"
                     r"insertf128|extractf128|broadcasts[ds])$")


def lanes(mnemonic_kind, operands):
    if mnemonic_kind == "s":
        return 1
    if "%zmm" in operands:
        return 8
    if "%ymm" in operands:
        return 4
    return 2


def disassemble(binary):
    """address -> (mnemonic, operands) of every instruction of the binary."""
    out = subprocess.run(["objdump", "-d", "--no-show-raw-insn", binary], check=True, capture_output=True,
                         text=True).stdout
    table = {}
    for line in out.splitlines():
        m = re.match(r"^\s+([0-9a-f]+):\s+(\S+)\s*(.*)$", line)
        if m:
            table[int(m.group(1), 16)] = (m.group(2), m.group(3))
    return table


def self_costs(callgrind_file):
    """(object, address) -> executed count, from a callgrind file written with
    --dump-instr=yes --dump-line=no (positions: instr; events: Ir)."""
    costs = {}
    names = {}
    obj = None
    last = 0
    skip_next = False
    with open(callgrind_file) as f:
        for raw in f:
            line = raw.strip()
            if not line or line.startswith("#"):
                continue
            m = re.match(r"(c?ob)=\((\d+)\)\s*(.*)", line)
            if m:  # object names are given once, at the first ob= or cob= of their id
                if m.group(3):
                    names[m.group(2)] = m.group(3)
                if m.group(1) == "ob":
                    obj = names[m.group(2)]
                continue
            if line.startswith("calls="):
                skip_next = True  # the next cost line is the call's inclusive cost
                continue
            if line.startswith(("0x", "+", "-", "*")):
                fields = line.split()
                pos = fields[0]
                if pos.startswith("0x"):
                    last = int(pos, 16)
                elif pos[0] == "+":
                    last += int(pos[1:])
                elif pos[0] == "-":
                    last -= int(pos[1:])
                executed = int(fields[1]) if len(fields) > 1 else 0
                if skip_next:
                    skip_next = False
                    continue
                costs[(obj, last)] = costs.get((obj, last), 0) + executed
    return costs


def count(binary, benchmark, n, workdir):
    out_file = os.path.join(workdir, f"callgrind.{benchmark}.out")
    run = subprocess.run(
        ["valgrind", "--tool=callgrind", f"--callgrind-out-file={out_file}", "--collect-atstart=no",
         f"--toggle-collect={TOGGLE}", "--dump-instr=yes", "--dump-line=no", binary,
         f"--benchmark_filter=^{benchmark}/n:{n}/threads:1/real_time$", "--benchmark_min_time=0"],
        check=True, capture_output=True, text=True)
    iterations = None
    for line in run.stdout.splitlines():
        m = re.match(rf"^{benchmark}/n:{n}/threads:1(?:/real_time)?\s+\S+ \S+\s+\S+ \S+\s+(\d+)\s", line)
        if m:
            iterations = int(m.group(1))
    if iterations is None:
        sys.exit(f"no result line for {benchmark}/{n} in:\n{run.stdout}")
    total_ir = int(re.search(r"refs:\s+([\d,]+)", run.stderr).group(1).replace(",", ""))
    code = disassemble(binary)
    costs = self_costs(out_file)
    tally = {"Ir": 0, "add": 0, "mul": 0, "div": 0, "fma": 0, "flops": 0, "packed": 0, "scalar": 0, "other_fp": 0,
             "memory": 0, "shuffle": 0, "unmapped_Ir": 0}
    mnemonics = {}
    real_binary = os.path.realpath(binary)
    for (obj, address), executed in costs.items():
        tally["Ir"] += executed
        if obj is None or os.path.realpath(obj) != real_binary or address not in code:
            tally["unmapped_Ir"] += executed
            continue
        mnemonic, operands = code[address]
        if "(" in operands and not mnemonic.startswith(("lea", "nop")):
            tally["memory"] += executed  # a load, a store or an operation with a memory operand
        if SHUFFLE.match(mnemonic) or (mnemonic.startswith(("movhp", "movlp", "vmovhp", "vmovlp"))
                                       and "(" not in operands):
            tally["shuffle"] += executed
        m = ARITH.match(mnemonic)
        f = FMA.match(mnemonic)
        if m:
            width = lanes(m.group(2), operands)
            kind = {"add": "add", "sub": "add", "mul": "mul", "div": "div", "sqrt": "div"}[m.group(1)]
            tally[kind] += executed * width
            tally["flops"] += executed * width
            tally["packed" if m.group(2) == "p" else "scalar"] += executed
            mnemonics[mnemonic] = mnemonics.get(mnemonic, 0) + executed
        elif f:
            width = lanes(f.group(4), operands)
            tally["fma"] += executed * width
            tally["flops"] += 2 * executed * width
            tally["packed" if f.group(4) == "p" else "scalar"] += executed
            mnemonics[mnemonic] = mnemonics.get(mnemonic, 0) + executed
        elif OTHER.match(mnemonic):
            tally["other_fp"] += executed
    if tally["Ir"] != total_ir:
        sys.exit(f"parsed {tally['Ir']} Ir but callgrind reports {total_ir}")
    element_cycles = iterations * n ** 3
    per_element = {k: v / element_cycles for k, v in tally.items()}
    per_element["mnemonics"] = {k: v / element_cycles for k, v in sorted(mnemonics.items())}
    return per_element


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("build_dir", nargs="?", default="build/h-perf")
    parser.add_argument("--n", type=int, default=22, help="box of n^3 elements (22, 46 or 100)")
    parser.add_argument("--json", help="write the counts to this file")
    args = parser.parse_args()
    binary = os.path.join(args.build_dir, "bench/element/element_bench")
    results = {}
    with tempfile.TemporaryDirectory() as workdir:
        for label, benchmark in BENCHMARKS:
            results[label] = count(binary, benchmark, args.n, workdir)
    print(f"per element-cycle, {binary}, box of {args.n}^3 elements, one call of add_internal_forces")
    print(f"{'kernel':<22} {'Ir':>7} {'flops':>7} {'add':>6} {'mul':>6} {'fma':>5} {'packed':>7} {'scalar':>7}"
          f" {'cmp/and/xor':>11} {'memory':>7} {'shuffle':>7}")
    for label, r in results.items():
        print(f"{label:<22} {r['Ir']:7.1f} {r['flops']:7.1f} {r['add']:6.1f} {r['mul']:6.1f} {r['fma']:5.1f} "
              f"{r['packed']:7.1f} {r['scalar']:7.1f} {r['other_fp']:11.1f} {r['memory']:7.1f} {r['shuffle']:7.1f}")
    for label, r in results.items():
        print(f"{label}: " + ", ".join(f"{k} {v:.1f}" for k, v in r["mnemonics"].items()))
    if args.json:
        with open(args.json, "w") as f:
            json.dump(results, f, indent=1)


if __name__ == "__main__":
    main()
