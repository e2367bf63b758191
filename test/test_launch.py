"""The launch files as a user starts them (roslaunch, a master of their own on a free port): a bad argument gets the
node's own message and exit, never a crash inside roslaunch or roscpp.

Run by `make run_tests` (pytest, in the devel space's environment).
"""
import os
import pathlib
import re
import socket
import subprocess
import tempfile
import time

import pytest

ROOT = pathlib.Path(__file__).resolve().parent.parent


def free_port():
    with socket.socket() as s:
        s.bind(("localhost", 0))
        return s.getsockname()[1]


def launched(seconds, *args):
    """`roslaunch -p PORT pneumatic_finger ARGS` on a port of its own, stopped after @p seconds (exit 124).

    Its output goes to files, not pipes: a launch that dies without stopping its master (roslaunch hung in its own
    shutdown once in CI, and the timeout's SIGTERM ended it there) leaves rosmaster and rosout, each in a session of
    its own, holding the pipes open, and subprocess.run then waits for ever. What still serves the port is stopped."""
    port = free_port()
    env = dict(os.environ, ROS_MASTER_URI=f"http://localhost:{port}", ROS_HOSTNAME="localhost")
    with tempfile.TemporaryFile("w+") as out, tempfile.TemporaryFile("w+") as err:
        done = subprocess.run(["timeout", "-k", "10", str(seconds), "roslaunch", "-p", str(port), "pneumatic_finger",
                               *args], stdout=out, stderr=err, text=True, env=env)
        out.seek(0)
        err.seek(0)
        result = subprocess.CompletedProcess(done.args, done.returncode, out.read(), err.read())
    subprocess.run(["pkill", "-f", f"rosmaster --core -p {port} "], capture_output=True)
    return result


def roslaunch(*args):
    return launched(90, *args)


def test_a_prefix_that_makes_no_valid_node_name_is_refused_by_the_node_with_the_reason():
    # finger.launch names the node PREFIXnode; "1xnode" is no ROS name, so the launch file falls back to finger_node,
    # which reads ~frame_prefix and refuses it (exit 2). Before, roscpp threw InvalidNameException and aborted.
    done = roslaunch("finger.launch", "prefix:=1x", "rviz:=false")
    out = done.stdout + done.stderr
    assert "finger_node: error: parameter 'frame_prefix' = '1x' must start with a letter" in out, out
    assert "exit code 2" in out, out
    assert "InvalidNameException" not in out and "exit code -6" not in out, out


def test_a_finished_cell_run_reads_clean_in_time_order():
    # The cell's log as a file (a pipe): one cycle, then the launch ends by itself with status 0, without
    # "REQUIRED process has died" (the sequencer ends the launch as Ctrl-C does), without a WARN (the start-up wait
    # for tf is not one), without per-finger INFO lines that read like failures, and every stamped line in time order
    # (every node writes line by line).
    done = roslaunch("pick_and_place_cell.launch", "rviz:=false", "loop_count:=1", "cycle_time:=8.0")
    out = done.stdout + done.stderr
    assert done.returncode == 0, out
    assert "cycle 1: grasped" in out, out
    assert "REQUIRED process" not in out and "[ WARN]" not in out and "[ERROR]" not in out, out
    assert "needs more than" not in out, out
    # Each finger's line names it (three alike read "finger_node: grasp object ..." before), the release says it opens,
    # and no number has the double's 17 digits (".635757 Pa", "0.10000000000000001").
    speakers = set(re.findall(r"\]: (\S+): grasp object 'cylinder'", out))
    assert {"/finger_a/finger_a_node", "/finger_b/finger_b_node", "/finger_c/finger_c_node"} <= speakers, speakers
    assert "needs the most); the goal comes before" not in out and "open: vent to 0 Pa" in out, out
    text = re.sub(r"\[ ?(?:INFO|WARN|ERROR|DEBUG)\] \[\d+\.\d+(?:, \d+\.\d+)?\]", "", out)  # the stamps' own digits
    long_number = re.search(r".*\d\.\d{9,}.*", text)
    assert long_number is None, long_number.group(0)
    # The nodelet manager's own "Unloading nodelet" lines at shutdown come from several of its threads, each stamped
    # before it writes: on a loaded machine two of them swap by a millisecond or so (a CI run saw 1.2 ms). They are
    # nodelet's, not ours, and come after the run.
    ours = "\n".join(line for line in out.splitlines() if "Unloading nodelet" not in line)
    stamps = [float(m.group(1)) for m in re.finditer(r"\[ ?(?:INFO|WARN|ERROR)\] \[(\d+\.\d+)\]", ours)]
    assert len(stamps) > 20, out
    assert all(b >= a - 1e-3 for a, b in zip(stamps, stamps[1:])), out


