#!/usr/bin/python3
"""How long a ring-by-ring flight around a scene must be, and how vertical flights are.

  scripts/sweep_bound.py VISIBLE_PLY [--standoff M ...] [--flight CSV ...] [--until M]

VISIBLE_PLY is an evaluation's ground_truth_visible.ply (nbv_evaluate, a
mission's trial_K/eval/): samples 0.05 m apart on the surface a sensor can
see. A level camera of vertical FOV --vfov flying past a wall at a horizontal
standoff d sees a strip 2 d tan(vfov / 2) high, and no more than the range
allows (--max-range along the strip's edge rays). The bound cuts the surface
into such strips from the ground up and flies each once around the convex
hull of its samples, d outside it (hull perimeter + 2 pi d): no overlap, no
climb between rings, no leftovers. A flight that sweeps in rings needs at
least that much path to see every strip.

Each --flight (a mission's path.csv, or nbv_oracle's oracle_flight.csv) gets
one row: its length up to --until metres, the sum of its |dz| there and that
sum's share of the length (a flight that sweeps in columns climbs most of it).
"""
import argparse
import sys

import numpy as np


def read_vertices(path):
    with open(path, "rb") as f:
        raw = f.read()
    end = raw.index(b"end_header\n") + len(b"end_header\n")
    header = raw[:end].decode("ascii").splitlines()
    if "format binary_little_endian 1.0" not in header:
        sys.exit(f"{path}: expected a binary little-endian PLY")
    types = {"float": "<f4", "double": "<f8", "uchar": "u1", "int": "<i4", "uint": "<u4"}
    count, fields, in_vertex = 0, [], False
    for line in header:
        words = line.split()
        if words[:2] == ["element", "vertex"]:
            count, in_vertex = int(words[2]), True
        elif words[:1] == ["element"]:
            in_vertex = False
        elif in_vertex and words[:1] == ["property"]:
            if words[1] not in types:
                sys.exit(f"{path}: unsupported vertex property type {words[1]}")
            fields.append((words[2], types[words[1]]))
    v = np.frombuffer(raw[end:end + count * np.dtype(fields).itemsize], dtype=np.dtype(fields))
    return np.stack([v["x"], v["y"], v["z"]], axis=1).astype(float)


def hull_perimeter(xy):
    """Perimeter of the 2-D convex hull (Andrew's monotone chain)."""
    pts = np.unique(np.round(xy, 3), axis=0)
    if len(pts) < 3:
        return 0.0

    def half(points):
        chain = []
        for p in points:
            while len(chain) >= 2:
                a, b = chain[-2], chain[-1]
                if (b[0] - a[0]) * (p[1] - a[1]) - (b[1] - a[1]) * (p[0] - a[0]) > 0:
                    break
                chain.pop()
            chain.append(p)
        return chain

    hull = np.array(half(pts)[:-1] + half(pts[::-1])[:-1])
    return float(np.linalg.norm(hull - np.roll(hull, 1, axis=0), axis=1).sum())


def ring_bound(points, standoff, vfov_deg, max_range):
    half = np.radians(0.5 * vfov_deg)
    # The strip's edge rays reach the wall at standoff / cos(half).
    strip = 2.0 * min(standoff, max_range * np.cos(half)) * np.tan(half)
    z, top, rings, length = points[:, 2].min(), points[:, 2].max(), 0, 0.0
    while z < top:
        inside = points[(points[:, 2] >= z) & (points[:, 2] < z + strip)]
        if len(inside) >= 3:
            length += hull_perimeter(inside[:, :2]) + 2.0 * np.pi * standoff
            rings += 1
        z += strip
    return strip, rings, length


def flight_row(path, until):
    d = np.genfromtxt(path, delimiter=",", names=True)
    p = np.stack([d["x_m"], d["y_m"], d["z_m"]], axis=1)
    steps = np.diff(p, axis=0)
    along = np.cumsum(np.linalg.norm(steps, axis=1))
    n = int(np.searchsorted(along, until, side="right")) if until > 0 else len(steps)
    length = float(along[n - 1]) if n > 0 else 0.0
    climb = float(np.abs(steps[:n, 2]).sum())
    return length, climb


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("visible_ply")
    parser.add_argument("--standoff", type=float, nargs="+", default=[3.6], help="horizontal standoffs [m]")
    parser.add_argument("--vfov", type=float, default=60.0, help="vertical FOV [deg]")
    parser.add_argument("--max-range", type=float, default=5.0, help="camera max range [m]")
    parser.add_argument("--flight", nargs="*", default=[], help="path.csv or oracle_flight.csv files")
    parser.add_argument("--until", type=float, default=0.0, help="count flights up to this length [m]; 0: all")
    args = parser.parse_args()
    if not (0.0 < args.vfov < 180.0) or not args.max_range > 0.0 or any(not s > 0.0 for s in args.standoff):
        sys.exit("expected vfov in (0, 180), max range > 0 and standoffs > 0")
    points = read_vertices(args.visible_ply)
    print(f"{args.visible_ply}: {len(points)} samples, {len(points) * 0.05 ** 2:.0f} m^2 at 0.05 m spacing\n")
    print("| standoff [m] | strip [m] | rings | rings' length [m] |\n|---|---|---|---|")
    for d in args.standoff:
        strip, rings, length = ring_bound(points, d, args.vfov, args.max_range)
        print(f"| {d:.2f} | {strip:.2f} | {rings} | {length:.0f} |")
    if args.flight:
        print("\n| flight | length [m] | sum of abs(dz) [m] | share |\n|---|---|---|---|")
        for path in args.flight:
            length, climb = flight_row(path, args.until)
            share = climb / length if length > 0 else 0.0
            print(f"| {path} | {length:.1f} | {climb:.1f} | {100 * share:.0f} % |")


if __name__ == "__main__":
    main()
