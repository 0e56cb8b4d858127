"""Property-based test (Hypothesis) of every public function that takes numbers or recordings:
random dtypes (float, int, bool, complex, str, bytes, object), shapes (0-d to 2-d, empty),
lengths (mismatched on purpose), NaN and inf. Each call either returns or raises one of the
documented exceptions (docs/python.md, "Errors"); anything else -- a crash, InternalError, a
ValueError or IndexError from inside -- fails the test. A SIGSEGV kills the interpreter and
fails the CTest.

Bounded time: max_examples per property (below) keeps the whole file near 20 s on one core of the
CI machine; arrays have at most 24 samples so no single call simulates or trains for long.
"""
import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings, strategies as st
from hypothesis.extra import numpy as hnp

import sysid

# What a public function may raise on bad input (docs/python.md): the library's errors for bad
# data, options and numerical failures, and TypeError for an argument of the wrong Python kind.
DOCUMENTED = (sysid.DataError, sysid.OptionsError, sysid.NumericalError, TypeError)

# Enough examples to hit every dtype x shape class several times; the deadline is generous
# because the first call of a property imports and warms up (the bound is the CTest timeout).
FUZZ = settings(max_examples=60, deadline=None, derandomize=True,
                suppress_health_check=[HealthCheck.too_slow, HealthCheck.data_too_large])
SLOW = settings(FUZZ, max_examples=25)

MAX_LEN = 24

REAL_DTYPES = [np.float64, np.float32, np.int64, np.int32, np.uint8, np.bool_]
BAD_DTYPES = [np.complex128, np.dtype("<U3"), np.dtype("S3"), np.dtype(object)]


def real_elements(dtype):
    if np.dtype(dtype).kind == "f":
        return st.floats(allow_nan=True, allow_infinity=True, width=32)
    return None  # hypothesis' default for the dtype


@st.composite
def arrays(draw, min_dims=0, max_dims=2):
    """An array of any dtype (mostly real), any shape up to 2-d, possibly empty, NaN and inf;
    sometimes a plain list or a scalar instead of an ndarray."""
    bad = draw(st.booleans()) and draw(st.booleans())  # a quarter of the draws
    dtype = draw(st.sampled_from(BAD_DTYPES if bad else REAL_DTYPES))
    shape = draw(hnp.array_shapes(min_dims=min_dims, max_dims=max_dims, min_side=0,
                                  max_side=MAX_LEN))
    if np.dtype(dtype) == np.dtype(object):
        a = np.empty(shape, dtype=object)
        a.fill(draw(st.sampled_from([None, "x", 1.5, b"y", (1, 2)])))
    else:
        a = draw(hnp.arrays(dtype, shape, elements=real_elements(dtype)))
    form = draw(st.sampled_from(["array", "array", "list", "scalar"]))
    if form == "list":
        return a.tolist()
    if form == "scalar" and a.size:
        return a.flat[0]
    return a


@st.composite
def vectors(draw, length=None):
    """A real 1-d float vector of `length` (or random) samples, with NaN and inf sometimes."""
    n = length if length is not None else draw(st.integers(0, MAX_LEN))
    finite = draw(st.booleans())
    return draw(hnp.arrays(np.float64, n, elements=st.floats(
        -10, 10, allow_nan=not finite, allow_infinity=not finite)))


@st.composite
def recordings(draw):
    """A recording that passes the reader's rules: t uniform, u and x finite floats."""
    n = draw(st.integers(3, MAX_LEN))
    dt = draw(st.sampled_from([1e-3, 1e-2]))
    t = np.arange(n) * dt
    elements = st.floats(-2, 2, allow_nan=False, allow_infinity=False)
    u = draw(hnp.arrays(np.float64, n, elements=elements))
    x = draw(hnp.arrays(np.float64, n, elements=elements)) * 1e-3
    cols = {"t": t, "u": u, "x": x}
    if draw(st.booleans()):
        cols["v"] = np.gradient(x, dt)
        cols["a"] = np.gradient(cols["v"], dt)
    return sysid.recording(source="fuzz", **cols)


def returns_or_documented(call, *args, **kwargs):
    try:
        return call(*args, **kwargs)
    except DOCUMENTED:
        return None


