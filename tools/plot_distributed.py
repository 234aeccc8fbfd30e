#!/usr/bin/env python3
"""Chart of bench/distributed.cu's CSV: time per step against ranks beside the
ideal (one rank's time over the ranks), the exchange's part shaded; the
speed-up over one rank above each bar.
Usage: tools/plot_distributed.py CSV -o PNG [--backend cpu|gpu] [--title TEXT]"""
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
    a = ap.parse_args()
    rows = [r for r in csv.DictReader(open(a.csv)) if a.backend is None or r.get("backend") == a.backend]
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


if __name__ == "__main__":
    main()
