#!/usr/bin/env python3
"""Charts the CSVs of gpusolve_bench_step (bench/step.cu), log-log:

  left:  time per whole step against the number of spheres, one line per
         backend, mode and GPU loop (the `loop` column; older CSVs have a
         `graphs` column instead);
  right: the GPU's detection and solve phases against the number of spheres,
         at 10 Jacobi iterations and at the defaults (loops as run).

Usage: python3 tools/plot_step.py CSV [CSV ...] -o step.png
"""
import argparse
import sys

from plot_atlas import pyplot, read


def series(rows, key, value):
    """{label: sorted [(n, value)]} for rows grouped by key(row)."""
    out = {}
    for r in rows:
        out.setdefault(key(r), []).append((int(r["n"]), float(r[value])))
    return {k: sorted(v) for k, v in out.items()}


def finish_axes(ax, xlabel, ylabel, title):
    ax.set_xscale("log"), ax.set_yscale("log")
    ax.set_xlabel(xlabel)
    ax.set_ylabel(ylabel)
    ax.set_title(title)
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=7)


def main(argv):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("csv", nargs="+")
    ap.add_argument("-o", "--out", required=True)
    a = ap.parse_args(argv)
    rows = read(a.csv)
    if not rows:
        sys.exit("plot_step: no rows")
    plt = pyplot()
    fig, (left, right) = plt.subplots(1, 2, figsize=(13, 5.2))

    def loop(r):
        return r["loop"] if "loop" in r else "graphs " + r["graphs"]

    def label(r):
        reorder = r.get("reorder_every", "0") or "0"
        return (r["backend"] + " " + r["mode"] + ("" if r["backend"] == "cpu" else ", " + loop(r)) +
                ("" if reorder == "0" else ", reordered every " + reorder))

    modes = sorted({r["mode"] for r in rows})
    colour = {m: f"C{k}" for k, m in enumerate(modes)}  # a colour per mode, a line style per loop
    dashes = {"auto": "-", "auto-grid": (0, (3, 1, 1, 1)), "auto-nograph": "--", "persistent": "-", "launches": ":",
              "graphs": "-.", "graphs on": "-.", "graphs off": ":"}

    def draw(ax, rows_, value, prefix=""):
        for name, pts in sorted(series(rows_, label, value).items()):
            r = next(r for r in rows_ if label(r) == name)
            ls = "-." if r["backend"] == "cpu" else dashes.get(loop(r), "-")
            ax.plot([p[0] for p in pts], [p[1] for p in pts], ls, color=colour[r["mode"]],
                    marker="s" if prefix.startswith("detection") else "o", label=prefix + name)

    draw(left, rows, "ms_step_median")
    finish_axes(left, "spheres (the shared pile of PILE.md, after it fell for a while)",
                "ms per whole step (median)", "time per step")

    gpu = [r for r in rows if r["backend"] == "gpu" and r["mode"] in ("jacobi10", "defaults")]
    for phase in ("ms_detection", "ms_solve"):
        draw(right, gpu, phase, phase[3:] + ": ")
    finish_axes(right, "spheres", "ms per step (median, CUDA events)", "GPU phases")
    threads = rows[0].get("cpu_threads")
    threads = f"{threads} OpenMP threads" if threads else "thread count not recorded"
    fig.suptitle(f'gpusolve whole step on {rows[0]["gpu"]} (cpu rows: the host backend on its host, {threads})')
    fig.tight_layout()
    fig.savefig(a.out, dpi=110)


if __name__ == "__main__":
    main(sys.argv[1:])
