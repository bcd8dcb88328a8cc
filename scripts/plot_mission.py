#!/usr/bin/python3
"""Plots one nbv_mission trial: the flown path over the reconstruction (top
and side views), the running coverage and ISE counts over flight time, and
the error histogram of the evaluation.

    scripts/plot_mission.py TRIAL_DIR

Reads TRIAL_DIR/path.csv, events.csv, reconstruction.ply (vertices),
eval/error.ply and, when nbv_mission --coverage-every wrote it,
coverage.csv; writes path_top.png, path_side.png, progress.png and
error_histogram.png into TRIAL_DIR. Needs python3-matplotlib and python3-numpy.
"""
import csv
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

PLY_TYPES = {"float": "<f4", "double": "<f8", "uchar": "u1", "int": "<i4", "uint": "<u4",
             "float32": "<f4", "uint8": "u1", "int32": "<i4", "uint32": "<u4"}
MAX_POINTS = 300000  # drawn per view; a regular stride keeps the picture repeatable


def read_ply_vertices(path):
    """Vertices of a binary little-endian PLY file (any other elements after them are ignored)."""
    with open(path, "rb") as f:
        if f.readline().strip() != b"ply":
            raise ValueError(f"{path}: not a PLY file")
        count, fields, in_vertex = 0, [], False
        while True:
            line = f.readline().decode("ascii").strip()
            if line == "end_header":
                break
            parts = line.split()
            if parts[0] == "format" and parts[1] != "binary_little_endian":
                raise ValueError(f"{path}: only binary_little_endian PLY is read")
            if parts[0] == "element":
                in_vertex = parts[1] == "vertex"
                if in_vertex:
                    count = int(parts[2])
            elif parts[0] == "property" and in_vertex and parts[1] != "list":
                fields.append((parts[2], PLY_TYPES[parts[1]]))
        return np.frombuffer(f.read(np.dtype(fields).itemsize * count), dtype=np.dtype(fields), count=count)


def read_csv(path):
    with open(path) as f:
        rows = list(csv.DictReader(f))
    return rows


def view(ax, cloud, path, a, b, labels):
    if cloud is not None and len(cloud):
        stride = max(1, len(cloud) // MAX_POINTS)
        ax.scatter(cloud[::stride, a], cloud[::stride, b], s=0.2, c="0.6", linewidths=0)
    ax.plot(path[:, a], path[:, b], "-", color="tab:red", linewidth=0.8, label="flown path")
    ax.plot(path[0, a], path[0, b], "o", color="tab:green", label="start")
    ax.plot(path[-1, a], path[-1, b], "s", color="tab:blue", label="end")
    ax.set_xlabel(labels[0])
    ax.set_ylabel(labels[1])
    ax.set_aspect("equal")
    ax.legend(loc="upper right", fontsize=7)


def main():
    if len(sys.argv) != 2:
        print(__doc__)
        return 2
    d = sys.argv[1]
    rows = read_csv(os.path.join(d, "path.csv"))
    path = np.array([[float(r["x_m"]), float(r["y_m"]), float(r["z_m"])] for r in rows])
    cloud = None
    mesh = os.path.join(d, "reconstruction.ply")
    if os.path.exists(mesh):
        v = read_ply_vertices(mesh)
        cloud = np.stack([v["x"], v["y"], v["z"]], axis=1)
    for name, (a, b), labels in (("path_top.png", (0, 1), ("x [m]", "y [m]")),
                                 ("path_side.png", (0, 2), ("x [m]", "z [m]"))):
        fig, ax = plt.subplots(figsize=(10, 7))
        view(ax, cloud, path, a, b, labels)
        ax.set_title(f"{os.path.basename(os.path.normpath(d))}: flown path over the reconstruction")
        fig.tight_layout()
        fig.savefig(os.path.join(d, name), dpi=110)
        plt.close(fig)

    events = read_csv(os.path.join(d, "events.csv"))
    t = np.array([float(e["t_s"]) for e in events]) / 60.0
    inside = np.array([int(e["inside"]) for e in events])
    ises = np.array([int(e["ises"]) for e in events])
    observed = np.array([float(e["observed"]) for e in events])
    fig, ax = plt.subplots(figsize=(9, 5))
    ax.plot(t, ises, color="0.5", label="ISEs")
    ax.plot(t, inside, color="tab:orange", label="ISEs of C_ins")
    ax.set_xlabel("flight time [min]")
    ax.set_ylabel("ISEs")
    ax2 = ax.twinx()
    mask = observed >= 0
    ax2.plot(t[mask], 100.0 * observed[mask], "o-", color="tab:blue", label="observed surface [%]")
    coverage_csv = os.path.join(d, "coverage.csv")
    if os.path.exists(coverage_csv):  # nbv_mission --coverage-every
        rows = read_csv(coverage_csv)
        ax2.plot([float(r["t_s"]) / 60.0 for r in rows], [100.0 * float(r["coverage"]) for r in rows], "s-",
                 color="tab:green", label="coverage, evaluated [%]")
    ax2.set_ylabel("observed surface, coverage [%]")
    ax2.set_ylim(0, 100)
    lines = ax.get_legend_handles_labels()
    lines2 = ax2.get_legend_handles_labels()
    ax.legend(lines[0] + lines2[0], lines[1] + lines2[1], loc="center right", fontsize=8)
    fig.tight_layout()
    fig.savefig(os.path.join(d, "progress.png"), dpi=110)
    plt.close(fig)

    err_path = os.path.join(d, "eval", "error.ply")
    if os.path.exists(err_path):
        err = read_ply_vertices(err_path)["error"] * 100.0
        fig, ax = plt.subplots(figsize=(8, 5))
        if len(err):
            lim = max(1e-3, float(np.percentile(np.abs(err), 99)))
            ax.hist(err, bins=100, range=(-lim, lim), color="tab:blue")
        ax.set_xlabel("signed error [cm]")
        ax.set_ylabel("samples")
        ax.set_title(f"error of {len(err)} covered samples")
        fig.tight_layout()
        fig.savefig(os.path.join(d, "error_histogram.png"), dpi=110)
        plt.close(fig)
    print(f"wrote {d}/path_top.png, path_side.png, progress.png, error_histogram.png")
    return 0


if __name__ == "__main__":
    sys.exit(main())
