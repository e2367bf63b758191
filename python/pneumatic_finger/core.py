"""The pneumatic finger model from Python: the C++ core through pybind11, with the package's parameter file.

    import pneumatic_finger.core as pf
    model = pf.FingerModel()                       # config/finger.yaml, the robust solver
    state = model.evaluate(numpy.linspace(0, 2e5, 101))
    state["joint_angle_rad"]                      # (101, 7)
    tips = model.evaluate(p, outputs=["tip_angle_rad"])["tip_angle_rad"]   # computes and allocates only that
    model.evaluate(p, out={"tip_angle_rad": tips})                        # fills the caller's array
    pf.STATUS[state["status"][0]]                  # 'ok': status is uint8 codes (one code for a scalar call)

FingerModel(config=None, overrides={}, solver="robust", max_gauge_pa=None): config is a parameter file (YAML) with
the keys of `finger_model --parameters`; None takes the package's config/finger.yaml. overrides sets keys on top of it
(a number, or a list with one number per chamber). max_gauge_pa is the top of the model's range (None: 3 kg/cm2, as
finger_node): evaluate() clamps a pressure above it to it, with status "clamped to max_gauge_pa" and a
RuntimeWarning. A bad file, key or value raises ValueError with the tools' message.
"""
import os

from pneumatic_finger._core import CONTACT_STATUS, STATUS, STATUS_FLAGS
from pneumatic_finger._core import FingerModel as _FingerModel
from pneumatic_finger._core import calibrate as _calibrate
from pneumatic_finger._core import design_to_target as _design_to_target
from pneumatic_finger._core import fit_coupon as _fit_coupon
from pneumatic_finger._core import grip_gauge_pa as _grip_gauge_pa
from pneumatic_finger._core import range_check

__all__ = ["FingerModel", "calibrate", "fit_coupon", "default_config", "default_data", "range_check", "STATUS", "STATUS_FLAGS",
           "status_flag_names", "CONTACT_STATUS"]


def _share(*parts):
    import rospkg
    return os.path.join(rospkg.RosPack().get_path("pneumatic_finger"), *parts)


def default_config():
    """The package's config/finger.yaml (found through ROS_PACKAGE_PATH, as roslaunch finds it)."""
    return _share("config", "finger.yaml")


def default_data():
    """The package's measured joint angles, data/sierra2022_table1.csv."""
    return _share("data", "sierra2022_table1.csv")


def status_flag_names(flags):
    """The names of the flags set in a status_flags code (evaluate()'s), as finger_model and finger_state name them:
    e.g. ['clamped', 'meets itself']; [] for 0. STATUS_FLAGS[b] names bit b."""
    return [name for bit, name in enumerate(STATUS_FLAGS) if int(flags) >> bit & 1]


def _keys(keys):
    # "a,b" as finger_calibrate --fit takes it, or a sequence of names.
    if keys is None:
        return []
    if isinstance(keys, str):
        return [k.strip() for k in keys.split(",") if k.strip()]
    return [str(k) for k in keys]


def _data(data):
    # A CSV path, or a mapping of column names to numbers (a dict of arrays or lists, a pandas DataFrame).
    if data is None:
        return default_data(), [], []
    if isinstance(data, (str, os.PathLike)):
        return os.fspath(data), [], []
    if isinstance(data, (list, tuple)) and data and all(isinstance(d, (str, os.PathLike)) for d in data):
        return [os.fspath(d) for d in data], [], []  # several files of one actuator, as --data repeated
    if hasattr(data, "keys"):
        import numpy
        names = [str(k) for k in data.keys()]
        columns = []
        for name in names:
            values = numpy.asarray(data[name], dtype=float)
            if values.ndim > 1:
                raise ValueError("data: column %s must be one number per row, got shape %s" % (name, values.shape))
            columns.append(values.ravel().tolist())
        return None, names, columns
    raise ValueError("data must be a CSV path or a mapping of column names to numbers (gauge_pa and any of "
                     "joint_1_rad..joint_N_rad, tip_angle_rad, chord_angle_rad, tip_x_m,tip_y_m), got %s" % type(data).__name__)


