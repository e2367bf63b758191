# The README's Python example (its output is in the README, made by running this file).
import numpy, pneumatic_finger.core as pf
model = pf.FingerModel()                                   # config/finger.yaml, solver "robust"
s = model.evaluate(numpy.linspace(0, 196133, 5))           # gauge Pa: 0 .. 2 kg/cm^2
print(s["joint_angle_rad"].shape, s["backbone_m"].shape)   # (P, N), (P, N+2, 2)
print(s["tip_angle_rad"])                                  # Theta_N (rad)
print(model.gauge_for_tip_angle(1.0))                      # Pa for a 1 rad tip
