"""What bounds the model of the two Marchese 2015 segments driven by volume, whatever its wall law's keys.

usage: python3 scripts/volume_bound.py [--plot docs/volume_bound.png]   (needs the built package: source devel/setup.bash)

A supply pushes a volume V into the segment; the model splits it between the drive's gas, which takes
V_d p / (p_atm + p) at the gauge pressure p (docs/MODEL.md, "Volume"), and the chambers' growth G. The chain of walls
turns G into a bend by geometry alone: the growth sets each wall's stretch, the stretch its bulge, the bulge against
the gap c the half angle. The shear modulus and J_m do not enter; they only set the pressure at which a growth is
reached. So a model whose pressures are all within a tolerance of the measured ones has, at every row, a growth
between V - V_d 1.1 p / (p_atm + 1.1 p) and V - V_d 0.9 p / (p_atm + 0.9 p) (for 10 %), and a bend between the
chain's bends at those growths (the bend rises with the growth). A measured bend outside that band is missed by at
least its distance to the band, for every wall law that shares the chain's geometry and every value of its keys.

This script searches the gas V_d (0 to 1 L, the calibration's range) and the gap c (0 to the chamber's extent) for
the smallest largest miss, on a grid refined twice around its best point, for the thin membrane wall, the thick wall
bent by its outer face and by its inner face (wall_flexion_face: the inner face's chain is the thin membrane's) and
the paper law (its half ellipses, with the
critical height docs/ACCURACY.md's law comparison uses). It reports the bound on every row and on the held-out half
(the odd rows by volume, as scripts/accuracy_volume.py splits them), for a pressure within 10 % and for the measured
pressure itself, and then with the skin's share of the growth free as well (chamber_growth_ratio, r_V: the walls'
growth is then G / r_V; searched over scripts/accuracy_volume.py's SKIN_RATIOS). Last, where the thin membrane law puts the cylindrical segment's limit point at the calibration's
softest modulus. Its output is docs/ACCURACY.md's "What bounds the volume input"; --plot draws the band at the best
point of the 10 % bound, every row, against the measured bends.
"""
import argparse
import math

import numpy as np

import pneumatic_finger.core as pf
from accuracy_volume import ROOT, SETS, SKIN_RATIOS, column, gas_uptake_m3, rows_of

DEG = 180 / math.pi
TOLERANCE = 0.10  # the pressure's relative error allowed: the accuracy target of the volume input
FLOOR_PA = 1e4  # the calibration's smallest shear_modulus_pa for the membrane laws (src/calibration/fit_space.hpp)
# Each law's geometry: the overrides that make its chain (the paper law's critical height as in accuracy_laws.py).
LAWS = {"membrane": {"wall_law": "membrane"},
        "thick, outer face": {"wall_law": "thick", "wall_flexion_face": "outer"},
        "thick, inner face": {"wall_law": "thick", "wall_flexion_face": "inner"},
        "paper": {"ribbed": {"wall_law": "paper", "wall_critical_height_m": 0.00155},
                  "cylindrical": {"wall_law": "paper", "wall_critical_height_m": 0.0014}}}


def geometry(name, law, gap_m, growth_ratio=1.0):
    """The chain alone: no gas (the supplied volume is the growth) and no lock (every growth has a shape); the skin
    taking @p growth_ratio times the walls' growth."""
    start = LAWS[law].get(name, LAWS[law])
    overrides = {**start, "chamber_gap_m": gap_m, "dead_volume_m3": 0.0, "chamber_growth_ratio": growth_ratio}
    if law != "paper":
        overrides["wall_locking_jm"] = 0.0
    return pf.FingerModel(str(ROOT / f"config/marchese2015_{name}.yaml"), overrides)


def band(model, rows, dead_m3, tolerance):
    """The lowest and highest bend (rad) of each row over pressures within @p tolerance of the measured one."""
    v, p = column(rows, "supplied_volume_m3"), column(rows, "gauge_pa")
    p_atm = model.parameters["atmospheric_pressure_pa"]
    bends = []
    for scale in (1.0 + tolerance, 1.0 - tolerance):  # a higher pressure: more gas, less growth
        growth = np.maximum(v - gas_uptake_m3(dead_m3, scale * p, p_atm), 0.0)
        bends.append(model.evaluate_volume(growth, outputs=["tip_angle_rad"])["tip_angle_rad"])
    return bends[0], bends[1]


def largest_miss_deg(model, rows, dead_m3, tolerance):
    lo, hi = band(model, rows, dead_m3, tolerance)
    b = column(rows, "bend_angle_rad")
    return float(np.max(np.maximum(0.0, np.maximum(b - hi, lo - b)))) * DEG


