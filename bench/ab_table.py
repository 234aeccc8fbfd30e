#!/usr/bin/env python3
"""The A/B table of bench/ab_step.sh's output: per size and mode, the deterministic
figures of both builds (equal or not, to every printed digit) and each round's
median step time. Usage: python3 bench/ab_table.py OUT_DIR"""
import csv
import sys
from pathlib import Path

d = Path(sys.argv[1])


def rows(name):
    return list(csv.DictReader(open(d / name)))


def table(kind, key, figures, time):
    runs = {f"{b}{r}": rows(f"{kind}_{b}_round{r}.csv") for b in ("base", "new") for r in ("1", "2")}
    print(f"| {' | '.join(key)} | {' | '.join(figures)} | same in both builds | ms base r1 / r2 | ms new r1 / r2 |")
    print("|" + " --- |" * (len(key) + len(figures) + 3))
    same_all = True
    for i, row in enumerate(runs["base1"]):
        vals = {k: tuple(v[i][f] for f in figures) for k, v in runs.items()}
        same = len(set(vals.values())) == 1
        same_all &= same
        t = {k: float(v[i][time]) for k, v in runs.items()}
        print(f"| {' | '.join(row[k] for k in key)} | {' | '.join(vals['new1'])} | {'yes' if same else 'NO'} | "
              f"{t['base1']:.3f} / {t['base2']:.3f} | {t['new1']:.3f} / {t['new2']:.3f} |")
    return same_all


ok = table("step", ["n", "mode"], ["contacts", "iterations_mean", "max_penetration", "residual_median"], "ms_step_median")
print()
ok &= table("pile", ["n", "method", "budget"], ["contacts", "max_penetration", "residual_median", "iterations_mean", "kinetic_energy", "height"],
            "ms_per_step_median")
print("\nall deterministic figures identical" if ok else "\nSOME FIGURES DIFFER")
