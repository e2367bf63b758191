"""A newcomer's first hour: what a new user met, each as it failed before its fix, through the CLI and Python alike.

Run by `make run_tests` (CMakeLists.txt passes the package's executables in PNEUMATIC_FINGER_BIN).
"""
import csv
import io
import os
import pathlib
import subprocess

import numpy
import pytest

import pneumatic_finger.core as pf

BIN = pathlib.Path(os.environ.get("PNEUMATIC_FINGER_BIN", "devel/lib/pneumatic_finger"))
PRESSURES = [50000.0, 100000.0, 150000.0, 200000.0]
TRUTH = {"shear_modulus_pa": 3.7e8, "chamber_gap_m": 8.5e-5}


def tool(name, *args):
    return subprocess.run([str(BIN / name), *args], capture_output=True, text=True)


@pytest.fixture
def tips_csv(tmp_path):
    # What a camera gives: the tip at four pressures, here from finger_model at known parameters.
    rows = ["gauge_pa,tip_x_m,tip_y_m"]
    for p in PRESSURES:
        out = tool("finger_model", "--gauge-pa", repr(p), "--set", "shear_modulus_pa=3.7e8",
                   "--set", "chamber_gap_m=8.5e-5")
        assert out.returncode == 0, out.stderr
        row = next(csv.DictReader(io.StringIO(out.stdout)))
        rows.append(",".join([row["gauge_pa"], row["tip_x_m"], row["tip_y_m"]]))
    path = tmp_path / "tips.csv"
    path.write_text("\n".join(rows) + "\n")
    return path


def test_tip_positions_calibrate_in_the_cli_as_in_python(tips_csv, tmp_path):
    out_file = tmp_path / "calibrated.yaml"
    done = tool("finger_calibrate", "--data", str(tips_csv), "--output", str(out_file))
    assert done.returncode == 0, done.stderr
    line = done.stdout.split("# fitted: ")[1].splitlines()[0].split()
    fitted = {line[i]: float(line[i + 2]) for i in range(0, len(line), 3)}
    python = pf.calibrate(data=str(tips_csv))["fitted"]
    assert fitted == python
    assert fitted["shear_modulus_pa"] == pytest.approx(3.7e8, rel=1e-6)
    # The written file loads, with the tip position's bar and no angle's.
    model = pf.FingerModel(config=str(out_file))
    assert model.parameters["chamber_gap_m"] == pytest.approx(8.5e-5, rel=1e-6)
    assert "tip_angle_rad: [.nan, .nan, .nan, .nan]" in out_file.read_text()


def test_the_written_file_claims_only_what_it_is(tips_csv, tmp_path):
    out_file = tmp_path / "calibrated.yaml"
    assert tool("finger_calibrate", "--data", str(tips_csv), "--output", str(out_file)).returncode == 0
    text = out_file.read_text()
    assert "parameters.cpp" not in text and "a test checks it" not in text
    assert "the paper's own model" not in text  # its error belongs to the paper's data only
    # The report in the data's units: Pa and rad (m), not kg/cm2 and degrees.
    assert "kg/cm" not in text and "pressure_kgcm2" not in text
    assert "#   gauge_pa" in text and "tip_m" in text


@pytest.mark.parametrize("interface", ["cli", "python"])
def test_degrees_in_a_radian_column_are_refused(tmp_path, interface):
    path = tmp_path / "deg.csv"
    path.write_text("gauge_pa,tip_angle_rad\n50000,16\n100000,33\n150000,51\n200000,69\n")
    words = "tip_angle_rad = 16 rad is beyond 2 pi (a full turn), more than this finger can bend; were the angles in degrees?"
    if interface == "cli":
        done = tool("finger_calibrate", "--data", str(path))
        assert done.returncode == 2 and words in done.stderr, done.stderr
        assert done.stdout == ""
    else:
        with pytest.raises(ValueError, match="were the angles in degrees"):
            pf.calibrate(data=str(path))
        with pytest.raises(ValueError, match="were the angles in degrees"):
            pf.calibrate(data={"gauge_pa": PRESSURES, "tip_angle_rad": [16, 33, 51, 69]})


def test_an_unknown_column_is_named(tips_csv, tmp_path):
    path = tmp_path / "mm.csv"
    path.write_text(tips_csv.read_text().replace("tip_x_m,tip_y_m", "tip_x_mm,tip_y_mm"))
    done = tool("finger_calibrate", "--data", str(path))
    assert done.returncode == 2
    assert "column 'tip_x_mm' is not read: did you mean 'tip_x_m'?" in done.stderr, done.stderr
    extra = tmp_path / "extra.csv"
    lines = tips_csv.read_text().splitlines()
    extra.write_text("\n".join([lines[0] + ",tip_x_mm"] + [l + ",1" for l in lines[1:]]) + "\n")
    done = tool("finger_calibrate", "--data", str(extra))
    assert done.returncode == 0
    assert "# warning: column 'tip_x_mm' is not read: did you mean 'tip_x_m'?" in done.stdout
    assert any("tip_x_mm" in w for w in pf.calibrate(data=str(extra))["warnings"])


