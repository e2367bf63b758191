#!/usr/bin/env python3
"""An independent reference for a drawn chamber: one cell of a row of cavities, by finite elements (CalculiX).

The closed-form wall laws read a chamber as a sphere (docs/MODEL.md). A drawn cavity is a box, and in a row its
neighbours press back on the walls between. This script asks a finite-element solver what such a row does, with no
reading of the shape: one half pitch of the row, from the middle of a cavity to the middle of the wall after it,
half the width, a neo-Hookean elastomer, under a pressure ramp.

  - x along the finger, y across, z up from the strain-limiting layer (mm, N, MPa inside the solver);
  - the plane x = 0 halves the cavity: a mirror (u_x = 0);
  - the plane y = 0 halves the width: a mirror (u_y = 0);
  - the face z = 0 is the strain-limiting layer: it neither lengthens nor narrows (u_x = u_y = 0), and it curves
    freely (u_z free, but for the line under the cavity's middle);
  - the plane x = X halves the wall between cavities. The next cell is this one mirrored, so that plane stays a
    plane: a rigid body that turns about its bottom edge, which may rise or fall with the layer. Its rotation is
    half the chamber's bend.

The rigid plane also keeps its own shape, a mild stiffening: the section through the middle of a wall carries no net
force or moment (the cavities on either side are closed), so it is barely strained.

The ramp runs to --top-kpa or until the solver stops converging. A limit point would stop it, and so does a mesh
too distorted at the cavity's edges; a stop where the bend's slope is still finite is not a limit point. So this
reference says where the solid has no snap (below its stop), not what a snap does. The bricks integrate fully by
default: the reduced ones (--element reduced) stall near P / mu = 0.9, where the full ones go on smoothly. The
geometry and the material enter only as the drawing and P / mu (neo-Hookean: the bends at pressure P and modulus mu
are those at P k and mu k).

Needs `apt-get install calculix-ccx` (not a build or test dependency; its tests, test/test_fem_cell.py, need none).

  python3 scripts/fem_cell.py --config config/epfl_ecoflex30_c7_coupon.yaml [--size 1] [--top-kpa 30] > table.csv
"""
import argparse
import math
import os
import re
import subprocess
import sys
import tempfile
import time

import yaml


# the 20-node bricks: full integration (27 points), or reduced (8 points), which bends 1.3 to 1.8 % more on this cell
# but stalls near P / mu = 0.9, where the full one goes on smoothly: that stall is the reduced brick's, not the solid's
ELEMENTS = {"full": "C3D20", "reduced": "C3D20R"}
# the drawing's keys this cell meshes (docs/DRAWING.md); chamber_count only scales the finger's bend
DRAWING_KEYS = ("chamber_count", "cavity_height_m", "cavity_width_m", "cavity_length_m", "wall_thickness_m",
                "roof_thickness_m", "body_width_m")


def axis(cuts, size):
    """Grid lines through every cut, no farther apart than size."""
    lines = [cuts[0]]
    for a, b in zip(cuts, cuts[1:]):
        n = max(1, math.ceil((b - a) / size - 1e-9))
        lines += [a + (b - a) * (i + 1) / n for i in range(n - 1)] + [b]  # each cut exactly
    return lines


