#!/usr/bin/env python3
"""Charts the CSVs of gpusolve_bench_atlas (bench/atlas.cu).

  pile:      time per step against the largest penetration and against the
             median LCP residual, one line per method and margin, one panel
             per pile size (log-log);
  column:    iterations per step to the tolerance against the mass ratio;
  stability: method x time step x mass ratio, each cell converged, capped or
             diverged, with its mean iterations;
  warm:      the warm-start factor (--warm): the pile's largest penetration
             against it, one line per method and budget, and each column's
             verdict per method, budget, mass ratio and factor.

  scenes:    any scenes (the shape piles, the pyramid and the stack): per
             scene, each method and budget's time per step against its
             largest penetration, or for the towers the largest move after
             settling (creep; drift where a CSV has no creep).

Usage: python3 tools/plot_atlas.py pile CSV [CSV ...] -o pile.png
       python3 tools/plot_atlas.py scenes CSV [CSV ...] -o shapes.png
       python3 tools/plot_atlas.py stability CSV [CSV ...] -o stability.png
       python3 tools/plot_atlas.py warm CSV [CSV ...] -o warm.png
"""
import argparse
import csv
import sys


def read(paths):
    rows = []
    for p in paths:
        with open(p, newline="") as f:
            rows.extend(csv.DictReader(f))
    return rows


def pyplot():
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    return plt


def budget_label(b):
    """Iterations for "itK"; "default" for SolverSettings{} as shipped."""
    return b[2:] if b.startswith("it") else b


def plot_pile(rows, out):
    plt = pyplot()
    sizes = sorted({int(r["n"]) for r in rows if r["scene"] == "pile"})
    fig, axes = plt.subplots(2, len(sizes), figsize=(6 * len(sizes), 9), squeeze=False)
    gpu = rows[0]["gpu"]
    for col, n in enumerate(sizes):
        lines = {}
        for r in rows:
            if r["scene"] != "pile" or int(r["n"]) != n or r["verdict"] == "diverged":
                continue
            lines.setdefault((r["method"], float(r["margin"])), []).append(r)
        for (method, margin), pts in sorted(lines.items()):
            pts.sort(key=lambda r: float(r["ms_per_step_mean"]))
            t = [float(r["ms_per_step_mean"]) for r in pts]
            label = f"{method}, margin {margin:g}"
            for row, key, scale in ((0, "max_penetration", 100), (1, "residual_median", 1)):
                ax = axes[row][col]
                y = [scale * float(r[key]) for r in pts]
                ax.plot(t, y, marker="o", label=label)
                for r, x, v in zip(pts, t, y):
                    ax.annotate(budget_label(r["budget"]), (x, v), textcoords="offset points", xytext=(4, 4),
                                fontsize=7)
        for row, what in ((0, "largest penetration (% of radius), last 200 steps"), (1, "LCP residual (m/s), median")):
            ax = axes[row][col]
            ax.set_xscale("log")
            ax.set_yscale("log")
            ax.set_xlabel("time per whole step (ms)")
            ax.set_ylabel(what)
            ax.set_title(f"shared pile, {n} spheres")
            ax.grid(True, which="both", alpha=0.3)
            ax.legend(fontsize=8)
        axes[0][col].axhline(0.25, color="grey", linestyle="--", linewidth=1)
    fig.suptitle(f"gpusolve atlas on {gpu}: time per step against accuracy (labels: iterations per step)")
    fig.tight_layout()
    fig.savefig(out, dpi=110)


VERDICT_COLOUR = {"converged": "#6cc26c", "capped": "#f0c040", "diverged": "#e05050", "fell": "#a070d0"}


def plot_warm(rows, out):
    plt = pyplot()
    pile = [r for r in rows if r["scene"] == "pile"]
    column = [r for r in rows if r["scene"] == "column"]
    fig, (left, right) = plt.subplots(1, 2, figsize=(14, 5.5))
    lines = {}
    for r in pile:
        lines.setdefault((r["method"], r["budget"], r["n"]), []).append(r)
    for (method, budget, n), pts in sorted(lines.items()):
        pts.sort(key=lambda r: float(r["warm_start"]))
        left.plot([float(r["warm_start"]) for r in pts], [100 * float(r["max_penetration"]) for r in pts], marker="o",
                  label=f"{method}, {budget_label(budget)} iterations, {n} spheres")
    left.set_xlabel("warm start (fraction of the last impulse)")
    left.set_ylabel("largest penetration (% of radius), last 200 steps")
    left.set_title("shared pile")
    left.grid(True, alpha=0.3)
    left.legend(fontsize=8)
    warms = sorted({float(r["warm_start"]) for r in column})
    cases = sorted({(r["method"], r["budget"], float(r["mass_ratio"])) for r in column})
    for r in column:
        x = warms.index(float(r["warm_start"]))
        y = cases.index((r["method"], r["budget"], float(r["mass_ratio"])))
        right.add_patch(plt.Rectangle((x - 0.5, y - 0.5), 1, 1, color=VERDICT_COLOUR[r["verdict"]]))
        right.text(x, y, f"{r['verdict']}, {r['contacts']} contacts", ha="center", va="center", fontsize=7)
    right.set_xlim(-0.5, len(warms) - 0.5)
    right.set_ylim(-0.5, len(cases) - 0.5)
    right.set_xticks(range(len(warms)), [f"{w:g}" for w in warms])
    right.set_yticks(range(len(cases)), [f"{m}, {budget_label(b)}, 1:{q:g}" for m, b, q in cases], fontsize=7)
    right.set_xlabel("warm start")
    right.set_title("ten-sphere column (10 contacts when it stands)")
    fig.suptitle(f"Warm start against accuracy and stability, on {rows[0]['gpu']}")
    fig.tight_layout()
    fig.savefig(out, dpi=110)


