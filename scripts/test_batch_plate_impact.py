#!/usr/bin/python3
"""Test of scripts/batch_plate_impact.py on a small grid: meshes 10 and 20 per
plate side, two local search methods, hex8; seconds.

    /usr/bin/python3 scripts/test_batch_plate_impact.py --exdyn PATH [--keep DIR]

Checks: the batch runs every case; a second run resumes without rerunning anything
(same summary files, untouched); a case whose summary is removed is run again, and only
it; the CSV has every column and a row per case with finite measures; the charts (and,
when pvpython is installed, the ParaView pictures) exist and are small; results.md has
its generated sections; ParaView reads the picture case with named stress components and
a time series; bad usage exits 2. Prints `N passed, M failed`; exit 0 when all passed.
"""

import argparse
import csv
import json
import os
import re
import shutil
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
import batch_plate_impact as batch  # noqa: E402

results = []


def check(name, ok, detail=""):
    results.append(bool(ok))
    print(f"{'ok  ' if ok else 'FAIL'} {name}" + (f": {detail}" if detail and not ok else ""), flush=True)


def run_batch(exdyn, out, docs, extra=()):
    cmd = [sys.executable, os.path.join(HERE, "batch_plate_impact.py"), "--meshes", "10,20",
           "--methods", "bfgs,newton", "--formulations", "hex8", "--jobs", "2", "--figure-mesh", "20",
           "--exdyn", exdyn, "--out", out, "--docs", docs, *extra]
    proc = subprocess.run(cmd, capture_output=True, text=True)
    return proc.returncode, proc.stdout + proc.stderr


