#!/usr/bin/python3
"""Many ranks (docs/parallel.md), through `mpirun -n N exdyn run`:

- equal fields: the plate contact (hex8, nodes), a hex20 contact deck (quadrature points
  on 8-node segments), a curved deck (the Hertz ball, hex20), friction on a curved rail,
  the two Taylor rods (finite strain, plasticity, contact at folds), a bar pulled apart at a
  prescribed velocity until every element has eroded, contact on the faces erosion opens
  (a rod punching a plug out of a plate; a punch down a column of failing bricks, nodes and
  Gauss points, on 2 ranks x 1 and 2 threads: two chunks), single-surface
  contact (the plates as `surface: all`, nodes, quadrature points and mortar), a rigid wall with
  friction, a mesh of 8- and 20-node elements (graded: many groups of equal Jacobians),
  gravity and friction between boxes, a spin with finite strain, hex8r plasticity, the
  hex20 plate impact (built and read from a Gmsh file, which rank 0 alone holds) and
  perturbed plates, mortar contact (with friction; and on the Hertz ball's curved 8-node
  segments) on 3 ranks x 2 threads (the plate contact also through mpirun -n 1, on 2
  ranks and on 3 ranks x 1 thread; the eroding column, two chunks, on 2 ranks x 1 and 2
  threads) give every field of every step, and the mesh, bit for bit as one process (the contact
  distributed: each rank its own slave points); the history (sums over the ranks) to
  1e-12; the summary says mpi.ranks, the same contact figures and mpi.setup (every deck
  set up rank by rank, but those whose contact follows erosion: whole);
- two passes on two mirror-image cylinders stay mirror images to 1e-12 on 2 and 3 ranks;
- the guards stop every rank with the message of one rank: an unstable run and an
  inverted element (exit 1, the same message as one process, the file readable);
- restarts on another number of ranks: a run on 1, 2 or 3 ranks writes checkpoints, a
  restart from one on 2, 3 or 1 ranks writes on, and every field of every step is one
  process's bits (the plates 1 -> 2, 2 -> 3, 3 -> 1; quadrature points, friction on curved
  segments, plasticity with folds, a single surface, a wall, a scattered mesh, erosion and
  the faces it opens, mortar with friction and on a single surface);
- SIGTERM to mpirun: the step is finished, written with a checkpoint, and the run stops
  ("stopped", the ranks exit 3); --restart on 3 ranks gives one process's bits; so does
  --wall-limit (exit 3) with a restart on one;
- SIGKILL of one rank at random moments: the file still opens, every listed step the
  same bits as the one-process run's;
- ParaView opens a result written by 3 ranks;
- more ranks than the mesh has chunks, a mesh file Gmsh cannot read (read by rank 0
  alone), and an mpirun that cannot start the ranks (more ranks than slots; a host file
  naming a machine that cannot be reached), end with a clear error and no result that
  looks complete.

  scripts/test_mpi.py --exdyn build/release/src/app/exdyn [--quick]

--quick (the sanitizer build): seven equal-fields cases (each kind of traffic once) and two
partition cases, on shorter runs and on 3 ranks alone; the guards and the start errors; three
restarts (the plates 2 -> 3, the punch-through 3 -> 2, mortar 1 -> 2); no mirror images, no
kills.
Exit 0 when every check passes.
"""
import argparse
import json
import os
import random
import re
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
    return bool(ok)


def mpirun(ranks, oversubscribe=True):
    cmd = ["mpirun", "-n", str(ranks)]
    if oversubscribe:
        cmd.append("--oversubscribe")
    if os.geteuid() == 0:
        cmd.append("--allow-run-as-root")
    return cmd


def command(exdyn, deck, out, ranks, threads=1, sets=(), options=()):
    """ranks 0: the executable alone, without mpirun."""
    cmd = (mpirun(ranks) if ranks > 0 else []) + [exdyn, "run", os.path.join(ROOT, "input", deck + ".yaml"),
                                                  "--quiet", "--output", out, "--threads", str(threads)]
    for s in sets:
        cmd += ["--set", s]
    return cmd + list(options)


