"""The pneumatic finger model from Python: the C++ core through pybind11, with the package's parameter file.

    import pneumatic_finger.core as pf
    model = pf.FingerModel()                       # config/finger.yaml, the robust solver
    state = model.evaluate(numpy.linspace(0, 2e5, 101))
    state["joint_angle_rad"]                      # (101, 7)

FingerModel(config=None, overrides={}, solver="robust"): config is a parameter file (YAML) with the keys of
`finger_model --parameters`; None takes the package's config/finger.yaml. overrides sets keys on top of it (a number,
or a list with one number per chamber). A bad file, key or value raises ValueError with the tools' message.
"""
import os

from pneumatic_finger._core import FingerModel as _FingerModel

__all__ = ["FingerModel", "default_config"]


def default_config():
    """The package's config/finger.yaml (found through ROS_PACKAGE_PATH, as roslaunch finds it)."""
    import rospkg
    return os.path.join(rospkg.RosPack().get_path("pneumatic_finger"), "config", "finger.yaml")


class FingerModel(_FingerModel):
    __doc__ = _FingerModel.__doc__

    def __init__(self, config=None, overrides=None, solver="robust"):
        super().__init__(config if config is not None else default_config(), dict(overrides or {}), solver)
