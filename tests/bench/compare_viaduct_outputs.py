#!/usr/bin/env python3
"""Two vsi binaries on the seven jobs/examples/viaduct-*.json, side by side.

  python3 tests/bench/compare_viaduct_outputs.py BASE_VSI NEW_VSI [WORK_DIR] [--reuse-base]

Runs `vsi simulate` of each example with both binaries (the histories of
-german and -dip too) and prints the largest relative difference:
- summary: every number of the summary JSON but run.wall_s (77 per job),
  |a - b| / |a| (0 when both are 0); run.energy_residual, itself a
  rounding-level residual (~1e-12), is listed apart as |a - b|;
- histories: every column of deck.csv, contact_forces.csv and carbody.csv,
  max |a - b| over the column / max |a| of the column.
--reuse-base: the base binary's outputs already in WORK_DIR/base are read,
not made again. Exit 1 when a summary number or a history column differs by more than
1e-12 (relative), an integer count differs, or the outputs' shapes differ.
"""
import csv
import json
import math
import os
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
EXAMPLES = os.path.join(HERE, "..", "..", "jobs", "examples")
JOBS = ["viaduct-ice3", "viaduct-ice3-german", "viaduct-ice3-dip", "viaduct-ice3-fra6",
        "viaduct-eurostar-german", "viaduct-eurostar-dip", "viaduct-eurostar-fra6"]
WITH_HISTORIES = {"viaduct-ice3-german", "viaduct-ice3-dip"}
TOLERANCE = 1e-12


def run(vsi, job, out_dir, reuse=False):
    os.makedirs(out_dir, exist_ok=True)
    saved = os.path.join(out_dir, job + ".json")
    if reuse and os.path.exists(saved):
        with open(saved) as f:
            return json.load(f)
    cmd = [vsi, "simulate", os.path.join(EXAMPLES, job + ".json")]
    if job in WITH_HISTORIES:
        cmd += ["--histories", os.path.join(out_dir, job)]
    env = dict(os.environ, OPENBLAS_NUM_THREADS="1")
    text = subprocess.run(cmd, check=True, capture_output=True, text=True, env=env).stdout
    with open(saved, "w") as f:
        f.write(text)
    return json.loads(text)


def leaves(x, path=""):
    if isinstance(x, dict):
        for k, v in x.items():
            yield from leaves(v, path + "/" + k)
    elif isinstance(x, list):
        for i, v in enumerate(x):
            yield from leaves(v, path + "/" + str(i))
    elif isinstance(x, (int, float)) and not isinstance(x, bool):
        yield path, x


def rel(a, b):
    if a == b:
        return 0.0
    if not (math.isfinite(a) and math.isfinite(b)):
        return math.inf
    return abs(a - b) / max(abs(a), abs(b))


def read_csv(path):
    with open(path) as f:
        rows = list(csv.reader(f))
    return rows[0], [[float(v) for v in r] for r in rows[1:]]


def main():
    args = [a for a in sys.argv[1:] if a != "--reuse-base"]
    reuse = "--reuse-base" in sys.argv[1:]
    base, new = args[0], args[1]
    work = args[2] if len(args) > 2 else "/tmp/compare_viaduct_outputs"
    worst_summary, worst_history, worst_energy, failed, numbers = 0.0, 0.0, 0.0, False, 0
    for job in JOBS:
        a = dict(leaves(run(base, job, os.path.join(work, "base"), reuse)))
        b = dict(leaves(run(new, job, os.path.join(work, "new"))))
        if a.keys() != b.keys():
            print(f"{job}: summary fields differ: {sorted(a.keys() ^ b.keys())}")
            failed = True
            continue
        job_worst, where = 0.0, ""
        for path, va in a.items():
            if path == "/run/wall_s":
                continue
            vb = b[path]
            if path == "/run/energy_residual":
                worst_energy = max(worst_energy, abs(va - vb))
                continue
            numbers += 1
            if isinstance(va, int) and isinstance(vb, int) and va != vb:
                print(f"{job}: {path} {va} != {vb}")
                failed = True
            d = rel(va, vb)
            if d > job_worst:
                job_worst, where = d, path
        print(f"{job}: summary max rel diff {job_worst:.3e} {where}")
        worst_summary = max(worst_summary, job_worst)
        if job not in WITH_HISTORIES:
            continue
        for name in ["deck.csv", "contact_forces.csv", "carbody.csv"]:
            ha, ra = read_csv(os.path.join(work, "base", job, name))
            hb, rb = read_csv(os.path.join(work, "new", job, name))
            if ha != hb or len(ra) != len(rb):
                print(f"{job}/{name}: columns or rows differ")
                failed = True
                continue
            col_worst, col_where = 0.0, ""
            for j, col in enumerate(ha):
                scale = max(abs(r[j]) for r in ra)
                diff = max(abs(x[j] - y[j]) for x, y in zip(ra, rb))
                d = diff / scale if scale > 0 else diff
                if not math.isfinite(d) or d > col_worst:
                    col_worst, col_where = d, col
            print(f"{job}/{name}: max rel diff (column max) {col_worst:.3e} {col_where}")
            worst_history = max(worst_history, col_worst)
    print(f"summary numbers compared: {numbers} (7 jobs), max rel diff {worst_summary:.3e}")
    print(f"histories (-german, -dip): max rel diff {worst_history:.3e}")
    print(f"energy_residual: max abs diff {worst_energy:.3e}")
    failed = failed or not (worst_summary <= TOLERANCE and worst_history <= TOLERANCE)
    print("FAIL" if failed else "OK (<= 1e-12)")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