def test_a_part_the_gripper_cannot_lift_at_this_cycle_is_refused_at_start_with_what_would_work():
    # A 150 g part at the 2 s cycle: its lift (16 m/s^2) needs about 2 N per finger, the gripper gives 0.91 N at the
    # top of its range. The sequencer refuses before the first cycle and names the heaviest part at this cycle and
    # the shortest cycle for this part (GraspHold.* checks the figures); nothing is grasped.
    done = roslaunch("pick_and_place_cell.launch", "rviz:=false", "loop_count:=1", "cycle_time:=2.0",
                     "object_mass:=0.15")
    out = done.stdout + done.stderr
    assert "cell_sequencer: the grip cannot hold a 0.15 kg part at a 2 s cycle" in out, out
    assert re.search(r"At this cycle, a part of at most 0\.0\d+ kg; for this part, a cycle of at least 5\.\d+ s", out), out
    assert "cycle 1: grasp" not in out, out


@pytest.fixture(scope="module")
def master():
    port = free_port()
    env = dict(os.environ, ROS_MASTER_URI=f"http://localhost:{port}", ROS_HOSTNAME="localhost")
    core = subprocess.Popen(["roscore", "-p", str(port)], env=env, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    for _ in range(100):
        if subprocess.run(["rosparam", "list"], env=env, capture_output=True).returncode == 0:
            break
        time.sleep(0.1)
    yield env
    core.terminate()
    core.wait()


# Every node reads its parameters with the one reader: a wrong type, a value out of range or an unknown key stops it
# with exit 2 and a message naming the key, the value and what is allowed (the core's words for a range).
REFUSALS = [
    ("gripper_action_server", {"finger_namespaces": "[/f]", "settle_timeout_s": "0.0625"},
     "parameter 'settle_timeout_s' = 0.0625 is outside its allowed range [0.1, 600] s"),
    ("gripper_action_server", {"finger_namespaces": "[/f]", "squeeze_margin": "1"},
     "unknown parameter 'squeeze_margin'"),
    ("gripper_action_server", {"finger_namespaces": "[/f, 3]"},
     "parameter 'finger_namespaces' = ['/f', 3] must be a non-empty list of non-empty strings"),
    ("gripper_action_server", {}, "parameter 'finger_namespaces' is missing"),
    ("pressure_regulator", {"finger_count": "0"},
     "parameter 'finger_count' = 0 is outside its allowed range integer in [1, 64]"),
    ("pressure_regulator", {"flow_m3_per_s": "fast"}, "parameter 'flow_m3_per_s' = 'fast' is not a number"),
    ("cell_sequencer", {"arm_joint_names": "[j1]", "home": "[0]", "above_pick": "[0]", "pick": "[0]",
                        "above_place": "[0]", "place": "[0, 1]"},
     "parameter 'place' = [0, 1] must be a list of 1 numbers"),
    ("cell_sequencer", {"arm_joint_names": "[j1]", "home": "[0]", "above_pick": "[0]", "pick": "[0]",
                        "above_place": "[0]", "place": "[0]", "cycle_time_s": "1.5"},
     "parameter 'cycle_time_s' = 1.5 is outside its allowed range [2, 600] s"),
    ("finger_node", {"max_rate_hz": "-1"}, "parameter 'max_rate_hz' = -1 is outside its allowed range [0, 100000] Hz"),
]


@pytest.mark.parametrize("node,params,message", REFUSALS)
def test_every_node_refuses_a_bad_parameter_by_name(master, node, params, message):
    subprocess.run(["rosparam", "delete", "/"], env=master, capture_output=True)
    for key, value in params.items():
        subprocess.run(["rosparam", "set", f"/{node}/{key}", value], env=master, check=True)
    done = subprocess.run(["timeout", "30", "rosrun", "pneumatic_finger", node], env=master, capture_output=True,
                          text=True)
    out = done.stdout + done.stderr
    assert done.returncode == 2, out
    assert message in out, out


def test_a_calibrated_file_with_round_values_loads_in_finger_launch(tmp_path):
    # finger_calibrate --output wrote 1e-05, a string to rosparam's YAML 1.1, and finger_node
    # refused the file ("parameter 'chamber_gap_m' = '1e-05' is not a number"). Round values, written and launched.
    out = tmp_path / "round.yaml"
    fit = subprocess.run(["rosrun", "pneumatic_finger", "finger_calibrate", "--fit", "shear_modulus_pa",
                          "--set", "chamber_gap_m=1e-5", "--set", "dead_volume_m3=1e-5", "--output", str(out)],
                         capture_output=True, text=True)
    assert fit.returncode == 0, fit.stderr
    text = out.read_text()
    assert "\nchamber_gap_m: 1.0e-05\n" in text and "\ndead_volume_m3: 1.0e-05\n" in text, text
    done = launched(25, "finger.launch", f"config:={out}", "rviz:=false")
    log = done.stdout + done.stderr
    assert "/finger_node: 7 chambers" in log, log  # the node read the file and started
    assert "is not a number" not in log and "exit code" not in log, log
    assert done.returncode == 124, log  # still running when the timeout ended it


def test_finger_launch_reads_a_drawing_and_refuses_one_a_key_contradicts(tmp_path):
    # The EPFL drawing with its chamber count changed (a sibling): the node draws 5 chambers. The same drawing with a
    # chamber_height_m that says otherwise: refused by the node, in the core's words.
    text = (ROOT / "config" / "epfl_ecoflex30_c7_coupon.yaml").read_text()
    assert "\n  chamber_count: 7\n" in text
    sibling = tmp_path / "five.yaml"
    sibling.write_text(text.replace("\n  chamber_count: 7\n", "\n  chamber_count: 5\n"))
    done = launched(20, "finger.launch", f"config:={sibling}", "rviz:=false")
    log = done.stdout + done.stderr
    assert "/finger_node: 5 chambers" in log and done.returncode == 124, log
    contradicting = tmp_path / "contradicting.yaml"
    contradicting.write_text(text + "chamber_height_m: 0.01\n")
    done = roslaunch("finger.launch", f"config:={contradicting}", "rviz:=false")
    log = done.stdout + done.stderr
    assert "parameter 'chamber_height_m' = 0.01 contradicts the drawing, which makes it 0.008" in log, log
    assert "exit code 2" in log, log


def test_each_finger_launch_starts_from_a_clean_namespace(master, tmp_path):
    # Two launches on one running master: a drawn file, then a calibrated one. Before, the second kept the first's
    # drawing/* on the server and refused its own base_segment_length_m ("contradicts the drawing"); and a calibrated
    # file's tip_uncertainty stayed on for an uncalibrated one. finger.launch clears the node's namespace first.
    port = master["ROS_MASTER_URI"].rsplit(":", 1)[1]

    def launch(config, seconds):
        done = subprocess.run(["timeout", "-k", "10", str(seconds), "roslaunch", "-p", port, "pneumatic_finger",
                               "finger.launch", f"config:={config}", "rviz:=false"], env=master,
                              capture_output=True, text=True)
        return done.stdout + done.stderr

    subprocess.run(["rosparam", "delete", "/"], env=master, capture_output=True)
    # A drawing, calibrated on chord angles alone, which bound neither the tip's angle nor its position: no error bar.
    calibrated = launch(ROOT / "config" / "epfl_ecoflex30_c7.yaml", 12)
    assert "/finger_node: 7 chambers" in calibrated and "no tip_uncertainty" in calibrated, calibrated
    undrawn = launch(ROOT / "config" / "finger.yaml", 12)  # no drawing: its own base_segment_length_m
    assert "/finger_node: 7 chambers" in undrawn and "contradicts" not in undrawn, undrawn
    launch(ROOT / "config" / "epfl_ecoflex30_c7.yaml", 12)
    uncalibrated = launch(ROOT / "config" / "epfl_ecoflex30_c7_drawing.yaml", 12)  # no error bar
    assert "the parameters have no tip_uncertainty" in uncalibrated, uncalibrated