def search(name, law, rows, tolerance, ratios=(1.0,)):
    """The smallest largest miss over (c, V_d) and the skin's share r_V among @p ratios: a 41 x 201 grid per share,
    then two finer grids around the best point (at its share)."""
    extent = float(np.max(geometry(name, law, 0.0).parameters["chamber_height_m"]))
    c_step, v_step, best = extent / 40, 1e-3 / 200, (math.inf, 0.0, 0.0, 1.0)
    c_grid, v_grid = np.linspace(0.0, extent, 41), np.linspace(0.0, 1e-3, 201)
    for level in range(3):
        for ratio in ratios if level == 0 else (best[3],):
            for c in c_grid:
                model = geometry(name, law, float(c), float(ratio))
                for v_d in v_grid:
                    miss = largest_miss_deg(model, rows, float(v_d), tolerance)
                    if miss < best[0]:
                        best = (miss, float(c), float(v_d), float(ratio))
        c_step, v_step = c_step / 10, v_step / 10
        c_grid = np.clip(best[1] + c_step * np.arange(-10, 11), 0.0, extent)
        v_grid = np.clip(best[2] + v_step * np.arange(-10, 11), 0.0, 1e-3)
    return best


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--plot", help="write the figure here (PNG)")
    args = parser.parse_args()
    bands = {}
    for title, name in SETS:
        rows = rows_of(name)
        print(f"- {title}: the smallest largest bend miss of any keys (deg), at its gap c and gas V_d")
        for law in LAWS:
            for part, part_rows in (("every row", rows), ("held-out half", rows[1::2])):
                cells = []
                for tolerance in (TOLERANCE, 0.0):
                    miss, c, v_d, _ = search(name, law, part_rows, tolerance)
                    cells.append(f"pressure {'within 10 %' if tolerance else 'as measured'}: {miss:.2f} "
                                 f"(c = {c * 1e3:.3f} mm, V_d = {v_d * 1e6:.1f} mL)")
                    if tolerance and part == "every row":
                        bands[(name, law)] = (c, v_d)
                miss, c, v_d, ratio = search(name, law, part_rows, TOLERANCE, SKIN_RATIOS)
                cells.append(f"with the skin, pressure within 10 %: {miss:.2f} (c = {c * 1e3:.3f} mm, "
                             f"V_d = {v_d * 1e6:.1f} mL, r_V = {ratio:g})")
                print(f"  - {law}, {part}: " + "; ".join(cells))
    print(limit_pressure_line())
    if args.plot:
        plot(args.plot, bands)


def limit_pressure_line():
    """Where the thin membrane law puts the cylindrical segment's limit point at the calibration's softest modulus,
    against the pressure at which the measured bend takes off (the first row whose bend is above 10 deg)."""
    model = pf.FingerModel(str(ROOT / "config/marchese2015_cylindrical.yaml"),
                           {"wall_law": "membrane", "wall_locking_jm": 0.0, "shear_modulus_pa": FLOOR_PA})
    rows = rows_of("cylindrical")
    takeoff = next(float(r["gauge_pa"]) for r in rows if float(r["bend_angle_rad"]) * DEG > 10.0)
    return (f"- Marchese 2015 cylindrical segment, thin membrane law: limit pressure {model.limit_gauge_pa / 1e3:.1f} kPa "
            f"at shear_modulus_pa = {FLOOR_PA:.0f} (the calibration's floor); the measured bend takes off at "
            f"{takeoff / 1e3:.1f} kPa, which needs shear_modulus_pa = {FLOOR_PA * takeoff / model.limit_gauge_pa:.0f} "
            f"(the limit pressure is proportional to it)")


def plot(path, bands):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, axes = plt.subplots(1, 2, figsize=(11, 4.2))
    for ax, (title, name) in zip(axes, SETS):
        rows = rows_of(name)
        v = column(rows, "supplied_volume_m3") * 1e6
        ax.plot(v, column(rows, "bend_angle_rad") * DEG, "ko", mfc="none", label="measured")
        for law, color in zip(LAWS, ("C0", "C1", "C1", "C2")):
            if law == "thick, inner face":
                continue  # the thin membrane's chain: its band is the membrane's
            c, v_d = bands[(name, law)]
            lo, hi = band(geometry(name, law, c), rows, v_d, TOLERANCE)
            shown = "membrane or thick, inner face" if law == "membrane" else law
            ax.fill_between(v, lo * DEG, hi * DEG, color=color, alpha=0.3,
                            label=f"{shown} (c = {c * 1e3:.2f} mm, V_d = {v_d * 1e6:.0f} mL)")
        ax.set_title(title)
        ax.set_xlabel("supplied volume (mL)")
        ax.set_ylabel("bend (deg)")
        ax.set_ylim(-5, 1.6 * np.max(column(rows, "bend_angle_rad")) * DEG)  # the paper law's band runs far above
        ax.grid(alpha=0.3)
        ax.legend(fontsize=7, loc="upper left", title="bends with pressure within 10 %", title_fontsize=7)
    fig.tight_layout()
    fig.savefig(path, dpi=110)


if __name__ == "__main__":
    main()
