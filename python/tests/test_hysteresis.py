"""sysid.hysteresis: fit, simulate, invert from Python, against the library's own closed forms
and the CLI of the same build."""
import json
import math

import numpy as np
import pandas
import pytest

import sysid
import sysid.hysteresis as hy
from conftest import run_cli


def _pi_recording(n=1500, dt=0.005):
    # A known classical PI written as a model file, simulated by the library: the fit must find
    # a model that reproduces it and whose closed-form inverse gives u back.
    t = np.arange(n) * dt
    u = 1.8 + 1.6 * np.sin(2 * np.pi * t / 2.0) * (0.6 + 0.4 * np.cos(2 * np.pi * t / (n * dt)))
    truth = sysid._sysid.hysteresis_model_from_json(
        '{"kind": "pi", "thresholds": [0.5, 1.0], "weights": [2e-6, 1e-6], '
        '"polynomial": [3e-6], "offset_m": -1e-4, "input_min_v": 0, "input_max_v": 3.6}',
        "truth.json")
    x = truth.simulate(u, dt)
    return sysid.recording(t=t, u=u, x=x), u, x, dt


def test_fit_simulate_invert_round_trip():
    rec, u, x, dt = _pi_recording()
    fit = hy.fit([rec], model="pi", operators=2)
    assert fit.model.kind == "pi"
    assert fit.fit_time_s >= 0
    names = [p.name for p in fit.parameters]
    assert names == ["p0", "w1", "w2", "c"]
    # Uniform thresholds on [0.2, 3.4] V: R = 1.6, r_i = 0.533, 1.067 (not the truth's), so the
    # fit is close but not exact: 2 % of the 40 um stroke is a loose bound.
    assert fit.training_rms_m < 0.02 * (x.max() - x.min())
    assert all(not math.isnan(p.std_error) or p.value == 0 for p in fit.parameters)
    # The reprs say the value to 6 significant digits with its standard error, and the kind.
    p0 = fit.parameters[0]
    assert repr(p0) == f"HysteresisParameter(p0={p0.value:.6g} ± {p0.std_error:.2g} m/V)"
    assert "e-06" in repr(p0)  # a micrometre-per-volt weight is not printed as 0.000002
    assert repr(fit.model) == "<HysteresisModel kind=pi, 4 parameters, invertible>"
    xm = hy.simulate(fit.model, u, dt)
    back = hy.invert(fit.model, xm, dt)
    assert np.max(np.abs(back - u)) < 1e-12  # the closed-form inverse
    text = fit.model.to_json()
    again = sysid._sysid.hysteresis_model_from_json(text, "again.json")
    assert np.array_equal(again.simulate(u, dt), xm)


def test_errors_are_the_library_errors():
    rec, *_ = _pi_recording(300)
    with pytest.raises(sysid.OptionsError, match="operators"):
        hy.fit([rec], model="pi", operators=201)
    with pytest.raises(sysid.OptionsError, match="preisach"):
        hy.fit([rec], model="preisach")
    assert "nn-operators" in hy.kinds()


def _scores(model, rec, split):
    """Forward and inverse RMS / NRMSE over the rows after `split`, computed here from the
    single-model functions (the definitions of docs/hysteresis.md's tables)."""
    t, u, x = (np.asarray(rec[c]) for c in ("t", "u", "x"))
    dt = t[1] - t[0]
    xm = hy.simulate(model, u, dt)
    ef = xm[split:] - x[split:]
    fwd = math.sqrt(np.mean(ef ** 2))
    um = hy.invert(model, x, dt)
    ei = um[split:] - u[split:]
    inv = math.sqrt(np.mean(ei ** 2))
    return fwd, fwd / np.std(x[split:]), inv, inv / np.std(u[split:])