def calibrate(data=None, keys=None, objective="minimax", config=None, overrides=None, average_column="",
              compare=None, leave_one_out=True, wall_law=None, drive=None, output=None):
    """finger_calibrate from Python: the same defaults, data check, fit and leave-one-out.

    data: a CSV path (or a list of them: one actuator's files, its bends and its blocked force), or a mapping of
    column names to arrays: gauge_pa and/or supplied_volume_m3, and any of joint_1_rad..joint_N_rad, tip_angle_rad,
    chord_angle_rad (base to tip), tip_x_m,tip_y_m, blocked_tip_force_n (None: the package's data).
    keys: the keys to fit (any number), a list or "a,b" (None: the tool's default). compare: "joints", "average",
    "joint_1", "tip_angle", "tip_position", "chord_angle" or
    "gauge_pa" (the model's pressure at each row's volume; needs drive="volume"), "tip_angle+gauge_pa" or
    "gauge_at_tip_angle" (None: what the data has, as the CLI chooses; by volume with gauge_pa, "tip_angle+gauge_pa"). drive:
    "pressure" (each row set by its gauge_pa) or "volume" (by its supplied_volume_m3; the pressure is then an output)
    (None: pressure where the data has gauge_pa). wall_law: "auto" (choose the law, the keys and the comparison by their bends held out: docs/CALIBRATE.md, "What auto chooses"), "paper", "membrane" or "thick" (None:
    the parameter file's).

    Returns a dict: fitted (key -> value), wall_law, compared, objective_value, residuals (a dict of arrays, a row
    per measurement: gauge_pa (R,), supplied_volume_m3, measured_/model_gauge_pa (R,), measured_/model_joint_rad (R, N), measured_/model_avg_rad, _joint1_rad,
    _tip_angle_rad, _chord_angle_rad, _blocked_tip_force_n (R,), measured_/model_tip_m (R, 2); NaN where nothing was
    measured), model_evaluations,
    uncertainty (key -> one standard deviation), correlation (keys x keys array), warnings (columns not read, keys
    that trade off or sit on their search range's end), and leave_one_out: the residuals of each row predicted by a
    fit to the others, as the CLI reports them (so the data need the CLI's rows: two more than the chamber keys);
    leave_one_out=False is the quick fit alone (no leave-one-out, no error bar, None here, and no output=);
    parameter_file: the text of the calibrated parameter file. output: a path to write that file to, as `finger_calibrate --output` does (the
    fitted keys, the calibrated range validated_max_gauge_pa, the error bar), which finger_node, finger_model and
    FingerModel(config=) load alike."""
    if output is not None and not leave_one_out:
        raise ValueError("output= writes finger_calibrate's file, whose error bar needs leave-one-out: drop "
                         "leave_one_out=False")
    path, names, columns = _data(data)
    result = _calibrate(path, names, columns, _keys(keys), objective,
                        config if config is not None else default_config(), dict(overrides or {}), average_column,
                        compare or "", wall_law or "", bool(leave_one_out) or wall_law == "auto", drive or "")
    if output is not None:
        with open(output, "w") as f:
            f.write("# A calibrated actuator, written by pneumatic_finger.core.calibrate(output=): the base parameters "
                    "with the\n# fitted keys replaced (docs/CALIBRATE.md). Load it with finger.launch config:=FILE.\n"
                    + result["parameter_file"])
    return result


def design_to_target(targets, free, config=None, overrides=None, chamber_counts=None, castable_m=1e-3,
                     max_body_m=(0.0, 0.0, 0.0), output=None, pareto=0, part=None):
    """finger_design --target from Python: the drawing that meets the targets, from a calibrated file's material.

    targets: "QUANTITY=VALUE" or "QUANTITY@AT=VALUE" strings (snap_gauge_pa, limit_gauge_pa, contact_gauge_pa in Pa;
    tip_angle_rad, chord_angle_rad at a pressure, blocked_tip_force_n at a pressure; gauge_for_tip_angle at an angle
    in rad; grip_gauge_pa, the lowest pressure that holds part, "=min" for as low as the bounds allow). part: for
    grip_gauge_pa, "mass_kg=M,diameter_m=D[,lift_mps2=A,fingers=3,mount_radius_m=0.035,friction=1,margin=1.5,limit_share=0.9]" (the
    gripper's defaults are the shipped gripper's and the cell's; the part is held at most at the file's max_gauge_pa).
    free: the drawing sizes it may change, a list of "drawing/KEY" (bounds: a quarter to four times the drawn
    size) or a dict {"drawing/KEY": (lo, hi)} in m. chamber_counts: the whole numbers to try (None: the drawing's).
    castable_m: the thinnest wall, end wall or roof. max_body_m: the body's largest (length, width, height), 0: none.

    Returns a dict: values (key -> m), drawn (key -> the base drawing's size, m), chamber_count, achieved (target -> value), miss (the largest relative miss),
    met, at_bound (the keys that stop it, where not met), reach (the largest |ln(size / drawn)|: how far the answer
    leaves the base drawing), seconds, parameter_file (its text; output= writes it, as finger_design --output), and
    pareto: with pareto=N (two targets or more), the Pareto front of targets that pull against each other, a list of
    dicts (values, chamber_count, achieved, misses: each target's relative miss, reach), the weights of the targets'
    squared misses stepping by 1/N over the simplex; [] otherwise."""
    bounds = dict(free) if isinstance(free, dict) else {key: (0.0, 0.0) for key in free}
    result = _design_to_target(config if config is not None else default_config(), dict(overrides or {}),
                               list(targets), {k: list(v) for k, v in bounds.items()}, list(chamber_counts or []),
                               float(castable_m), [float(x) for x in max_body_m], int(pareto), part or "")
    if output is not None:
        with open(output, "w") as f:
            f.write(result["parameter_file"])
    return result


