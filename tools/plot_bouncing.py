#!/usr/bin/env python3
"""Draws gpusolve_bench_bouncing's CSV (bench/bouncing.cu): each bounce's
energy over the start's against the bounce number, per restitution and time
step, beside the exact e^(2n) (log scale).

Usage: python3 tools/plot_bouncing.py CSV -o bouncing.png
"""
import argparse
import csv


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("csv")
    ap.add_argument("-o", "--out", required=True)
    a = ap.parse_args()
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    with open(a.csv, newline="") as f:
        rows = list(csv.DictReader(f))
    fig, ax = plt.subplots(figsize=(6.5, 4))
    for e in sorted({r["e"] for r in rows}, reverse=True):
        exact = sorted({(int(r["bounce"]), float(r["exact"])) for r in rows if r["e"] == e})
        ax.plot([p[0] for p in exact], [p[1] for p in exact], color="grey", lw=3, alpha=0.35)
        for dt in sorted({r["dt"] for r in rows if r["e"] == e}, key=float, reverse=True):
            pts = [(int(r["bounce"]), float(r["energy_mean"])) for r in rows if r["e"] == e and r["dt"] == dt]
            ax.plot([p[0] for p in pts], [p[1] for p in pts], marker="o", ms=3, label=f"e = {float(e):g}, dt = {dt}")
    ax.set_yscale("log")
    ax.set_xlabel("bounce n")
    ax.set_ylabel("energy / energy at the start")
    ax.set_title(f'7 x 7 bouncing balls, grey: e^(2n) ({rows[0]["device"] if rows else ""})')
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(a.out, dpi=120)


if __name__ == "__main__":
    main()