MODEL = sysid.Model.paper()
NET = sysid.Network([sysid.ScaledVariable("v", "m/s", -0.1, 0.1),
                     sysid.ScaledVariable("a", "m/s^2", -1.0, 1.0)],
                    sysid.ScaledVariable("u", "V", -2.0, 2.0), 3)
# A classical PI hysteresis model (test_hysteresis.py's truth): x = c u + sum w_i F_r_i(u) + offset.
PI = sysid._sysid.hysteresis_model_from_json(
    '{"kind": "pi", "thresholds": [0.5, 1.0], "weights": [2e-6, 1e-6], "polynomial": [3e-6], '
    '"offset_m": -1e-4, "input_min_v": 0, "input_max_v": 3.6}', "pi.json")


# ---- The cases of issue 29, exactly --------------------------------------------------------

def test_issue_cases():
    with pytest.raises(sysid.DataError, match=r"column 'u': expected real numbers, got dtype <U1"):
        sysid.recording(t=np.arange(10) * 1e-3, u=np.array(["a"] * 10), x=np.zeros(10))
    with pytest.raises(sysid.DataError, match=r"'u': expected real numbers, got dtype <U1"):
        sysid.recording(t=list(np.arange(10) * 1e-3), u=["a"] * 10, x=[0.0] * 10)
    with pytest.raises(sysid.DataError, match=r"'u': expected real numbers, got dtype \|S1"):
        sysid.recording(t=np.arange(10) * 1e-3, u=[b"a"] * 10, x=np.zeros(10))
    with pytest.raises(sysid.DataError, match="'u': expected real numbers, got dtype complex128"):
        sysid.recording(t=np.arange(3) * 1e-3, u=np.array([1 + 1j, 2, 3]), x=np.zeros(3))
    with pytest.raises(sysid.DataError, match="'u': expected real numbers, got dtype object"):
        sysid.recording(t=np.arange(3) * 1e-3, u=[None, 1.0, 2.0], x=np.zeros(3))
    v = np.full(10, 0.01)
    with pytest.raises(sysid.DataError, match="v_mps has 10 values, a_mps2 has 5"):
        sysid.analytic_inverse(MODEL, 1e-3, v, np.zeros(5))
    with pytest.raises(sysid.DataError, match="v_mps has 2000000 values, a_mps2 has 1"):
        sysid.analytic_inverse(MODEL, 1e-3, np.zeros(2_000_000), np.zeros(1))
    # With equal lengths, the right answer: (a1p v + a2p) / a3 at a steady slide.
    u = sysid.analytic_inverse(MODEL, 1e-3, v, np.zeros(10))
    assert u[-1] == pytest.approx((MODEL.a1p * 0.01 + MODEL.a2p) / MODEL.a3, rel=1e-12)
    with pytest.raises(sysid.DataError, match="v_mps has 10 values, a_mps2 has 5"):
        sysid.network_inverse(NET, v, np.zeros(5))
    with pytest.raises(sysid.DataError, match="a_mps2: expected real numbers, got dtype complex"):
        sysid.analytic_inverse(MODEL, 1e-3, v, v * (1 + 1j))
    rec = sysid.read_recording(sysid_virtual() / "pulses.csv")
    for call in (sysid.dominance, sysid.tune_delay, sysid.refine):
        with pytest.raises(sysid.DataError, match="recordings: no recordings"):
            call(MODEL, [])
    with pytest.raises(sysid.DataError, match="recordings: no recordings"):
        sysid.identify_pulses([])
    assert len(rec) > 0