class Cell:
    """The half-pitch cell of a drawing, meshed in hexahedra (mm)."""

    def __init__(self, drawing, size):
        mm = 1000.0
        self.cav_x = drawing["cavity_length_m"] * mm / 2
        self.cav_y = drawing["cavity_width_m"] * mm / 2
        floor = drawing.get("floor_height_m", 0.0) * mm
        if floor != 0.0:
            sys.exit("fem_cell: only a cavity floor on the strain-limiting layer (floor_height_m 0) is meshed")
        self.cav_z = drawing["cavity_height_m"] * mm
        wall = drawing["wall_thickness_m"] * mm
        if drawing.get("gap_m", 0.0) != 0.0:
            sys.exit("fem_cell: a split wall (gap_m) is not meshed")
        roof = drawing.get("roof_thickness_m", drawing["wall_thickness_m"]) * mm
        width = drawing.get("body_width_m", drawing["cavity_width_m"] + 2 * drawing["wall_thickness_m"]) * mm
        self.X = self.cav_x + wall / 2
        self.Y = width / 2
        self.Z = self.cav_z + roof
        self.xs = axis([0.0, self.cav_x, self.X], size / 2)
        self.ys = axis([0.0, self.cav_y, self.Y], size)
        self.zs = axis([0.0, self.cav_z, self.Z], size)

    def grid(self):
        """The node grid's lines: the cells' corners, and their edges' middles for 20-node elements."""
        def refine(lines):
            out = [lines[0]]
            for a, b in zip(lines, lines[1:]):
                out += [(a + b) / 2, b]
            return out
        return [refine(v) for v in (self.xs, self.ys, self.zs)]

    def node(self, i, j, k):
        """The node at (i, j, k) of the node grid (two steps per cell)."""
        nx, ny = 2 * len(self.xs) - 1, 2 * len(self.ys) - 1
        return 1 + i + nx * (j + ny * k)

    def apex(self):
        """The node at the middle of the cavity's roof."""
        return self.node(0, 0, 2 * self.zs.index(self.cav_z))

    def in_cavity(self, i, j, k):
        """Whether the grid cell (i, j, k) lies in the cavity."""
        return (self.xs[i + 1] <= self.cav_x + 1e-9 and self.ys[j + 1] <= self.cav_y + 1e-9
                and self.zs[k + 1] <= self.cav_z + 1e-9)

    def elements(self):
        """(id, (i, j, k), node ids) of every solid cell: a 20-node brick in CalculiX's order."""
        corners = [(0, 0, 0), (2, 0, 0), (2, 2, 0), (0, 2, 0), (0, 0, 2), (2, 0, 2), (2, 2, 2), (0, 2, 2)]
        middles = [(1, 0, 0), (2, 1, 0), (1, 2, 0), (0, 1, 0), (1, 0, 2), (2, 1, 2), (1, 2, 2), (0, 1, 2),
                   (0, 0, 1), (2, 0, 1), (2, 2, 1), (0, 2, 1)]
        out, eid = [], 0
        for k in range(len(self.zs) - 1):
            for j in range(len(self.ys) - 1):
                for i in range(len(self.xs) - 1):
                    if self.in_cavity(i, j, k):
                        continue
                    eid += 1
                    out.append((eid, (i, j, k), [self.node(2 * i + a, 2 * j + b, 2 * k + c)
                                                  for a, b, c in corners + middles]))
        return out

    def pressure_faces(self, elements):
        """(element, face) pairs that bound the cavity; a face is named by its corners: 6 is x-, 3 is y-, 1 is z-."""
        faces = []
        for eid, (i, j, k), _ in elements:
            if i > 0 and self.in_cavity(i - 1, j, k):
                faces.append((eid, 6))
            if j > 0 and self.in_cavity(i, j - 1, k):
                faces.append((eid, 3))
            if k > 0 and self.in_cavity(i, j, k - 1):
                faces.append((eid, 1))
        return faces


def write_sets(f, cell, coords, used):
    """The node sets the boundary conditions name (see the module's comment)."""
    def nset(name, pick):
        members = [n for n in used if pick(*coords[n])]
        f.write("*NSET,NSET=%s\n" % name)
        for c in range(0, len(members), 12):
            f.write(",".join(map(str, members[c:c + 12])) + "\n")
    eps = 1e-9
    wall = lambda x: abs(x - cell.X) < eps  # the rigid plane holds its own nodes
    nset("MIDCAVITY", lambda x, y, z: abs(x) < eps)
    nset("MIDWIDTH", lambda x, y, z: abs(y) < eps and not wall(x))
    nset("LAYER", lambda x, y, z: abs(z) < eps and not wall(x))
    nset("LAYERMID", lambda x, y, z: abs(z) < eps and abs(x) < eps)
    nset("MIDWALL", lambda x, y, z: wall(x))