def environment(ranks, threads):
    """The sanitizer build's leak check stays on for one process (which starts no MPI);
    under mpirun it is off: OpenMPI leaves its own allocations (of components it has
    unloaded) at MPI_Finalize. Address and undefined-behaviour errors are still reported.
    More threads than cores in all: OpenMP's threads sleep while they wait
    (OMP_WAIT_POLICY=passive) instead of spinning on the cores the others need (3 ranks
    x 2 threads on 2 cores: 16.6 s against 24.6 s for the Hertz ball to 3 us). More ranks
    than cores: a rank that waits in MPI yields its core (OMPI_MCA_mpi_yield_when_idle)
    instead of polling (3 ranks x 1 thread beside one busy core: the plates 18.3 s against
    46.7 s, the Hertz ball to 3 us 10.4 s against 24.3 s; with 2 ranks polling is faster:
    the plates 1.6 s against 10.0 s). The same bits."""
    env = dict(os.environ)
    if ranks > 0:
        env["ASAN_OPTIONS"] = (env.get("ASAN_OPTIONS", "") + ":detect_leaks=0").lstrip(":")
    if max(ranks, 1) * threads > (os.cpu_count() or 1):
        env.setdefault("OMP_WAIT_POLICY", "passive")
    if ranks > (os.cpu_count() or 1):
        env.setdefault("OMPI_MCA_mpi_yield_when_idle", "1")
    return env


def run(exdyn, deck, out, ranks, threads=1, sets=(), options=()):
    proc = subprocess.run(command(exdyn, deck, out, ranks, threads, sets, options), capture_output=True, text=True,
                          timeout=1800, env=environment(ranks, threads))
    return proc.returncode, proc.stdout + proc.stderr


def summary(out, name):
    with open(os.path.join(out, name + ".json")) as f:
        return json.load(f)


def compare(reference, other):
    """(fields and mesh bit for bit, the largest relative difference of the history, detail)."""
    with h5py.File(reference, "r") as a, h5py.File(other, "r") as b:
        if sorted(a["steps"]) != sorted(b["steps"]):
            return False, float("inf"), "different steps"
        paths = ["mesh/coordinates", "mesh/connectivity", "mesh/part", "time"]
        if "mixed_topology" in a["mesh"] or "mixed_topology" in b["mesh"]:
            paths.append("mesh/mixed_topology")
        for path in paths:
            if path not in a or path not in b or not np.array_equal(a[path][...], b[path][...]):
                return False, float("inf"), path
        for step in a["steps"]:
            for field in a["steps"][step]:
                x, y = a["steps"][step][field][...], b["steps"][step][field][...]
                if not np.array_equal(x, y):
                    return False, float("inf"), (f"steps/{step}/{field}: max difference "
                                                 f"{np.abs(x - y).max():.3e} of {np.abs(x).max():.3e}")
        worst = 0.0
        def visit(name, item):
            nonlocal worst
            if isinstance(item, h5py.Dataset):
                x, y = item[...], b["history"][name][...]
                scale = np.abs(x).max() if x.size else 0.0
                if scale > 0:
                    worst = max(worst, float(np.abs(x - y).max() / scale))
        a["history"].visititems(visit)
    return True, worst, ""