def test_calibrate_takes_columns_and_answers_in_arrays(tips_csv):
    table = numpy.loadtxt(tips_csv, delimiter=",", skiprows=1)
    from_file = pf.calibrate(data=str(tips_csv), keys="shear_modulus_pa")
    from_dict = pf.calibrate(data={"gauge_pa": table[:, 0], "tip_x_m": table[:, 1], "tip_y_m": table[:, 2]},
                             keys="shear_modulus_pa")
    assert list(from_file["fitted"]) == ["shear_modulus_pa"]
    assert from_dict["fitted"] == from_file["fitted"]
    r = from_dict["residuals"]
    assert isinstance(r["gauge_pa"], numpy.ndarray) and r["gauge_pa"].tolist() == PRESSURES
    assert r["model_tip_m"].shape == (4, 2) and r["model_joint_rad"].shape == (4, 7)
    assert numpy.isnan(r["measured_joint_rad"]).all()  # not measured
    assert from_dict["correlation"].shape == (1, 1)
    with pytest.raises(ValueError, match="data must be a CSV path or a mapping"):
        pf.calibrate(data=[1, 2, 3])


def test_wall_law_auto_takes_a_wall_only_the_membrane_law_allows(tmp_path):
    # A wall taller than its chamber, five tip angles: refused before, because the paper law was checked first.
    path = tmp_path / "bend.csv"
    path.write_text("gauge_pa,tip_angle_rad\n" + "".join("%g,%g\n" % (p, a) for p, a in
                                                         [(2e4, 0.05), (4e4, 0.12), (6e4, 0.2), (8e4, 0.3),
                                                          (1e5, 0.42), (1.2e5, 0.55)]))
    done = tool("finger_calibrate", "--data", str(path), "--wall-law", "auto", "--fit",
                "shear_modulus_pa,chamber_gap_m", "--set", "wall_critical_height_m=0.02")
    assert done.returncode == 0, done.stderr
    assert "it starts from its uniform wall, b = L/2" in done.stdout
    fit = pf.calibrate(data=str(path), wall_law="auto", keys=["shear_modulus_pa", "chamber_gap_m"],
                       overrides={"wall_critical_height_m": 0.02})
    assert fit["wall_law"] in ("paper", "membrane") and fit["leave_one_out"] is not None
    refused = tool("finger_calibrate", "--data", str(path), "--wall-law", "paper", "--set",
                   "wall_critical_height_m=0.02")
    assert refused.returncode == 2 and "wall_critical_height_m" in refused.stderr


CLAMP_WORDS = "gauge pressure 4900000 Pa is above max_gauge_pa 294199.5 Pa, the top of the model's range: clamped to it"


def test_one_pressure_above_the_range_gets_one_answer_everywhere():
    # The CLI: the row at the top of the range, with the core's words (finger_node says them too: test_pressure_range).
    above = tool("finger_model", "--gauge-pa", "4.9e6")
    top = tool("finger_model", "--gauge-pa", "294199.5")
    assert above.returncode == 0 and CLAMP_WORDS in above.stderr, above.stderr
    assert above.stdout == top.stdout
    # Python: the same state, the status the node publishes as STATUS_CLAMPED, and the same words.
    model = pf.FingerModel()
    with pytest.warns(RuntimeWarning, match=CLAMP_WORDS.replace("(", r"\(").replace(")", r"\)")):
        state = model.evaluate(4.9e6)
    assert pf.STATUS[state["status"]] == "clamped to max_gauge_pa"
    assert state["tip_angle_rad"] == model.evaluate(294199.5)["tip_angle_rad"]
    assert state["tip_angle_rad"] < 2.0  # not the 15 rad of an unclamped paper wall
    row = next(csv.DictReader(io.StringIO(top.stdout)))
    assert float(row["tip_x_m"]) == state["backbone_m"][-1][0]
    # An explicit range, the same in both.
    lower = tool("finger_model", "--gauge-pa", "2e5", "--max-gauge-pa", "1.5e5")
    assert "above max_gauge_pa 150000 Pa" in lower.stderr
    with pytest.warns(RuntimeWarning, match="above max_gauge_pa 150000 Pa"):
        assert pf.STATUS[pf.FingerModel(max_gauge_pa=1.5e5).evaluate(2e5)["status"]] == "clamped to max_gauge_pa"