def write_input(cell, shear_pa, bulk_ratio, top_pa, step_pa, path, element=ELEMENTS["full"]):
    """CalculiX's input for the cell under a pressure ramp to top_pa in increments of at most step_pa, in 20-node
    bricks of the given type (ELEMENTS); returns the element count."""
    elements = cell.elements()
    used = sorted({n for _, _, ns in elements for n in ns})
    gx, gy, gz = cell.grid()
    coords = {cell.node(i, j, k): (x, y, z)
              for k, z in enumerate(gz) for j, y in enumerate(gy) for i, x in enumerate(gx)}
    ref, rot = len(coords) + 1, len(coords) + 2  # the rigid plane's reference and rotation nodes
    mu = shear_pa * 1e-6
    with open(path, "w") as f:
        f.write("*NODE\n")
        for n in used:
            f.write("%d,%.9g,%.9g,%.9g\n" % ((n,) + coords[n]))
        f.write("%d,%.9g,0,0\n%d,%.9g,0,0\n" % (ref, cell.X, rot, cell.X))
        f.write("*ELEMENT,TYPE=%s,ELSET=BODY\n" % element)
        for eid, _, ns in elements:  # at most 16 entries a line
            f.write("%d,%s,\n%s\n" % (eid, ",".join(map(str, ns[:15])), ",".join(map(str, ns[15:]))))
        write_sets(f, cell, coords, used)
        f.write("*NSET,NSET=ROTNODE\n%d\n*NSET,NSET=APEX\n%d\n" % (rot, cell.apex()))
        f.write("*MATERIAL,NAME=ELASTOMER\n*HYPERELASTIC,NEO HOOKE\n%.9g,%.9g\n" % (mu / 2, 2.0 / (bulk_ratio * mu)))
        f.write("*SOLID SECTION,ELSET=BODY,MATERIAL=ELASTOMER\n")
        f.write("*RIGID BODY,NSET=MIDWALL,REF NODE=%d,ROT NODE=%d\n" % (ref, rot))
        f.write("*BOUNDARY\nMIDCAVITY,1,1\nMIDWIDTH,2,2\nLAYER,1,2\nLAYERMID,3,3\n")
        f.write("%d,1,2\n%d,1,1\n%d,3,3\n" % (ref, rot, rot))  # the plane turns about y alone
        # the pressure follows the deformed faces; the solver halves an increment that does not converge
        f.write("*STEP,NLGEOM,INC=2000\n*STATIC\n%.9g,1.0,1e-6,%.9g\n*DLOAD\n" % (step_pa / top_pa, step_pa / top_pa))
        for eid, face in cell.pressure_faces(elements):
            f.write("%d,P%d,%.9g\n" % (eid, face, top_pa * 1e-6))
        f.write("*NODE PRINT,NSET=ROTNODE\nU\n*NODE PRINT,NSET=APEX\nU\n*END STEP\n")
    return len(elements)


def read_table(dat_path):
    """(load fraction, the rotation node's rotation about y in rad, the roof's rise in mm) of every converged
    increment. The solver prints the rotation node's rotations as its "displacements"."""
    rows, time, which = [], None, None
    for line in open(dat_path):
        m = re.search(r"displacements.*set (\w+).*time\s+([0-9.Ee+-]+)", line)
        if m:
            which, time = m.group(1), float(m.group(2))
            continue
        parts = line.split()
        if which is None or len(parts) != 4:
            continue
        if which == "ROTNODE":
            rows.append([time, float(parts[2]), math.nan])
        elif rows and rows[-1][0] == time:
            rows[-1][2] = float(parts[3])
        which = None
    return [tuple(r) for r in rows]


def header(args, cell, count, params, seconds, rows):
    """The comment lines that say where the table comes from, as the data files' do."""
    ended = rows[-1][0] * args.top_kpa if rows else 0.0
    stop = ("the solver stopped converging at %.3g kPa (at a limit point, or where the mesh\n# is too distorted:"
            " fem_cell.py says how to tell)" % ended if ended < args.top_kpa * (1 - 1e-9) else "it reached its end")
    return "\n".join([
        "# Written by: python3 scripts/fem_cell.py %s" % " ".join(command_arguments(sys.argv[1:])),
        "# One half-pitch cell of the drawing's row of cavities by finite elements (CalculiX %s, %d 20-node bricks %s,"
        % (ccx_version(), count, ELEMENTS[args.element]),
        "# cell %.3g x %.3g x %.3g mm), neo-Hookean, mu %.6g Pa, bulk/shear %g; %.0f s on %s." % (
            cell.X, cell.Y, cell.Z, params["shear_modulus_pa"], args.bulk_ratio, seconds, machine()),
        "# The pressure ramp: %s." % stop,
        "# bend_angle_rad is the finger's, chamber_count times the chamber's; roof_rise_m, the cavity roof's middle."])


