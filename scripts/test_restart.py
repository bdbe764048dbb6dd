#!/usr/bin/python3
"""Restart checkpoints through the executable (docs/output.md, "Checkpoints"): a run that
stops and goes on gives the same bits as a run that never stopped.

    /usr/bin/python3 scripts/test_restart.py --exdyn PATH [--parts decks,stops] [--kills N] [--quick] [--keep DIR]

Checks:
- every deck of input/ (the long ones to a shorter end time; perforation_fine left
  out, perforation.yaml on a finer mesh): a restart from the first of a run's two
  checkpoints (some decks on the other number of threads, 1 -> 2 and 2 -> 1) rewrites
  NAME.h5 and NAME.json with the same bits as the run that went on: every dataset,
  every number of the summary but wall times (a deck that fails, fails at the same
  step with the same message); that checkpointing changes nothing is checked against
  a plain run by the stops below;
- SIGTERM and SIGINT: exit 3, the step and the command that goes on named, NAME.json
  "stopped", a checkpoint; --restart to the end gives the plain run's bits;
- --wall-limit: exit 3 before the limit, then the same bits;
- --kills N (default 20) SIGKILLs at random moments of a checkpointing run of
  input/punch_through.yaml (to 4 us), each followed by --restart to the end: the same
  bits as a plain run;
- a SIGKILL while a checkpoint is being written (its .tmp on disk): the previous
  checkpoint goes on, the same bits;
- going further: --restart --set time.end_time=T2 equals a run to T2; output.every and
  output.fields changed at restart: the new steps have the new fields (/steps says from
  which step), the earlier ones stay, and ParaView reads the result;
- refused with exit 2, the reason named, nothing written or changed: a material value
  changed, another program version, a truncated checkpoint, flipped bytes, a missing
  checkpoint, --restart with nothing to go on from.
--quick (the sanitizer build): four small decks (gravity and friction, a wall, a single
surface, mortar); SIGTERM, the kills (--kills 4) and the refusals on a shorter
punch-through.
Prints `N passed, M failed`; exit 0 when all passed.
"""

import argparse
import hashlib
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
import checkpoint_file  # noqa: E402

results = []

# Decks run to a shorter end time here (a few seconds each on 2 threads); every other
# deck of input/ runs whole.
SHORTER = {
    "block_on_rail": 5.0e-5,
    "contact_patch_hex20": 6.0e-7,
    "cylinders": 2.3e-6,
    "eroding_column": 4.0e-5,
    "hertz_ball": 5.0e-6,
    "hertz_ball_gmsh": 5.0e-6,
    "perforation": 4.0e-6,
    "plate_impact_hex20_gmsh": 1.2e-7,
    "punch_through": 6.0e-6,
    "taylor_bar": 5.0e-6,
    "taylor_rods": 2.0e-5,
    "taylor_wall": 5.0e-6,
    "tube_crush": 5.0e-6,
}
# The steps between checkpoints of each deck: 2/5 of its steps (to the end times above), so
# that a run writes two and a restart goes on from the first.
EVERY = {
    "bar_impact": 241, "block_drop": 14, "block_on_rail": 1194, "c_slot": 2410, "cantilever": 22434,
    "contact_patch": 10, "contact_patch_hex20": 310, "contact_patch_mortar": 16, "cylinders": 251,
    "eroding_column": 104, "hertz_ball": 157, "hertz_ball_gmsh": 154, "hourglass_block": 8, "inverting_bar": 1,
    "oblique_impact": 48, "perforation": 26, "plastic_wave": 117, "plate_impact": 179, "plate_impact_gmsh": 179,
    "plate_impact_hex20": 179, "plate_impact_hex20_gmsh": 92, "plate_impact_reference": 179,
    "plates_one_surface": 179, "punch_through": 275, "rod_on_plate": 92, "shear_wave": 24, "sliding_block": 482,
    "spinning_block": 3026, "taylor_bar": 69, "taylor_rods": 190, "taylor_wall": 69, "tension_failure": 40,
    "tube_crush": 51, "tube_impact": 133, "u_shape": 1657, "unstable_plate": 1, "wave_bar": 19,
}
# Decks left out, and why.
LEFT_OUT = {"perforation_fine": "input/perforation.yaml on a finer mesh: the same state to save"}
# Decks restarted on the other number of threads (1 -> 2, 2 -> 1 in turn); the others run
# on one thread (under ctest -j2 a second thread only waits for a core).
THREADS_CHANGE = ["c_slot", "contact_patch_mortar", "eroding_column", "hertz_ball", "plate_impact",
                  "plates_one_surface", "sliding_block", "taylor_wall"]
