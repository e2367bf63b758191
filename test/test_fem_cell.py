"""scripts/fem_cell.py's mesh, against the drawing's own arithmetic (no solver needed): the cell's volume, the
cavity's faces, and CalculiX's node order for a 20-node brick."""
import os
import sys

import pytest

sys.path.insert(0, os.path.join(os.path.dirname(__file__), "..", "scripts"))
import fem_cell  # noqa: E402

DRAWING = dict(chamber_count=7, cavity_height_m=0.008, cavity_width_m=0.008, cavity_length_m=0.002,
               wall_thickness_m=0.007)
# CalculiX's C3D20: corners 1-8 as C3D8, then the middles of the edges 1-2, 2-3, 3-4, 4-1, 5-6, 6-7, 7-8, 8-5,
# 1-5, 2-6, 3-7, 4-8; its faces by their corners: 1 = (1,2,3,4), 3 = (1,2,6,5), 6 = (1,5,8,4).
EDGES = [(1, 2), (2, 3), (3, 4), (4, 1), (5, 6), (6, 7), (7, 8), (8, 5), (1, 5), (2, 6), (3, 7), (4, 8)]
FACES = {1: (1, 2, 3, 4), 3: (1, 2, 6, 5), 6: (1, 5, 8, 4)}


@pytest.fixture(scope="module")
def mesh():
    cell = fem_cell.Cell(DRAWING, 1.0)
    gx, gy, gz = cell.grid()
    coords = {cell.node(i, j, k): (x, y, z)
              for k, z in enumerate(gz) for j, y in enumerate(gy) for i, x in enumerate(gx)}
    return cell, cell.elements(), coords


def box(coords, nodes):
    pts = [coords[n] for n in nodes[:8]]
    return [(min(p[a] for p in pts), max(p[a] for p in pts)) for a in range(3)]


def test_the_cell_is_half_a_pitch_of_the_body_less_a_quarter_of_the_cavity(mesh):
    cell, elements, coords = mesh
    volume = 0.0
    for _, _, nodes in elements:
        (x0, x1), (y0, y1), (z0, z1) = box(coords, nodes)
        volume += (x1 - x0) * (y1 - y0) * (z1 - z0)
    # half the 2 mm cavity and half the 7 mm wall; half the 8 + 2 x 7 mm body; the 8 mm cavity and the 7 mm roof
    assert (cell.X, cell.Y, cell.Z) == pytest.approx((4.5, 11.0, 15.0), abs=1e-12)
    assert volume == pytest.approx(4.5 * 11 * 15 - 1 * 4 * 8, rel=1e-12)


def test_the_pressure_lies_on_the_cavitys_three_walls(mesh):
    cell, elements, coords = mesh
    nodes_of = {eid: nodes for eid, _, nodes in elements}
    area = {1: 0.0, 3: 0.0, 6: 0.0}
    for eid, face in cell.pressure_faces(elements):
        pts = [coords[nodes_of[eid][c - 1]] for c in FACES[face]]
        normal_axis = {6: 0, 3: 1, 1: 2}[face]
        plane = {0: 1.0, 1: 4.0, 2: 8.0}[normal_axis]  # the cavity's quarter: x < 1, y < 4, z < 8 mm
        assert all(p[normal_axis] == pytest.approx(plane, abs=1e-12) for p in pts)
        a, b = [ax for ax in range(3) if ax != normal_axis]
        span = lambda ax: max(p[ax] for p in pts) - min(p[ax] for p in pts)
        area[face] += span(a) * span(b)
    assert area[6] == pytest.approx(4 * 8, rel=1e-12)  # the face of the wall between cavities
    assert area[3] == pytest.approx(1 * 8, rel=1e-12)  # the side wall
    assert area[1] == pytest.approx(1 * 4, rel=1e-12)  # the roof


