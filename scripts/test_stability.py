#!/usr/bin/python3
"""Stability tests through the executable (docs/stability.md): the run-time
guards, interrupted runs, and results that survive SIGKILL.

    /usr/bin/python3 scripts/test_stability.py --exdyn PATH [--kills N] [--write-kills N] [--keep DIR]

Checks:
- input/unstable_plate.yaml (Courant 1.5), hex8 and hex8r: exit 1 within a few steps,
  a message naming the step, NAME.json "failed", and a result that ParaView reads
  (../shared/tools/paraview/check_xdmf.py, all three XDMF readers) whose last step is
  the step the guard fired at;
- input/inverting_bar.yaml: exit 1 naming element 9;
- a fixed penalty stiffness above any stable bound: refused (exit 2) with the bound; one
  between that optimistic bound and the real one: caught by the energy guard;
- every local search failing (simplex, one iteration): counted, reported, no force;
- SIGTERM during a run: the run finishes its step, writes it and a checkpoint, exits 3
  with "stopped by SIGTERM"; the result is complete up to that step (going on from the
  checkpoint: scripts/test_restart.py);
- SIGKILL at random moments of the run's progress (--kills, default 20): every time, the files left are a
  result that h5py and ParaView read, holding every step the .xmf lists, with the
  same data as an uninterrupted run of the same deck at those steps;
- with --write-kills N (default 0; a campaign, not part of the suite): N more SIGKILLs, at
  uniformly random moments, of a run that writes a step every 8 steps, so that most of its
  wall time is spent writing NAME.h5 and most kills land inside a write
  (docs/stability.md, "Interrupted and killed runs"). Same checks, against an uninterrupted run of it.
Prints `N passed, M failed`; exit 0 when all passed.
"""

import argparse
import json
import os
import random
import re
import shutil
import signal
import subprocess
import sys
import tempfile
import time

import h5py
import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
sys.path.insert(0, HERE)
import batch_plate_impact as batch  # noqa: E402  (the ParaView runner, one at a time)

CHECKER = batch.PVPYTHON_RUNNER

results = []


def check(name, ok, detail=""):
    results.append(bool(ok))
    print(f"{'ok  ' if ok else 'FAIL'} {name}" + (f": {detail}" if detail and not ok else ""), flush=True)


def run(exdyn, deck, out, *sets, name=None):
    cmd = [exdyn, "run", os.path.join(ROOT, "input", deck), "--quiet", "--output", out]
    if name:
        cmd += ["--set", f"name={name}"]
    for s in sets:
        cmd += ["--set", s]
    proc = subprocess.run(cmd, capture_output=True, text=True, timeout=600)
    return proc.returncode, proc.stdout + proc.stderr


def xmf_steps(xmf_path):
    """Step numbers the .xmf names (from its /steps/NNNNNN/ references), in order."""
    text = open(xmf_path).read()
    steps = []
    for m in re.finditer(r":/steps/(\d{6})/", text):
        n = int(m.group(1))
        if not steps or steps[-1] != n:
            steps.append(n)
    return sorted(set(steps))


def paraview_reads(xmf_path, readers="all", max_steps=None):
    if not os.access(CHECKER, os.X_OK):
        return False, f"{CHECKER} not found (../shared must sit beside the repository)"
    cmd = batch.pvpython("check_xdmf.py", xmf_path, "--strict", "--compact", "--readers", readers)
    if max_steps:
        cmd += ["--max-steps", str(max_steps)]
    proc = subprocess.run(cmd, capture_output=True, text=True, timeout=600)
    return proc.returncode == 0, (proc.stdout + proc.stderr)[-2000:]


def summary(out, name):
    with open(os.path.join(out, name + ".json")) as f:
        return json.load(f)


