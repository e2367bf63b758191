"""The Python API's lean calls: only the outputs asked for, into the caller's arrays, status as codes. Every subset and
every out= call is checked bit for bit against the full evaluate() (itself checked against the CLI in
test_python_api.py), and every bad outputs/out raises ValueError naming the problem.
"""
import itertools

import numpy
import pytest

import pneumatic_finger.core as pf

NAMES = ["stretch", "bulge_m", "half_angle_rad", "joint_angle_rad", "backbone_m", "tip_angle_rad", "status"]
# Ordinary pressures, the hard ones (rest, contact, the range's ends, far beyond) and the refused (vacuum, NaN, inf).
PRESSURES = numpy.concatenate([numpy.linspace(0, 2.9e5, 37), [1e-300, 5e-324, 3e6, 1e9, -5.0, numpy.nan, numpy.inf]])
# The two far beyond the range are clamped to it, with a RuntimeWarning (test_first_hour.py checks its words).
pytestmark = pytest.mark.filterwarnings("ignore:gauge pressure .* is above max_gauge_pa:RuntimeWarning")


def same(a, b):
    return a.dtype == b.dtype and a.shape == b.shape and numpy.array_equal(a, b, equal_nan=a.dtype.kind == "f")


@pytest.fixture(scope="module", params=[{}, {"chamber_gap_m": [3e-5, 4e-5, 5e-5, 6e-5, 5e-5, 4e-5, 3e-5]}],
                ids=["identical chambers (SIMD)", "unequal chambers (one at a time)"])
def model(request):
    return pf.FingerModel(overrides=request.param)


def test_status_is_a_uint8_array_of_codes_named_by_status(model):
    full = model.evaluate(PRESSURES)
    assert full["status"].dtype == numpy.uint8
    names = [pf.STATUS[c] for c in full["status"]]
    assert names[:37] == ["ok"] * 37
    assert names[39:41] == ["clamped to max_gauge_pa"] * 2
    assert names[-3:] == ["vacuum", "not finite", "not finite"]
    assert model.evaluate(-5.0)["status"] == pf.STATUS.index("vacuum")  # a scalar call gives the code too


@pytest.mark.parametrize("size", [1, 2, 3])
def test_every_subset_equals_the_full_evaluation_bit_for_bit(model, size):
    full = model.evaluate(PRESSURES)
    for subset in itertools.combinations(NAMES, size):
        got = model.evaluate(PRESSURES, outputs=list(subset))
        assert sorted(got) == sorted(subset)
        for name in subset:
            assert same(got[name], full[name]), (subset, name)


def test_out_fills_the_callers_arrays_bit_for_bit_and_allocates_nothing_else(model):
    full = model.evaluate(PRESSURES)
    out = {name: numpy.full_like(full[name], 7) for name in NAMES}
    got = model.evaluate(PRESSURES, out=out)
    for name in NAMES:
        assert got[name] is out[name]
        assert same(out[name], full[name]), name
    # In chunks, into slices of one array: a sweep that never allocates its outputs.
    tips = numpy.empty(len(PRESSURES))
    for start in range(0, len(PRESSURES), 8):
        model.evaluate(PRESSURES[start:start + 8], out={"tip_angle_rad": tips[start:start + 8]})
    assert same(tips, full["tip_angle_rad"])
    # outputs and out together: the rest is allocated fresh.
    mixed = model.evaluate(PRESSURES, outputs=["tip_angle_rad", "status"], out={"status": numpy.empty(len(PRESSURES),
                                                                                                       numpy.uint8)})
    assert same(mixed["tip_angle_rad"], full["tip_angle_rad"]) and same(mixed["status"], full["status"])


P = numpy.linspace(0, 2e5, 5)
BAD = [
    (dict(outputs=["tip_angle"]), "unknown output 'tip_angle' (known: stretch, bulge_m"),
    (dict(outputs="tip_angle_rad"), "outputs must be a sequence of names"),
    (dict(outputs=[3]), "outputs must be names"),
    (dict(out=[numpy.empty(5)]), "out must be a dict"),
    (dict(out={"tip_angle_rad": [0.0] * 5}), "out['tip_angle_rad']: expected a numpy float64 array of shape (5,)"),
    (dict(out={"tip_angle_rad": numpy.empty(4)}), "out['tip_angle_rad']: expected a float64 array of shape (5,), got "
                                                  "float64 of shape (4,)"),
    (dict(out={"tip_angle_rad": numpy.empty(5, numpy.float32)}), "got float32 of shape (5,)"),
    (dict(out={"status": numpy.empty(5)}), "out['status']: expected a uint8 array of shape (5,)"),
    (dict(out={"joint_angle_rad": numpy.empty((7, 5)).T}), "out['joint_angle_rad']: must be C-contiguous"),
    (dict(out={"tip_angle_rad": numpy.empty(10)[::2]}), "out['tip_angle_rad']: must be C-contiguous"),
    (dict(outputs=["status"], out={"tip_angle_rad": numpy.empty(5)}), "out['tip_angle_rad']: not among the outputs"),
]


