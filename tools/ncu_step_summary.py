#!/usr/bin/env python3
"""Per-kernel time of one whole step, from an ncu CSV of gpusolve_bench_step.

The CSV comes from
  ncu --graph-profiling node --cache-control none --clock-control none \
      --metrics gpu__time_duration.sum --csv gpusolve_bench_step ... > ncu.csv
Steps are delimited by the solver's persistent kernel (one per step at one
residual check; persistent_iterations_kernel before b5ad911, then
persistent_checked_kernel); the summary covers the last --steps of them.
"""
import argparse
import collections
import csv
import gzip
import re


def read_csv_rows(path):
    """The rows of an ncu --csv output, plain or gzipped (.gz)."""
    opener = gzip.open if path.endswith(".gz") else open
    with opener(path, "rt") as f:
        return list(csv.reader(f))


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("csv", help="ncu --csv output (plain or .gz)")
    ap.add_argument("--steps", type=int, default=100, help="how many of the last steps to summarise")
    args = ap.parse_args()
    rows = [r for r in read_csv_rows(args.csv) if len(r) > 14 and r[0] != "ID" and r[12] == "gpu__time_duration.sum"]
    if not rows:
        raise SystemExit("no gpu__time_duration.sum rows in " + args.csv)
    scale = {"ns": 1e-3, "nsecond": 1e-3, "us": 1.0, "usecond": 1.0, "ms": 1e3, "msecond": 1e3}[rows[0][13]]
    ends = [i for i, r in enumerate(rows) if re.search(r"persistent_(iterations|checked)_kernel", r[4])]
    if len(ends) <= args.steps:
        raise SystemExit(f"only {len(ends)} persistent kernels: fewer than --steps {args.steps} + 1")
    step = rows[ends[-args.steps - 1] + 1 : ends[-1] + 1]
    count, total, first = collections.Counter(), collections.defaultdict(float), {}
    for i, r in enumerate(step):
        name = re.sub(r"\s+", " ", r[4])
        name = re.sub(r"^void ", "", name)[:100]
        count[name] += 1
        total[name] += float(r[14].replace(",", "")) * scale
        first.setdefault(name, i)
    n = args.steps
    print(f"{len(step) / n:.1f} kernels and {sum(total.values()) / n:.1f} us of kernel time per step (last {n} steps)")
    print("per step  us each  kernel")
    for name in sorted(total, key=first.get):
        print(f"{count[name] / n:8.1f} {total[name] / count[name]:8.2f}  {name}")


if __name__ == "__main__":
    main()