def command_arguments(argv):
    """The command's arguments less --keep DIR, which changes where the solver's files go, not the table."""
    out, skip = [], False
    for arg in argv:
        if skip or arg == "--keep" or arg.startswith("--keep="):
            skip = arg == "--keep"
            continue
        out.append(arg)
    return out


def ccx_version():
    out = subprocess.run(["ccx", "-v"], capture_output=True, text=True).stdout
    m = re.search(r"Version\s+(\S+)", out)
    return m.group(1) if m else "?"


def machine():
    cpu = next((line.split(":", 1)[1].strip() for line in open("/proc/cpuinfo") if line.startswith("model name")), "?")
    return "%d x %s" % (os.cpu_count() or 1, cpu)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--config", required=True, help="a parameter file with a drawing: section and the material")
    ap.add_argument("--size", type=float, default=1.0, help="element size, mm (along the finger, half of it)")
    ap.add_argument("--bulk-ratio", type=float, default=100.0, help="bulk over shear modulus (near incompressible)")
    ap.add_argument("--top-kpa", type=float, default=30.0, help="the ramp's end, kPa")
    ap.add_argument("--step-kpa", type=float, default=0.6, help="the ramp's largest increment, kPa")
    ap.add_argument("--element", choices=sorted(ELEMENTS), default="full",
                    help="the bricks' integration (full: C3D20; reduced: C3D20R, which stalls sooner)")
    ap.add_argument("--set", action="append", default=[], metavar="drawing/KEY=VALUE",
                    help="change a key of the drawing, as finger_model --set does (m)")
    ap.add_argument("--keep", help="a directory to keep the solver's files in")
    args = ap.parse_args()
    with open(args.config) as f:
        params = yaml.safe_load(f)
    if "drawing" not in params:
        sys.exit("fem_cell: %s has no drawing: section" % args.config)
    for item in args.set:
        key, _, value = item.partition("=")
        if not key.startswith("drawing/") or key[8:] not in DRAWING_KEYS or not value:
            sys.exit("fem_cell: --set %s: expected drawing/KEY=VALUE with KEY one of %s"
                     % (item, ", ".join(DRAWING_KEYS)))
        params["drawing"][key[8:]] = float(value)
    cell = Cell(params["drawing"], args.size)
    work = args.keep or tempfile.mkdtemp(prefix="fem_cell_")
    os.makedirs(work, exist_ok=True)
    count = write_input(cell, params["shear_modulus_pa"], args.bulk_ratio, args.top_kpa * 1e3,
                        args.step_kpa * 1e3, os.path.join(work, "cell.inp"), ELEMENTS[args.element])
    start = time.monotonic()
    with open(os.path.join(work, "ccx.log"), "w") as log:
        threads = str(os.cpu_count() or 1)
        subprocess.run(["ccx", "-i", "cell"], cwd=work, stdout=log, env=dict(os.environ, OMP_NUM_THREADS=threads))
    rows = sorted(dict((t, (t, r, rise)) for t, r, rise in read_table(os.path.join(work, "cell.dat"))).values())
    print(header(args, cell, count, params, time.monotonic() - start, rows))
    print("gauge_pa,bend_angle_rad,chamber_bend_rad,roof_rise_m")
    for t, r, rise in [(0.0, 0.0, 0.0)] + rows:
        chamber = 2 * abs(r)  # the cell is half a chamber
        print("%.6g,%.6g,%.6g,%.6g" % (t * args.top_kpa * 1e3, params["drawing"]["chamber_count"] * chamber, chamber,
                                       rise * 1e-3))


if __name__ == "__main__":
    main()
