"""The cell arm's masses and inertias, computed from its shapes: urdf/industrial_arm.urdf's <inertial> elements.

usage: python3 scripts/arm_inertials.py [--check]

Every link of the arm with shapes gets, from its <visual> primitives (cylinders, boxes, spheres, each at its own
origin), the mass of those solids at one effective density, their common centre of mass, and their inertia tensor
about it (each solid's own tensor, turned into the link's frame, moved by the parallel-axis theorem, and summed). Each
link also gets a <collision> per visual, the same shape: simulators collide with those. The density stands for the
arm's hollow aluminium castings, motors and gearboxes together: DENSITY_KG_M3 = 1000 gives the arm 10 kg, about
what a 3 kg-payload arm of this reach weighs. With --check, exits 1 (naming the link) when the file's inertials differ
from the computed ones: a test runs it, so the numbers in the file stay computed, not typed.
"""
import argparse
import copy
import math
import pathlib
import sys
import xml.etree.ElementTree as ET

import numpy as np

ROOT = pathlib.Path(__file__).resolve().parent.parent
ARM = ROOT / "urdf/industrial_arm.urdf"
DENSITY_KG_M3 = 1000.0


def rotation(rpy):
    """URDF's fixed-axis roll, pitch, yaw: R = Rz(yaw) Ry(pitch) Rx(roll)."""
    r, p, y = rpy
    rx = np.array([[1, 0, 0], [0, math.cos(r), -math.sin(r)], [0, math.sin(r), math.cos(r)]])
    ry = np.array([[math.cos(p), 0, math.sin(p)], [0, 1, 0], [-math.sin(p), 0, math.cos(p)]])
    rz = np.array([[math.cos(y), -math.sin(y), 0], [math.sin(y), math.cos(y), 0], [0, 0, 1]])
    return rz @ ry @ rx


def solid(geometry):
    """Mass and inertia tensor about the solid's own centre, in its own frame, at DENSITY_KG_M3."""
    shape = geometry[0]
    if shape.tag == "cylinder":
        r, h = float(shape.get("radius")), float(shape.get("length"))
        m = DENSITY_KG_M3 * math.pi * r * r * h
        side = m * (3 * r * r + h * h) / 12
        return m, np.diag([side, side, m * r * r / 2])
    if shape.tag == "box":
        a, b, c = (float(v) for v in shape.get("size").split())
        m = DENSITY_KG_M3 * a * b * c
        return m, np.diag([m * (b * b + c * c) / 12, m * (a * a + c * c) / 12, m * (a * a + b * b) / 12])
    if shape.tag == "sphere":
        r = float(shape.get("radius"))
        m = DENSITY_KG_M3 * 4 / 3 * math.pi * r ** 3
        return m, np.eye(3) * (2 / 5 * m * r * r)
    raise SystemExit(f"arm_inertials: a <{shape.tag}> has no closed-form inertia here; use a primitive")


def origin_of(element):
    o = element.find("origin")
    xyz = [float(v) for v in (o.get("xyz", "0 0 0") if o is not None else "0 0 0").split()]
    rpy = [float(v) for v in (o.get("rpy", "0 0 0") if o is not None else "0 0 0").split()]
    return np.array(xyz), rotation(rpy)


def link_inertial(link):
    """The link's mass, centre of mass and inertia about it (link frame), from its visuals; None without any."""
    parts = []
    for visual in link.findall("visual"):
        position, turn = origin_of(visual)
        m, inertia = solid(visual.find("geometry"))
        parts.append((m, position, turn @ inertia @ turn.T))
    if not parts:
        return None
    mass = sum(m for m, _, _ in parts)
    com = sum(m * p for m, p, _ in parts) / mass
    total = np.zeros((3, 3))
    for m, p, inertia in parts:
        d = p - com
        total += inertia + m * (np.dot(d, d) * np.eye(3) - np.outer(d, d))
    return mass, com, total


def fmt(v):
    return f"{v:.6g}"


def inertial_element(mass, com, inertia):
    e = ET.Element("inertial")
    ET.SubElement(e, "origin", xyz=" ".join(fmt(v) for v in com), rpy="0 0 0")
    ET.SubElement(e, "mass", value=fmt(mass))
    names = {"ixx": (0, 0), "ixy": (0, 1), "ixz": (0, 2), "iyy": (1, 1), "iyz": (1, 2), "izz": (2, 2)}
    ET.SubElement(e, "inertia", {k: fmt(0.0 if abs(inertia[i]) < 1e-15 else inertia[i]) for k, i in names.items()})
    return e


def numbers(e):
    """An <inertial>'s numbers as written: origin, mass and the six inertia entries."""
    o, i = e.find("origin"), e.find("inertia")
    return (o.get("xyz"), o.get("rpy"), e.find("mass").get("value"),
            tuple(i.get(k) for k in ("ixx", "ixy", "ixz", "iyy", "iyz", "izz")))


def same(a, b):
    """Two <inertial> elements with the same numbers (to the 6 digits written)."""
    return numbers(a) == numbers(b)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--check", action="store_true", help="compare only; exit 1 when the file differs")
    args = parser.parse_args()
    tree = ET.parse(ARM, parser=ET.XMLParser(target=ET.TreeBuilder(insert_comments=True)))
    stale, total = [], 0.0
    for link in tree.getroot().findall("link"):
        computed = link_inertial(link)
        if computed is None:
            continue
        total += computed[0]
        want = inertial_element(*computed)
        have = link.find("inertial")
        if have is None or not same(have, want):
            stale.append(link.get("name"))
            if have is not None:
                link.remove(have)
            link.insert(0, want)
        for visual in link.findall("visual"):
            if link.find("collision") is None or len(link.findall("collision")) < len(link.findall("visual")):
                collision = ET.SubElement(link, "collision")
                for child in visual:
                    if child.tag in ("origin", "geometry"):
                        collision.append(copy.deepcopy(child))
                stale.append(link.get("name") + " (collision)")
    if args.check:
        if stale:
            sys.exit(f"arm_inertials: {ARM.name} differs from its shapes at {DENSITY_KG_M3:g} kg/m^3 for: "
                     f"{', '.join(stale)}; run python3 scripts/arm_inertials.py")
        print(f"arm_inertials: every link's inertial is its shapes' ({total:.2f} kg at {DENSITY_KG_M3:g} kg/m^3)")
        return
    # What comes before <robot> (the declaration and the file's own comment) is not in the tree: kept as it was.
    prologue = ARM.read_text().split("<robot", 1)[0]
    ET.indent(tree, space="  ")
    ARM.write_text(prologue + ET.tostring(tree.getroot(), encoding="unicode") + "\n")
    print(f"arm_inertials: wrote {ARM.relative_to(ROOT)}: {total:.2f} kg at {DENSITY_KG_M3:g} kg/m^3"
          + (f" (updated: {', '.join(stale)})" if stale else ""))



if __name__ == "__main__":
    main()
