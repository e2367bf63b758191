"""Writes test/data/pressure_ramp.bag: what a regulator recorded with `rosbag record /pressure` would hold.
2 s of sensor_msgs/FluidPressure at 50 Hz on /pressure, stamped with their record time starting at t = 100 s,
the gauge pressure ramping from 0 to 2 kg/cm^2. The bag-loop rostest plays it with --clock --loop.

usage: python3 scripts/make_test_bag.py     (needs python3-rosbag and python3-sensor-msgs)
"""
import pathlib

import rosbag
import rospy
from sensor_msgs.msg import FluidPressure

ROOT = pathlib.Path(__file__).resolve().parent.parent
OUT = ROOT / "test/data/pressure_ramp.bag"
ATMOSPHERE_PA, KGF_PER_CM2_PA = 101325.0, 98066.5
with rosbag.Bag(str(OUT), "w") as bag:
    for i in range(100):
        t = rospy.Time.from_sec(100.0 + 0.02 * i)
        msg = FluidPressure()
        msg.header.stamp = t
        msg.header.frame_id = "regulator"
        msg.fluid_pressure = ATMOSPHERE_PA + 2 * KGF_PER_CM2_PA * i / 99
        bag.write("/pressure", msg, t)
print(f"wrote {OUT}")