def test_unstable(exdyn, work):
    for form in ("hex8", "hex8r"):
        out = os.path.join(work, "unstable_" + form)
        status, text = run(exdyn, "unstable_plate.yaml", out, f"parts[0].formulation={form}")
        m = re.search(r"at step (\d+), time", text)
        check(f"unstable_plate {form}: exit 1 naming the step", status == 1 and m, text)
        if not m:
            continue
        step = int(m.group(1))
        check(f"unstable_plate {form}: caught within a few steps ({step})", step <= 10, text)
        check(f"unstable_plate {form}: an energy guard message", "the energy grew by" in text, text)
        s = summary(out, "unstable_plate")
        check(f"unstable_plate {form}: summary failed at step {step}",
              s["status"] == "failed" and s["steps"] == step and "at step" in s["message"], json.dumps(s)[:400])
        xmf = os.path.join(out, "unstable_plate.xmf")
        check(f"unstable_plate {form}: the last step written is the guard's",
              xmf_steps(xmf)[-1] == step, str(xmf_steps(xmf)))
        with h5py.File(os.path.join(out, "unstable_plate.h5"), "r") as f:
            finite = all(np.isfinite(f[f"steps/{n:06d}/{d}"][...]).all()
                         for n in xmf_steps(xmf) for d in f[f"steps/{n:06d}"])
        check(f"unstable_plate {form}: every value written is finite", finite)
        ok, detail = paraview_reads(xmf)
        check(f"unstable_plate {form}: ParaView reads the failed run", ok, detail)


def test_inverting(exdyn, work):
    out = os.path.join(work, "inverting")
    status, text = run(exdyn, "inverting_bar.yaml", out)
    check("inverting_bar: exit 1 naming element 9", status == 1 and "element 9 is inverted" in text, text)
    check("inverting_bar: and the step", re.search(r"at step \d+, time", text), text)
    ok, detail = paraview_reads(os.path.join(out, "inverting_bar.xmf"))
    check("inverting_bar: ParaView reads the failed run", ok, detail)


def test_stiff_penalty(exdyn, work):
    out = os.path.join(work, "stiff")
    for k in ("1e9", "1e12"):  # above the bound even for the most favourable contact: refused
        status, text = run(exdyn, "plate_impact.yaml", out, f"contact[0].penalty={{stiffness: {k}}}",
                           "output.every=100000", name="stiff")
        check(f"plate_impact, fixed stiffness {k} N/m: refused (exit 2) with the bound",
              status == 2 and "stability bound" in text and "k > 3.04e+08 N/m" in text
              and not os.path.exists(os.path.join(out, "stiff.h5")), text)
    for k in ("1e8", "3e8"):  # below that bound, above the real one (the master's mass counts): caught
        status, text = run(exdyn, "plate_impact.yaml", out, f"contact[0].penalty={{stiffness: {k}}}",
                           "output.every=100000", name="stiff")
        check(f"plate_impact, fixed stiffness {k} N/m (automatic: 2.8e7): caught by the energy guard",
              status == 1 and "the energy grew by" in text and "contact node pair" in text
              and summary(out, "stiff")["status"] == "failed", text)
    status, text = run(exdyn, "plate_impact.yaml", out, "output.every=100000", name="auto")
    s = summary(out, "auto")
    check("plate_impact, automatic stiffness: runs to the end, energy bounded",
          status == 0 and s["guards"]["largest_energy_growth"] < 0.01, text + json.dumps(s.get("guards")))


def test_failed_projections(exdyn, work):
    out = os.path.join(work, "failed_search")
    # One simplex iteration never meets the stopping test: every projection fails (the method
    # bare: no fallback).
    status, text = run(exdyn, "plate_impact.yaml", out,
                       "contact[0].local_search={method: simplex, max_iterations: 1, fallback: none}",
                       "output.every=64", name="nosearch")
    s = summary(out, "nosearch")
    c = s["contact"]
    check("failed local searches: counted in NAME.json and reported on stderr",
          status == 0 and c["projections"] > 0 and c["not_converged"] == c["projections"]
          and f"{c['projections']} of {c['projections']} local contact searches failed" in text, text + json.dumps(c))
    with h5py.File(os.path.join(out, "nosearch.h5"), "r") as f:
        forces = [float(np.abs(f[f"steps/{n}/contact_force"][...]).max()) for n in f["steps"]]
    check("failed local searches: never a force (contact_force zero at every step written)",
          max(forces) == 0.0, str(forces))


# A run long enough to be killed at any moment: the reference plate at 50 x 50,
# 7225 steps, a step written every 96 (76 steps of 0.2 MB).
EVERY = 96
KILL_SETS = ["parts[0].elements=[50,1,50]", "parts[0].box={min: [-2.5e-3, 0, 0], max: [0, 5.0e-5, 2.5e-3]}",
             "time.end_time=7.5e-6", f"output.every={EVERY}"]


