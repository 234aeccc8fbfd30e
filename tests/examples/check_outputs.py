#!/usr/bin/env python3
"""Checks what one gpusolve_scenes run wrote: the files exist, parse, and hold sane numbers.

usage: check_outputs.py DIR SCENE STEPS [--max-penetration X] [--min-contacts N]
Exits 1 with the list of problems, 0 when all checks pass. Standard library only.
"""
import argparse
import csv
import glob
import json
import math
import os
import sys

COLUMNS = ["step", "time", "bodies", "contacts", "iterations", "residual", "status", "retries", "omega",
           "max_penetration",
           "kinetic", "potential", "energy", "t_detection", "t_solve", "t_integration", "t_step"]


def check_stats(path, steps, bound, problems):
    with open(path, newline="") as f:
        rows = list(csv.reader(f))
    if not rows or rows[0] != COLUMNS:
        problems.append(f"{path}: header {rows[0] if rows else None} != {COLUMNS}")
        return []
    data = []
    for n, row in enumerate(rows[1:], start=2):
        if len(row) != len(COLUMNS):
            problems.append(f"{path}:{n}: {len(row)} values, expected {len(COLUMNS)}")
            continue
        values = dict(zip(COLUMNS, map(float, row)))
        bad = [k for k, v in values.items() if not math.isfinite(v)]
        if bad:
            problems.append(f"{path}:{n}: not finite: {', '.join(bad)}")
        data.append(values)
    if len(data) != steps:
        problems.append(f"{path}: {len(data)} rows, expected {steps}")
    if [int(r["step"]) for r in data] != list(range(len(data))):
        problems.append(f"{path}: steps are not 0, 1, 2, ...")
    for r in data:
        if r["max_penetration"] > bound:
            problems.append(f"{path}: step {int(r['step'])}: penetration {r['max_penetration']} > {bound}")
            break
        if r["contacts"] < 0 or r["iterations"] < 0 or r["residual"] < 0 or r["kinetic"] < 0:
            problems.append(f"{path}: step {int(r['step'])}: a negative count, residual or energy")
            break
        if int(r["status"]) == 2:
            problems.append(f"{path}: step {int(r['step'])}: the solver diverged")
            break
    times = [r["time"] for r in data]
    if any(b <= a for a, b in zip(times, times[1:])):
        problems.append(f"{path}: simulated time does not increase")
    return data


def check_summary(path, scene, steps, bound, stats, problems):
    with open(path) as f:
        s = json.load(f)
    if s.get("scene") != scene:
        problems.append(f"{path}: scene {s.get('scene')!r} != {scene!r}")
    if s.get("backend") not in ("cpu", "gpu") or not s.get("device"):
        problems.append(f"{path}: backend/device missing")
    p, t = s.get("parameters", {}), s.get("totals", {})
    if p.get("steps") != steps or t.get("steps") != steps:
        problems.append(f"{path}: steps {p.get('steps')}/{t.get('steps')} != {steps}")
    pen = t.get("max_penetration")
    if not isinstance(pen, (int, float)) or not 0 <= pen <= bound:
        problems.append(f"{path}: max_penetration {pen} not in [0, {bound}]")
    if t.get("divergence_events") != 0:
        problems.append(f"{path}: divergence_events {t.get('divergence_events')}")
    # iterations count every attempt of a step: a retried solve runs up to max_iterations again.
    if not 0 <= t.get("mean_iterations", -1) <= p.get("max_iterations", 0) * (1 + p.get("max_retries", 0)):
        problems.append(f"{path}: mean_iterations {t.get('mean_iterations')} out of range")
    if stats:
        if abs(max(r["max_penetration"] for r in stats) - pen) > 1e-6 * max(1.0, pen):
            problems.append(f"{path}: max_penetration {pen} disagrees with stats.csv")
        if t.get("bodies") != int(stats[-1]["bodies"]):
            problems.append(f"{path}: bodies {t.get('bodies')} disagrees with stats.csv")
    return s


def check_vtk(path, problems):
    with open(path) as f:
        lines = f.read().splitlines()
    if lines[:1] != ["# vtk DataFile Version 3.0"] or "ASCII" not in lines[:3]:
        problems.append(f"{path}: not a legacy ASCII VTK file")
        return -1
    heads = [i for i, l in enumerate(lines) if l.startswith("POINTS ")]
    if not heads:
        problems.append(f"{path}: no POINTS")
        return -1
    n = int(lines[heads[0]].split()[1])
    for l in lines[heads[0] + 1:heads[0] + 1 + n]:
        xyz = [float(x) for x in l.split()]
        if len(xyz) != 3 or not all(map(math.isfinite, xyz)):
            problems.append(f"{path}: bad point {l!r}")
            return -1
    return n


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("dir")
    ap.add_argument("scene")
    ap.add_argument("steps", type=int)
    ap.add_argument("--max-penetration", type=float, default=0.5)
    ap.add_argument("--min-contacts", type=int, default=0, help="contacts some step must reach")
    a = ap.parse_args()
    problems = []
    need = [os.path.join(a.dir, n) for n in ("stats.csv", "summary.json")]
    missing = [p for p in need if not os.path.isfile(p)]
    frames = sorted(glob.glob(os.path.join(a.dir, "frame_*.vtk")))
    povs = sorted(glob.glob(os.path.join(a.dir, "frame_*.pov")))
    if missing or not frames or not povs:
        print("missing:", missing, "frames:", len(frames), "pov:", len(povs))
        return 1
    stats = check_stats(need[0], a.steps, a.max_penetration, problems)
    check_summary(need[1], a.scene, a.steps, a.max_penetration, stats, problems)
    if stats and max(r["contacts"] for r in stats) < a.min_contacts:
        problems.append(f"no step reached {a.min_contacts} contact(s): nothing was solved")
    spheres = check_vtk(frames[-1], problems)
    if stats and spheres >= 0 and spheres > stats[-1]["bodies"]:
        problems.append(f"{frames[-1]}: {spheres} spheres but {stats[-1]['bodies']} bodies")
    fixed = sorted(glob.glob(os.path.join(a.dir, "fixed_*.vtk")))
    if fixed:
        check_vtk(fixed[-1], problems)
    with open(povs[-1]) as f:
        pov = f.read()
    if "camera {" not in pov or pov.count("sphere {") != spheres:
        problems.append(f"{povs[-1]}: no camera or {pov.count('sphere {')} spheres, VTK has {spheres}")
    for p in problems:
        print("FAIL:", p)
    print(f"{a.scene}: {len(stats)} steps, {spheres} spheres in the last frame, "
          f"{len(problems)} problem(s)")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
