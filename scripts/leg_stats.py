#!/usr/bin/python3
"""How a mission's legs went: flown length against the straight line.

  scripts/leg_stats.py TRIAL_DIR [TRIAL_DIR ...] [--until S]

TRIAL_DIR is an nbv_mission trial folder (trial_K/ with path.csv and
events.csv). A leg runs from one "fly" decision to the next (or to the end,
or to --until S seconds of flight). Prints one Markdown row per trial: legs,
flown and straight-line metres, their ratio, the median leg and the share of
the path in legs longer than 8 m or flown more than 1.5x their straight line.
"""
import argparse
import csv
import sys

import numpy as np


def leg_rows(trial, until):
    with open(f"{trial}/events.csv") as f:
        starts = [float(e["t_s"]) for e in csv.DictReader(f) if e["action"] == "fly"]
    d = np.genfromtxt(f"{trial}/path.csv", delimiter=",", names=True)
    t = d["t_s"]
    end = min(until, t[-1]) if until > 0 else t[-1]
    starts = [s for s in starts if s < end]
    p = np.stack([d["x_m"], d["y_m"], d["z_m"]], axis=1)
    along = np.concatenate([[0.0], np.cumsum(np.linalg.norm(np.diff(p, axis=0), axis=1))])
    flown, straight = [], []
    for a, b in zip(starts, starts[1:] + [end]):
        i, j = np.searchsorted(t, a), np.searchsorted(t, b, side="right") - 1
        if j <= i:
            continue
        flown.append(along[j] - along[i])
        straight.append(np.linalg.norm(p[j] - p[i]))
    return np.array(flown), np.array(straight)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("trials", nargs="+")
    ap.add_argument("--until", type=float, default=0.0, help="seconds of flight to stop at (0: all)")
    args = ap.parse_args()
    print("| trial | legs | flown [m] | straight [m] | ratio | median leg [m] | in legs > 8 m | in legs > 1.5x straight |")
    print("|---|---|---|---|---|---|---|---|")
    for trial in args.trials:
        try:
            flown, straight = leg_rows(trial, args.until)
        except (OSError, ValueError, KeyError) as e:
            print(f"leg_stats: {trial}: {e}", file=sys.stderr)
            return 2
        moved = flown > 0.3  # turns in place are not legs of the path
        flown, straight = flown[moved], straight[moved]
        if flown.size == 0:
            print(f"| {trial} | 0 | 0 | 0 | - | - | - | - |")
            continue
        total = flown.sum()
        detour = flown > 1.5 * np.maximum(straight, 1e-9)
        print(f"| {trial} | {flown.size} | {total:.0f} | {straight.sum():.0f} | {total / straight.sum():.2f} | "
              f"{np.median(flown):.2f} | {100 * flown[flown > 8].sum() / total:.1f} % | "
              f"{100 * flown[detour].sum() / total:.1f} % |")
    return 0


if __name__ == "__main__":
    sys.exit(main())
