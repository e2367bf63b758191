#!/usr/bin/python3
"""Draws the pictures of docs/CONCEPTS.md from the model itself (pneumatic_finger.core):

- docs/concepts_wall.png: a chamber's wall, its bulge h and its half angle theta, and the finger they bend;
- docs/concepts_snap.png: a wall's limit point, the snap to its far branch and the snap back (pressure against the
  volume the supply pushed in);
- docs/concepts_range.png: the validated range, the extrapolated pressures above it and the clamp at the top, as the
  status flags every interface reports.

    source devel/setup.bash; /usr/bin/python3 scripts/plot_concepts.py [--output-dir docs]
"""
import argparse
import os
import warnings

import numpy

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def plot_wall(pf, plt, path):
    """Left: one wall at rest and bulged (its bulge drawn 10 times larger); right: the backbone at five pressures."""
    model = pf.FingerModel()
    gauge_pa = 196133.0
    state = model.evaluate(gauge_pa)
    height_m = model.parameters["chamber_height_m"]
    bulge_m, half_rad = float(state["bulge_m"][0]), float(state["half_angle_rad"][0])
    fig, (wall, finger) = plt.subplots(1, 2, figsize=(11, 4.8), gridspec_kw={"width_ratios": [1, 2.2]})
    scale = 10.0  # the bulge is a fraction of a millimetre: drawn ten times larger
    y = numpy.linspace(0.0, height_m, 101)
    # The paper's wall bulges into half an ellipse with one radius L/2 and the other the bulge h (docs/MODEL.md).
    x = scale * bulge_m * numpy.sqrt(numpy.clip(1.0 - ((y - height_m / 2) / (height_m / 2)) ** 2, 0.0, None))
    wall.plot([0, 0], [0, height_m * 1e3], color="0.6", lw=3, label="the wall at rest (height L)")
    wall.plot(x * 1e3, y * 1e3, color="C3", lw=3, label=f"at {gauge_pa / 1e3:.0f} kPa: bulge h (x{scale:.0f})")
    wall.annotate("", xy=(x.max() * 1e3, height_m / 2 * 1e3), xytext=(0, height_m / 2 * 1e3),
                  arrowprops=dict(arrowstyle="<->", color="k"))
    wall.text(x.max() * 0.5e3, height_m / 2 * 1e3 + 0.3, "h", ha="center")
    wall.set_title(f"one wall: bulge h = {bulge_m * 1e3:.2f} mm,\nhalf angle theta = {numpy.degrees(half_rad):.1f} deg",
                   fontsize=10)
    wall.set_xlabel("mm (across the wall)")
    wall.set_ylabel("mm (up the wall)")
    wall.set_aspect("equal")
    wall.set_xlim(-1, 5)
    wall.legend(loc="lower right", fontsize=8)
    for p in (0.0, 49033.25, 98066.5, 147099.75, 196133.0):
        b = model.evaluate(p)["backbone_m"] * 1e3
        finger.plot(b[:, 0], b[:, 1], "-o", ms=3, label=f"{p / 1e3:.0f} kPa")
    finger.set_title("each wall's tilt turns a joint: the finger bends")
    finger.set_xlabel("x (mm, along the unbent finger)")
    finger.set_ylabel("y (mm, toward the strain-limited side)")
    finger.set_aspect("equal")
    finger.grid(alpha=0.3)
    finger.legend(fontsize=8, title="gauge pressure")
    fig.tight_layout()
    fig.savefig(path, dpi=110)


