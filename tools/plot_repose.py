#!/usr/bin/env python3
"""Draws the poured piles of gpusolve_bench_repose (bench/repose.cu): left,
each row's highest centre per ring against the ring's distance from the
pile's axis; right, the angle of the flank against the rolling resistance,
one line per kind and friction coefficient.

Usage: python3 tools/plot_repose.py PROFILE_CSV ANGLES_CSV -o repose.png
"""
import argparse
import csv


def key(r):
    """A row's kind, friction and rolling resistance (older CSVs: 0.5 and 0)."""
    return (r["kind"], float(r.get("friction", 0.5)), float(r.get("rolling", 0)))


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
        angles = {key(r): r for r in csv.DictReader(f)}
    rings = {}
    with open(a.profile, newline="") as f:
        for r in csv.DictReader(f):
            rings.setdefault(key(r), []).append((float(r["ring_centre"]), float(r["height"])))
    fig, (left, right) = plt.subplots(1, 2, figsize=(12, 4))
    for k, pts in rings.items():
        info = angles.get(k)
        label = f"{k[0]}, mu {k[1]:g}, rolling {k[2]:g}"
        if info:
            label += f': {float(info["angle_deg"]):.1f} deg'
        left.plot([p[0] for p in pts], [p[1] for p in pts], marker="o", ms=2, label=label)
    any_row = next(iter(angles.values()), {})
    left.set_xlabel("distance from the pile's axis")
    left.set_ylabel("highest centre in the ring")
    left.legend(fontsize=7)
    lines = {}
    for (kind, mu, rolling), r in sorted(angles.items()):
        lines.setdefault((kind, mu), []).append((rolling, float(r["angle_deg"])))
    for (kind, mu), pts in lines.items():
        right.plot([p[0] for p in pts], [p[1] for p in pts], marker="o", label=f"{kind}, friction {mu:g}")
    right.set_xlabel("rolling resistance (fraction of the radius)")
    right.set_ylabel("angle of repose (deg)")
    right.legend(fontsize=8)
    fig.suptitle(f'poured piles of {any_row.get("n", "?")} bodies ({any_row.get("device", "")})')
    fig.tight_layout()
    fig.savefig(a.out, dpi=120)


if __name__ == "__main__":
    main()