def start(exdyn, out, name, sets=None):
    cmd = [exdyn, "run", os.path.join(ROOT, "input", "plate_impact_reference.yaml"), "--quiet", "--output", out,
           "--set", f"name={name}"]
    for s in sets or KILL_SETS:
        cmd += ["--set", s]
    return subprocess.Popen(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)


def same_steps(path, reference_path, steps):
    """Every dataset of every listed step equals the uninterrupted run's, bit for bit."""
    with h5py.File(path, "r") as f, h5py.File(reference_path, "r") as g:
        for n in steps:
            group = f"steps/{n:06d}"
            for d in g[group]:
                if not np.array_equal(f[f"{group}/{d}"][...], g[f"{group}/{d}"][...]):
                    return False, f"{group}/{d} differs"
        times = f["time"][...]
        if len(times) < len(steps) or not np.array_equal(times[:len(steps)], g["time"][:len(steps)]):
            return False, "/time differs"
    return True, ""


def test_sigterm(exdyn, work, reference):
    out = os.path.join(work, "sigterm")
    proc = start(exdyn, out, "term")
    # After a written step, not after a fixed time: the whole run takes about 0.5 s on
    # one machine and several seconds under load or a sanitizer.
    wait_for_step(proc, os.path.join(out, "term.xmf"), 10 * EVERY)
    proc.send_signal(signal.SIGTERM)
    text = proc.communicate(timeout=60)[0]
    check("SIGTERM: exit 3, 'stopped by SIGTERM' and the command that goes on",
          proc.returncode == 3 and "stopped by SIGTERM" in text and "--restart" in text, f"{proc.returncode}: {text}")
    m = re.search(r"after step (\d+),", text)
    if not m:
        return
    step = int(m.group(1))
    s = summary(out, "term")
    steps = xmf_steps(os.path.join(out, "term.xmf"))
    check(f"SIGTERM: summary stopped at step {step}, the step written last, a checkpoint of step {step + 1}",
          s["status"] == "stopped" and s["steps"] == step and steps[-1] == step
          and os.path.exists(os.path.join(out, f"term.{step + 1:08d}.restart")), f"{s['steps']} {steps[-3:]}")
    ok, detail = same_steps(os.path.join(out, "term.h5"), reference, [n for n in steps if n % EVERY == 0])
    check("SIGTERM: the steps written equal the uninterrupted run's", ok, detail)
    ok, detail = paraview_reads(os.path.join(out, "term.xmf"), readers="xdmf3s", max_steps=10)
    check("SIGTERM: ParaView reads the result", ok, detail)


def wait_for_step(proc, xmf, step, timeout=120.0):
    """Poll until the .xmf lists `step` (or the run ends): the kill moment is then set by the
    run's progress, not by the wall clock, so a loaded machine cannot bunch the kills."""
    deadline = time.monotonic() + timeout
    marker = f":/steps/{step:06d}/"
    while proc.poll() is None and time.monotonic() < deadline:
        try:
            with open(xmf) as f:
                if marker in f.read():
                    return
        except OSError:
            pass
        time.sleep(0.002)


