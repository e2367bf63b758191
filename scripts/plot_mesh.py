#!/usr/bin/python3
"""Draws a body mesh (finger_urdf --stl's ASCII STL) in 3-D, translucent, so that its cavities show through.

usage: python3 scripts/plot_mesh.py BODY.stl OUT.png [TITLE]
"""
import sys

import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy  # noqa: E402
from mpl_toolkits.mplot3d.art3d import Poly3DCollection  # noqa: E402


def triangles(path):
    """The STL's triangles, (T, 3, 3) in mm."""
    corners = [[float(x) for x in line.split()[1:4]] for line in open(path) if line.strip().startswith("vertex")]
    return 1e3 * numpy.array(corners).reshape(-1, 3, 3)


def main(stl, png, title="the drawn body"):
    t = triangles(stl)
    fig = plt.figure(figsize=(10, 4.5))
    ax = fig.add_subplot(projection="3d")
    outer = 12  # finger_urdf --stl writes the outer box first, then each cavity
    ax.add_collection3d(Poly3DCollection(t[:outer], facecolor="0.75", edgecolor="0.4", alpha=0.25, linewidths=0.5))
    ax.add_collection3d(Poly3DCollection(t[outer:], facecolor="C0", edgecolor="C0", alpha=0.6, linewidths=0.3))
    lo, hi = t.reshape(-1, 3).min(axis=0), t.reshape(-1, 3).max(axis=0)
    ax.set(xlim=(lo[0], hi[0]), ylim=(lo[1], hi[1]), zlim=(lo[2], hi[2]), xlabel="x along (mm)", ylabel="y across (mm)",
           zlabel="z up (mm)")
    ax.set_box_aspect(hi - lo, zoom=1.3)
    ax.set_yticks([lo[1], 0.0, hi[1]])
    ax.view_init(elev=25, azim=-60)
    ax.set_title(f"{title}: the elastomer (grey) and its cavities (blue)")
    fig.tight_layout()
    fig.savefig(png, dpi=100)


if __name__ == "__main__":
    main(*sys.argv[1:])