def field_cases(quick):
    """(deck, sets[, label]) of the equal-fields cases."""
    return [("plate_impact", []),
             ("contact_patch_hex20", ["time.end_time=3.0e-7"] if quick else []),
             # 8- and 20-node elements in one mesh: the mixed topology written in pieces; the
             # 20-node part graded: each rank's part takes the whole block's 16 groups of
             # equal Jacobians, and the step follows from them (courant)
             ("contact_patch_hex20", ["parts[1].formulation=hex8", "parts[0].grading=[0.5, 2.0, 1.0]",
                                      "time.end_time=3.0e-7"], "mixed_patch"),
             ("hertz_ball", ["time.end_time=3.0e-6" if quick else "time.end_time=1.2e-5", "output.every=100"]),
             # friction with anchors, gravity, curved 8-node master segments
             ("block_on_rail", ["time.end_time=3.0e-5", "output.every=200"]),
             # finite strain, plasticity, Gauss points sliding over distorting segments, the
             # contact at folds, the step following the deformation (2,592 bricks a rod)
             ("taylor_rods", ["parts[0].elements=[8, 4, 54]", "parts[1].elements=[8, 4, 54]",
                              "time.end_time=" + ("3.0e-6" if quick else "1.2e-5"), "output.every=500"]),
             # plate nodes under a rod's end beside its curved side: the nearer edge point of
             # a valley between the end's facets, on ranks that hold none of the rod's faces
             ("rod_on_plate", ["time.end_time=1.5e-6", "output.every=50"]),
             # single-surface contact, `surface: all`: every point of the plates' exterior
             # faces against every segment sharing no node with it; nodes, and quadrature
             # points on 8-node segments
             ("plates_one_surface", ["time.end_time=1.2e-7", "output.every=56"]),
             ("plates_one_surface", ["parts[0].formulation=hex20", "parts[1].formulation=hex20",
                                     "parts[0].elements=[30, 1, 30]", "parts[1].elements=[30, 1, 30]",
                                     "time.end_time=1.2e-7", "output.every=56"], "plates_one_surface_hex20"),
             ("plates_one_surface", ["contact[0].slave_points=mortar", "time.end_time=1.2e-7", "output.every=56"],
              "plates_one_surface_mortar"),
             # a rigid wall with friction, every point slipping
             ("oblique_impact", ["parts[0].elements=[80, 1, 40]", "time.end_time=3.0e-6", "output.every=100"]),
             # set up rank by rank: gravity and friction between two boxes; a spin with
             # finite strain; plasticity of hex8r
             ("sliding_block", ["parts[0].elements=[16, 16, 2]", "parts[1].elements=[32, 28, 2]",
                                "time.end_time=1.0e-5", "output.every=100"]),
             ("spinning_block", ["parts[0].elements=[16, 16, 8]", "time.end_time=4.0e-5", "output.every=100"]),
             ("plastic_wave", ["parts[0].elements=[2000, 1, 1]", "output.every=100"]),
             # the paper's setting: 20-node plates, two passes of quadrature points
             ("plate_impact_hex20", ["time.end_time=6.0e-8"]),
             # the same read from a Gmsh file: scattered by rank 0, which alone reads and
             # holds it (each rank takes the whole blocks' groups from the ranks' starts)
             ("plate_impact_hex20_gmsh", ["time.end_time=6.0e-8"]),
             # a distorted grid: a part made whole on every rank (mesh::build_part_mesh;
             # the cylinders and balls above are set up by numbers)
             ("plate_impact", ["parts[0].perturbation.fraction=0.2", "parts[1].perturbation.fraction=0.1",
                               "time.end_time=1.2e-7", "output.every=56"], "perturbed_plates"),
             # mortar: pieces cut on each rank from its own slave segments and the ghost
             # master segments; friction with a sliding start (anchors kept by piece)
             ("contact_patch_mortar", ["contact[0].friction={coefficient: 0.3}", "output.every=8",
                                       "parts[1].initial_velocity=[0.3, 0.1, -1.0]"], "mortar_patch"),
             # damage and erosion: a bar of 1,536 bricks pulled apart at a prescribed
             # velocity until every layer has failed (the reactions summed over the ranks)
             ("tension_failure", ["parts[0].elements=[8, 8, 24]",
                                  "parts[0].box={min: [0, 0, 0], max: [0.01, 0.01, 0.03]}",
                                  "parts[0].kinematics=finite", "boundary_conditions[3].velocity={z: 100.0}",
                                  "time={end_time: 6.0e-5}", "output.every=25"], "eroding_bar"),
             # mortar on curved 8-node segments, one pass
             ("hertz_ball", ["contact[0].slave_points=mortar", "contact[0].penalty={scale: 1.0}",
                             "time.end_time=6.0e-6", "output.every=100"],
              "mortar_hertz"),
             # contact on the faces erosion opens: a rod punching a plug out of a plate (672
             # elements eroded, the crack walls and the plug's faces joining the contact as
             # they open; 592 by 3 us), and a punch down a column of bricks that fail one
             # after another, the punch and the column on different ranks (nodes; Gauss
             # points on 8-node segments). Set up from the whole model on every rank.
             ("punch_through", ["time.end_time=3.0e-6", "output.every=20"] if quick else [], "punch_through"),
             # (every 10th step written: the deck writes every step, 3,893 of them with 20-node
             # bricks, and writing and comparing those took 184 s of this test's 433)
             ("eroding_column", ["output.every=10"]),
             ("eroding_column", ["parts[0].formulation=hex20", "parts[1].formulation=hex20", "output.every=10"],
              "eroding_column_hex20"),
             # time.erode: the blunt projectile on a coarse Weldox plate to 40 us, the bricks
             # crushed beside its rim eroded by the corner checks' marks
             ("perforation", ["parts[1].elements=[16, 16, 4]", "parts[0].elements=[4, 2, 16]",
                              "time.end_time=4.0e-5", "output.every=40"], "distortion_erosion")]