def summary_mtimes(out):
    found = {}
    for root, _, files in os.walk(os.path.join(out, "cases")):
        for f in files:
            if f.startswith("plate_impact") and f.endswith(".json"):
                p = os.path.join(root, f)
                found[p] = os.stat(p).st_mtime_ns
    return found


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--exdyn", required=True)
    parser.add_argument("--keep", help="work in this directory and keep it")
    args = parser.parse_args()
    work = args.keep or tempfile.mkdtemp(prefix="batch_plate_impact_")
    if args.keep:
        shutil.rmtree(work, ignore_errors=True)
        os.makedirs(work)
    out, docs = os.path.join(work, "out"), os.path.join(work, "docs")
    pictures = os.path.exists(batch.PVPYTHON_RUNNER) and shutil.which("pvpython") is not None
    extra = () if pictures else ("--skip-paraview",)

    rc, log = run_batch(args.exdyn, out, docs, extra)
    check("first run exits 0", rc == 0, log[-2000:])
    check("first run runs all 6 cases", "ran 6 cases, skipped 0, 0 failed" in log, log[-2000:])
    first = summary_mtimes(out)
    check("a summary JSON per case", len(first) == 6, str(sorted(first)))

    with open(os.path.join(out, "batch.csv")) as f:
        reader = csv.DictReader(f)
        header, rows = reader.fieldnames, list(reader)
    check("CSV has every column", header == batch.COLUMNS, str(header))
    check("CSV has a row per case", len(rows) == 6, str(len(rows)))
    check("every case completed", all(r["status"] == "completed" for r in rows))
    contact = [r for r in rows if r["kind"] == "contact"]
    check("4 contact rows, 2 reference rows", len(contact) == 4 and sum(r["kind"] == "reference" for r in rows) == 2)
    finite = all(r[k] not in ("", "nan") for r in contact for k in batch.MEASURES)
    check("contact rows have every measure", finite)
    check("deck values varied are in the rows",
          sorted((r["mesh"], r["method"]) for r in contact) == [("10", "bfgs"), ("10", "newton"),
                                                                 ("20", "bfgs"), ("20", "newton")])
    check("contact statistics present", all(int(r["contact_projections"]) > 0 for r in contact))
    # Accuracy sanity on the coarse meshes: plateau within 5 %, plates mirror images, contact ~ reference.
    check("plateau within 5 % of -2.3333", all(abs(float(r["plateau_error"])) < 0.05 for r in contact),
          str([r["plateau_error"] for r in contact]))
    check("mirror symmetry below 1e-4 of the plateau",
          all(float(r["mirror_symmetry"]) < 1e-4 for r in contact), str([r["mirror_symmetry"] for r in contact]))
    check("contact against reference along z = 0 within 5 %",
          all(float(r["contact_vs_reference_row"]) < 0.05 for r in contact))

    figures = ["results_fig8.png", "results_fig9.png", "results_convergence.png", "results_speed_accuracy.png",
               "results_contact_share.png"]
    if pictures:
        figures += ["results_pv_sigma_xx.png", "results_pv_line.png"]
    else:
        print("note: pvpython or ../shared/tools/paraview not found: ParaView pictures not tested")
    for name in figures:
        p = os.path.join(docs, "figures", name)
        check(f"{name} written, < 200 kB", os.path.exists(p) and 0 < os.path.getsize(p) < 200_000)
    if pictures:   # what a user opening the picture case's .xmf in ParaView sees
        xmf = os.path.join(out, "cases", "contact_hex8_n20_bfgs", "plate_impact.xmf")
        report = os.path.join(work, "check_xdmf.json")
        proc = subprocess.run(batch.pvpython("check_xdmf.py", xmf, "--fields",
                                            "displacement:point:3,velocity:point:3,stress:cell:6,von_mises:cell:1",
                                            "--strict", "--compact", "--json", report), capture_output=True, text=True,
                              env=dict(os.environ, PV_HEADLESS="none"))   # reads only: no X needed
        try:
            with open(report) as f:
                info = json.load(f)
        except (OSError, ValueError):
            info = {}
        check("ParaView reads the picture case (3 readers)", proc.returncode == 0 and info.get("ok"),
              proc.stdout[-1000:] + proc.stderr[-1000:])
        names = info.get("fields", {}).get("stress", {}).get("component_names")
        check("ParaView names the stress components XX YY ZZ XY YZ XZ",
              names == ["XX", "YY", "ZZ", "XY", "YZ", "XZ"], str(names))
        check("ParaView has a time series (> 2 steps)", info.get("n_times", 0) > 2, str(info.get("n_times")))
    with open(os.path.join(docs, "results.md")) as f:
        doc = f.read()
    for key in ("run", "accuracy", "reference", "cases", "pareto", "share"):
        m = re.search(r"<!-- batch:%s -->\n(.*?)<!-- /batch:%s -->" % (key, key), doc, re.S)
        check(f"results.md section {key} filled", m is not None and m.group(1).strip() != "")
    check("results.md names the machine", batch.cpu_model() in doc)

    # Resume: nothing runs again, the summaries are untouched; prose outside markers survives.
    with open(os.path.join(docs, "results.md"), "a") as f:
        f.write("\nHand-written note that must survive.\n")
    rc, log = run_batch(args.exdyn, out, docs, ("--skip-paraview",))
    check("second run exits 0", rc == 0, log[-2000:])
    check("second run reruns nothing", "ran 0 cases, skipped 6" in log, log[-2000:])
    check("summaries untouched", summary_mtimes(out) == first)
    with open(os.path.join(docs, "results.md")) as f:
        check("text outside the markers kept", "Hand-written note that must survive." in f.read())

    # A case whose summary is gone runs again, and only it.
    victim = next(p for p in first if "contact_hex8_n10_newton" in p)
    os.remove(victim)
    rc, log = run_batch(args.exdyn, out, docs, ("--no-plots",))
    check("removed case reruns alone", rc == 0 and "ran 1 cases, skipped 5" in log
          and "contact_hex8_n10_newton" in log, log[-2000:])

    # The formulation study: every formulation and slave points, its own sections and chart; the
    # method study's sections of the same results.md stay as they were.
    with open(os.path.join(docs, "results.md")) as f:
        before = re.search(r"<!-- batch:cases -->\n(.*?)<!-- /batch:cases -->", f.read(), re.S).group(1)
    study_out = os.path.join(work, "formulations")
    proc = subprocess.run([sys.executable, os.path.join(HERE, "batch_plate_impact.py"), "--study", "formulations",
                           "--meshes", "10", "--jobs", "2", "--exdyn", args.exdyn, "--out", study_out,
                           "--docs", docs], capture_output=True, text=True)
    check("formulation study: 12 cases (8 contact, 4 reference) ran", proc.returncode == 0
          and "ran 12 cases, skipped 0, 0 failed" in proc.stdout, (proc.stdout + proc.stderr)[-2000:])
    with open(os.path.join(study_out, "batch.csv")) as f:
        study = [r for r in csv.DictReader(f) if r["kind"] == "contact"]
    check("formulation study: every formulation with both slave points",
          sorted((r["formulation"], r["slave_points"]) for r in study)
          == sorted((f, p) for f in batch.ALL_FORMULATIONS for p in batch.ALL_SLAVE_POINTS), str(study))
    check("formulation study: quadrature points keep the hex20 plates mirror images (1e-12)",
          all(float(r["mirror_symmetry"]) < 1e-12 for r in study if r["slave_points"] == "quadrature"),
          str([r["mirror_symmetry"] for r in study]))
    p = os.path.join(docs, "figures", "results_formulations.png")
    check("results_formulations.png written, < 200 kB", os.path.exists(p) and 0 < os.path.getsize(p) < 200_000)
    with open(os.path.join(docs, "results.md")) as f:
        doc = f.read()
    for key in ("formulations_run", "formulations", "formulations_pareto"):
        m = re.search(r"<!-- batch:%s -->\n(.*?)<!-- /batch:%s -->" % (key, key), doc, re.S)
        check(f"results.md section {key} filled", m is not None and m.group(1).strip() != "")
    after = re.search(r"<!-- batch:cases -->\n(.*?)<!-- /batch:cases -->", doc, re.S).group(1)
    check("the method study's sections are kept", after == before)

    rc, log = run_batch(args.exdyn, out, docs, ("--methods", "nosuch"))
    check("unknown method: exit 2", rc == 2, f"exit {rc}")

    if not args.keep:
        shutil.rmtree(work, ignore_errors=True)
    failed = results.count(False)
    print(f"{len(results) - failed} passed, {failed} failed")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
