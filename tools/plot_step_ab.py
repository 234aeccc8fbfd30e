#!/usr/bin/env python3
"""Charts an A/B run of gpusolve_bench_step (bench/step.cu): two builds, each
run one or more rounds on the same machine, their median step times side by
side per mode and number of spheres (the mean of the rounds' medians, with
each round as a dot). --columns compares two columns instead (by default
both ms_step_median), e.g. the same run's queued and unattended step times.

Usage: python3 tools/plot_step_ab.py --a LABEL CSV [CSV ...] --b LABEL CSV [CSV ...]
                                     [--columns A_COLUMN B_COLUMN] -o ab.png
"""
import argparse
import sys

from plot_atlas import pyplot, read


def main(argv):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--a", nargs="+", required=True, metavar="LABEL_THEN_CSVS")
    ap.add_argument("--b", nargs="+", required=True, metavar="LABEL_THEN_CSVS")
    ap.add_argument("--columns", nargs=2, default=["ms_step_median", "ms_step_median"], metavar="COLUMN")
    ap.add_argument("-o", "--out", required=True)
    a = ap.parse_args(argv)
    builds = [(g[0], read(g[1:])) for g in (a.a, a.b)]
    if any(not rows for _, rows in builds):
        sys.exit("plot_step_ab: a build has no rows")
    rows = builds[0][1]
    modes = list(dict.fromkeys(r["mode"] for r in rows))
    sizes = sorted({int(r["n"]) for r in rows})
    plt = pyplot()
    fig, axes = plt.subplots(1, len(modes), figsize=(4.2 * len(modes), 4.4), squeeze=False)
    width = 0.38
    for ax, mode in zip(axes[0], modes):
        for k, (label, build) in enumerate(builds):
            x, means = [], []
            for j, n in enumerate(sizes):
                ms = [float(r[a.columns[k]]) for r in build if r["mode"] == mode and int(r["n"]) == n]
                if not ms:
                    continue
                pos = j + (k - 0.5) * width
                ax.plot([pos] * len(ms), ms, "k.", markersize=4)
                x.append(pos), means.append(sum(ms) / len(ms))
            ax.bar(x, means, width, color=f"C{k}", label=label)
        ax.set_xticks(range(len(sizes)), [f"{n:,}" for n in sizes])
        ax.set_yscale("log")
        ax.set_xlabel("spheres")
        ax.set_ylabel("ms per whole step" + (" (median)" if a.columns[0] == "ms_step_median" else ""))
        ax.set_title(mode)
        ax.grid(True, axis="y", which="both", alpha=0.3)
        ax.legend(fontsize=7)
    fig.suptitle(f'gpusolve whole step, A/B on {rows[0]["gpu"]}')
    fig.tight_layout()
    fig.savefig(a.out, dpi=110)


if __name__ == "__main__":
    main(sys.argv[1:])