def test_equal_fields(exdyn, work, quick):
    cases = field_cases(quick)
    # Two chunks: two ranks at most. Surfaces that follow erosion: set up whole.
    two_ranks = ("eroding_column", "eroding_column_hex20")
    whole_setup = ("punch_through", "eroding_column", "eroding_column_hex20", "distortion_erosion")
    if quick:  # the sanitizer build: each kind of traffic once (nodes, quadrature points on
        # mixed 8- and 20-node faces, curved segments, folds with finite strain and plasticity,
        # a mesh scattered by rank 0, mortar with friction, faces that erosion opens); the rest is
        # the release build's
        cases = [c for c in cases if (c[-1] if len(c) > 2 else c[0]) in
                 ("plate_impact", "mixed_patch", "hertz_ball", "taylor_rods", "plate_impact_hex20_gmsh",
                  "mortar_patch", "punch_through")]
    for deck, sets, *label in cases:
        label = label[0] if label else deck
        start = time.time()
        reference = os.path.join(work, f"{label}_1")
        code, text = run(exdyn, deck, reference, 0, sets=sets)
        check(f"{label}: one process runs", code == 0, text[-400:])
        if code != 0:
            continue
        one = summary(reference, deck)
        # mpirun -n 1, 2 and 3 ranks of one thread and 3 of two on the first deck; every
        # other case on 3 ranks of 2 threads (threads give the bits of one thread:
        # tests/solver), whose end ranks have one neighbour each as 2 ranks do.
        # --quick: 3 ranks of one thread alone.
        if quick:
            variants = [(3, 1)]
        elif label == cases[0][0]:
            variants = [(1, 1), (2, 1), (3, 1), (3, 2)]
        elif label in two_ranks:
            variants = [(2, 1), (2, 2)]
        else:
            variants = [(3, 2)]
        for ranks, threads in variants:
            out = os.path.join(work, f"{label}_{ranks}x{threads}")
            code, text = run(exdyn, deck, out, ranks, threads, sets)
            if not check(f"{label}: {ranks} ranks x {threads} threads run", code == 0, text[-600:]):
                continue
            same, history, detail = compare(os.path.join(reference, deck + ".h5"), os.path.join(out, deck + ".h5"))
            check(f"{label}: {ranks} ranks x {threads} threads: every field of every step bit for bit", same, detail)
            check(f"{label}: {ranks} ranks: the history to 1e-12 ({history:.1e})", history <= 1e-12)
            s = summary(out, deck)
            check(f"{label}: {ranks} ranks: mpi.ranks = {s['mpi']['ranks']}", s["mpi"]["ranks"] == ranks)
            # every deck on many ranks by rank, but one whose contact follows erosion (rank_setup.hpp)
            setup = "by_rank" if ranks > 1 and label not in whole_setup else "whole"
            check(f"{label}: {ranks} ranks: mpi.setup = {s['mpi'].get('setup')} ({setup})",
                  s["mpi"].get("setup") == setup)
            same_contact = all(s["contact"][k] == one["contact"][k]
                               for k in ("projections", "mean_iterations", "max_iterations", "not_converged",
                                         "saddle_points", "max_penetration_over_h"))
            check(f"{label}: {ranks} ranks: the contact figures of one process", same_contact,
                  f"{s['contact']} vs {one['contact']}")
        print(f"     {label}: {time.time() - start:.1f} s", flush=True)


def test_partitions(exdyn, work, quick):
    """Imported meshes and boxes dealt by METIS, and chunks weighed by their measured work
    (the boxes set up rank by rank: their chunk graph made from their lattices, their
    work timed on a first setup): every field of N ranks is one rank's, bit for bit.
    --quick: METIS on 3 ranks for the Gmsh plates, the measured work for the hex20 patch."""
    decks = [("plate_impact_gmsh", ["output.every=112"]),
             ("hertz_ball_gmsh", ["time.end_time=3.0e-6", "output.every=100"]),
             ("plate_impact", ["time.end_time=1.2e-7", "output.every=56"]),
             # its contact work all on one rank when weighed by elements
             ("contact_patch_hex20", ["time.end_time=3.0e-7"])]
    if quick:  # METIS on the Gmsh plates, the measured work on the hex20 patch
        decks = [d for d in decks if d[0] in ("plate_impact_gmsh", "contact_patch_hex20")]
    for deck, sets in decks:
        reference = os.path.join(work, f"{deck}_partition_1")
        code, text = run(exdyn, deck, reference, 0, sets=sets)
        if not check(f"{deck}: one process runs", code == 0, text[-400:]):
            continue
        for ranks, options, key, value in [(2, ["--partition", "metis"], "partition", "metis"),
                                           (3, ["--partition", "metis"], "partition", "metis"),
                                           (3, ["--weigh", "work"], "weigh", "work")]:
            if quick and (ranks == 2 or (options[0] == "--weigh") != (deck == "contact_patch_hex20")):
                continue
            name = " ".join(options)
            out = os.path.join(work, f"{deck}_{value}_{ranks}")
            code, text = run(exdyn, deck, out, ranks, 1, sets, options=options)
            if not check(f"{deck}: {ranks} ranks with {name} run", code == 0, text[-600:]):
                continue
            same, history, detail = compare(os.path.join(reference, deck + ".h5"), os.path.join(out, deck + ".h5"))
            check(f"{deck}: {ranks} ranks, {name}: every field of every step bit for bit", same, detail)
            check(f"{deck}: {ranks} ranks, {name}: the history to 1e-12 ({history:.1e})", history <= 1e-12)
            s = summary(out, deck)
            check(f"{deck}: {ranks} ranks: the summary says {key} {value}", s["mpi"][key] == value)
            setup = "by_rank"
            check(f"{deck}: {ranks} ranks, {name}: mpi.setup = {s['mpi'].get('setup')} ({setup})",
                  s["mpi"].get("setup") == setup)