@pytest.mark.parametrize("kwargs,message", BAD)
def test_bad_outputs_and_out_raise_value_error_naming_the_problem(kwargs, message):
    with pytest.raises(ValueError) as error:
        pf.FingerModel().evaluate(P, **kwargs)
    assert message in str(error.value)


def test_out_refuses_read_only_and_shared_memory_and_a_scalar():
    m = pf.FingerModel()
    frozen = numpy.empty(5)
    frozen.flags.writeable = False
    with pytest.raises(ValueError, match=r"out\['tip_angle_rad'\]: must be writeable"):
        m.evaluate(P, out={"tip_angle_rad": frozen})
    pressures = P.copy()
    with pytest.raises(ValueError, match="'tip_angle_rad' shares memory with 'gauge_pa'"):
        m.evaluate(pressures, out={"tip_angle_rad": pressures})
    with pytest.raises(ValueError, match="out= needs gauge_pa as a 1-D array"):
        m.evaluate(1e5, out={"tip_angle_rad": numpy.empty(1)})


def test_contact_takes_arrays_of_pressures_and_of_disks_with_the_same_rules():
    m = pf.FingerModel()
    disks = numpy.array([[0.075, 0.035, 0.01]] * 3 + [[0.07, 0.03, 0.012]] * 3)
    p = numpy.array([0.0, 1.5e5, 2.9e5] * 2)
    per_disk = m.contact(p, disk=disks)
    for i in range(6):
        alone = m.contact(p[i], disk=tuple(disks[i]))
        for name in ("joint_angle_rad", "backbone_m", "held", "first_touch_gauge_pa"):
            assert numpy.array_equal(numpy.asarray(alone[name]), per_disk[name][i], equal_nan=name != "held"), (i, name)
        assert alone["status"] == per_disk["status"][i]
    assert per_disk["held"].dtype == bool and per_disk["status"].dtype == numpy.uint8
    lean = m.contact(p, disk=disks, outputs=["first_touch_gauge_pa"])
    assert list(lean) == ["first_touch_gauge_pa"]
    assert numpy.array_equal(lean["first_touch_gauge_pa"], per_disk["first_touch_gauge_pa"], equal_nan=True)
    out = {"status": numpy.empty(6, numpy.uint8)}
    m.contact(p, disk=disks, out=out)
    assert numpy.array_equal(out["status"], per_disk["status"])
    with pytest.raises(ValueError, match=r"an array of shape \(P, 3\)"):
        m.contact(p, disk=disks[:4])
    with pytest.raises(ValueError, match="disk 2: "):
        m.contact(p, disk=numpy.array([[0.075, 0.035, 0.01]] * 2 + [[0.075, 0.035, -1.0]] * 4))


def test_sweep_designs_equals_one_model_per_design():
    base = pf.FingerModel()
    values = numpy.array([[2e-5, 0.010], [5e-5, 0.011], [1e-4, 0.0115], [-1.0, 0.0115]])
    swept = base.sweep_designs(["chamber_gap_m", "chamber_height_m"], values, 1.5e5)
    for d, (gap, height) in enumerate(values[:3]):
        alone = pf.FingerModel(overrides={"chamber_gap_m": gap, "chamber_height_m": height})
        state = alone.evaluate(1.5e5)
        assert swept["tip_angle_rad"][d] == state["tip_angle_rad"]
        assert swept["tip_x_m"][d] == state["backbone_m"][-1, 0]
        assert swept["tip_y_m"][d] == state["backbone_m"][-1, 1]
        assert swept["contact_gauge_pa"][d] == alone.contact_gauge_pa
        assert swept["snap_gauge_pa"][d] == alone.snap_gauge_pa  # inf: the paper law's walls only stiffen
        assert swept["limit_gauge_pa"][d] == alone.limit_gauge_pa
    assert numpy.isnan(swept["tip_angle_rad"][3])
    assert swept["refused"] == [(3, "parameter 'chamber_gap_m' = -1 is outside its allowed range [0, 0.1] m")]
    lean = base.sweep_designs(["chamber_gap_m", "chamber_height_m"], values, 1.5e5, outputs=["tip_angle_rad"])
    assert sorted(lean) == ["refused", "tip_angle_rad"]
    assert numpy.array_equal(lean["tip_angle_rad"], swept["tip_angle_rad"], equal_nan=True)
    with pytest.raises(ValueError, match="unknown parameter 'gap'"):
        base.sweep_designs(["gap"], values[:, :1], 1e5)
    with pytest.raises(ValueError, match=r"values must be an array of shape \(designs, len\(keys\)\)"):
        base.sweep_designs(["chamber_gap_m"], values, 1e5)
