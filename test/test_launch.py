"""The launch files as a user starts them (roslaunch, a master of their own on a free port): a bad argument gets the
node's own message and exit, never a crash inside roslaunch or roscpp.

Run by `make run_tests` (pytest, in the devel space's environment).
"""
import os
import re
import socket
import subprocess


def free_port():
    with socket.socket() as s:
        s.bind(("localhost", 0))
        return s.getsockname()[1]


def roslaunch(*args):
    port = free_port()
    env = dict(os.environ, ROS_MASTER_URI=f"http://localhost:{port}", ROS_HOSTNAME="localhost")
    return subprocess.run(["timeout", "90", "roslaunch", "-p", str(port), "pneumatic_finger", *args],
                          capture_output=True, text=True, env=env)


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
    stamps = [float(m.group(1)) for m in re.finditer(r"\[ ?(?:INFO|WARN|ERROR)\] \[(\d+\.\d+)\]", out)]
    assert len(stamps) > 20, out
    assert all(b >= a - 1e-3 for a, b in zip(stamps, stamps[1:])), out
