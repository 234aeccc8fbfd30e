#!/usr/bin/env python3
"""Charts bench/build_time.sh's build_times.csv of one or more machines: the
median seconds of each way of compiling the README's World program, one group
of bars per machine, the one-time compile of the prebuilt library beside them.

Usage: python3 tools/plot_build_time.py LABEL=build_times.csv [...] -o build_time.png
"""
import argparse
import csv
import statistics

WAYS = [("before", "nvcc, headers\n(before: World, all shapes inlined)"),
        ("nvcc_headers", "nvcc, headers\n(SphereWorld)"),
        ("nvcc_prebuilt", "nvcc, prebuilt\nWorlds"),
        ("gxx_prebuilt", "g++, prebuilt\nWorlds"),
        ("library_gpu", "the library's\nGPU Worlds (once)")]


def medians(path):
    """Returns {way: median seconds} of one build_times.csv."""
    runs = {}
    with open(path, newline="") as f:
        for row in csv.DictReader(f):
            runs.setdefault(row["way"], []).append(float(row["seconds"]))
    return {way: statistics.median(s) for way, s in runs.items()}


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("machines", nargs="+", help="LABEL=build_times.csv")
    p.add_argument("-o", "--out", default="build_time.png")
    a = p.parse_args(argv)
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    data = [(spec.split("=", 1)[0], medians(spec.split("=", 1)[1])) for spec in a.machines]
    width = 0.8 / len(data)
    fig, ax = plt.subplots(figsize=(10, 4.5))
    for m, (label, med) in enumerate(data):
        xs = [k + m * width for k, (way, _) in enumerate(WAYS) if way in med]
        ys = [med[way] for way, _ in WAYS if way in med]
        bars = ax.bar(xs, ys, width, label=label)
        ax.bar_label(bars, fmt="%.1f s", fontsize=8)
    ax.axhline(20, color="grey", linestyle="--", linewidth=1)
    ax.text(len(WAYS) - 0.6, 21, "target: 20 s", color="grey", fontsize=8, ha="right")
    ax.set_xticks([k + width * (len(data) - 1) / 2 for k in range(len(WAYS))])
    ax.set_xticklabels([name for _, name in WAYS], fontsize=8)
    ax.set_ylabel("seconds (median of the runs)")
    ax.set_title("Compiling the README's World program (examples/readme/readme_world.cu) for sm_90")
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(a.out, dpi=120)


if __name__ == "__main__":
    main()
