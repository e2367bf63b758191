"""The cylindrical segment's pressure against its supplied volume alone: can the wall law mapped to it predict the
held-out half within 10 %, with its keys fitted to the pressures and not to the bends?

usage: python3 scripts/pressure_against_volume.py   (needs the built package: source devel/setup.bash)

scripts/accuracy_volume.py fits each law's keys to the bends, or to the bends and the pressures at once; on the
cylindrical segment no way there comes within 10 % on the pressure. This script asks the pressure alone of the law
its parameter file maps (config/marchese2015_cylindrical.yaml: the thick wall bent by its inner face), in its Gent
form, whose stiffening the measured pressure shows after the snap: shear_modulus_pa, wall_locking_jm and the drive's
gas dead_volume_m3 fitted to the pressures of the even rows by volume (least squares, in Pa), at each
skin share chamber_growth_ratio of scripts/accuracy_volume.py's SKIN_RATIOS, keeping the share whose fit leaves the
smaller objective on those rows; then the gap chamber_gap_m fitted to the same rows' bends with the rest held. The
held-out half (the odd rows) plays no part in any choice. Prints the chosen keys and, for both halves driven by
volume, the pressure's error and the bend's, and each held-out row's. Its output is docs/ACCURACY.md's "The pressure
alone". About three minutes.
"""
import numpy as np

import pneumatic_finger.core as pf
from accuracy_volume import JM, MU, GAP, ROOT, best_skin_share, errors, rows_of, summary, table

PRESSURE_KEYS = [MU, JM, "dead_volume_m3"]


def main():
    rows = rows_of("cylindrical")
    even, odd = rows[0::2], rows[1::2]
    config = str(ROOT / "config/marchese2015_cylindrical.yaml")
    base = {"wall_law": "thick", MU: 2e4, JM: 30.0, "dead_volume_m3": 8e-5}
    keys = best_skin_share(config, even, base, PRESSURE_KEYS, "gauge_pa",
                           lambda ratio, value: print(f"- r_V = {ratio:g}: objective on the fitted half {value:.4g}"))
    keys.update(pf.calibrate(table(even), [GAP], "minimax", config, keys, compare="tip_angle",
                             drive="volume", leave_one_out=False)["fitted"])
    model = pf.FingerModel(config, keys)
    print("- Marchese 2015 cylindrical segment, thick Gent wall bent by its inner face, keys fitted to the pressures "
          f"({len(even)} rows), then the gap to the bends: " +
          ", ".join(f"{k} = {keys[k]:.4g}" for k in PRESSURE_KEYS + ["chamber_growth_ratio", GAP]) +
          f" (face: {model.parameters['wall_flexion_face']})")
    for half, part in (("fitted half", even), ("held-out half", odd)):
        print(summary(f"{half}, driven by volume", *errors(model, part)))
    bend, rel = errors(model, odd)
    print("  - held-out rows (supplied volume: bend error, pressure error): " +
          "; ".join(f"{float(r['supplied_volume_m3']) * 1e6:.1f} mL: {b:+.1f} deg, {e:+.1f} %"
                    for r, b, e in zip(odd, bend, rel)))


if __name__ == "__main__":
    main()