def test_audit_cases():
    # detect_pulses, HysteresisModel.simulate / .invert and analytic_inverse's model skipped the
    # rules above: lengths were an InternalError, "1e-5" was parsed, 1+1j lost its imaginary
    # part, None became NaN, dt_s = nan and a3 = 0 (u = inf) were accepted.
    t = np.arange(20) * 0.1
    u = np.where((t > 0.55) & (t < 1.15), 1.5, 0.0)  # 1.5 V on rows 6..11 (0.6 s >= 0.2 s)
    with pytest.raises(sysid.DataError, match="detect_pulses: t_s has 20 values, u_v has 10"):
        sysid.detect_pulses(t, u[:10])
    with pytest.raises(sysid.DataError, match="u_v: expected real numbers, got dtype <U"):
        sysid.detect_pulses(t, u.astype(str))
    (pulse,) = sysid.detect_pulses(t, u)
    assert (pulse.first_row, pulse.end_row, pulse.amplitude_v) == (6, 12, 1.5)
    assert pulse.duration_s == pytest.approx(0.6, rel=1e-12)
    assert len(sysid.detect_pulses(list(t), (u > 0).astype(int))) == 1  # int: converted, 1 V
    for call, name in ((PI.simulate, "u_v"), (PI.simulate_periodic, "u_period_v"),
                       (PI.invert, "x_m")):
        expected = f"{name}: expected real numbers, got dtype"
        with pytest.raises(sysid.DataError, match=f"{expected} complex"):
            call(np.full(5, 1e-5 + 1e-3j), 1e-3)
        with pytest.raises(sysid.DataError, match=f"{expected} <U4"):
            call(np.array(["1e-5"] * 3), 1e-3)
        with pytest.raises(sysid.DataError, match=f"{expected} object"):
            call([None, 1e-5], 1e-3)
        with pytest.raises(sysid.DataError, match=f"{name}: expected a 1-D array, got 2 dim"):
            call(np.full((3, 3), 1e-5), 1e-3)
        for dt in (float("nan"), 0.0, -1e-3, float("inf")):
            with pytest.raises(sysid.OptionsError, match=r"dt_s = .*0 < dt_s < infinity"):
                call(np.full(5, 2e-6), dt)
    # The reference: the model's own closed form (the PI is exact), u = 2 V from rest, x(0) = 0
    # state: x = 3e-6 u + 2e-6 (u - 0.5) + 1e-6 (u - 1) - 1e-4; an int array gives the same.
    x = PI.simulate(np.array([2]), 1e-3)
    assert x[0] == pytest.approx(3e-6 * 2 + 2e-6 * 1.5 + 1e-6 * 1.0 - 1e-4, rel=1e-12)
    assert np.array_equal(PI.simulate([0, 1, 2, 3, 2], 1e-3), PI.simulate(
        np.array([0.0, 1.0, 2.0, 3.0, 2.0]), 1e-3))
    v = np.full(5, 0.01)
    for bad, rule in ((dict(a3=0.0), "a3 = 0. Violated constraint: a3 > 0"),
                      (dict(a1p=float("nan")), "a1p = nan. Violated constraint: finite")):
        model = sysid.Model(**{**dict(a1p=1.0, a1n=1.0, a2p=1.0, a2n=1.0, a3=6.0, tau_s=0.0),
                               **bad})
        with pytest.raises(sysid.OptionsError, match=rule):
            sysid.analytic_inverse(model, 1e-3, v, np.zeros(5))
        # The Model's own elementwise methods refuse it too (they returned inf / NaN).
        with pytest.raises(sysid.OptionsError, match=rule):
            model.steady_velocity([1.0, 2.0])
        with pytest.raises(sysid.OptionsError, match=rule):
            model.inverse_voltage(1.0, 0.1, 0.1)
    # A valid model still answers, against the closed forms by hand (a1p = 2, a2p = 1, a3 = 6):
    # v = (6 u - 1) / 2 at u = 1 V; u = (a + a1p v_d + a2p) / a3 = (3 + 2 * 0.5 + 1) / 6.
    good = sysid.Model(a1p=2.0, a1n=4.0, a2p=1.0, a2n=1.0, a3=6.0, tau_s=0.0)
    assert good.steady_velocity(1.0) == pytest.approx(2.5, rel=1e-15)
    assert good.inverse_voltage(3.0, 0.5, 0.5) == pytest.approx(5.0 / 6.0, rel=1e-15)
    # a1 = 0 is valid (pure Coulomb): the unbalanced force has no steady state, +inf.
    assert sysid.Model(a1p=0.0, a1n=1.0, a2p=1.0, a2n=1.0, a3=6.0).steady_velocity(1.0) == np.inf


def sysid_virtual():
    from conftest import VIRTUAL
    return VIRTUAL


# ---- Functions of arrays -----------------------------------------------------------------

