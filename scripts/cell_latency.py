"""Latency through the gripper in the running cell: from the regulator's publish (its stamp, taken from the clock
just before it publishes) to the arrival here of finger A's joint states with that stamp (the finger nodes stamp
their output with the pressure's stamp). The path is regulator -> finger node -> this subscriber; this process's own
overhead is common to every configuration compared, so the figure is for side-by-side comparison.

usage: python3 scripts/cell_latency.py SECONDS      (with a cell running; prints one line: count, p50, p99 in us)
"""
import sys
import threading
import time

import rospy
from sensor_msgs.msg import JointState

SECONDS = float(sys.argv[1]) if len(sys.argv) > 1 else 20.0
lock = threading.Lock()
latencies = []


def on_joints(msg):
    now = time.time()  # the same clock ROS stamps with (wall time; the cell does not use simulated time)
    if msg.name and msg.name[0].startswith("finger_a_"):
        with lock:
            latencies.append(now - msg.header.stamp.to_sec())


rospy.init_node("cell_latency", anonymous=True, disable_signals=True)
rospy.Subscriber("/joint_states", JointState, on_joints, queue_size=1000, tcp_nodelay=True)
time.sleep(SECONDS)
with lock:
    values = sorted(latencies)
if not values:
    print("latency: no joint states from finger A")
    sys.exit(1)
p = lambda q: values[min(len(values) - 1, int(q * len(values)))] * 1e6  # noqa: E731
print(f"{len(values)} messages, p50 {p(0.5):.0f} us, p99 {p(0.99):.0f} us")