def test_sigkill(exdyn, work, reference, kills, rng):
    killed_steps = []
    for k in range(kills):
        out = os.path.join(work, f"kill{k}")
        proc = start(exdyn, out, "kill")
        # Every fourth kill at a random early moment (often before the first output); the others
        # after a random written step, a random fraction of an output interval later, so the kills
        # fall at every phase of a step: computing, writing /steps, rewriting the .xmf.
        if k % 4 == 0:
            time.sleep(rng.uniform(0.0, 0.3))
        else:
            # The run writes steps 0, 96, ..., 7200, then its last, 7225.
            wait_for_step(proc, os.path.join(out, "kill.xmf"), EVERY * rng.randrange(0, 76))
            time.sleep(rng.uniform(0.0, 0.03))
        proc.kill()
        proc.wait()
        xmf = os.path.join(out, "kill.xmf")
        if not os.path.exists(xmf):  # killed before the first step was written: nothing to read, nothing promised
            check(f"SIGKILL {k}: killed before the first output; no .xmf and so no result claimed",
                  not os.path.exists(os.path.join(out, "kill.json")))
            continue
        steps = xmf_steps(xmf)
        killed_steps.append(steps[-1])
        try:
            ok, detail = same_steps(os.path.join(out, "kill.h5"), reference, steps)
        except Exception as error:  # noqa: BLE001 - any reading error is the failure under test
            ok, detail = False, f"h5py: {error}"
        check(f"SIGKILL {k}: the {len(steps)} steps the .xmf lists (last {steps[-1]}) read back equal", ok, detail)
        ok, detail = paraview_reads(xmf, readers="xdmf3s", max_steps=10)
        check(f"SIGKILL {k}: ParaView reads the result", ok, detail)
        shutil.rmtree(out, ignore_errors=True)
    print(f"SIGKILL: last steps listed at the kills: {sorted(killed_steps)}")
    check("SIGKILL: the kills landed at different moments", len(set(killed_steps)) >= min(5, kills // 2),
          str(killed_steps))


def test_write_kills(exdyn, work, kills, rng):
    """SIGKILL at uniformly random moments of a run that spends most of its time writing."""
    sets = KILL_SETS[:-1] + ["output.every=8"]
    ref_out = os.path.join(work, "write_reference")
    begin = time.monotonic()
    p = start(exdyn, ref_out, "wwhole", sets)
    text = p.communicate(timeout=600)[0]
    duration = time.monotonic() - begin
    check("write kills: the uninterrupted run completes", p.returncode == 0, text)
    reference = os.path.join(ref_out, "wwhole.h5")
    failed, listed = 0, []
    for k in range(kills):
        out = os.path.join(work, f"wkill{k}")
        proc = start(exdyn, out, "wkill", sets)
        time.sleep(rng.uniform(0.0, duration))
        proc.kill()
        proc.wait()
        xmf = os.path.join(out, "wkill.xmf")
        if os.path.exists(xmf):
            steps = xmf_steps(xmf)
            listed.append(len(steps))
            try:
                ok, detail = same_steps(os.path.join(out, "wkill.h5"), reference, steps)
            except Exception as error:  # noqa: BLE001 - any reading error is the failure under test
                ok, detail = False, f"h5py: {error}"
            if not ok:
                failed += 1
                print(f"write kill {k}: {len(steps)} steps listed: {detail}", flush=True)
        shutil.rmtree(out, ignore_errors=True)
    print(f"write kills: {len(listed)} of {kills} left a result ({min(listed, default=0)} to "
          f"{max(listed, default=0)} steps listed), {failed} unreadable")
    check(f"write kills: every one of {len(listed)} results reads back equal", failed == 0, f"{failed} failed")


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--exdyn", required=True)
    parser.add_argument("--kills", type=int, default=20)
    parser.add_argument("--write-kills", type=int, default=0,
                        help="a campaign of kills of a run that writes every 8 steps (docs/stability.md)")
    parser.add_argument("--seed", type=int, default=None, help="random kill times (default: from the clock)")
    parser.add_argument("--keep", help="work in this directory and keep it")
    args = parser.parse_args()
    seed = args.seed if args.seed is not None else int(time.time())
    print(f"seed {seed}")
    rng = random.Random(seed)
    work = args.keep or tempfile.mkdtemp(prefix="exdyn_stability_")
    try:
        test_unstable(args.exdyn, work)
        test_inverting(args.exdyn, work)
        test_stiff_penalty(args.exdyn, work)
        test_failed_projections(args.exdyn, work)
        ref_out = os.path.join(work, "reference")
        p = start(args.exdyn, ref_out, "whole")
        text = p.communicate(timeout=600)[0]
        check("the uninterrupted run completes", p.returncode == 0, text)
        reference = os.path.join(ref_out, "whole.h5")
        test_sigterm(args.exdyn, work, reference)
        test_sigkill(args.exdyn, work, reference, args.kills, rng)
        if args.write_kills > 0:
            test_write_kills(args.exdyn, work, args.write_kills, rng)
    finally:
        if not args.keep:
            shutil.rmtree(work, ignore_errors=True)
    passed = sum(results)
    print(f"{passed} passed, {len(results) - passed} failed")
    return 0 if passed == len(results) else 1


if __name__ == "__main__":
    sys.exit(main())