def test_mirror(exdyn, work):
    import cylinders_study
    for ranks, n_around in [(2, 16), (3, 80)]:
        out = os.path.join(work, f"cylinders_{ranks}")
        sets = [f"parts[0].elements=[{n_around}, 8, 1]", f"parts[1].elements=[{n_around}, 8, 1]",
                "time.end_time=5.0e-6"]
        code, text = run(exdyn, "cylinders", out, ranks, 1, sets)
        if not check(f"cylinders n_around {n_around}: {ranks} ranks run", code == 0, text[-600:]):
            continue
        m = cylinders_study.measure(out, summary(out, "cylinders"))
        # As scripts/cylinders_study.py asks (the velocity, near 0 at the mirror plane's
        # ends, is mirrored to a few 1e-12 on one process too: the mapped mesh is
        # symmetric to round-off).
        for field in ("displacement", "stress"):
            check(f"cylinders, two passes on {ranks} ranks: mirror images, {field} to "
                  f"{m['mirror'][field]:.1e} (1e-12)", m["mirror"][field] <= 1e-12)
        one = os.path.join(work, f"cylinders_{ranks}_one")
        code, text = run(exdyn, "cylinders", one, 0, 1, sets)
        same, _, detail = compare(os.path.join(one, "cylinders.h5"), os.path.join(out, "cylinders.h5"))
        check(f"cylinders n_around {n_around}: {ranks} ranks give the fields of one process bit for bit "
              f"(velocity mirrored to {m['mirror']['velocity']:.1e} on both)", code == 0 and same, detail)
        check(f"cylinders on {ranks} ranks: in contact", m["force_per_length"] > 0.0)


def first_line(text, pattern):
    for line in text.splitlines():
        if re.search(pattern, line):
            return line
    return ""


def test_guards(exdyn, work):
    for deck, sets, ranks in [("unstable_plate", [], 2), ("inverting_bar", ["parts[0].elements=[1200,1,1]"], 3)]:
        one = os.path.join(work, f"{deck}_one")
        code1, text1 = run(exdyn, deck, one, 0, sets=sets)
        many = os.path.join(work, f"{deck}_many")
        code, text = run(exdyn, deck, many, ranks, sets=sets)
        message = first_line(text, "exdyn: run failed")
        check(f"{deck} on {ranks} ranks: exit 1 (one process: {code1})", code == 1 and code1 == 1, text[-600:])
        check(f"{deck}: the message once, as one process says it",
              text.count("exdyn: run failed") == 1 and message == first_line(text1, "exdyn: run failed"),
              f"{message!r} vs {first_line(text1, 'exdyn: run failed')!r}")
        s = summary(many, deck)
        check(f"{deck}: the summary says failed", s["status"] == "failed" and s["message"] in message)
        same, _, detail = compare(os.path.join(one, deck + ".h5"), os.path.join(many, deck + ".h5"))
        check(f"{deck}: the steps written are those of one process", same, detail)


def xmf_steps(path):
    try:
        return sorted({int(m) for m in re.findall(r":/steps/(\d{6})/", open(path).read())})
    except OSError:
        return []


def wait_for_step(proc, xmf, step, timeout=300.0):
    end = time.time() + timeout
    while time.time() < end and proc.poll() is None:
        steps = xmf_steps(xmf)
        if steps and steps[-1] >= step:
            return True
        time.sleep(0.02)
    return False


