#!/usr/bin/env python3
"""Where one kernel's warps wait, from ncu's per-instruction stall samples.

The CSV comes from a report with the SourceCounters and WarpStateStats sections:
  ncu --section SourceCounters --section WarpStateStats -o rep <program> ...
  ncu -i rep.ncu-rep --page source --csv --print-source sass > sass.csv
Prints the share of every stall reason over the whole kernel, then the SASS
instructions with the most samples in program order, each with its main reason:
the loads a chain of dependent loads waits on show up as long-scoreboard stalls
at the first instruction that uses them.
"""
import argparse

from ncu_step_summary import read_csv_rows

SAMPLES = "Warp Stall Sampling (All Samples)"


def number(text):
    try:
        return float(text.replace(",", ""))
    except ValueError:
        return 0.0


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("csv", help="ncu --page source --csv --print-source sass output (plain or .gz)")
    ap.add_argument("--top", type=int, default=25, help="how many instructions to list")
    args = ap.parse_args()
    rows = read_csv_rows(args.csv)
    header = next((i for i, r in enumerate(rows) if SAMPLES in r), None)
    if header is None:
        raise SystemExit(f"no '{SAMPLES}' column in {args.csv}")
    names, body = rows[header], rows[header + 1 :]
    col = {n: i for i, n in enumerate(names)}
    reasons = [n for n in names if n.startswith("stall_") and "Not Issued" not in n]
    total = sum(number(r[col[SAMPLES]]) for r in body)
    if total == 0:
        raise SystemExit("no stall samples")
    print(f"{len(body)} instructions, {total:.0f} samples")
    shares = {s: sum(number(r[col[s]]) for r in body) for s in reasons}
    for s, v in sorted(shares.items(), key=lambda x: -x[1]):
        if v / total >= 0.005:
            print(f"  {s[6:]:<18} {100 * v / total:5.1f}%")
    top = sorted(range(len(body)), key=lambda i: -number(body[i][col[SAMPLES]]))[: args.top]
    print(f"the {args.top} instructions with the most samples, in program order:")
    for i in sorted(top):
        r = body[i]
        main_reason = max(reasons, key=lambda s: number(r[col[s]]))[6:]
        print(f"  {i:5d} {100 * number(r[col[SAMPLES]]) / total:5.1f}% {main_reason:<18} {r[col['Source']].strip()[:60]}")


if __name__ == "__main__":
    main()
