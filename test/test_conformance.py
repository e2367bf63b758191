"""One table of cases, every interface: test/conformance/cases.yaml driven through finger_model, finger_design,
finger_urdf (URDF and MJCF), Python and finger_node, each of which must answer alike.

Run by `make run_tests` (CMakeLists.txt passes the package's executables in PNEUMATIC_FINGER_BIN). The node's cases
start one master of their own on a free port, load each file with rosparam as finger.launch does, and start the node
on it.
"""
import csv
import io
import math
import os
import pathlib
import re
import socket
import subprocess
import time
import warnings

import pytest
import yaml

import pneumatic_finger.core as pf

ROOT = pathlib.Path(__file__).resolve().parent.parent
BIN = pathlib.Path(os.environ.get("PNEUMATIC_FINGER_BIN", ROOT / "devel/lib/pneumatic_finger"))
TABLE = yaml.safe_load((ROOT / "test/conformance/cases.yaml").read_text())
ANGLE_TOLERANCE_RAD = 1e-12  # the model's own exactness: every interface runs the same core

# The warning classes, by the core's words (pressure_range.cpp): every interface says them in these words.
WARNING_WORDS = {"clamped": "the top of the model's range: clamped to it", "vacuum": "is a vacuum, outside the model",
                 "extrapolated": "is above the validated range", "zero_shot": "a zero-shot prediction"}


def warning_classes(text):
    return sorted(name for name, words in WARNING_WORDS.items() if words in text) or ["none"]


def message_number(x):
    """A number as the core's messages print it (formatMessage): shortest round trip, no trailing '.0'."""
    return repr(float(x)).removesuffix(".0")


@pytest.fixture(scope="module")
def files(tmp_path_factory):
    """Every file of the table, written out: shipped ones as they are, edited ones edited."""
    folder = tmp_path_factory.mktemp("conformance")
    out = {}
    for name, spec in TABLE["files"].items():
        if "path" in spec:
            out[name] = ROOT / spec["path"]
            continue
        if "written_by" in spec:  # a tool's --output, as a user makes the file
            out[name] = folder / f"{name}.yaml"
            args = [str(ROOT / a) if (ROOT / a).is_file() else a for a in spec["written_by"][1:]]
            done = tool(spec["written_by"][0], *args, "--output", out[name])
            assert done.returncode == 0, done.stderr
            continue
        text = (ROOT / spec["base"]).read_text()
        for key in spec.get("drop", []):
            text, count = re.subn(rf"(?m)^{key}:.*\n", "", text)
            assert count == 1, (name, key)
        for old, new in spec.get("replace", []):
            assert text.count(old) == 1, (name, old)
            text = text.replace(old, new)
        text += spec.get("append", "")
        out[name] = folder / f"{name}.yaml"
        out[name].write_text(text)
    return out


def tool(name, *args):
    return subprocess.run([str(BIN / name), *map(str, args)], capture_output=True, text=True, timeout=120)


# ---- each interface's answer, in one form: (tip angle in rad, the printed gauge, warning classes) or a refusal ----

def python_answer(path, gauge_pa):
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        model = pf.FingerModel(config=str(path))
        state = model.evaluate(gauge_pa)
    words = " ".join(str(w.message) for w in caught)
    return float(state["tip_angle_rad"]), warning_classes(words), report(state["status"], state["status_flags"])


def report(status, flags):
    """A status and its flags by name (pf.STATUS, pf.status_flag_names), as the table writes them."""
    return pf.STATUS[int(status)], pf.status_flag_names(int(flags))


def finger_model_answer(path, gauge_pa):
    done = tool("finger_model", "--config", path, "--gauge-pa", repr(gauge_pa), "--status")
    assert done.returncode == 0, done.stderr
    row = next(csv.DictReader(io.StringIO(done.stdout)))
    joints = [float(v) for k, v in row.items() if k.startswith("joint_")]
    return (math.fsum(joints), float(row["gauge_pa"]), warning_classes(done.stderr),
            report(row["status"], row["status_flags"]))


