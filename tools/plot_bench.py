#!/usr/bin/env python3
"""Charts the CSV of gpusolve_bench_accuracy: LCP residual against wall time and
against iterations, one line per solver, backend and omega, both axes logarithmic.

Usage: python3 tools/plot_bench.py accuracy.csv [-o accuracy.png]
"""
import argparse
import csv
import math
import sys


def read_curves(path):
    """Returns {(solver, backend, omega): [(iterations_run, seconds, residual), ...]}
    in file order; rows with a non-finite or non-positive residual are left out
    (a log axis cannot show them; a diverged solve ends its curve)."""
    curves = {}
    with open(path, newline="") as f:
        for row in csv.DictReader(f):
            residual = float(row["residual"])
            if not math.isfinite(residual) or residual <= 0:
                continue
            key = (row["solver"], row["backend"], float(row["omega"]))
            curves.setdefault(key, []).append(
                (int(row["iterations_run"]), float(row["seconds_median"]), residual))
    return curves


def label(key):
    solver, backend, omega = key
    where = "GPU" if backend == "gpu" else "CPU"
    name = "Gauss-Seidel (host reference)" if solver == "gauss_seidel" else "Jacobi"
    return f"{name}, {where}, omega {omega:g}"


def plot(curves, title, out):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, (by_time, by_iter) = plt.subplots(1, 2, figsize=(13, 5))
    for key, pts in sorted(curves.items()):
        style = "--" if key[1] == "cpu" else "-"
        its, secs, res = zip(*pts)
        by_time.plot([s * 1e3 for s in secs], res, style, marker=".", label=label(key))
        by_iter.plot(its, res, style, marker=".", label=label(key))
    by_time.set_xlabel("wall time of the solve (ms)")
    by_iter.set_xlabel("iterations")
    for ax in (by_time, by_iter):
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_ylabel("LCP residual (m/s)")
        ax.grid(True, which="both", alpha=0.3)
    by_time.legend(fontsize=8)
    fig.suptitle(title)
    fig.tight_layout()
    fig.savefig(out, dpi=120)


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("csv")
    p.add_argument("-o", "--output", default="accuracy.png")
    a = p.parse_args(argv)
    curves = read_curves(a.csv)
    if not curves:
        print(f"plot_bench: no finite residuals in {a.csv}", file=sys.stderr)
        return 1
    with open(a.csv, newline="") as f:
        first = next(csv.DictReader(f))
    plot(curves, f"One step's contact solve, {first['contacts']} contacts ({first['gpu']})", a.output)
    print(f"plot_bench: wrote {a.output}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