def test_every_brick_has_calculix_node_order(mesh):
    _, elements, coords = mesh
    for _, _, nodes in elements:
        p = [coords[n] for n in nodes]
        (x0, x1), (y0, y1), (z0, z1) = box(coords, nodes)
        corners = [(x0, y0, z0), (x1, y0, z0), (x1, y1, z0), (x0, y1, z0),
                   (x0, y0, z1), (x1, y0, z1), (x1, y1, z1), (x0, y1, z1)]
        assert p[:8] == pytest.approx(corners, abs=1e-12)
        for m, (a, b) in enumerate(EDGES):
            assert p[8 + m] == pytest.approx(tuple((u + v) / 2 for u, v in zip(p[a - 1], p[b - 1])), abs=1e-12)


def test_a_drawing_it_cannot_mesh_is_refused_by_name():
    with pytest.raises(SystemExit, match="floor_height_m"):
        fem_cell.Cell(dict(DRAWING, floor_height_m=0.001), 1.0)
    with pytest.raises(SystemExit, match="gap_m"):
        fem_cell.Cell(dict(DRAWING, gap_m=0.001), 1.0)


def test_the_rotation_and_the_roofs_rise_are_read_from_the_solvers_table(tmp_path):
    dat = tmp_path / "cell.dat"
    dat.write_text(" displacements (vx,vy,vz) for set ROTNODE and time  0.5000000E+00\n\n"
                   "      1922  0.000000E+00  3.109327E-03  0.000000E+00\n\n"
                   " displacements (vx,vy,vz) for set APEX and time  0.5000000E+00\n\n"
                   "       693  0.000000E+00  0.000000E+00  4.843619E-02\n\n"
                   " displacements (vx,vy,vz) for set ROTNODE and time  0.1000000E+01\n\n"
                   "      1922  0.000000E+00 -6.2E-03  0.000000E+00\n\n"
                   " displacements (vx,vy,vz) for set APEX and time  0.1000000E+01\n\n"
                   "       693  0.000000E+00  0.000000E+00  1.5E-01\n")
    assert fem_cell.read_table(str(dat)) == [(0.5, 3.109327e-03, 4.843619e-02), (1.0, -6.2e-03, 0.15)]


def test_the_apex_is_the_middle_of_the_roof(mesh):
    cell, _, coords = mesh
    assert coords[cell.apex()] == pytest.approx((0.0, 0.0, 8.0), abs=1e-12)


def test_a_change_it_cannot_make_is_refused_by_name(monkeypatch):
    config = os.path.join(os.path.dirname(__file__), "..", "config", "epfl_ecoflex30_c7_coupon.yaml")
    for bad in ("wall_thickness_m=0.003", "drawing/floor=1", "drawing/wall_thickness_m="):
        monkeypatch.setattr(sys, "argv", ["fem_cell.py", "--config", config, "--set", bad])
        with pytest.raises(SystemExit, match="expected drawing/KEY=VALUE with KEY one of chamber_count"):
            fem_cell.main()


@pytest.mark.parametrize("integration, element", [("full", "C3D20"), ("reduced", "C3D20R")])
def test_the_input_names_the_bricks_integration_and_lists_each_brick_once(tmp_path, mesh, integration, element):
    cell, elements, _ = mesh
    path = tmp_path / "cell.inp"
    count = fem_cell.write_input(cell, 20.8e3, 100.0, 30e3, 600.0, str(path), fem_cell.ELEMENTS[integration])
    text = path.read_text()
    assert count == len(elements)
    assert text.count("*ELEMENT,TYPE=%s,ELSET=BODY\n" % element) == 1
    assert text.count("*ELEMENT") == 1
    body = text.split("*ELEMENT,TYPE=%s,ELSET=BODY\n" % element)[1].split("*")[0].splitlines()
    assert [int(line.split(",")[0]) for line in body[::2]] == [eid for eid, _, _ in elements]


def test_the_tables_command_leaves_out_where_the_solvers_files_went():
    argv = ["--config", "c.yaml", "--keep", "/tmp/k", "--top-kpa", "40", "--keep=/tmp/j", "--size", "1"]
    assert fem_cell.command_arguments(argv) == ["--config", "c.yaml", "--top-kpa", "40", "--size", "1"]