def finger_design_answer(path, gauge_pa):
    mu = pf.FingerModel(config=str(path)).parameters["shear_modulus_pa"]
    done = tool("finger_design", "--config", path, "--vary", f"shear_modulus_pa={mu!r}:{mu!r}:1",
                "--quantity", f"tip_angle_rad@{gauge_pa!r}")
    assert done.returncode == 0, done.stderr
    row = next(csv.DictReader(io.StringIO(done.stdout)))
    return (float(row[f"tip_angle_rad@{gauge_pa!r}"]), warning_classes(done.stderr),
            report(row["status"], row["status_flags"]))


def mjcf_answer(path, gauge_pa):
    done = tool("finger_urdf", "--config", path, "--mjcf", "--gauge-pa", repr(gauge_pa))
    assert done.returncode == 0, done.stderr
    angles = [float(x) for x in re.findall(r'<joint name="finger_joint_\d+"[^>]*springref="([^"]+)"', done.stdout)]
    assert angles, done.stdout[:500]
    return math.fsum(angles), warning_classes(done.stderr)


def urdf_upper_limits(path, *args):
    done = tool("finger_urdf", "--config", path, *args)
    assert done.returncode == 0, done.stderr
    return math.fsum(float(x) for x in re.findall(r'<limit [^>]*upper="([^"]+)"', done.stdout))


def gripper_file(path, folder):
    """A gripper file in @p folder whose one finger (prefix finger_) is the parameter file @p path: the cell's road."""
    gripper = folder / f"gripper_{path.stem}.yaml"
    gripper.write_text(f"fingers:\n  - {{prefix: finger_, parent: tool0, xyz: [0, 0, 0], rpy: [0, 0, 0], "
                       f"config: {path}}}\n")
    return gripper


def tip_at(path, gauge_pa):
    """The reference: the core through Python, warnings aside."""
    return reference_state(path, gauge_pa)[0]


def reference_state(path, gauge_pa):
    """The core through Python, warnings aside: (tip angle in rad, status code)."""
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        state = pf.FingerModel(config=str(path)).evaluate(gauge_pa)
    return float(state["tip_angle_rad"]), int(state["status"])


def refusals_of_the_tools(path):
    """Every interface but the node, each refusing the file: its message."""
    messages = {}
    for name, args in {"finger_model": ["--gauge-pa", "1000"], "finger_urdf": [], "finger_urdf --mjcf": ["--mjcf"],
                       "finger_design": ["--vary", "chamber_gap_m=1e-5:2e-5:2", "--quantity", "tip_angle_rad@1000"],
                       "finger_calibrate --coupon": ["--coupon", ROOT / "data/epfl_ecoflex30_uniaxial.csv"]}.items():
        done = tool(name.split()[0], "--config", path, *args)
        messages[name] = (done.returncode, done.stderr)
    try:
        pf.FingerModel(config=str(path))
        messages["python"] = (0, "")
    except ValueError as e:
        messages["python"] = (2, str(e))
    return messages


@pytest.mark.parametrize("case", TABLE["refusals"], ids=lambda c: c["file"])
def test_every_tool_refuses_the_file_in_the_same_words(files, case):
    for interface, (code, message) in refusals_of_the_tools(files[case["file"]]).items():
        assert code == 2 and case["words"] in message, (interface, code, message)


@pytest.mark.parametrize("case", TABLE["ranges"], ids=lambda c: c["file"])
def test_every_tool_reads_the_file_range_alike(files, case, tmp_path):
    path, top, validated = files[case["file"]], case["max_gauge_pa"], case["validated_max_gauge_pa"]
    model = pf.FingerModel(config=str(path))
    assert (model.max_gauge_pa, model.validated_max_gauge_pa) == (top, validated)
    # Above the top: every interface clamps there, in the same words, with the top's number.
    above = top * 1.01
    at_top = tip_at(path, top)
    tip, printed, classes, _ = finger_model_answer(path, above)
    assert printed == top and abs(tip - at_top) <= ANGLE_TOLERANCE_RAD and "clamped" in classes
    for answer in (python_answer, finger_design_answer, mjcf_answer):
        tip, classes = answer(path, above)[:2]
        assert abs(tip - at_top) <= ANGLE_TOLERANCE_RAD and "clamped" in classes, (answer.__name__, tip, classes)
    assert abs(urdf_upper_limits(path) - at_top) <= ANGLE_TOLERANCE_RAD  # the joint limits are the finger at the top
    # The same file through a gripper file (the cell's road): its finger keeps the file's range.
    via_gripper = urdf_upper_limits(path, "--gripper", gripper_file(path, tmp_path), "--prefix", "finger_")
    assert abs(via_gripper - at_top) <= ANGLE_TOLERANCE_RAD, (via_gripper, at_top)
    # Just above the validated range (below the top): the tools extrapolate and say so, with the range's number.
    if 0 < validated < top:
        done = tool("finger_model", "--config", path, "--gauge-pa", repr(validated * 1.0001))
        assert f"(0 to {message_number(validated)} Pa)" in done.stderr, done.stderr
        assert warning_classes(tool("finger_model", "--config", path, "--gauge-pa",
                                    repr(validated * 0.9999)).stderr) == ["none"]


