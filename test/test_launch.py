"""The launch files as a user starts them (roslaunch, a master of their own on a free port): a bad argument gets the
node's own message and exit, never a crash inside roslaunch or roscpp.

Run by `make run_tests` (pytest, in the devel space's environment).
"""
import os
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
