#!/usr/bin/env python3
"""Chart of bench/distributed.cu's CSV: time per step against ranks beside the
ideal (one rank's time over the ranks), the exchange's part shaded; the
speed-up over one rank above each bar. With --efficiency instead: the parallel
efficiency against ranks, a line per mode and scaling (strong: the same pile at
every count, one rank's time over ranks x the time; weak: the same spheres per
rank, one rank's time over the time: the bench's --per-rank runs). With --skin:
the runs of one rank count against their skin (the bench's --skin), the step's
time split into bodies (moved, rebuilt), the solve's exchanges and the rest,
and the share of the measured steps that rebuilt.
Usage: tools/plot_distributed.py CSV -o PNG [--backend cpu|gpu] [--title TEXT] [--efficiency | --skin]"""
import argparse
import csv

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("csv")
    ap.add_argument("-o", "--output", required=True)
    ap.add_argument("--title", default="")
    ap.add_argument("--backend", default=None)
    ap.add_argument("--efficiency", action="store_true")
    ap.add_argument("--skin", action="store_true")
    a = ap.parse_args()
    rows = [r for r in csv.DictReader(open(a.csv)) if a.backend is None or r.get("backend") == a.backend]
    if a.efficiency:
        return plot_efficiency(rows, a)
    if a.skin:
        return plot_skin(rows, a)
    rows = sorted(rows, key=lambda r: int(r["ranks"]))
    ranks = [int(r["ranks"]) for r in rows]
    # Both of the bench's formats: ms_per_step and ms_exchange (bodies and the
    # solve's exchanges in one) before 2026-12-06 noon, then ms_step with the phases apart.
    total = [float(r.get("ms_step") or r["ms_per_step"]) for r in rows]
    exchange = [float(r["ms_exchange"]) + float(r.get("ms_bodies") or 0) for r in rows]
    one = total[ranks.index(1)] if 1 in ranks else total[0] * ranks[0]
    fig, ax = plt.subplots(figsize=(6, 4))
    ax.bar([str(r) for r in ranks], total, color="#4c72b0", label="whole step")
    ax.bar([str(r) for r in ranks], exchange, color="#dd8452", label="bodies and exchange (slowest rank)")
    ax.plot([str(r) for r in ranks], [one / r for r in ranks], "k--", marker="o", label="ideal: one rank / ranks")
    for i, r in enumerate(ranks):
        ax.annotate(f"{one / total[i]:.2f}x", (i, total[i]), ha="center", va="bottom", fontsize=9)
    ax.set_xlabel("MPI ranks (one core each)")
    ax.set_ylabel("ms per step (median)")
    ax.set_title(a.title, fontsize=9)
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(a.output, dpi=120)


def plot_efficiency(rows, a):
    lines = {}  # (mode, scaling, spheres) -> {ranks: ms}
    for r in rows:
        ranks, per_rank = int(r["ranks"]), int(r.get("per_rank") or 0)
        key = (r.get("mode") or "defaults", "weak" if per_rank else "strong", per_rank or int(r["n"]))
        lines.setdefault(key, {})[ranks] = float(r["ms_step"])
    fig, ax = plt.subplots(figsize=(6, 4))
    for (mode, scaling, n), times in sorted(lines.items()):
        if 1 not in times or len(times) < 2:
            continue
        ranks = sorted(times)
        eff = [times[1] / (times[r] * (r if scaling == "strong" else 1)) for r in ranks]
        per = "per rank" if scaling == "weak" else "in all"
        ax.plot(ranks, eff, marker="o", label=f"{mode}, {scaling}: {n} spheres {per}")
    ax.axhline(1.0, color="k", lw=0.8, ls="--")
    ax.set_xlabel("MPI ranks")
    ax.set_ylabel("parallel efficiency")
    ax.set_ylim(0, 1.2)
    ax.set_title(a.title, fontsize=9)
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(a.output, dpi=120)


def plot_skin(rows, a):
    rows = sorted(rows, key=lambda r: float(r["skin"]))
    labels = [f'{float(r["skin"]):g}' for r in rows]
    bodies = [float(r["ms_bodies"]) for r in rows]
    exchange = [float(r["ms_exchange"]) for r in rows]
    rest = [float(r["ms_step"]) - b - e for r, b, e in zip(rows, bodies, exchange)]
    rebuilt = [100 * int(r["rebuilds"]) / (int(r["steps"]) // 3) for r in rows]
    fig, ax = plt.subplots(figsize=(6, 4))
    ax.bar(labels, rest, color="#4c72b0", label="the rest of the step")
    ax.bar(labels, exchange, bottom=rest, color="#55a868", label="the solve's exchanges")
    ax.bar(labels, bodies, bottom=[x + e for x, e in zip(rest, exchange)], color="#dd8452",
           label="bodies: checked, moved, rebuilt")
    for i, r in enumerate(rows):
        ax.annotate(f'{rebuilt[i]:.0f}% rebuilt\n{int(r["shadows"])} shadows', (i, float(r["ms_step"])), ha="center",
                    va="bottom", fontsize=8)
    ax.set_xlabel("skin (m)")
    ax.set_ylabel("ms per step (median, slowest rank)")
    ax.set_ylim(0, 1.2 * max(float(r["ms_step"]) for r in rows))
    ax.set_title(a.title, fontsize=9)
    ax.legend(fontsize=8, loc="lower right")
    fig.tight_layout()
    fig.savefig(a.output, dpi=120)


if __name__ == "__main__":
    main()