@pytest.mark.parametrize("case", TABLE["pressures"], ids=lambda c: f"{c['file']}@{c['gauge_pa']}")
def test_every_tool_gives_the_same_finger_and_warning(files, case):
    path, gauge_pa = files[case["file"]], float(case["gauge_pa"])
    reference = tip_at(path, gauge_pa)
    tip, printed, classes, reported = finger_model_answer(path, gauge_pa)
    answers = {"finger_model": (tip, classes, reported)}
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        evaluated = float(pf.FingerModel(config=str(path)).evaluate(gauge_pa)["gauge_pa"])
    assert evaluated == printed, (evaluated, printed)  # the pressure evaluated: the top, for a clamped one
    # The blocked tip force through the same range rule: finger_model's column and Python's call agree.
    done = tool("finger_model", "--config", path, "--gauge-pa", repr(gauge_pa), "--blocked-tip-force")
    cli_force = float(next(csv.DictReader(io.StringIO(done.stdout)))["blocked_tip_force_n"])
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        python_force = float(pf.FingerModel(config=str(path)).blocked_tip_force(gauge_pa))
    assert cli_force == pytest.approx(python_force, rel=1e-12, abs=1e-15), (cli_force, python_force)
    for answer in (python_answer, finger_design_answer, mjcf_answer):
        answers[answer.__name__] = answer(path, gauge_pa)
    expected = (case["status"], case["flags"])
    for interface, (tip, classes, *reported) in answers.items():
        assert abs(tip - reference) <= ANGLE_TOLERANCE_RAD, (interface, tip, reference)
        assert classes == [case["warning"]], (interface, classes)
        assert not reported or reported[0] == expected, (interface, reported, expected)


# ---- finger_node, as finger.launch starts it: the file loaded by rosparam into its private namespace ----

def free_port():
    with socket.socket() as s:
        s.bind(("localhost", 0))
        return s.getsockname()[1]


