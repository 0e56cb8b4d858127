"""sysid.validate and its pieces: fit % by MATLAB compare's formula written in NumPy, the
correlations against numpy.correlate, and the binding against `sysid validate --json` of the
same build (the CLI prints 17 digits, so the numbers must be equal)."""
import math

import numpy as np
import pytest

import sysid
from conftest import VIRTUAL, cli_json


def test_score_fit_is_matlab_compare_formula():
    rng = np.random.default_rng(4)
    y = np.cumsum(rng.normal(size=300))
    yhat = y + 0.3 * rng.normal(size=300)
    s = sysid.score_fit(y, yhat)
    fit = 100 * (1 - np.linalg.norm(y - yhat) / np.linalg.norm(y - y.mean()))
    rmse = math.sqrt(np.mean((y - yhat) ** 2))
    assert s.fit_percent == pytest.approx(fit, rel=1e-13)
    assert s.rmse == pytest.approx(rmse, rel=1e-13)
    assert s.nrmse_std == pytest.approx(rmse / np.std(y), rel=1e-13)
    assert s.nrmse_range == pytest.approx(rmse / np.ptp(y), rel=1e-13)
    assert sysid.score_fit([1, 2, 3, 4], [1, 2, 3, 5]).fit_percent == pytest.approx(
        100 * (1 - 1 / math.sqrt(5)), rel=1e-14)


def test_correlations_match_numpy_correlate():
    rng = np.random.default_rng(5)
    e = rng.normal(size=500) + 2.0
    u = np.convolve(rng.normal(size=500), [1, 0.5, 0.25], mode="same")
    ce, cu = e - e.mean(), u - u.mean()
    full_ee = np.correlate(ce, ce, mode="full")[len(e) - 1:]   # sum_t e_{t+k} e_t, k >= 0
    full_eu = np.correlate(ce, cu, mode="full")[len(e) - 1:]   # sum_t e_{t+k} u_t
    r = sysid.normalised_autocorrelation(e, 20)
    c = sysid.normalised_cross_correlation(e, u, 20)
    np.testing.assert_allclose(r, full_ee[:21] / (ce @ ce), rtol=0, atol=1e-13)
    np.testing.assert_allclose(c, full_eu[:21] / math.sqrt((ce @ ce) * (cu @ cu)), rtol=0,
                               atol=1e-13)
    with pytest.raises(sysid.OptionsError):
        sysid.normalised_autocorrelation(e, 500)


def test_validate_matches_cli(model_file):
    rec = VIRTUAL / "waveform_square.csv"
    j = cli_json("validate", "--model", model_file, "--lags", 12, rec)
    [v] = sysid.validate(model_file, rec, max_lag=12)
    assert v.model_kind == "friction"
    assert [o.output for o in v.outputs] == ["v", "x"]
    d = v.to_dict()
    assert d == j["recordings"][0]
    out = v.outputs[0]
    assert out.scores.fit_percent == j["recordings"][0]["outputs"][0]["fit_percent"]
    assert len(out.autocorrelation.r) == 12 and list(out.cross_correlation.lags) == list(range(13))
    n = len(v.t_s)
    assert out.autocorrelation.bound == pytest.approx(2.58 / math.sqrt(n), rel=1e-15)
    assert out.measured.shape == out.simulated.shape == (n,)


def test_validate_own_simulation_scores_100():
    model = sysid.Model.paper()
    t = np.arange(1500) * 1e-3
    u = np.where((t % 0.5) < 0.1, 2.0, np.where(((t % 0.5) > 0.25) & ((t % 0.5) < 0.35), -2.2, 0))
    sim = sysid.simulate(model, (t, u), output_times_s=list(t), t0_s=0, t_end_s=t[-1],
                         rtol=1e-8, atol=1e-12)
    tr = sim.trajectory
    rec = sysid.recording(t=tr.t_s, u=tr.u_v, x=tr.x_m, v=tr.v_mps, a=tr.a_mps2)
    [v] = sysid.validate(model, rec)
    for o in v.outputs:
        assert o.scores.fit_percent > 99.99
    wrong = sysid.Model.paper()
    wrong.a3 *= 1.3
    [w] = sysid.validate(wrong, rec)
    assert w.outputs[0].scores.fit_percent < 95
    assert not w.outputs[0].cross_correlation.passed