def test_python_is_numpy_shaped():
    model = pf.FingerModel()
    one = model.evaluate(1e5)
    assert isinstance(one["status"], numpy.uint8)  # a code, as in an array; pf.STATUS names it
    many = model.evaluate([1e5, 2e5])
    assert many["status"].dtype == numpy.uint8 and pf.STATUS[one["status"]] == pf.STATUS[many["status"][0]]
    angles = model.gauge_for_tip_angle(numpy.array([0.2, 0.5]))
    assert angles.shape == (2,) and angles[0] == model.gauge_for_tip_angle(0.2)
    with pytest.raises(ValueError, match=r"tip_angle_rad\[1\]"):
        model.gauge_for_tip_angle([0.2, 50.0])
    assert len(pf.STATUS) == 8 and pf.STATUS[2] == "clamped to max_gauge_pa" and pf.STATUS[4] == "snapped through"


def readme_block(after):
    # The first ``` block after the heading or sentence @after, as a user copies it.
    text = (pathlib.Path(__file__).resolve().parent.parent / "README.md").read_text()
    rest = text[text.index(after):]
    return rest.split("```\n", 2)[1]


def test_the_readme_quick_start_runs_as_pasted():
    import socket
    with socket.socket() as s:
        s.bind(("localhost", 0))
        port = s.getsockname()[1]
    root = pathlib.Path(__file__).resolve().parent.parent
    env = dict(os.environ, ROS_MASTER_URI=f"http://localhost:{port}", ROS_HOSTNAME="localhost",
               PATH="/usr/bin:/bin:" + os.environ.get("PATH", ""))
    script = readme_block("## Quick start")
    done = subprocess.run(["timeout", "120", "bash", "-c", "set -m\n" + script], cwd=root, env=env,
                          capture_output=True, text=True)
    assert done.returncode == 0, done.stdout + done.stderr
    assert "finger_joint_1" in done.stdout and "position:" in done.stdout, done.stdout
    without_ros = subprocess.run(["bash", "-c", "source devel/setup.bash\n" + readme_block("Without ROS, the same")],
                                 cwd=root, env=env, capture_output=True, text=True)
    assert without_ros.returncode == 0, without_ros.stderr
    assert float(without_ros.stdout.splitlines()[-1]) > 0


def test_the_calibration_walkthrough_runs_as_written():
    # docs/CALIBRATE.md's ```bash blocks, in order, in one shell, as a user pastes them; on the shipped example.
    import re
    import socket
    root = pathlib.Path(__file__).resolve().parent.parent
    blocks = re.findall(r"```bash\n(.*?)```", (root / "docs" / "CALIBRATE.md").read_text(), re.S)
    assert len(blocks) == 7
    with socket.socket() as s:
        s.bind(("localhost", 0))
        port = s.getsockname()[1]
    env = dict(os.environ, ROS_MASTER_URI=f"http://localhost:{port}", ROS_HOSTNAME="localhost",
               PATH="/usr/bin:/bin:" + os.environ.get("PATH", ""))
    done = subprocess.run(["timeout", "180", "bash", "-ec", "set -m\n" + "\n".join(blocks)], cwd=root, env=env,
                          capture_output=True, text=True)
    out = done.stdout
    assert done.returncode == 0, out + done.stderr
    assert "# compared: tip_position" in out and "# leave-one-out error" in out, out
    # The page's figures are the report's: 2.1 mm fitted, 4.4 mm left out.
    assert "largest |error|: tip position 0.00206759 m (2.068 mm)" in out, out
    assert "largest leave-one-out |error|: tip position 0.00444253 m (4.443 mm)" in out, out
    assert "(4, 2)" in out  # Python's leave-one-out arrays
    # The ribbed segment filled by volume: its bends within 2.0 deg, and then its drive's gas.
    assert "largest |error|: tip angle 0.035266 rad (2.021 deg), pressure 10726 Pa" in out, out
    assert "# fitted: dead_volume_m3 = 0.000135" in out, out
    # Both together: the bends within 2.5 deg, the pressure 38 % off at worst.
    assert "largest |error|: tip angle 0.044032 rad (2.523 deg), pressure 12452 Pa (largest relative 38.4 %)" in out, out
    # The cylindrical segment by volume with the paper law: 3.7 deg fitted, 6.0 deg left out.
    assert "largest |error|: tip angle 0.065035 rad (3.726 deg), pressure 13173 Pa" in out, out
    assert "largest leave-one-out |error|: tip angle 0.104558 rad (5.991 deg)" in out, out
    # The node published the file's bar at 147 kPa (147108 Pa gauge), between the third and fourth rows: both are the
    # fit's residual scatter, sqrt(sum e^2 / (4 - 2)) of its tip positions, 0.00270873 m (their own errors, 2.4 mm
    # and 1.4 mm left out, are below it).
    lines = out.splitlines()
    bar = float(lines[lines.index("---") - 1])
    assert abs(bar - 0.00270873) < 1e-6, out
    # The EPFL actuator's bends and blocked force together: the report gives both errors.
    assert re.search(r"largest \|error\|: chord angle [0-9.]+ rad \([0-9.]+ deg\), blocked force [0-9.]+ N", out), out


