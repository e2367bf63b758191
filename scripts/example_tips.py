"""Writes data/example_tip_positions.csv: the tip positions a camera would see of the paper's finger (Table 1), for
docs/CALIBRATE.md's walkthrough.

Each row is the tip of the measured joints of data/sierra2022_table1.csv laid along the model's segments (eq 38, the
core's own backbone, as finger_calibrate reports a measured tip): real measurements, in the form a photo gives.
Usage: /usr/bin/python3 scripts/example_tips.py [--check]
"""
import pathlib
import sys

import pneumatic_finger.core as pf

ROOT = pathlib.Path(__file__).resolve().parent.parent
OUT = ROOT / "data" / "example_tip_positions.csv"


def text():
    r = pf.calibrate()["residuals"]
    lines = ["# The tip of the paper's finger in its own frame (m: x along the straight finger from the mount, y toward",
             "# the strain-limited side), at each pressure of Table 1 (Sierra & Ordonez-Avila 2022): the measured joints",
             "# laid along the model's segments. Written by scripts/example_tips.py; docs/CALIBRATE.md uses it.",
             "gauge_pa,tip_x_m,tip_y_m"]
    for p, (x, y) in zip(r["gauge_pa"], r["measured_tip_m"]):
        lines.append("%r,%.5f,%.5f" % (float(p), x, y))  # 10 um: a camera's resolution, not the double's
    return "\n".join(lines) + "\n"


if __name__ == "__main__":
    if "--check" in sys.argv:
        sys.exit(0 if OUT.read_text() == text() else 1)
    OUT.write_text(text())
