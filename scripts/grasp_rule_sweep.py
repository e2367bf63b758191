#!/usr/bin/python3
"""Does the cell's grasp rule hold? Runs grasp_rule_sweep (the part's mass against the lift's acceleration, each case
in MuJoCo) and writes its table into docs/SIMULATION.md's measured block and its plot to docs/grasp_rule_sweep.png.

    /usr/bin/python3 scripts/grasp_rule_sweep.py [--plot PATH]      (about a minute; needs the build's grasp_rule_sweep)

Three rules are judged against the physics: the twin's bare claim (friction x the twin's normal forces >= m (g + a)),
the cell's rule before the sweep (>= 1.5 m g) and after it (>= 1.5 m (g + a)). A case counts as "away from the
threshold" when its mass is more than 25 % from the rule's threshold mass at that acceleration.
"""
import csv
import io
import os
import pathlib
import subprocess
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import page_support  # noqa: E402

ROOT = pathlib.Path(__file__).resolve().parent.parent
EXE = ROOT / "devel" / "lib" / "pneumatic_finger" / "grasp_rule_sweep"
PAGE = ROOT / "docs" / "SIMULATION.md"
COMMAND = "python3 scripts/grasp_rule_sweep.py"
G = 9.80665
# name, margin, with the lift's acceleration
RULES = [("twin, bare: μΣN ≥ m(g+a)", 1.0, True), ("cell before: μΣN ≥ 1.5 mg", 1.5, False),
         ("cell now: μΣN ≥ 1.5 m(g+a)", 1.5, True)]


def run_sweep():
    out = subprocess.run([str(EXE)], cwd=ROOT, check=True, capture_output=True, text=True)
    rows = list(csv.DictReader(io.StringIO(out.stdout)))
    for r in rows:
        for k in ("mass_kg", "peak_acceleration_mps2", "grasp_gauge_pa", "twin_normal_force_n", "mujoco_normal_force_n", "slip_m"):
            r[k] = float(r[k])
        r["carried"] = r["mujoco_carried"] == "1"
    return rows, out.stderr.strip()


def threshold_kg(row, margin, with_lift):
    return row["twin_normal_force_n"] / (margin * (G + (row["peak_acceleration_mps2"] if with_lift else 0.0)))


def judge(rows):
    """Per rule: the cases it disagrees on, and the largest distance of one from its threshold (share of it)."""
    verdicts = []
    for name, margin, with_lift in RULES:
        wrong = []
        for r in rows:
            t = threshold_kg(r, margin, with_lift)
            if (r["mass_kg"] <= t) != r["carried"]:
                wrong.append(abs(r["mass_kg"] - t) / t)
        verdicts.append((name, len(wrong), max(wrong, default=0.0)))
    return verdicts


def table(rows, lift_note):
    accelerations = sorted({r["peak_acceleration_mps2"] for r in rows})
    masses = sorted({r["mass_kg"] for r in rows})
    by = {(r["mass_kg"], r["peak_acceleration_mps2"]): r for r in rows}
    lines = [lift_note, f"grasp at {rows[0]['grasp_gauge_pa']:.0f} Pa; the twin's normal force, all fingers: "
             f"{rows[0]['twin_normal_force_n']:.4f} N", "",
             "physics: C carried, s slipped; * where the cell's rule now (1.5 m(g+a)) says otherwise",
             "mass g  | " + " | ".join(f"{a:6.3g}" for a in accelerations) + "  (peak lift acceleration, m/s^2)"]
    for m in masses:
        cells = []
        for a in accelerations:
            r = by[(m, a)]
            rule = m <= threshold_kg(r, 1.5, True)
            cells.append(f"{'C' if r['carried'] else 's':>5}{'*' if rule != r['carried'] else ' '}")
        lines.append(f"{1e3 * m:7.4g} | " + " | ".join(cells))
    lines += ["", "rule                          cases wrong   farthest wrong case from its threshold"]
    for name, wrong, farthest in judge(rows):
        lines.append(f"{name:30s}{wrong:3d}/{len(rows):<3d}     {100 * farthest:5.1f} %")
    held = [r for r in rows if r["carried"] and r["peak_acceleration_mps2"] == accelerations[0]]
    lines += ["", "MuJoCo's normal force, all fingers, hanging before the lift (N), by mass: " +
              ", ".join(f"{1e3 * r['mass_kg']:g} g {r['mujoco_normal_force_n']:.4f}" for r in held)]
    return "\n".join(lines)


def plot(rows, path):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(figsize=(10, 5))
    for carried, marker, color, label in ((True, "o", "tab:green", "MuJoCo: carried"),
                                          (False, "x", "tab:red", "MuJoCo: slipped")):
        pts = [r for r in rows if r["carried"] == carried]
        ax.scatter([r["peak_acceleration_mps2"] for r in pts], [1e3 * r["mass_kg"] for r in pts], marker=marker,
                   color=color, label=label, zorder=3)
    a = sorted({r["peak_acceleration_mps2"] for r in rows})
    ref = rows[0]
    for (name, margin, with_lift), style in zip(RULES, ("--", ":", "-")):
        t = [1e3 * threshold_kg(dict(ref, peak_acceleration_mps2=x), margin, with_lift) for x in a]
        ax.plot(a, t, style, color="black", label=f"threshold, {name}")
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("the lift's peak acceleration (m/s²)")
    ax.set_ylabel("the part's mass (g)")
    ax.set_title("Does the grasp hold? The cell's rule against MuJoCo")
    ax.grid(alpha=0.3, which="both")
    ax.legend(fontsize=8, loc="center left", bbox_to_anchor=(1.01, 0.5))
    page_support.save(fig, path)


def main():
    args = page_support.plot_arguments(__doc__, ROOT / "docs" / "grasp_rule_sweep.png")
    rows, lift_note = run_sweep()
    text = table(rows, lift_note.replace("grasp_rule_sweep: ", ""))
    subprocess.run([sys.executable, str(ROOT / "scripts" / "measured_block.py"), str(PAGE), COMMAND], input=text,
                   text=True, check=True)
    plot(rows, args.plot)
    print(text)
    print(f"wrote {args.plot}")


if __name__ == "__main__":
    sys.exit(main())
