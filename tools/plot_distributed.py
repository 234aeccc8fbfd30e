#!/usr/bin/env python3
"""Chart of bench/distributed.cu's CSV: time per step against ranks beside the
ideal (one rank's time over the ranks), the exchange's part shaded; the
speed-up over one rank above each bar. With --efficiency instead: the parallel
efficiency against ranks, a line per mode and scaling (strong: the same pile at
every count, one rank's time over ranks x the time; weak: the same spheres per
rank, one rank's time over the time: the bench's --per-rank runs).
Usage: tools/plot_distributed.py CSV -o PNG [--backend cpu|gpu] [--title TEXT] [--efficiency]"""
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
    a = ap.parse_args()
    rows = [r for r in csv.DictReader(open(a.csv)) if a.backend is None or r.get("backend") == a.backend]
    if a.efficiency:
        return plot_efficiency(rows, a)
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


if __name__ == "__main__":
    main()