def plot_stability(rows, out):
    plt = pyplot()
    rows = [r for r in rows if r["scene"] == "column" and r["budget"].startswith("tol")]
    methods = sorted({r["method"] for r in rows})
    dts = sorted({float(r["dt"]) for r in rows})
    ratios = sorted({float(r["mass_ratio"]) for r in rows})
    cols = min(2, len(methods))
    grid_rows = (len(methods) + cols - 1) // cols
    fig, axes = plt.subplots(grid_rows, cols, figsize=(6.5 * cols, 4.2 * grid_rows), squeeze=False)
    for ax in axes.flat[len(methods):]:
        ax.set_visible(False)
    for ax, m in zip(axes.flat, methods):
        for r in rows:
            if r["method"] != m:
                continue
            x, y = dts.index(float(r["dt"])), ratios.index(float(r["mass_ratio"]))
            ax.add_patch(plt.Rectangle((x - 0.5, y - 0.5), 1, 1, color=VERDICT_COLOUR[r["verdict"]]))
            ax.text(x, y, f"{r['verdict']}\n{float(r['iterations_mean']):.0f} it\n{100 * float(r['max_penetration']):.3f}%",
                    ha="center", va="center", fontsize=7)
        ax.set_xlim(-0.5, len(dts) - 0.5)
        ax.set_ylim(-0.5, len(ratios) - 0.5)
        ax.set_xticks(range(len(dts)), [f"{d:g}" for d in dts])
        ax.set_yticks(range(len(ratios)), [f"1:{r:g}" for r in ratios])
        ax.set_xlabel("time step (s)")
        ax.set_ylabel("mass ratio of the column")
        ax.set_title(f"{m}, tolerance {rows[0]['budget'][3:]}, cap 2000")
    fig.suptitle(f"Stability map, ten-sphere column, on {rows[0]['gpu']}")
    fig.tight_layout()
    fig.savefig(out, dpi=110)


def plot_scenes(rows, out):
    """One panel per scene: each method and budget a point of time per step
    against the largest penetration (log), and, for the towers, the creep
    (the largest move after the first quarter of the steps; the drift from
    the start in CSVs written before the atlas measured the creep)."""
    plt = pyplot()
    scenes = sorted({r["scene"] for r in rows})
    fig, axes = plt.subplots(1, len(scenes), figsize=(4.5 * len(scenes), 4), squeeze=False)
    for ax, scene in zip(axes[0], scenes):
        tower = scene in ("pyramid", "stack", "field", "slabs")
        creep = all(r.get("creep") for r in rows if r["scene"] == scene)
        for r in (r for r in rows if r["scene"] == scene):
            y = float(r["max_penetration"])
            if tower:
                y = max(float(r["creep"] if creep else r["drift"]), 1e-6)  # a point on the log axis
            ax.scatter(float(r["ms_per_step_median"]), 100 * y)
            ax.annotate(f'{r["method"]} {budget_label(r["budget"])}', (float(r["ms_per_step_median"]), 100 * y),
                        fontsize=7)
        if tower:
            ax.axhline(1.0, color="grey", lw=0.8, ls="--")
        ax.set_yscale("log")
        ax.set_xlabel("ms per step (median)")
        moved = "largest move after settling" if creep else "largest move"
        ax.set_ylabel(f"{moved} / box size, %" if tower else "largest penetration / feature size, %")
        ax.set_title(f'{scene}, n = {rows[0]["n"] if len(scenes) == 1 else next(r["n"] for r in rows if r["scene"] == scene)}')
    fig.suptitle(rows[0].get("gpu", ""), fontsize=8)
    fig.tight_layout()
    fig.savefig(out, dpi=120)


def main(argv):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("chart", choices=["pile", "stability", "warm", "scenes"])
    ap.add_argument("csv", nargs="+")
    ap.add_argument("-o", "--out", required=True)
    a = ap.parse_args(argv)
    rows = read(a.csv)
    if not rows:
        sys.exit("plot_atlas: no rows in " + ", ".join(a.csv))
    {"pile": plot_pile, "stability": plot_stability, "warm": plot_warm, "scenes": plot_scenes}[a.chart](rows, a.out)
    print("wrote", a.out)


if __name__ == "__main__":
    main(sys.argv[1:])