@pytest.fixture(scope="module")
def ros(tmp_path_factory):
    """A master of this test's own, and this process as a rospy node on it."""
    port = free_port()
    os.environ.update(ROS_MASTER_URI=f"http://localhost:{port}", ROS_HOSTNAME="localhost",
                      ROS_HOME=str(tmp_path_factory.mktemp("ros_home")))
    core = subprocess.Popen(["roscore", "-p", str(port)], stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    import rospy
    for _ in range(200):
        if subprocess.run(["rosparam", "list"], capture_output=True).returncode == 0:
            break
        time.sleep(0.1)
    rospy.init_node("conformance", anonymous=True, disable_signals=True)
    yield rospy
    rospy.signal_shutdown("done")
    core.terminate()
    core.wait()


class StartedNode:
    """finger_node in namespace /NS, its private parameters loaded from @p path (rosparam load, as the launch file)."""

    count = 0

    def __init__(self, rospy, path, extra=None):
        import rosparam
        from sensor_msgs.msg import FluidPressure
        from pneumatic_finger.msg import FingerModelState
        StartedNode.count += 1
        self.rospy, self.ns = rospy, f"/conformance_{StartedNode.count}"
        for params, sub_ns in rosparam.load_file(str(path), default_namespace=f"{self.ns}/finger_node/") if path else []:
            rosparam.upload_params(sub_ns, params)
        for key, value in (extra or {}).items():  # a launch argument, as finger.launch sets it
            rospy.set_param(f"{self.ns}/finger_node/{key}", value)
        self.process = subprocess.Popen([str(BIN / "finger_node"), f"__ns:={self.ns}", "__name:=finger_node"],
                                        stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
        self.states = []
        self.subscriber = rospy.Subscriber(f"{self.ns}/finger_state", FingerModelState, self.states.append)
        if extra and extra.get("volume_topic"):
            from std_msgs.msg import Float64
            self.publisher = rospy.Publisher(f"{self.ns}/{extra['volume_topic']}", Float64, queue_size=10)
            self.message = lambda fluid_pressure: Float64(data=fluid_pressure)  # a volume, in the same call
        else:
            self.publisher = rospy.Publisher(f"{self.ns}/pressure", FluidPressure, queue_size=10)
            self.message = FluidPressure

    def refusal(self):
        out, _ = self.process.communicate(timeout=60)
        return self.process.returncode, out

    def state_at(self, gauge_pa, atmospheric_pa):
        for _ in range(300):  # the node subscribed
            if self.publisher.get_num_connections() > 0 and self.subscriber.get_num_connections() > 0:
                break
            assert self.process.poll() is None, self.process.communicate()[0]
            time.sleep(0.05)
        for _ in range(10):
            seen = len(self.states)
            message = self.message(fluid_pressure=gauge_pa + atmospheric_pa)
            if hasattr(message, "header"):
                message.header.stamp = self.rospy.Time.now()
            self.publisher.publish(message)
            for _ in range(40):
                if len(self.states) > seen:
                    return self.states[-1]
                time.sleep(0.025)
        raise AssertionError(f"no finger_state for {gauge_pa} Pa")

    def stop(self):
        self.subscriber.unregister()
        self.publisher.unregister()
        if self.process.poll() is None:
            self.process.terminate()
            self.process.wait(timeout=30)


class Diagnostics:
    """The /diagnostics statuses of @p node as they arrive: their messages and their key/value pairs."""

    def __init__(self, rospy, node):
        from diagnostic_msgs.msg import DiagnosticArray
        self.messages, self.values = [], {}
        prefix = node.ns.lstrip("/") + "/"
        self.listener = rospy.Subscriber("/diagnostics", DiagnosticArray, lambda a: self._heard(a, prefix))

    def _heard(self, array, prefix):
        for status in array.status:
            if prefix in status.name:
                self.messages.append(status.message)
                self.values.update({kv.key: kv.value for kv in status.values})

    def said(self, words):
        return any(words in m for m in self.messages)

    def stop(self):
        self.listener.unregister()


def node_warning(state, validated):
    if state.status_flags & state.FLAG_CLAMPED:
        return ["clamped"]
    if state.status == state.STATUS_VACUUM:
        return ["vacuum"]
    if not state.in_validated_range:
        return ["zero_shot" if validated == 0 else "extrapolated"]
    return ["none"]


@pytest.mark.parametrize("case", TABLE["refusals"], ids=lambda c: c["file"])
def test_the_node_refuses_the_file_in_the_same_words(ros, files, case):
    node = StartedNode(ros, files[case["file"]])
    code, out = node.refusal()
    node.stop()
    assert code == 2 and case["words"] in out, out


@pytest.mark.parametrize("file", sorted({c["file"] for c in TABLE["pressures"]} | {c["file"] for c in TABLE["ranges"]}))
def test_the_node_gives_the_same_finger_range_and_warning(ros, files, file, tmp_path):
    path = files[file]
    model = pf.FingerModel(config=str(path))
    atmospheric_pa = model.parameters["atmospheric_pressure_pa"]
    node = StartedNode(ros, path)
    try:
        for case in [c for c in TABLE["pressures"] if c["file"] == file]:
            state = node.state_at(float(case["gauge_pa"]), atmospheric_pa)
            tip, status = reference_state(path, float(case["gauge_pa"]))
            assert abs(state.tip_angle_rad - tip) <= ANGLE_TOLERANCE_RAD and state.status == status, case
            assert report(state.status, state.status_flags) == (case["status"], case["flags"]), case
            with warnings.catch_warnings():
                warnings.simplefilter("ignore")
                chord = float(pf.FingerModel(config=str(path)).evaluate(float(case["gauge_pa"]))["chord_angle_rad"])
            assert abs(state.chord_angle_rad - chord) <= ANGLE_TOLERANCE_RAD or math.isnan(chord), case  # a marker's
            assert node_warning(state, model.validated_max_gauge_pa) == [case["warning"]], (case, state.status)
        for case in [c for c in TABLE["ranges"] if c["file"] == file]:
            top, validated = case["max_gauge_pa"], case["validated_max_gauge_pa"]
            state = node.state_at(top * 1.01, atmospheric_pa)
            assert state.gauge_pa == top and state.status == reference_state(path, top * 1.01)[1], case
            if validated > 0:
                assert node.state_at(validated * 0.9999, atmospheric_pa).in_validated_range, case
            if validated < top:
                assert not node.state_at(validated * 1.0001 + 1e-3, atmospheric_pa).in_validated_range, case
    finally:
        node.stop()
    # The same file through a gripper file, as the cell starts its fingers: the node keeps the file's range.
    for case in [c for c in TABLE["ranges"] if c["file"] == file]:
        node = StartedNode(ros, None, {"gripper_file": str(gripper_file(path, tmp_path)), "frame_prefix": "finger_"})
        try:
            state = node.state_at(case["max_gauge_pa"] * 1.01, atmospheric_pa)
            assert state.gauge_pa == case["max_gauge_pa"] and state.status_flags & state.FLAG_CLAMPED, case
        finally:
            node.stop()


# ---- data files: finger_calibrate and Python read a measurement or a coupon CSV alike ----

def data_file_text(case):
    if "text" in case:
        return case["text"]
    rows = [line.split(",") for line in (ROOT / case["from"]).read_text().splitlines()
            if line and not line.startswith("#")][1:]
    kept = [(float(strain), float(stress)) for strain, stress, *_ in rows if float(strain) <= case["up_to_strain"]]
    return "engineering_strain,nominal_stress_pa\n" + "".join(
        f"{strain * case['strain_scale']!r},{stress * case['stress_scale']!r}\n" for strain, stress in kept)


@pytest.mark.parametrize("case", TABLE["data_files"], ids=lambda c: f"{c['kind']}:{c['words'][:30]}")
def test_every_interface_refuses_the_data_file_in_the_same_words(tmp_path, case):
    path = tmp_path / "data.csv"
    path.write_text(data_file_text(case))
    coupon = case["kind"] == "coupon"
    done = tool("finger_calibrate", "--coupon" if coupon else "--data", path, "--config",
                ROOT / "config/epfl_ecoflex30_c7_drawing.yaml")
    assert done.returncode == 2 and case["words"] in done.stderr, done.stderr
    with pytest.raises(ValueError) as refused:
        if coupon:
            pf.fit_coupon(str(path), config=str(ROOT / "config/epfl_ecoflex30_c7_drawing.yaml"))
        else:
            pf.calibrate(data=str(path), config=str(ROOT / "config/epfl_ecoflex30_c7_drawing.yaml"))
    assert case["words"] in str(refused.value), str(refused.value)


@pytest.mark.parametrize("case", TABLE["parts"], ids=lambda c: c["words"][:30])
def test_every_interface_reads_a_part_to_grip_alike(case):
    config = ROOT / "config/epfl_ecoflex30_c7.yaml"
    design = tool("finger_design", "--config", config, "--target", "grip_gauge_pa=min", "--part", case["part"],
                  "--free", "drawing/wall_thickness_m")
    model = tool("finger_model", "--config", config, "--pressures", "--grip-part", case["part"])
    assert case["words"] in design.stderr and design.returncode == 2, design.stderr
    if case.get("held", True):  # not a part: refused
        assert model.returncode == 2 and case["words"] in model.stderr and model.stdout == "", model.stderr
        for call in (lambda: pf.grip_gauge_pa(case["part"], config=str(config)),
                     lambda: pf.design_to_target(["grip_gauge_pa=min"], ["drawing/wall_thickness_m"],
                                                 config=str(config), part=case["part"])):
            with pytest.raises(ValueError, match=re.escape(case["words"])):
                call()
        return
    assert model.returncode == 0 and case["words"] in model.stderr, model.stderr  # a part, too heavy: nan
    assert next(csv.DictReader(io.StringIO(model.stdout)))["grip_gauge_pa"] == "nan"
    with pytest.warns(RuntimeWarning, match=re.escape(case["words"])):
        assert math.isnan(pf.grip_gauge_pa(case["part"], config=str(config)))
    with pytest.raises(ValueError, match=re.escape(case["words"])):
        pf.design_to_target(["grip_gauge_pa=min"], ["drawing/wall_thickness_m"], config=str(config), part=case["part"])


@pytest.mark.parametrize("file", sorted({c["file"] for c in TABLE["volumes"]}))
def test_every_interface_driven_by_volume_gives_the_same_finger(ros, files, file):
    path = files[file]
    node = StartedNode(ros, path, {"volume_topic": "volume"})
    try:
        for case in [c for c in TABLE["volumes"] if c["file"] == file]:
            v = float(case["supplied_volume_m3"])
            with warnings.catch_warnings(record=True) as caught:
                warnings.simplefilter("always")
                python = pf.FingerModel(config=str(path)).evaluate_volume(v)
            done = tool("finger_model", "--config", path, "--supplied-volume-m3", repr(v), "--status")
            assert done.returncode == 0, done.stderr
            row = next(csv.DictReader(io.StringIO(done.stdout)))
            cli_tip = math.fsum(float(x) for k, x in row.items() if k.startswith("joint_"))
            state = node.state_at(v, 0.0)
            expected = (case["status"], case["flags"])
            assert report(python["status"], python["status_flags"]) == expected, case
            assert report(row["status"], row["status_flags"]) == expected, case
            assert report(state.status, state.status_flags) == expected, case
            if "extrapolated" in case["flags"] and "clamped" not in case["flags"]:  # said, as for a pressure
                said = warning_classes(done.stderr) + warning_classes(" ".join(str(w.message) for w in caught))
                assert said.count("zero_shot") + said.count("extrapolated") == 2, (case, said)
            if "words" in case:  # no shape: the same words, NaN in the CLI and Python, the last shape kept by the node
                assert case["words"] in done.stderr and any(case["words"] in str(w.message) for w in caught), case
                assert math.isnan(cli_tip) and math.isnan(python["tip_angle_rad"]), case
                continue
            tip = float(python["tip_angle_rad"])
            assert abs(cli_tip - tip) <= ANGLE_TOLERANCE_RAD and abs(state.tip_angle_rad - tip) <= ANGLE_TOLERANCE_RAD
            assert float(row["gauge_pa"]) == float(python["gauge_pa"]) == state.gauge_pa, case
    finally:
        node.stop()


@pytest.mark.parametrize("case", TABLE["not_finite"], ids=lambda c: c["words"])
def test_every_interface_refuses_an_input_that_is_no_number_in_the_same_words(ros, files, case):
    path, by_volume = files[case["file"]], "supplied_volume_m3" in case
    x = float(case["supplied_volume_m3"] if by_volume else case["gauge_pa"])
    done = tool("finger_model", "--config", path, "--supplied-volume-m3" if by_volume else "--gauge-pa", repr(x))
    assert done.returncode == 2 and case["words"] in done.stderr, done.stderr
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        model = pf.FingerModel(config=str(path))
        state = model.evaluate_volume(x) if by_volume else model.evaluate(x)
    assert pf.STATUS[int(state["status"])] == "not finite" and math.isnan(state["tip_angle_rad"])
    assert any(case["words"] in str(w.message) for w in caught), [str(w.message) for w in caught]
    node = StartedNode(ros, path, {"volume_topic": "volume"} if by_volume else None)
    diagnostics = Diagnostics(ros, node)
    try:
        node.state_at(0.0 if by_volume else 1000.0, 0.0 if by_volume else model.parameters["atmospheric_pressure_pa"])
        for _ in range(100):  # the refusal is said in diagnostics (published every second)
            node.publisher.publish(node.message(fluid_pressure=x))
            if diagnostics.said(case["words"]):
                break
            time.sleep(0.1)
        assert diagnostics.said(case["words"]), diagnostics.messages[-3:]
    finally:
        diagnostics.stop()
        node.stop()


@pytest.mark.parametrize("case", TABLE["impossible_pressures"], ids=lambda c: c["words"])
def test_every_interface_refuses_a_negative_absolute_pressure_in_the_same_words(ros, files, case):
    path, p = files[case["file"]], float(case["gauge_pa"])
    for name, args in {"finger_model": ["--gauge-pa", repr(p)], "finger_urdf": ["--mjcf", "--gauge-pa", repr(p)],
                       "finger_design": ["--vary", "chamber_gap_m=1e-5:2e-5:2", "--quantity",
                                         f"tip_angle_rad@{p!r}"]}.items():
        done = tool(name, "--config", path, *args)
        assert done.returncode == 2 and case["words"] in done.stderr, (name, done.stderr)
    with pytest.raises(ValueError) as refused:
        pf.FingerModel(config=str(path)).evaluate(p)
    assert case["words"] in str(refused.value)
    model = pf.FingerModel(config=str(path))
    node = StartedNode(ros, path)
    diagnostics = Diagnostics(ros, node)
    try:
        atmospheric_pa = model.parameters["atmospheric_pressure_pa"]
        node.state_at(1000.0, atmospheric_pa)
        for _ in range(100):
            message = node.message(fluid_pressure=p + atmospheric_pa)
            message.header.stamp = ros.Time.now()
            node.publisher.publish(message)
            if diagnostics.said(case["words"]):
                break
            time.sleep(0.1)
        assert diagnostics.said(case["words"]), diagnostics.messages[-3:]
    finally:
        diagnostics.stop()
        node.stop()


@pytest.mark.parametrize("case", TABLE["calibrations"], ids=lambda c: ",".join(c["fit"]))
def test_every_written_file_reproduces_its_report_in_every_interface(ros, tmp_path, case):
    truth = pf.FingerModel(config=str(ROOT / case["from"]), overrides=case["set"])
    pressures = [float(p) for p in case["pressures"]]
    tips = truth.evaluate(pressures, outputs=["tip_angle_rad"])["tip_angle_rad"]
    data = tmp_path / "data.csv"
    data.write_text("gauge_pa,tip_angle_rad\n" + "".join(f"{p!r},{t!r}\n" for p, t in zip(pressures, tips)))
    written = tmp_path / "cli.yaml"
    done = tool("finger_calibrate", "--data", data, "--config", ROOT / case["config"], "--fit", ",".join(case["fit"]),
                "--compare", "tip_angle", "--output", written)
    assert done.returncode == 0, done.stderr
    fit = pf.calibrate(data=str(data), config=str(ROOT / case["config"]), keys=case["fit"], compare="tip_angle",
                       output=str(tmp_path / "python.yaml"))
    reported = fit["residuals"]["model_tip_angle_rad"]
    model = pf.FingerModel(config=str(written))
    assert model.parameters == pf.FingerModel(config=str(tmp_path / "python.yaml")).parameters
    loaded = model.evaluate(pressures, outputs=["tip_angle_rad"])["tip_angle_rad"]
    for p, tip, report_tip in zip(pressures, loaded, reported):
        assert abs(tip - report_tip) <= ANGLE_TOLERANCE_RAD, (p, tip, report_tip)
        cli_tip, *_ = finger_model_answer(written, p)
        assert abs(cli_tip - report_tip) <= ANGLE_TOLERANCE_RAD, (p, cli_tip, report_tip)
    node = StartedNode(ros, written)
    try:
        atmospheric_pa = model.parameters["atmospheric_pressure_pa"]
        for p, report_tip in zip(pressures, reported):
            assert abs(node.state_at(p, atmospheric_pa).tip_angle_rad - report_tip) <= ANGLE_TOLERANCE_RAD, p
    finally:
        node.stop()


@pytest.mark.parametrize("case", TABLE["follows"], ids=lambda c: c["wall_law"])
def test_every_interface_says_whether_a_calibration_follows_its_data(ros, tmp_path, case):
    written = tmp_path / "cli.yaml"
    done = tool("finger_calibrate", "--data", ROOT / case["data"], "--config", ROOT / case["config"], "--wall-law",
                case["wall_law"], "--output", written)
    assert done.returncode == 0, done.stderr
    assert (case["words"] in done.stdout) == (not case["follows"]), done.stdout
    fit = pf.calibrate(data=str(ROOT / case["data"]), config=str(ROOT / case["config"]), wall_law=case["wall_law"])
    assert fit["calibration_error"]["follows_data"] == case["follows"]
    assert any(case["words"] in w for w in fit["warnings"]) == (not case["follows"]), fit["warnings"]
    text = written.read_text()
    assert f"follows_data: {str(case['follows']).lower()}" in text
    model = pf.FingerModel(config=str(written))
    node = StartedNode(ros, written)
    diagnostics = Diagnostics(ros, node)
    try:
        node.state_at(20000.0, model.parameters["atmospheric_pressure_pa"])
        for _ in range(50):  # published every second
            if "calibration" in diagnostics.values:
                break
            time.sleep(0.1)
        said = diagnostics.values.get("calibration", "")
        assert ("does NOT follow its data" in said) == (not case["follows"]), said
        assert diagnostics.said("calibration does not follow its data") == (not case["follows"])
    finally:
        diagnostics.stop()
        node.stop()


@pytest.mark.parametrize("case", TABLE["designs"], ids=lambda c: c["target"])
def test_every_designed_file_reproduces_its_prediction_in_every_interface(ros, tmp_path, case):
    written = tmp_path / "cli.yaml"
    counts = ["--chamber-count", str(case["chamber_count"])] if "chamber_count" in case else []
    part = ["--part", case["part"]] if "part" in case else []
    done = tool("finger_design", "--config", ROOT / case["config"], "--target", case["target"], "--free", case["free"],
                *counts, *part, "--output", written)
    assert done.returncode == 0 and "# met" in done.stdout, done.stdout + done.stderr
    design = pf.design_to_target([case["target"]], [case["free"]], config=str(ROOT / case["config"]),
                                 chamber_counts=[case["chamber_count"]] if "chamber_count" in case else None,
                                 part=case.get("part"))
    assert written.read_text() == design["parameter_file"]  # the CLI's file is Python's, byte for byte
    achieved = design["achieved"][case["target"]]
    quantity, _, rest = case["target"].partition("@")
    quantity = quantity.partition("=")[0]
    model = pf.FingerModel(config=str(written))
    assert model.validated_max_gauge_pa == 0.0  # a drawing not yet cast: every answer a zero-shot prediction
    if quantity in ("snap_gauge_pa", "grip_gauge_pa"):
        grip = ["--grip-part", case["part"]] if quantity == "grip_gauge_pa" else []
        done = tool("finger_model", "--config", written, "--pressures", *grip)
        row = next(csv.DictReader(io.StringIO(done.stdout)))
        python = model.snap_gauge_pa if not grip else pf.grip_gauge_pa(case["part"], config=str(written))
        for answer in (python, float(row[quantity])):
            assert abs(answer / achieved - 1.0) <= 1e-12, (answer, achieved)
        pressure = achieved / 2 if not grip else achieved
    else:
        pressure = float(rest.partition("=")[0])
        tip = float(model.evaluate(pressure)["tip_angle_rad"])
        assert abs(tip - achieved) <= ANGLE_TOLERANCE_RAD
        cli_tip, *_ = finger_model_answer(written, pressure)
        assert abs(cli_tip - achieved) <= ANGLE_TOLERANCE_RAD
    assert tool("finger_urdf", "--config", written, "--mjcf").returncode == 0
    node = StartedNode(ros, written)
    try:
        state = node.state_at(pressure, model.parameters["atmospheric_pressure_pa"])
        assert abs(state.tip_angle_rad - float(model.evaluate(pressure)["tip_angle_rad"])) <= ANGLE_TOLERANCE_RAD
    finally:
        node.stop()