def grip_gauge_pa(part, config=None, overrides=None, max_gauge_pa=None):
    """finger_model --pressures --grip-part from Python: the lowest gauge pressure (Pa) at which a ring of these
    fingers holds a part by its side, by the cell's grasp rule (docs/DESIGN.md, "A grip").

    part: "mass_kg=M,diameter_m=D[,lift_mps2=A,fingers=3,mount_radius_m=0.035,friction=1,margin=1.5,limit_share=0.9]".
    The search goes up to max_gauge_pa (None: the file's) and limit_share of the walls' limit point. Returns nan,
    with a RuntimeWarning saying why, where no pressure there holds it."""
    import warnings
    gauge_pa, why = _grip_gauge_pa(config if config is not None else default_config(), dict(overrides or {}), part,
                                   max_gauge_pa)
    if why:
        warnings.warn(f"the part is not held: {why}", RuntimeWarning, stacklevel=2)
    return gauge_pa


def fit_coupon(data, law="gent", config=None, overrides=None, output=None):
    """finger_calibrate --coupon from Python: the elastomer's shear_modulus_pa and wall_locking_jm fitted to a uniaxial
    coupon test (Ceres Solver; least squares on the relative stress error), with the same checks and words.

    data: a CSV path (engineering_strain, nominal_stress_pa columns) or a mapping with those two keys (arrays; the
    strain a ratio, the stress in Pa). law: "gent" or "neo-hookean". config and overrides: the base parameter file
    (membrane or thick law; None: the package's, which the paper law refuses) into which the material goes.

    Returns a dict: shear_modulus_pa, wall_locking_jm (0: no locking), preload_strain (the test's zero taken
    stretched), uncertainty (key -> one standard deviation), rms_relative_error, max_relative_error,
    engineering_strain, nominal_stress_pa and model_stress_pa (arrays, a row per coupon row), report (text) and
    parameter_file (the text output= writes, as `finger_calibrate --coupon --output`)."""
    if isinstance(data, (str, os.PathLike)):
        path, strain, stress = os.fspath(data), [], []
    elif hasattr(data, "keys"):
        missing = [k for k in ("engineering_strain", "nominal_stress_pa") if k not in data]
        if missing:
            raise ValueError("data needs the columns engineering_strain and nominal_stress_pa; missing: "
                             + ", ".join(missing))
        path = None
        strain, stress = (_finite_list(data[k], k) for k in ("engineering_strain", "nominal_stress_pa"))
    else:
        raise ValueError("data must be a coupon CSV path or a mapping with engineering_strain and nominal_stress_pa, "
                         "got %s" % type(data).__name__)
    result = _fit_coupon(path, strain, stress, law, config if config is not None else default_config(),
                         dict(overrides or {}))
    if output is not None:
        with open(output, "w") as f:
            f.write("# An elastomer from its coupon test, written by pneumatic_finger.core.fit_coupon(output=): the "
                    "base parameters\n# with the wall law's material replaced (docs/CALIBRATE.md); nothing is fitted "
                    "to an actuator.\n" + result["report"] + "\n" + result["parameter_file"])
    return result


def _finite_list(values, name):
    """A 1-D sequence of numbers as a list of floats, or ValueError naming the column."""
    import numpy
    array = numpy.asarray(values)
    if array.ndim != 1 or not numpy.issubdtype(array.dtype, numpy.number):
        raise ValueError(f"{name} must be a 1-D sequence of numbers, got {array.dtype} of shape {array.shape}")
    return array.astype(float).tolist()


class FingerModel(_FingerModel):
    __doc__ = _FingerModel.__doc__

    def __init__(self, config=None, overrides=None, solver="robust", max_gauge_pa=None):
        super().__init__(config if config is not None else default_config(), dict(overrides or {}), solver,
                         max_gauge_pa)