QUICK = ["sliding_block", "taylor_wall", "plates_one_surface", "contact_patch_mortar"]
# Summary keys that are wall times (or count them): not compared.
WALL = {"wall_seconds", "element_cycles_per_second", "phase_seconds", "local_search_seconds",
        "segmentation_seconds", "exchange_seconds", "per_rank", "checkpoints", "restart", "threads",
        "peak_resident_mb", "wait_seconds", "element_seconds", "contact_seconds"}


def check(name, ok, detail=""):
    results.append(bool(ok))
    print(f"{'ok  ' if ok else 'FAIL'} {name}" + (f": {detail}" if detail and not ok else ""), flush=True)


def command(exdyn, deck, out, sets=(), threads=1, extra=()):
    cmd = [exdyn, "run", deck if os.path.isabs(deck) else os.path.join(ROOT, "input", deck + ".yaml"), "--quiet",
           "--output", out, "--threads", str(threads)]
    for s in sets:
        cmd += ["--set", s]
    return cmd + list(extra)


def run(*args, **kwargs):
    proc = subprocess.run(command(*args, **kwargs), capture_output=True, text=True, timeout=1800)
    return proc.returncode, proc.stdout + proc.stderr


def deck_name(out):
    return [f[:-5] for f in os.listdir(out) if f.endswith(".json")][0]


def summary(out):
    with open(os.path.join(out, deck_name(out) + ".json")) as f:
        return json.load(f)


def checkpoints(out):
    found = sorted(f for f in os.listdir(out) if re.fullmatch(r".+\.\d{8,}\.restart", f))
    return [os.path.join(out, f) for f in found]


def datasets(path):
    names = []
    with h5py.File(path, "r") as f:
        f.visit(lambda n: names.append(n) if isinstance(f[n], h5py.Dataset) else None)
    return sorted(names)


def same_files(out, reference):
    """Every dataset of NAME.h5 and every number of NAME.json (wall times aside) the same bits."""
    name = deck_name(reference)
    a, b = os.path.join(out, name + ".h5"), os.path.join(reference, name + ".h5")
    if datasets(a) != datasets(b):
        return False, f"datasets differ: {sorted(set(datasets(a)) ^ set(datasets(b)))[:6]}"
    with h5py.File(a, "r") as f, h5py.File(b, "r") as g:
        for n in datasets(b):
            x, y = f[n][...], g[n][...]
            if x.shape != y.shape or x.tobytes() != y.tobytes():
                return False, f"{n} differs"
    differences = []

    def walk(x, y, path):
        if isinstance(y, dict):
            for k in y:
                if k in WALL:
                    continue
                if not isinstance(x, dict) or k not in x:
                    differences.append(path + k + " missing")
                else:
                    walk(x[k], y[k], path + k + ".")
        elif x != y:
            differences.append(f"{path}: {x} != {y}")

    walk(summary(out), summary(reference), "")
    return not differences, "; ".join(differences[:4])


def snapshot(out):
    """Each file of a directory with its size and content hash (to see that nothing changed)."""
    state = {}
    for f in sorted(os.listdir(out)):
        with open(os.path.join(out, f), "rb") as handle:
            state[f] = hashlib.sha256(handle.read()).hexdigest()
    return state


# ---------------------------------------------------------------------------

