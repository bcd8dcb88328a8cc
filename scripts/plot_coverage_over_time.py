#!/usr/bin/python3
"""Coverage over flight time of nbv_mission trials run with --coverage-every.

    scripts/plot_coverage_over_time.py OUT.png RUN_DIR... [--goal PERCENT]
                                       [--reference LABEL,MIN,PERCENT]...

Reads RUN_DIR/trial_*/coverage.csv of every run directory (one nbv_mission
--out each), plots the coverage of each trial against flight time and path
length, with the mean over trials at the flight times they all have a
checkpoint at, and the reference points given (for example Table 2's statue
column: Table 2,36,92.3).
Prints a Markdown table of the mean and, with --goal, when each trial first
reached it (linear between checkpoints). Needs python3-matplotlib.
"""
import argparse
import csv
import glob
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def read_trial(path):
    with open(path) as f:
        rows = list(csv.DictReader(f))
    return [(float(r["t_s"]) / 60.0, float(r["path_m"]), 100.0 * float(r["coverage"])) for r in rows]


def crossing(points, goal):
    """(minutes, metres) where the coverage first reaches goal, or None."""
    prev = (0.0, 0.0, 0.0)
    for t, p, c in points:
        if c >= goal:
            f = (goal - prev[2]) / (c - prev[2]) if c > prev[2] else 1.0
            return prev[0] + f * (t - prev[0]), prev[1] + f * (p - prev[1])
        prev = (t, p, c)
    return None


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("out")
    ap.add_argument("runs", nargs="+")
    ap.add_argument("--goal", type=float)
    ap.add_argument("--reference", action="append", default=[])
    a = ap.parse_args()
    trials = []
    for run in a.runs:
        for f in sorted(glob.glob(os.path.join(run, "trial_*", "coverage.csv"))):
            trials.append((os.path.relpath(os.path.dirname(f)), read_trial(f)))
    if not trials:
        print("no trial_*/coverage.csv under " + " ".join(a.runs) + " (run nbv_mission with --coverage-every)",
              file=sys.stderr)
        return 2
    references = []
    for r in a.reference:
        parts = r.split(",")
        if len(parts) != 3:
            print(f"--reference expects LABEL,MIN,PERCENT, got '{r}'", file=sys.stderr)
            return 2
        references.append((parts[0], float(parts[1]), float(parts[2])))

    # The mean at the flight times every trial has a checkpoint at (to 0.01 min).
    by_time = {}
    for _, points in trials:
        for t, p, c in points:
            by_time.setdefault(round(t, 2), []).append((p, c))
    mean = [(t, sum(p for p, _ in v) / len(v), sum(c for _, c in v) / len(v))
            for t, v in sorted(by_time.items()) if len(v) == len(trials)]

    fig, (ax, bx) = plt.subplots(1, 2, figsize=(12, 5))
    for name, points in trials:
        ax.plot([p[0] for p in points], [p[2] for p in points], "-", linewidth=0.8, alpha=0.6, label=name)
        bx.plot([p[1] for p in points], [p[2] for p in points], "-", linewidth=0.8, alpha=0.6)
    if mean:
        ax.plot([m[0] for m in mean], [m[2] for m in mean], "k-o", markersize=3, label="mean")
        bx.plot([m[1] for m in mean], [m[2] for m in mean], "k-o", markersize=3)
    for label, minutes, percent in references:
        ax.plot([minutes], [percent], "r*", markersize=12)
        ax.annotate(label, (minutes, percent), textcoords="offset points", xytext=(6, -12), fontsize=8)
    if a.goal is not None:
        for x in (ax, bx):
            x.axhline(a.goal, color="r", linewidth=0.6, linestyle="--")
    ax.set_xlabel("flight time [min]")
    bx.set_xlabel("path [m]")
    for x in (ax, bx):
        x.set_ylabel("coverage [%]")
        x.set_ylim(0, 100)
        x.grid(alpha=0.3)
    ax.legend(fontsize=7, loc="lower right")
    fig.tight_layout()
    fig.savefig(a.out, dpi=110)

    print("| flight [min] | mean coverage [%] | mean path [m] |\n|---|---|---|")
    for t, p, c in mean:
        print(f"| {t:.1f} | {c:.2f} | {p:.0f} |")
    if a.goal is not None:
        for name, points in trials:
            hit = crossing(points, a.goal)
            print(f"{name}: {a.goal:g} % " + (f"at {hit[0]:.1f} min, {hit[1]:.0f} m" if hit else "not reached"))
    print(f"wrote {a.out}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
