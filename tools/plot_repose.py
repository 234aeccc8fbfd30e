#!/usr/bin/env python3
"""Draws the poured piles' surfaces of gpusolve_bench_repose (bench/repose.cu):
each kind's highest centre per ring against the ring's distance from the
pile's axis, with the angle of its flank from the CSV of angles.

Usage: python3 tools/plot_repose.py PROFILE_CSV ANGLES_CSV -o repose.png
"""
import argparse
import csv


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("profile")
    ap.add_argument("angles")
    ap.add_argument("-o", "--out", required=True)
    a = ap.parse_args()
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    with open(a.angles, newline="") as f:
        angles = {r["kind"]: r for r in csv.DictReader(f)}
    rings = {}
    with open(a.profile, newline="") as f:
        for r in csv.DictReader(f):
            rings.setdefault(r["kind"], []).append((float(r["ring_centre"]), float(r["height"])))
    fig, ax = plt.subplots(figsize=(7, 3.5))
    for kind, pts in rings.items():
        info = angles.get(kind, {})
        label = f'{kind}: {float(info.get("angle_deg", "nan")):.1f} deg' if info else kind
        ax.plot([p[0] for p in pts], [p[1] for p in pts], marker="o", ms=3, label=label)
    any_row = next(iter(angles.values()), {})
    ax.set_xlabel("distance from the pile's axis")
    ax.set_ylabel("highest centre in the ring")
    ax.set_title(f'poured piles of {any_row.get("n", "?")} bodies, friction 0.5 ({any_row.get("device", "")})')
    ax.set_aspect("equal", adjustable="datalim")
    ax.legend()
    fig.tight_layout()
    fig.savefig(a.out, dpi=120)


if __name__ == "__main__":
    main()
