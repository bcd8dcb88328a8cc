#!/usr/bin/python3
"""Plots an nbv_evaluate report: error histogram, top and side views of the
matched ground-truth samples coloured by signed error.

    scripts/plot_evaluation.py OUTPUT_DIR

Reads OUTPUT_DIR/error.ply and OUTPUT_DIR/report.json, writes
error_histogram.png, error_top.png and error_side.png next to them.
Needs python3-matplotlib and python3-numpy (Debian packages).
"""
import json
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

PLY_TYPES = {"float": "<f4", "double": "<f8", "uchar": "u1", "int": "<i4", "uint": "<u4"}
MAX_SCATTER = 400000  # points drawn in a view; a regular stride keeps it repeatable


def read_ply(path):
    """Vertices of a binary little-endian PLY point cloud as a numpy record array."""
    with open(path, "rb") as f:
        if f.readline().strip() != b"ply":
            raise ValueError(f"{path}: not a PLY file")
        count, fields = 0, []
        for raw in iter(f.readline, b""):
            words = raw.decode("ascii").split()
            if not words:
                continue
            if words[0] == "format" and words[1] != "binary_little_endian":
                raise ValueError(f"{path}: expected binary_little_endian, got {words[1]}")
            if words[0] == "element" and words[1] == "vertex":
                count = int(words[2])
            elif words[0] == "property":
                fields.append((words[2], PLY_TYPES[words[1]]))
            elif words[0] == "end_header":
                break
        return np.frombuffer(f.read(), dtype=np.dtype(fields), count=count)


def view(points, error, limit, axes, title, path):
    step = max(1, len(points) // MAX_SCATTER)
    a, b = axes
    order = np.argsort(np.abs(error[::step]))  # largest errors drawn last, on top
    x, y, e = points[::step, a][order], points[::step, b][order], error[::step][order]
    fig, ax = plt.subplots(figsize=(10, 7))
    size = float(np.clip(40000.0 / max(len(x), 1), 0.3, 6.0))  # sparse clouds get bigger dots
    sc = ax.scatter(x, y, c=100 * e, s=size, cmap="coolwarm", vmin=-100 * limit, vmax=100 * limit, linewidths=0)
    ax.set_aspect("equal")
    ax.set_xlabel("xyz"[a] + " [m]")
    ax.set_ylabel("xyz"[b] + " [m]")
    ax.set_title(title)
    fig.colorbar(sc, ax=ax, label="signed error [cm]", shrink=0.8)
    fig.savefig(path, dpi=150, bbox_inches="tight")
    plt.close(fig)


def main():
    if len(sys.argv) != 2:
        print(__doc__, file=sys.stderr)
        return 2
    out = sys.argv[1]
    with open(os.path.join(out, "report.json")) as f:
        report = json.load(f)
    cloud = read_ply(os.path.join(out, "error.ply"))
    points = np.stack([cloud["x"], cloud["y"], cloud["z"]], axis=1)
    error = cloud["error"].astype(np.float64)
    stats = report["error_m"]
    limit = report["error_colour_range_m"]
    name = os.path.basename(report["inputs"]["reconstruction"])
    figures = ("coverage {:.2f} %, mean {:.2f} cm, std {:.2f} cm, RMSE {:.2f} cm".format(
        report["coverage_percent"], 100 * (stats["mean"] or 0), 100 * (stats["std_dev"] or 0),
        100 * (stats["rmse"] or 0)))

    fig, ax = plt.subplots(figsize=(8, 5))
    if len(error) > 0:
        # Up to the 99.5th percentile of |error|; the few beyond pile up in the end bins.
        edge = max(limit, float(np.percentile(np.abs(error), 99.5)))
        ax.hist(100 * np.clip(error, -edge, edge), bins=101, range=(-100 * edge, 100 * edge), color="#4a7ab5")
    ax.set_xlabel("signed error along the ground-truth normal [cm]")
    ax.set_ylabel("samples")
    ax.set_title(f"{name}: {figures}", fontsize=9)
    fig.savefig(os.path.join(out, "error_histogram.png"), dpi=150, bbox_inches="tight")
    plt.close(fig)

    view(points, error, limit, (0, 1), f"top view (x, y): {figures}", os.path.join(out, "error_top.png"))
    view(points, error, limit, (0, 2), f"side view (x, z): {figures}", os.path.join(out, "error_side.png"))
    print(f"wrote {out}/error_histogram.png, error_top.png, error_side.png")
    return 0


if __name__ == "__main__":
    sys.exit(main())