def test_the_example_tip_positions_are_the_scripts():
    root = pathlib.Path(__file__).resolve().parent.parent
    done = subprocess.run(["/usr/bin/python3", str(root / "scripts" / "example_tips.py"), "--check"])
    assert done.returncode == 0


def test_the_time_column_reads_as_its_decimal():
    out = tool("finger_model", "--flow-lpm", "1", "--duration-s", "0.02", "--step-s", "0.002").stdout
    times = [line.split(",")[0] for line in out.splitlines()[1:]]
    assert times[7] == "0.014", times  # not the product's 0.014000000000000002


def test_small_ones():
    # finger_node --help answers at once, without a master.
    done = subprocess.run(["timeout", "10", str(BIN / "finger_node"), "--help"], capture_output=True, text=True,
                          env=dict(os.environ, ROS_MASTER_URI="http://localhost:1"))
    assert done.returncode == 0 and "Usage: rosrun pneumatic_finger finger_node" in done.stdout, done.stdout
    # finger_design names the option of a value that is not a number, and warns of a vacuum as finger_model does.
    design = [str(pathlib.Path(__file__).resolve().parent.parent / "scripts" / "finger_design"),
              "--vary", "chamber_gap_m=2e-5:5e-5:2"]
    bad = subprocess.run(["/usr/bin/python3", *design, "--quantity", "tip_angle_rad@150kPa"], capture_output=True,
                         text=True)
    assert bad.returncode == 2
    assert "--quantity tip_angle_rad@150kPa: '150kPa' is not a number (Pa gauge" in bad.stderr, bad.stderr
    vacuum = subprocess.run(["/usr/bin/python3", *design, "--quantity", "tip_angle_rad@-5"], capture_output=True,
                            text=True)
    words = "gauge pressure -5 Pa is a vacuum, outside the model: the straight finger"
    assert vacuum.returncode == 0 and words in vacuum.stderr, vacuum.stderr
    assert words in tool("finger_model", "--gauge-pa", "-5").stderr


def test_the_readme_says_how_far_to_trust_the_real_finger():
    # Beside the solver's 1e-12, the real-world error, as finger_calibrate measures it on the shipped data.
    readme = (pathlib.Path(__file__).resolve().parent.parent / "README.md").read_text()
    report = tool("finger_calibrate").stdout
    fit = report.split("# largest |error|:")[1].splitlines()[0]
    loo = report.split("# largest leave-one-out |error|:")[1].splitlines()[0]
    assert "joints 0.0210734 rad (1.207 deg)" in fit and "average 0.00928543 rad (0.532 deg)" in fit
    assert "(2.156 mm)" in fit and "joints 0.0286891 rad (1.644 deg)" in loo and "(5.629 mm)" in loo
    for figure in ("within 1.21°", "within 0.53°", "within 2.2 mm", "within 1.64°", "5.6 mm at the tip"):
        assert figure in readme, figure
    # And mu is called what it is.
    table = tool("finger_model", "--parameters").stdout
    row = next(line for line in table.splitlines() if line.startswith("| `shear_modulus_pa`"))
    assert "not the elastomer's measured shear modulus" in row


def test_force_counts_only_pressures_where_the_model_predicts_a_force():
    # FORCE.md's summary: a pressure predicted at 0 N is not met by the goal's 0.05 N floor.
    page = (pathlib.Path(__file__).resolve().parent.parent / "docs" / "FORCE.md").read_text()
    ribbed = page[page.index("**ribbed**"):]
    rows = []
    for line in ribbed.splitlines()[4:]:  # the ribbed table's rows, up to its end
        if not line.startswith("| "):
            break
        rows.append(line.split("|")[1:-1])
    assert len(rows) == 22
    pressing = [r for r in rows if float(r[2]) > 0]
    met = sum(1 for r in pressing if r[5].strip() == "yes")
    assert f"| {met} of {len(pressing)} where it predicts a force" in page
    assert len(pressing) < len(rows)  # some rows below the touch exist, and are not counted