def test_batch_models_by_recordings_equals_the_single_model_functions(tmp_path):
    # Two recordings of a known PI whose first 40 % spans the input range of the rest (a scored
    # reference outside the fitted range is refused, as it should be): sines of constant
    # amplitude; the second at another amplitude and period, with 1 nm of noise.
    truth = sysid._sysid.hysteresis_model_from_json(
        '{"kind": "pi", "thresholds": [0.5, 1.0], "weights": [2e-6, 1e-6], '
        '"polynomial": [3e-6], "offset_m": -1e-4, "input_min_v": 0, "input_max_v": 3.6}', "t.json")
    dt = 0.005
    t = np.arange(1500) * dt
    u = 1.8 + 1.5 * np.sin(2 * np.pi * t / 2.0)
    rec = sysid.recording(source="first", t=t, u=u, x=truth.simulate(u, dt))
    rng = np.random.default_rng(3)
    t2 = np.arange(1000) * dt
    u2 = 1.8 + 1.2 * np.sin(2 * np.pi * t2 / 1.5)
    x2 = truth.simulate(u2, dt) + 1e-9 * rng.standard_normal(len(u2))
    path2 = tmp_path / "second.csv"
    path2.write_text("t,u,x\n" + "".join(f"{float(a)!r},{float(b)!r},{float(c)!r}\n" for a, b, c in zip(t2, u2, x2)))
    models = [{"kind": "pi", "operators": 4, "label": "PI 4"},
              {"kind": "gpi", "operators": 4, "label": "GPI 4"}]
    table = sysid.batch([rec, str(path2)], task="hysteresis", models=models, threads=2)
    assert list(table["model"]) == ["PI 4", "GPI 4", "PI 4", "GPI 4"]
    assert list(table["kind"]) == ["pi", "gpi", "pi", "gpi"]
    serial = sysid.hysteresis_batch([rec, str(path2)], models=models, threads=1)
    pandas.testing.assert_frame_equal(table.drop(columns="fit_time_s"),
                                      serial.drop(columns="fit_time_s"))
    for row in table.to_dict("records"):
        r = rec if row["recording"] == rec.source else sysid.read_recording(str(path2))
        n = len(r["t"])
        split = int(round(0.4 * n))
        assert (row["train_samples"], row["test_samples"]) == (split, n - split)
        train = sysid.recording(t=np.asarray(r["t"])[:split], u=np.asarray(r["u"])[:split],
                                x=np.asarray(r["x"])[:split])
        fit = hy.fit([train], model=row["kind"], operators=4)
        assert row["parameters"] == len(fit.parameters)
        expected = _scores(fit.model, r, split)
        got = (row["forward_rms_m"], row["forward_nrmse_std"], row["inverse_rms_v"],
               row["inverse_nrmse_std"])
        assert got == pytest.approx(expected, rel=1e-9, abs=0)
        assert row["inverse_error"] == "" and row["fit_error"] == ""
        assert row["fit_time_s"] >= 0
    # The default models are the pipeline's six; a model that cannot invert is a row with the
    # model's reason (rdpi's rate feedback), not an exception.
    assert len(sysid._sysid.stack_model_specs()) == 6
    with pytest.raises(sysid.OptionsError, match="spec"):
        sysid.hysteresis_batch([rec], models=[{"kind": "pi", "nope": 1}])
    bad = tmp_path / "bad.csv"
    bad.write_text("t,u,x\n0,1,2\n0.005,1,oops\n")
    with pytest.raises(sysid.DataError, match="bad.csv:3:"):
        sysid.batch([bad], task="hysteresis", models=["pi"])
    recorded = sysid.batch([rec, bad], task="hysteresis", models=["pi"], errors="record")
    assert pandas.isna(recorded.loc[0, "error"]) and "DataError" in recorded.loc[1, "error"]


def test_compare_scores_the_models_inverse_like_the_cli(tmp_path):
    rec, u, x, dt = _pi_recording(1200)
    fit = hy.fit([rec], model="pi", operators=2)
    path = tmp_path / "pi2.json"
    path.write_text(fit.model.to_json())
    table = hy.compare([str(path)], [rec], trim_samples=5)
    assert list(table["model"]) == ["pi:pi2"]
    back = hy.invert(fit.model, x, dt)[5:-5]
    e = back - u[5:-5]
    assert table.loc[0, "rmse_v"] == pytest.approx(math.sqrt(np.mean(e ** 2)), rel=1e-12)
    assert table.loc[0, "samples"] == len(u) - 10


def test_hysteresis_batch_on_dask_equals_threads():
    distributed = pytest.importorskip("distributed")
    rec, *_ = _pi_recording(1000)
    models = ["pi", {"kind": "gpi", "operators": 3, "label": "GPI 3"}]
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                                  dashboard_address=":0") as cluster, \
            distributed.Client(cluster) as client:
        table = sysid.hysteresis_batch([rec, rec], models=models, client=client)
    serial = sysid.hysteresis_batch([rec, rec], models=models, threads=1)
    pandas.testing.assert_frame_equal(table.drop(columns="fit_time_s"),
                                      serial.drop(columns="fit_time_s"))


def test_bouc_wen_fit_defaults_are_the_clis(tmp_path):
    # The library resolves `auto` (integrator and input) for the CLI and Python alike: a
    # mechanical Bouc-Wen fit from Python with no option takes the fixed step and the input
    # chosen from the recording (a whole period of a multisine: band-limited), and gives the
    # CLI's model with no flag, to the last digit.
    n, dt = 512, 1.0 / 750
    t = np.arange(n) * dt
    u = sum(6.0 * np.cos(2 * np.pi * l * t / (n * dt) + 2.39996 * l * l) for l in range(7, 60))
    truth = sysid._sysid.hysteresis_model_from_json(
        '{"kind": "bouc-wen", "parameters": {"m": 2, "c": 10, "k": 5e4, "alpha": 5e4, '
        '"beta": 1e3, "gamma": 0.8, "delta": -1.1, "nu": 1}, '
        '"simulation": {"integrator": "cvode", "input": "band-limited"}}', "truth.json")
    x = truth.simulate(u, dt)
    rec = sysid.recording(t=t, u=u, x=x)
    fit = hy.fit([rec], model="bouc-wen")
    model = json.loads(fit.model.to_json())
    assert model["simulation"]["integrator"] == "fixed-step"
    assert model["simulation"]["input"] == "band-limited"
    assert "fixed step:" in fit.summary.message
    assert "input band-limited between samples (chosen" in fit.summary.message
    path = tmp_path / "rec.csv"
    pandas.DataFrame({"t": t, "u": u, "x": x}).to_csv(path, index=False)
    run_cli("hysteresis", "fit", "--model", "bouc-wen", path, "-o", tmp_path / "m.json")
    cli = json.loads((tmp_path / "m.json").read_text())
    assert cli["simulation"] == model["simulation"]
    for name, value in cli["parameters"].items():
        assert model["parameters"][name] == pytest.approx(value, rel=1e-9), name
