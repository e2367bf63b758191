"""The pneumatic finger model from Python: the C++ core through pybind11, with the package's parameter file.

    import pneumatic_finger.core as pf
    model = pf.FingerModel()                       # config/finger.yaml, the robust solver
    state = model.evaluate(numpy.linspace(0, 2e5, 101))
    state["joint_angle_rad"]                      # (101, 7)
    tips = model.evaluate(p, outputs=["tip_angle_rad"])["tip_angle_rad"]   # computes and allocates only that
    model.evaluate(p, out={"tip_angle_rad": tips})                        # fills the caller's array
    pf.STATUS[state["status"][0]]                  # 'ok': status is a uint8 array of codes

FingerModel(config=None, overrides={}, solver="robust"): config is a parameter file (YAML) with the keys of
`finger_model --parameters`; None takes the package's config/finger.yaml. overrides sets keys on top of it (a number,
or a list with one number per chamber). A bad file, key or value raises ValueError with the tools' message.
"""
import os

from pneumatic_finger._core import CONTACT_STATUS, STATUS
from pneumatic_finger._core import FingerModel as _FingerModel
from pneumatic_finger._core import calibrate as _calibrate

__all__ = ["FingerModel", "calibrate", "default_config", "default_data", "STATUS", "CONTACT_STATUS"]


def _share(*parts):
    import rospkg
    return os.path.join(rospkg.RosPack().get_path("pneumatic_finger"), *parts)


def default_config():
    """The package's config/finger.yaml (found through ROS_PACKAGE_PATH, as roslaunch finds it)."""
    return _share("config", "finger.yaml")


def default_data():
    """The package's measured joint angles, data/sierra2022_table1.csv."""
    return _share("data", "sierra2022_table1.csv")


def calibrate(data=None, keys=None, objective="minimax", config=None, overrides=None, average_column="",
              compare=None, leave_one_out=False):
    """finger_calibrate from Python: fits one to three keys to what a CSV measured (gauge_pa and any of
    joint_1_rad..joint_N_rad, tip_angle_rad, tip_x_m,tip_y_m; None: the package's data). compare: "joints",
    "average", "joint_1", "tip_angle" or "tip_position" (None: what the file has, as the tool decides); keys None: the
    tool's default for it. Returns a dict: fitted (key -> value), compared, objective_value, residuals (per row:
    gauge_pa, measured/model joints, joints 2..N average, joint 1, tip angle and tip position), model_evaluations,
    uncertainty (key -> one standard deviation, from the fit's curvature), correlation (keys x keys), warnings (keys
    that trade off, or sit on their search range's end), and with leave_one_out=True the same rows as each is predicted by a fit to the others (finger_calibrate's
    leave-one-out table; None otherwise)."""
    return _calibrate(data if data is not None else default_data(), list(keys or []), objective,
                      config if config is not None else default_config(), dict(overrides or {}), average_column,
                      compare or "", bool(leave_one_out))


class FingerModel(_FingerModel):
    __doc__ = _FingerModel.__doc__

    def __init__(self, config=None, overrides=None, solver="robust"):
        super().__init__(config if config is not None else default_config(), dict(overrides or {}), solver)