@FUZZ
@given(t=arrays(), u=arrays(), x=arrays())
def test_recording_from_arrays(t, u, x):
    rec = returns_or_documented(sysid.recording, t=t, u=u, x=x)
    if rec is not None:
        assert rec.rows == len(np.atleast_1d(t)) and rec.names == ["t", "u", "x"]
        assert np.all(np.isfinite(rec.data))  # the reader's rules: finite numbers only


@FUZZ
@given(a=arrays(), b=arrays(), c=arrays(), dt=st.floats(allow_nan=True))
def test_elementwise_and_vector_functions(a, b, c, dt):
    returns_or_documented(sysid.analyze_sampling, a)
    returns_or_documented(sysid.differentiate, a, abs(dt) if dt == dt else dt)
    returns_or_documented(MODEL.steady_velocity, a)
    returns_or_documented(MODEL.inverse_voltage, a, b, c)
    returns_or_documented(sysid.stage.StageParameters.default().steady_velocity, a)
    wave = sysid.stage.VelocityWaveform.sine(1e-3, 2.0)
    returns_or_documented(wave.velocity, a)
    returns_or_documented(wave.position, a)
    returns_or_documented(sysid.analytic_inverse, MODEL, dt, a, b)
    returns_or_documented(sysid.network_inverse, NET, a, b)
    returns_or_documented(sysid.detect_pulses, a, b)
    returns_or_documented(PI.simulate, a, dt)
    returns_or_documented(PI.invert, a, dt)
    returns_or_documented(NET.predict, a)
    returns_or_documented(NET.predict, {"v": a, "a": b})
    net = sysid.Network([sysid.ScaledVariable("v")], sysid.ScaledVariable("u"), 2)
    returns_or_documented(setattr, net, "parameters", a)
    returns_or_documented(sysid.stage.reference_from_positions, a, b)
    signal = returns_or_documented(sysid.table_input, a, b)
    if signal is not None:
        returns_or_documented(signal.value, c)
    rec = sysid.Recording()
    returns_or_documented(rec.set_column, "t", a)
    returns_or_documented(rec.set_column, "u", b)


@SLOW
@given(a=arrays(max_dims=1), b=arrays(max_dims=1))
def test_simulation_and_stage(a, b):
    returns_or_documented(sysid.simulate, MODEL, (a, b), t_end_s=0.02)
    returns_or_documented(sysid.stage.run_open_loop, sysid.stage.StageParameters.default(), a)


# ---- Functions of recordings -----------------------------------------------------------------

@SLOW
@given(rec=recordings(), levels=arrays(max_dims=1))
def test_recording_consumers(rec, levels):
    returns_or_documented(sysid.derive, rec)
    returns_or_documented(sysid.extract_motion, rec)
    returns_or_documented(sysid.resample, rec, 500.0)
    returns_or_documented(sysid.identify_pulses, rec)
    returns_or_documented(sysid.identify_trajectory, rec)
    returns_or_documented(sysid.dominance, MODEL, rec)
    returns_or_documented(sysid.dominance, MODEL, [rec, rec])
    returns_or_documented(sysid.tune_delay, MODEL, rec)
    returns_or_documented(sysid.refine, MODEL, rec, max_iterations=3)
    returns_or_documented(sysid.voltage_loop, rec, levels)
    if "v" in rec:
        data = returns_or_documented(sysid.make_dataset, rec, ["v"], "u")
        if data is not None:
            trained = returns_or_documented(sysid.train, data, hidden=2, max_epochs=5)
            if trained is not None:
                returns_or_documented(sysid.mean_squared_error, trained.network, data)


@SLOW
@given(empty=st.sampled_from([[], (), [[]], [[], []]]),
       junk=st.sampled_from([1, 2.5, None, np.zeros(3), {"t": 1}, b"x"]))
def test_recording_arguments_empty_or_of_the_wrong_kind(empty, junk):
    for bad in (empty, junk):
        for call in (lambda r: sysid.dominance(MODEL, r), lambda r: sysid.tune_delay(MODEL, r),
                     lambda r: sysid.refine(MODEL, r), sysid.identify_pulses,
                     sysid.identify_trajectory, sysid.derive, sysid.voltage_loop):
            with pytest.raises(DOCUMENTED):
                call(bad)