def plot_snap(pf, plt, path):
    """The EPFL actuator as drawn with its coupon's elastomer: the pressure each supplied volume makes."""
    model = pf.FingerModel(os.path.join(ROOT, "config", "epfl_ecoflex30_c7_coupon.yaml"))
    volumes = numpy.linspace(0.0, 0.995 * model.volume_limit_m3, 400)
    gauge = model.evaluate_volume(volumes, outputs=["gauge_pa"])["gauge_pa"]
    limit, turning = model.limit_gauge_pa, model.far_turning_gauge_pa
    v_limit = volumes[numpy.nanargmax(numpy.where(volumes < volumes[len(volumes) // 2], gauge, -1))]
    fig, ax = plt.subplots(figsize=(8, 4.8))
    ax.plot(volumes * 1e6, gauge / 1e3, color="C0", lw=2, label="the walls' pressure at each supplied volume")
    ax.axhline(limit / 1e3, color="C3", ls="--", lw=1)
    ax.axhline(turning / 1e3, color="C2", ls="--", lw=1)
    ax.plot([v_limit * 1e6], [limit / 1e3], "o", color="C3")
    ax.text(v_limit * 1e6, limit / 1e3 + 1.0, f"limit point {limit / 1e3:.1f} kPa", color="C3", ha="center")
    ax.annotate("snap: a rising pressure jumps to the far branch", xy=(0.8 * volumes[-1] * 1e6, limit / 1e3),
                xytext=(0.25 * volumes[-1] * 1e6, limit / 1e3 + 5), arrowprops=dict(arrowstyle="->", color="C3"),
                color="C3")
    ax.text(0.5 * volumes[-1] * 1e6, turning / 1e3 - 2.5,
            f"far branch's turning point {turning / 1e3:.1f} kPa: a falling pressure snaps back here", color="C2",
            ha="center")
    ax.set_xlabel("supplied volume (mL)")
    ax.set_ylabel("gauge pressure (kPa)")
    ax.set_title("a wall that folds: under pressure control it snaps; under volume control it follows the curve")
    ax.set_ylim(0, max(limit / 1e3 + 10, numpy.nanmax(gauge) / 1e3 + 2))
    ax.grid(alpha=0.3)
    ax.legend(loc="lower right", fontsize=8)
    fig.tight_layout()
    fig.savefig(path, dpi=110)


def plot_range(pf, plt, path):
    """The calibrated EPFL actuator from 0 to 120 % of its range, each pressure coloured by its status flags."""
    model = pf.FingerModel(os.path.join(ROOT, "config", "epfl_ecoflex30_c7.yaml"))
    pressures = numpy.linspace(0.0, 1.2 * model.max_gauge_pa, 241)
    state = model.evaluate(pressures, outputs=["tip_angle_rad", "status_flags"])
    flags = state["status_flags"]
    bit = {name: 1 << i for i, name in enumerate(pf.STATUS_FLAGS)}
    clamped = (flags & bit["clamped"]) > 0
    groups = {"in the validated range (no flag)": flags == 0,
              "extrapolated (above validated_max_gauge_pa)": ((flags & bit["extrapolated"]) > 0) & ~clamped,
              "clamped and extrapolated (above max_gauge_pa)": clamped}
    fig, ax = plt.subplots(figsize=(8, 4.6))
    for (label, mask), color in zip(groups.items(), ("C2", "C1", "C3")):
        ax.plot(pressures[mask] / 1e3, numpy.degrees(state["tip_angle_rad"][mask]), "o", ms=3, color=color,
                label=label)
    ax.axvline(model.validated_max_gauge_pa / 1e3, color="C1", ls="--", lw=1)
    ax.axvline(model.max_gauge_pa / 1e3, color="C3", ls="--", lw=1)
    ax.set_xlabel("gauge pressure asked for (kPa)")
    ax.set_ylabel("tip angle (deg)")
    ax.set_title("config/epfl_ecoflex30_c7.yaml: calibrated to 45 kPa, its range to 50 kPa")
    ax.grid(alpha=0.3)
    ax.legend(loc="upper left", fontsize=8)
    fig.tight_layout()
    fig.savefig(path, dpi=110)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--output-dir", default=os.path.join(ROOT, "docs"))
    args = parser.parse_args()
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    import pneumatic_finger.core as pf
    warnings.simplefilter("ignore", RuntimeWarning)  # the pictures cross the range's edges on purpose
    for name, plot in (("wall", plot_wall), ("snap", plot_snap), ("range", plot_range)):
        path = os.path.join(args.output_dir, f"concepts_{name}.png")
        plot(pf, plt, path)
        print(f"plot_concepts: wrote {path}")


if __name__ == "__main__":
    main()