# Restarts on another number of ranks (docs/output.md, "Checkpoints"): (label of an
# equal-fields case, ranks of the run that writes the checkpoints, ranks of the restart).
RESTARTS = [("plate_impact", 1, 2), ("plate_impact", 2, 3), ("plate_impact", 3, 1),
            ("contact_patch_hex20", 3, 2),  # quadrature points on 8-node segments
            ("block_on_rail", 2, 3),  # friction anchors on curved segments, gravity
            ("taylor_rods", 3, 1),  # plasticity, finite strain, contact at folds
            ("plates_one_surface", 1, 3),  # a single surface: corners, neighbours, exposure offsets
            ("oblique_impact", 2, 3),  # a rigid wall with friction
            ("plate_impact_hex20_gmsh", 3, 2),  # a mesh scattered by rank 0
            ("eroding_bar", 3, 2),  # erosion, the reactions' sums
            ("punch_through", 2, 3),  # faces erosion opens, set up whole
            ("mortar_patch", 2, 1),  # mortar: segment pairs, pieces and their friction anchors
            ("plates_one_surface_mortar", 3, 2)]  # mortar on a single surface
QUICK_RESTARTS = [("plate_impact", 2, 3), ("punch_through", 3, 2), ("mortar_patch", 1, 2)]


def test_restarts(exdyn, work, quick):
    """A run on R1 ranks writes two checkpoints (every 2/5 of its steps); a restart from the
    first on R2 ranks writes on into its files: every field of every step is one process's
    (the equal-fields case's reference), the history to 1e-12, the contact figures equal."""
    cases = {(c[2] if len(c) > 2 else c[0]): c for c in field_cases(quick)}
    for label, before, after in QUICK_RESTARTS if quick else RESTARTS:
        deck, sets = cases[label][0], cases[label][1]
        reference = os.path.join(work, f"{label}_1")
        if not os.path.exists(os.path.join(reference, deck + ".json")):
            check(f"restart {label}: the one-process reference exists", False)
            continue
        one = summary(reference, deck)
        every = max(1, one["steps"] * 2 // 5)
        out = os.path.join(work, f"{label}_restart_{before}_{after}")
        checkpointing = list(sets) + [f"checkpoint={{every: {every}, keep: 100}}"]
        code, text = run(exdyn, deck, out, before if before > 1 else 0, 1, checkpointing)
        found = sorted(f for f in os.listdir(out) if f.endswith(".restart")) if os.path.isdir(out) else []
        if not check(f"restart {label}: {before} rank(s) write checkpoints every {every} steps",
                     code == 0 and len(found) >= 2, text[-600:] + str(found)):
            continue
        code, text = run(exdyn, deck, out, after if after > 1 else 0, 1, checkpointing,
                         options=["--restart", os.path.join(out, found[0])])
        if not check(f"restart {label}: {before} -> {after} rank(s) from step {every} runs", code == 0, text[-600:]):
            continue
        same, history, detail = compare(os.path.join(reference, deck + ".h5"), os.path.join(out, deck + ".h5"))
        s = summary(out, deck)
        check(f"restart {label}: {before} -> {after} rank(s): every field of every step the bits of one process, "
              f"the history to 1e-12 ({history:.1e})", same and history <= 1e-12
              and s.get("restart", {}).get("from_step") == every, detail)
        check(f"restart {label}: {before} -> {after} rank(s): the contact figures of one process",
              all(s["contact"][k] == one["contact"][k] for k in ("projections", "mean_iterations", "max_iterations",
                                                                  "not_converged", "saddle_points",
                                                                  "max_penetration_over_h")),
              f"{s['contact']} vs {one['contact']}")


LONG = ["time.end_time=4.0e-5", "output.every=16"]  # plate_impact: about 77,000 steps


def test_sigterm(exdyn, work, reference_dir):
    """SIGTERM to mpirun: every rank finishes the step, writes a checkpoint and the step, and
    stops (the ranks exit 3; mpirun, signalled itself, exits non-zero); --restart on 3
    ranks to the reference's end gives one process's bits."""
    out = os.path.join(work, "term")
    proc = subprocess.Popen(command(exdyn, "plate_impact", out, 2, 1, LONG), stdout=subprocess.PIPE,
                            stderr=subprocess.STDOUT, text=True, env=environment(2, 1))
    started = wait_for_step(proc, os.path.join(out, "plate_impact.xmf"), 960)
    proc.send_signal(signal.SIGTERM)
    text, _ = proc.communicate(timeout=300)
    check("SIGTERM to mpirun: the run had started", started)
    match = re.search(r"stopped by SIGTERM after step (\d+)", text)
    check("SIGTERM: exit non-zero, 'stopped by SIGTERM after step N', the checkpoint written",
          proc.returncode != 0 and match and summary(out, "plate_impact")["status"] == "stopped"
          and any(f.endswith(".restart") for f in os.listdir(out)), text[-600:])
    if not match:
        return
    step = int(match.group(1))
    steps = xmf_steps(os.path.join(out, "plate_impact.xmf"))
    check(f"SIGTERM: step {step} is the last written", steps and steps[-1] == step, str(steps[-3:]))
    with h5py.File(os.path.join(out, "plate_impact.h5"), "r") as f:
        check("SIGTERM: the file opens with every step", len(f["steps"]) == len(steps))
    code, text = run(exdyn, "plate_impact", out, 3, 1, LONG + ["time.end_time=2.0e-6"], options=["--restart"])
    same, history, detail = (compare(os.path.join(reference_dir, "plate_impact.h5"),
                                     os.path.join(out, "plate_impact.h5")) if code == 0 else (False, 0, text[-600:]))
    check(f"SIGTERM: --restart on 3 ranks to 2 us: one process's bits, the history to 1e-12 ({history:.1e})",
          same and history <= 1e-12, detail)
    # --wall-limit on many ranks: agreed by all, exit 3 through mpirun, then the same bits.
    out = os.path.join(work, "wall_limit")
    started = time.time()
    code, text = run(exdyn, "plate_impact", out, 2, 1, LONG, options=["--wall-limit", "4"])
    check(f"--wall-limit 4 on 2 ranks: exit 3 after {time.time() - started:.1f} s with a checkpoint",
          code == 3 and "stopped by --wall-limit" in text, text[-600:])
    code, text = run(exdyn, "plate_impact", out, 0, 1, LONG + ["time.end_time=2.0e-6"], options=["--restart"])
    same, history, detail = (compare(os.path.join(reference_dir, "plate_impact.h5"),
                                     os.path.join(out, "plate_impact.h5")) if code == 0 else (False, 0, text[-600:]))
    check(f"--wall-limit: --restart on 1 rank to 2 us: one process's bits ({history:.1e})",
          same and history <= 1e-12, detail)


def test_kills(exdyn, work, reference_dir, kills, rng):
    reference = os.path.join(reference_dir, "plate_impact.h5")
    for k in range(kills):
        out = os.path.join(work, f"kill{k}")
        proc = subprocess.Popen(command(exdyn, "plate_impact", out, 2, 1, LONG), stdout=subprocess.DEVNULL,
                                stderr=subprocess.DEVNULL, env=environment(2, 1))
        wait_for_step(proc, os.path.join(out, "plate_impact.xmf"), 16)
        time.sleep(rng.uniform(0.0, 1.5))
        ranks = subprocess.run(["pgrep", "-P", str(proc.pid)], capture_output=True, text=True).stdout.split()
        victim = rng.choice(ranks) if ranks else None
        if victim:
            os.kill(int(victim), signal.SIGKILL)
        proc.wait(timeout=120)
        try:
            with h5py.File(os.path.join(out, "plate_impact.h5"), "r") as f, h5py.File(reference, "r") as r:
                listed = xmf_steps(os.path.join(out, "plate_impact.xmf"))
                same = all(np.array_equal(f["steps"][f"{s:06d}"]["displacement"][...],
                                          r["steps"][f"{s:06d}"]["displacement"][...])
                           for s in listed if f"{s:06d}" in r["steps"])
                check(f"kill {k} (rank pid {victim}): the file opens, {len(listed)} steps listed, "
                      f"the bits of one process", victim and same)
        except OSError as error:
            check(f"kill {k}: the file opens", False, str(error))


def test_paraview(work):
    xmf = os.path.join(work, "plate_impact_3x1", "plate_impact.xmf")
    if not os.access(CHECKER, os.X_OK):
        check("ParaView check", False, f"{CHECKER} not found (../shared must sit beside the repository)")
        return
    proc = subprocess.run(batch.pvpython("check_xdmf.py", xmf, "--strict", "--compact"), capture_output=True,
                          text=True, timeout=600)
    check("ParaView opens the result of 3 ranks (every reader)", proc.returncode == 0,
          (proc.stdout + proc.stderr)[-1500:])


def test_errors(exdyn, work):
    out = os.path.join(work, "too_many")
    code, text = run(exdyn, "contact_patch", out, 3)
    check("more ranks than chunks: exit 2", code == 2, text[-400:])
    check("more ranks than chunks: one clear message",
          text.count("every rank needs a chunk") == 1 and "run on at most 2 ranks" in text, text[-400:])
    check("more ranks than chunks: no result", not os.path.exists(os.path.join(out, "contact_patch.h5")))
    if (os.cpu_count() or 1) < 4:
        cmd = mpirun(4, oversubscribe=False) + [exdyn, "run", os.path.join(ROOT, "input", "plate_impact.yaml"),
                                                "--quiet", "--output", os.path.join(work, "no_start")]
        proc = subprocess.run(cmd, capture_output=True, text=True, timeout=120, env=environment(4, 1))
        check("mpirun that cannot start 4 ranks on this machine: an error, no result",
              proc.returncode != 0 and "slots" in proc.stdout + proc.stderr
              and not os.path.exists(os.path.join(work, "no_start")), (proc.stdout + proc.stderr)[-400:])
    # A mesh file Gmsh cannot read: read by rank 0 alone, its error is every rank's,
    # in one process's words (exit 2, no result).
    bad = os.path.join(work, "bad.msh")
    with open(bad, "w") as f:
        f.write("$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$Nodes\ngarbage\n")
    sets = [f"parts[0].mesh.file={bad}"]
    code1, text1 = run(exdyn, "plate_impact_gmsh", os.path.join(work, "bad_1"), 0, sets=sets)
    out = os.path.join(work, "bad_2")
    code2, text2 = run(exdyn, "plate_impact_gmsh", out, 2, sets=sets)
    message = [line for line in text1.splitlines() if line.startswith("exdyn: error:")]
    check("a mesh file Gmsh cannot read, on 2 ranks: exit 2 with one process's message, no result",
          code1 == 2 and code2 == 2 and len(message) == 1 and text2.count(message[0]) == 1
          and not os.path.exists(out), text2[-400:])
    test_unreachable_host(exdyn, work)


def test_unreachable_host(exdyn, work):
    """A host file naming a machine that cannot be reached (the .invalid domain never
    resolves, RFC 6761): mpirun's own error and exit code, and nothing on disk that
    looks like a finished run: no summary that says completed, no .xmf index."""
    hosts = os.path.join(work, "unreachable_hosts")
    with open(hosts, "w") as f:
        f.write("localhost slots=1\nexdyn-unreachable.invalid slots=1\n")
    out = os.path.join(work, "unreachable")
    cmd = mpirun(2, oversubscribe=False) + ["--hostfile", hosts, "--mca", "plm_rsh_args",
                                            "-o BatchMode=yes -o ConnectTimeout=10"]
    cmd += [exdyn, "run", os.path.join(ROOT, "input", "plate_impact.yaml"), "--quiet", "--output", out]
    proc = subprocess.run(cmd, capture_output=True, text=True, timeout=300, env=environment(2, 1))
    text = proc.stdout + proc.stderr
    summary = os.path.join(out, "plate_impact.json")
    completed = False
    if os.path.exists(summary):
        with open(summary) as f:
            completed = json.load(f).get("status") == "completed"
    check("a host file naming an unreachable machine: mpirun's error, a non-zero exit",
          proc.returncode != 0 and "exdyn:" not in text, text[-600:])
    check("a host file naming an unreachable machine: no result that looks complete",
          not completed and not os.path.exists(os.path.join(out, "plate_impact.xmf")),
          str(os.listdir(out)) if os.path.isdir(out) else "no output directory")


def timed(section, *args):
    """Runs one section and prints its wall time (s): where a long run of this script goes."""
    start = time.time()
    section(*args)
    print(f"---- {section.__name__}: {time.time() - start:.1f} s", flush=True)


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--exdyn", required=True)
    p.add_argument("--quick", action="store_true")
    p.add_argument("--kills", type=int, default=4)
    p.add_argument("--seed", type=int, default=14)
    args = p.parse_args()
    rng = random.Random(args.seed)
    with tempfile.TemporaryDirectory(prefix="exdyn_mpi_") as work:
        timed(test_errors, args.exdyn, work)
        timed(test_equal_fields, args.exdyn, work, args.quick)
        timed(test_partitions, args.exdyn, work, args.quick)
        timed(test_guards, args.exdyn, work)
        timed(test_restarts, args.exdyn, work, args.quick)
        if not args.quick:
            timed(test_mirror, args.exdyn, work)
            reference = os.path.join(work, "long")
            code, text = run(args.exdyn, "plate_impact", reference, 0, sets=LONG + ["time.end_time=2.0e-6"])
            check("the one-process reference of the kills runs", code == 0, text[-400:])
            timed(test_sigterm, args.exdyn, work, reference)
            timed(test_kills, args.exdyn, work, reference, args.kills, rng)
            timed(test_paraview, work)
    failed = results.count(False)
    print(f"test_mpi: {len(results) - failed} passed, {failed} failed")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