def test_decks(exdyn, work, decks):
    for k, deck in enumerate(decks):
        sets = [f"time.end_time={SHORTER[deck]}"] if deck in SHORTER else []
        out, first = os.path.join(work, deck, "restart"), os.path.join(work, deck, "first")
        every = EVERY.get(deck)
        if every is None:  # a deck the table does not know: its steps from a plain run
            status, text = run(exdyn, deck, os.path.join(work, deck, "plain"), sets)
            if status not in (0, 1):
                check(f"{deck}: the plain run", False, text[-400:])
                continue
            every = max(1, summary(os.path.join(work, deck, "plain"))["steps"] * 2 // 5)
        threads = ((1, 2) if k % 2 == 0 else (2, 1)) if deck in THREADS_CHANGE else (1, 1)
        checkpointing = sets + [f"checkpoint={{every: {every}, keep: 100}}"]
        status, text = run(exdyn, deck, out, checkpointing, threads=threads[0])
        found = checkpoints(out)
        if status not in (0, 1) or not found:
            check(f"{deck}: a run with a checkpoint every {every} steps (EVERY: 2/5 of its steps)", False,
                  text[-300:] + f" {summary(out)['steps'] if os.path.isdir(out) else ''} steps")
            continue
        shutil.copytree(out, first, ignore=shutil.ignore_patterns("*.restart"))
        status2, text2 = run(exdyn, deck, out, checkpointing, threads=threads[1], extra=["--restart", found[0]])
        ok, detail = same_files(out, first)
        restart = summary(out).get("restart", {})
        check(f"{deck}: restarted from step {restart.get('from_step')} on {threads[1]} thread(s) after "
              f"{threads[0]}: the same bits as the run that went on", status2 == status and ok
              and restart.get("from_step") == every, detail or text2[-300:])


def test_signals(exdyn, work, reference, deck, sets, signals):
    for sig in signals:
        out = os.path.join(work, "signal_" + sig.name)
        proc = subprocess.Popen(command(exdyn, deck, out, sets), stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                                text=True)
        xmf = os.path.join(out, deck + ".xmf")
        deadline = time.monotonic() + 120
        while proc.poll() is None and time.monotonic() < deadline and not os.path.exists(xmf):
            time.sleep(0.01)
        time.sleep(0.3)
        proc.send_signal(sig)
        text = proc.communicate(timeout=300)[0]
        m = re.search(r"stopped by (\w+) after step (\d+), time .*checkpoint (\S+) is written: go on with `(.+)`",
                      text)
        check(f"{sig.name}: exit 3 naming the step, the checkpoint and the command that goes on",
              proc.returncode == 3 and m and m.group(1) == sig.name and "--restart" in m.group(4), text[-500:])
        if not m:
            continue
        s = summary(out)
        check(f"{sig.name}: NAME.json stopped at step {m.group(2)}, the checkpoint on disk",
              s["status"] == "stopped" and s["steps"] == int(m.group(2)) and os.path.exists(m.group(3)), str(s)[:300])
        status, text = run(exdyn, deck, out, sets, extra=["--restart"])
        ok, detail = same_files(out, reference)
        check(f"{sig.name}: --restart to the end, the same bits", status == 0 and ok, detail or text[-300:])


def test_wall_limit(exdyn, work, reference, deck, sets, limit):
    out = os.path.join(work, "wall_limit")
    started = time.monotonic()
    status, text = run(exdyn, deck, out, sets, extra=["--wall-limit", str(limit)])
    took = time.monotonic() - started
    check(f"--wall-limit {limit}: exit 3 in {took:.2f} s, before the limit", status == 3 and took < limit
          and "stopped by --wall-limit" in text, text[-300:])
    status, text = run(exdyn, deck, out, sets, extra=["--restart"])
    ok, detail = same_files(out, reference)
    check("--wall-limit: --restart to the end, the same bits", status == 0 and ok, detail or text[-300:])


def test_kills(exdyn, work, reference, deck, sets, kills, seconds, rng):
    checkpointing = sets + ["checkpoint.every=100"]
    for k in range(kills):
        out = os.path.join(work, f"kill{k}")
        proc = subprocess.Popen(command(exdyn, deck, out, checkpointing), stdout=subprocess.DEVNULL,
                                stderr=subprocess.DEVNULL)
        time.sleep(rng.uniform(0.0, seconds))
        proc.kill()
        proc.wait()
        before = len(checkpoints(out)) if os.path.isdir(out) else 0
        extra = ["--restart"] if before else []
        status, text = run(exdyn, deck, out, checkpointing, extra=extra)
        ok, detail = same_files(out, reference)
        check(f"SIGKILL {k + 1} ({before} checkpoint(s) left), then {'--restart' if before else 'a new run'}: "
              "the same bits", status == 0 and ok, detail or text[-300:])


def test_kill_in_checkpoint(exdyn, work, reference, deck, sets):
    """Polls for the .tmp a checkpoint is written to and kills the run while it is there."""
    checkpointing = sets + ["checkpoint.every=40"]
    for attempt in range(10):
        out = os.path.join(work, f"kill_in_checkpoint{attempt}")
        proc = subprocess.Popen(command(exdyn, deck, out, checkpointing), stdout=subprocess.DEVNULL,
                                stderr=subprocess.DEVNULL)
        hit = False
        while proc.poll() is None:
            if os.path.isdir(out) and checkpoints(out) and any(f.endswith(".restart.tmp") for f in os.listdir(out)):
                proc.kill()
                hit = True
                break
            time.sleep(0.0005)
        proc.wait()
        left = [f for f in os.listdir(out) if f.endswith(".restart.tmp")]
        if not (hit and left):
            continue
        previous = checkpoints(out)[-1]
        status, text = run(exdyn, deck, out, checkpointing, extra=["--restart"])
        ok, detail = same_files(out, reference)
        check(f"SIGKILL while {left[0]} was written: {os.path.basename(previous)} goes on, the same bits",
              status == 0 and ok and summary(out)["restart"]["checkpoint"] == previous, detail or text[-300:])
        return
    check("SIGKILL while a checkpoint is written: caught one in 10 runs", False)


def test_further(exdyn, work, deck, end_1, end_2):
    further = os.path.join(work, "further_reference")
    run(exdyn, deck, further, [f"time.end_time={end_2}"])
    out = os.path.join(work, "further")
    status, text = run(exdyn, deck, out, [f"time.end_time={end_1}", "checkpoint.every=40"])
    status, text = run(exdyn, deck, out, [f"time.end_time={end_2}", "checkpoint.every=40"], extra=["--restart"])
    ok, detail = same_files(out, further)
    check(f"{deck}: run to {end_1} s, then --restart --set time.end_time={end_2}: a run to {end_2} s, the same bits",
          status == 0 and ok, detail or text[-300:])


def test_output_change(exdyn, work, reference, deck, sets):
    out = os.path.join(work, "output_change")
    run(exdyn, deck, out, sets + ["checkpoint.every=400"])
    first = checkpoints(out)[0]
    step = int(re.search(r"\.(\d+)\.restart$", first).group(1))
    status, text = run(exdyn, deck, out, sets + ["checkpoint.every=400", "output.every=50",
                                                 "output.fields=[displacement, velocity]"], extra=["--restart", first])
    name = deck_name(out)
    with h5py.File(os.path.join(out, name + ".h5"), "r") as f, \
            h5py.File(os.path.join(reference, name + ".h5"), "r") as g:
        steps = sorted(int(s) for s in f["steps"])
        before = [s for s in steps if s < step]
        after = [s for s in steps if s >= step]
        old = all(sorted(f[f"steps/{s:06d}"]) == sorted(g[f"steps/{s:06d}"]) for s in before)
        new = all(sorted(f[f"steps/{s:06d}"]) == ["displacement", "velocity"] for s in after)
        same = all(f[f"steps/{s:06d}/{d}"][...].tobytes() == g[f"steps/{s:06d}/{d}"][...].tobytes()
                   for s in steps if f"steps/{s:06d}" in g for d in f[f"steps/{s:06d}"])
        told = str(f["steps"].attrs.get("output_fields", b""))
        every = all(s % 50 == 0 for s in after[:-1])
    check(f"output changed at step {step}: the steps before keep their fields, those after have the new ones "
          "every 50 steps, the values the plain run's", status == 0 and old and new and same and every and after,
          text[-300:] + f" {before[-2:]} {after[:3]}")
    check("output changed: /steps says from which step", f"from step {step}" in told, told)
    # (not --strict: the checker's lint notes that the steps' fields differ, as they should)
    ok, detail = paraview_reads(os.path.join(out, name + ".xmf"), strict=False)
    check("output changed: ParaView reads the result", ok, detail)


def paraview_reads(xmf_path, strict=True):
    if not os.access(batch.PVPYTHON_RUNNER, os.X_OK):
        return False, f"{batch.PVPYTHON_RUNNER} not found (../shared must sit beside the repository)"
    cmd = batch.pvpython("check_xdmf.py", xmf_path, *(["--strict"] if strict else []), "--compact", "--readers",
                         "xdmf3s")
    proc = subprocess.run(cmd, capture_output=True, text=True, timeout=600)
    return proc.returncode == 0, (proc.stdout + proc.stderr)[-2000:]


def test_refusals(exdyn, work, deck, sets, quick):
    out = os.path.join(work, "refusals")
    run(exdyn, deck, out, sets + ["checkpoint={every: 40, keep: 10}"])
    found = checkpoints(out)
    newest = found[-1]
    sections = checkpoint_file.read(newest)
    bad = os.path.join(work, "bad")
    os.makedirs(bad, exist_ok=True)

    def refused(what, expected, extra, changed_sets=()):
        before = snapshot(out)
        status, text = run(exdyn, deck, out, list(sets) + ["checkpoint={every: 40, keep: 10}"] + list(changed_sets),
                           extra=extra)
        check(f"refused, exit 2, nothing changed: {what}", status == 2 and re.search(expected, text)
              and snapshot(out) == before, f"{status}: {text[-400:]}")

    refused("a material value changed", r"materials\.\w+\.youngs_modulus", ["--restart"],
            ["materials.steel.youngs_modulus=2.0e11"])
    other = dict(sections)
    other["exdyn_version"] = b"0.0.9"
    checkpoint_file.write(os.path.join(bad, "version.restart"), other)
    refused("another program version", r"written by exdyn 0\.0\.9", ["--restart", os.path.join(bad, "version.restart")])
    data = open(newest, "rb").read()
    with open(os.path.join(bad, "truncated.restart"), "wb") as f:
        f.write(data[:len(data) // 2])
    refused("a truncated checkpoint", r"truncated", ["--restart", os.path.join(bad, "truncated.restart")])
    rng = random.Random(5)
    for k in range(1 if quick else 4):
        flipped = bytearray(data)
        where = rng.randrange(len(flipped))
        flipped[where] ^= 1 << rng.randrange(8)
        path = os.path.join(bad, f"flipped{k}.restart")
        with open(path, "wb") as f:
            f.write(flipped)
        refused(f"a flipped bit at byte {where} of {len(data)}", r"damaged|truncated|not an exdyn|format",
                ["--restart", path])
    refused("a missing checkpoint", r"does not exist", ["--restart", os.path.join(bad, "none.restart")])
    empty = os.path.join(work, "empty")
    os.makedirs(empty, exist_ok=True)
    status, text = run(exdyn, deck, empty, sets, extra=["--restart"])
    check("refused, exit 2: --restart with nothing to go on from", status == 2 and "no checkpoint" in text
          and not os.listdir(empty), text[-300:])


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--exdyn", required=True)
    parser.add_argument("--kills", type=int, default=20)
    parser.add_argument("--quick", action="store_true")
    parser.add_argument("--decks", help="these decks of input/ (names, comma-separated) instead of every one")
    parser.add_argument("--keep", help="keep the runs in this directory")
    parser.add_argument("--parts", default="decks,stops",
                        help="decks (every deck restarted), stops (signals, limits, kills, refusals, going "
                             "further), or both (the default)")
    args = parser.parse_args()
    work = args.keep or tempfile.mkdtemp(prefix="exdyn_restart_")
    os.makedirs(work, exist_ok=True)
    rng = random.Random(2026)
    try:
        decks = args.decks.split(",") if args.decks else QUICK if args.quick else sorted(
            f[:-5] for f in os.listdir(os.path.join(ROOT, "input")) if f.endswith(".yaml") and f[:-5] not in LEFT_OUT)
        parts = args.parts.split(",")
        if "decks" in parts:
            test_decks(args.exdyn, work, decks)
        if "stops" not in parts:
            return finish(work, args.keep)
        # The punch-through (erosion, surface: all, plasticity) to 6 us (the plug is punched
        # out from about 4 us), or to 2 us in the sanitizer build.
        sets = [f"time.end_time={2.0e-6 if args.quick else 6.0e-6}"]
        reference = os.path.join(work, "punch_reference")
        started = time.monotonic()
        status, text = run(args.exdyn, "punch_through", reference, sets)
        seconds = time.monotonic() - started
        check("the punch-through runs", status == 0, text[-600:])
        if status != 0:
            return finish(work, args.keep)
        test_signals(args.exdyn, work, reference, "punch_through", sets, [signal.SIGTERM] if args.quick else
                     [signal.SIGTERM, signal.SIGINT])
        # The kills on its first 4 us (the plate cracks from about 3 us).
        short, short_reference, short_seconds = sets, reference, seconds
        if not args.quick:
            short = ["time.end_time=4.0e-6"]
            short_reference = os.path.join(work, "punch_short_reference")
            started = time.monotonic()
            run(args.exdyn, "punch_through", short_reference, short)
            short_seconds = time.monotonic() - started
        test_kills(args.exdyn, work, short_reference, "punch_through", short, args.kills, short_seconds, rng)
        if not args.quick:  # a property of the file system, not of memory
            test_kill_in_checkpoint(args.exdyn, work, short_reference, "punch_through", short)
        test_refusals(args.exdyn, work, "punch_through", sets, args.quick)
        if args.quick:  # the sanitizer build: the paths above, where memory is read and written
            return finish(work, args.keep)
        test_wall_limit(args.exdyn, work, reference, "punch_through", sets, round(max(1.5, 0.5 * seconds), 1))
        test_output_change(args.exdyn, work, reference, "punch_through", sets)
        test_further(args.exdyn, work, "plate_impact", 1.2e-7, 2.3255e-7)
        test_further(args.exdyn, work, "taylor_bar", 3.0e-6, 6.0e-6)  # a step that follows the deformation
    except BaseException:
        finish(work, args.keep)
        raise
    return finish(work, args.keep)


def finish(work, keep):
    if not keep:
        shutil.rmtree(work, ignore_errors=True)
    failed = results.count(False)
    print(f"{results.count(True)} passed, {failed} failed")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
