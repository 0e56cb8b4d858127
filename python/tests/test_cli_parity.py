"""Each binding against the CLI on the same files: the CLI prints doubles with all 17
significant digits in --json, so the numbers must be equal, not merely close."""
import json

import numpy as np
import pandas
import pytest

import sysid
from conftest import VIRTUAL, cli_json, run_cli

MODEL_KEYS = {"a1p": "a1p", "a1n": "a1n", "a2p": "a2p", "a2n": "a2n", "a3": "a3", "tau": "tau_s"}


def assert_model_equals_json(model, j):
    for key, attr in MODEL_KEYS.items():
        assert getattr(model, attr) == j[key], key


def test_read_recording_matches_cli_info():
    rec = sysid.read_recording(VIRTUAL / "pulses.csv")
    info = cli_json("info", VIRTUAL / "pulses.csv")
    assert rec.rows == info["rows"]
    assert rec.names == info["columns"]
    s = sysid.analyze_sampling(rec["t"])
    assert s.nominal_dt_s == info["sampling"]["nominal_dt_s"]
    assert s.max_jitter_s == info["sampling"]["max_jitter_s"]
    assert rec.meta("procedure") == "pulse test"
    # The column is a view on the recording's memory, not a copy.
    x = rec["x"]
    assert not x.flags.owndata and x.base is not None
    frame = pandas.DataFrame(rec.to_dict())
    assert list(frame.columns) == rec.names and len(frame) == rec.rows


def test_identify_pulses(model_file):
    j = cli_json("identify", VIRTUAL / "pulses.csv")
    r = sysid.identify_pulses(VIRTUAL / "pulses.csv")
    assert_model_equals_json(r.model, j)
    assert r.termination == "solved" and "10 equations" in r.message
    assert "pulse least squares: 10 equations" in r.brief_report()
    assert len(r.pulses) == 10 and all(p.usable for p in r.pulses)
    # The CLI's model file loads to the same model.
    assert sysid.Model.load(str(model_file)) == r.model
    # The CLI prints the library's JSON, which reads back to the same text.
    assert json.loads(r.to_json()) == j
    assert sysid.PulseIdentificationResult.from_json(r.to_json()).to_json() == r.to_json()


def test_identify_trajectory():
    j = cli_json("identify", "--method", "trajectory", VIRTUAL / "training.csv")
    r = sysid.identify_trajectory(VIRTUAL / "training.csv")
    assert_model_equals_json(r.model, j)
    assert r.relative_error == j["diagnostics"]["relative_error"]
    assert json.loads(r.to_json()) == j


def test_tune_delay(model_file):
    j = cli_json("tune-delay", "--model", model_file, VIRTUAL / "pulses.csv")
    r = sysid.tune_delay(str(model_file), VIRTUAL / "pulses.csv")
    assert r.tau_s == j["tau"] and r.cost == j["cost"]
    assert r.evaluations == j["evaluations"] and r.termination == j["termination"]
    assert r.message == j["message"]
    assert "tau" in r.brief_report()


def test_refine(model_file):
    args = ("--model", model_file, "--max-iterations", "2", VIRTUAL / "pulses.csv")
    j = cli_json("refine", *args)
    r = sysid.refine(str(model_file), VIRTUAL / "pulses.csv", max_iterations=2)
    d = j["diagnostics"]
    assert r.final_cost == d["final_cost"] and r.message == d["message"]
    assert r.iterations == d["iterations"]
    assert_model_equals_json(r.model, j)
    assert r.termination in ("converged", "budget-exhausted")


def test_dominance_single_and_batch(model_file, tmp_path):
    files = sorted(VIRTUAL.glob("waveform_*.csv"))
    table = tmp_path / "table.csv"
    j = cli_json("dominance", "--model", model_file, "-o", table, *files)
    model = sysid.Model.load(str(model_file))
    summary = sysid.dominance(model, str(VIRTUAL / "waveform_*.csv"))
    assert [r.to_dict() for r in summary.results] == j["recordings"]
    assert summary.min_margin == j["summary"]["min_margin"]
    assert json.loads(summary.to_json()) == j
    # The records are the CLI's CSV table (printed to 9 significant digits).
    cli_table = pandas.read_csv(table, comment="#")
    ours = pandas.DataFrame(summary.records())
    assert list(ours.columns) == list(cli_table.columns)
    for col in ("rms", "peak", "ratio_to_top", "ratio_bound", "ratio_max", "margin"):
        np.testing.assert_array_equal(ours[col].map(lambda v: float(f"{v:.9g}")), cli_table[col])
    assert summary.table_csv() == table.read_text()
    # One recording: a DominanceResult equal to the batch's entry.
    single = sysid.dominance(model, files[0])
    assert single.to_dict() == j["recordings"][0]
    assert single.brief_report() == summary.results[0].brief_report()
    assert single.termination == "analysed" and "dominant variable" in single.message


def test_derive_matches_cli(tmp_path):
    out = tmp_path / "d.csv"
    run_cli("derive", "--method", "butterworth", "--cutoff", "30", "-o", out,
            VIRTUAL / "pulses.csv")
    cli = sysid.read_recording(out)
    ours = sysid.derive(VIRTUAL / "pulses.csv", method="butterworth", cutoff_hz=30)
    np.testing.assert_array_equal(ours["v"], cli["v"])
    np.testing.assert_array_equal(ours["a"], cli["a"])


def test_simulate_matches_cli(tmp_path):
    out = tmp_path / "s.csv"
    run_cli("simulate", "--paper-model", "--waveform", "paper-pulses", "--t-end", "2", "-o", out)
    cli = sysid.read_recording(out)
    r = sysid.simulate(sysid.Model.paper(), "paper-pulses", t_end_s=2.0)
    assert r.termination == "converged" and r.summary.is_solution_usable()
    rec = r.to_recording()
    for c in ("t", "u", "x", "v", "a"):
        np.testing.assert_array_equal(rec[c], cli[c])
    assert "steps" in r.brief_report()


def test_train_both_trainers_and_predict(tmp_path):
    for trainer in ("lm", "ceres"):
        nn = tmp_path / f"nn_{trainer}.json"
        j = cli_json("train", "--train", VIRTUAL / "training.csv", "--hidden", "3",
                     "--max-epochs", "8", "--trainer", trainer, "-o", nn)
        r = sysid.train(VIRTUAL / "training.csv", hidden=3, max_epochs=8, trainer=trainer)
        assert r.train_mse == j["train_mse"] and r.epochs == j["epochs"]
        assert r.termination == j["termination"] and r.stop_reason == j["stop_reason"]
        assert r.message == j["message"]
        net = sysid.Network.load(str(nn))
        np.testing.assert_array_equal(net.parameters, r.network.parameters)
    # predict: the CLI's MSE on the test set from the saved network.
    p = cli_json("predict", "--nn", nn, VIRTUAL / "test.csv")
    test = sysid.read_recording(VIRTUAL / "test.csv")
    net = sysid.Network.load(str(nn))
    y = net.predict(test)
    assert np.mean((y - test["u"]) ** 2) == pytest.approx(p["mse"], rel=1e-14)
    np.testing.assert_array_equal(net.predict(test["v"][:, None]), y)
    # save -> load round trip through the library's writer.
    net.save(str(tmp_path / "copy.json"))
    np.testing.assert_array_equal(sysid.Network.load(str(tmp_path / "copy.json")).parameters,
                                  net.parameters)


def test_sweep(tmp_path):
    j = cli_json("sweep", "--train", VIRTUAL / "training.csv", "--test", VIRTUAL / "test.csv",
                 "--hidden", "2,3", "--max-epochs", "5")
    r = sysid.sweep(VIRTUAL / "training.csv", test=VIRTUAL / "test.csv", hidden_sizes="2,3",
                    max_epochs=5)
    assert r.rule == j["rule"]
    assert r.rows[r.chosen].hidden == j["chosen_hidden"]
    for row, cj in zip(r.records(), j["rows"]):
        assert row["hidden"] == cj["hidden"] and row["train_mse"] == cj["train_mse"]
        assert row["test_mse"] == cj["test_mse"] and row["stop_reason"] == cj["stop_reason"]


def test_stage_pulse_test_matches_cli_generate(tmp_path):
    run_cli("generate", "pulses", "-o", tmp_path)
    cli = sysid.read_recording(tmp_path / "pulses.csv")
    rec = sysid.stage.run_pulse_test(sysid.stage.StageParameters.default(), seed=1)
    for c in ("t", "u", "x", "v", "a"):
        np.testing.assert_array_equal(rec[c], cli[c])


def test_stage_presets_match_cli_generate(tmp_path):
    # A preset by name gives the same pulse recording in Python as on the command line; the
    # default carries the drive's hysteresis and creep, velocity-source neither.
    StageParameters = sysid.stage.StageParameters
    run_cli("generate", "pulses", "--stage", "velocity-source", "-o", tmp_path)
    cli = sysid.read_recording(tmp_path / "pulses.csv")
    rec = sysid.stage.run_pulse_test(StageParameters.preset("velocity-source"), seed=1)
    for c in ("t", "u", "x"):
        np.testing.assert_array_equal(rec[c], cli[c])
    default = sysid.read_recording(VIRTUAL / "pulses.csv")
    assert np.abs(default["x"] - cli["x"]).max() > 1e-4  # the drive hysteresis moves it [m]
    assert StageParameters.preset("virtual").to_json() == StageParameters.default().to_json()
    assert "hysteresis" in StageParameters.default().to_json()
    assert "hysteresis" not in StageParameters.preset("velocity-source").to_json()
    with pytest.raises(sysid.OptionsError, match="velocity-source"):
        StageParameters.preset("no-such-stage")
    names = StageParameters.preset_names()
    assert names[0] == "virtual" and "drive-hysteresis-static" in names
    for name in names:  # each loads, and its name is in the docstring
        assert StageParameters.preset(name).to_json()
        assert name in StageParameters.preset.__doc__


def test_stage_model_and_actuator_delay_attributes():
    # The stage holds one plant: model names it; the actuator-delay plant's fields keep their
    # old attribute names, write through to the file, and are refused on a velocity source.
    StageParameters = sysid.stage.StageParameters
    assert StageParameters.default().model == "velocity-source"
    ad = StageParameters.preset("actuator-delay")
    assert ad.model == "actuator-delay"
    assert ad.gain_mps2_per_v == 6.0 and ad.dead_zone_v == 0.15
    ad.gain_mps2_per_v = 5.5
    ad.dead_zone_v = 0.2
    back = StageParameters.from_json(ad.to_json())
    assert back.gain_mps2_per_v == 5.5 and back.dead_zone_v == 0.2
    with pytest.raises(sysid.OptionsError, match="velocity-source"):
        StageParameters.default().gain_mps2_per_v
    vs = StageParameters.default()
    with pytest.raises(sysid.OptionsError, match="velocity-source"):
        vs.dead_zone_v = 0.1


def test_stage_shared_settings_are_nested_structs():
    # The driver, rig and integrator are their own structs (one attribute per file key); a
    # change through the stage's attribute writes through to the file, and the rig's old flat
    # names are deprecated aliases of rig.*.
    import json
    import pickle
    stage = sysid.stage
    p = stage.StageParameters.default()
    assert list(stage.DriverSettings.__fields__) == [
        "saturation_v", "transport_delay_s", "lag_time_constant_s"]
    assert "max_steps_per_sample" in stage.IntegratorSettings.__fields__
    p.driver.saturation_v = 9.0
    p.rig.dac_bits = 12
    p.integrator.max_steps_per_sample = 500
    j = json.loads(p.to_json())
    assert j["drive"]["saturation_v"] == 9.0
    assert j["rig"]["dac_bits"] == 12
    assert j["integrator"]["max_steps_per_sample"] == 500
    assert p.sample_rate_hz == p.rig.sample_rate_hz == j["rig"]["control_rate_hz"]
    p.position_noise_m = 0.0
    assert p.rig.position_noise_m == 0.0
    rig = stage.RigSettings(dac_bits=14)
    assert pickle.loads(pickle.dumps(rig)) == rig and "dac_bits=14" in repr(rig)
    with pytest.raises(sysid.OptionsError, match="lag_time_constant_s"):
        stage.DriverSettings(lag_time_constant_s=0.0).validate()


def test_stage_tracking_matches_bundled_waveform():
    # datasets/virtual/waveform_*.csv are `sysid generate waveforms` with seed 1.
    waves = sysid.stage.paper_test_waveforms()
    i = next(k for k, w in enumerate(waves) if w.name == "square")
    rec = sysid.stage.track_waveform(sysid.stage.StageParameters.default(), waves[i],
                                     seed=sysid.stage.derive_seed(1, 100 + i))
    bundled = sysid.read_recording(VIRTUAL / "waveform_square.csv")
    for c in ("t", "u", "x"):
        np.testing.assert_allclose(rec[c], bundled[c], rtol=1e-15, atol=0)


def test_model_json_round_trip(tmp_path, model_file):
    m = sysid.Model.load(str(model_file))
    m.tau_s = 0.004
    m.save(str(tmp_path / "m.json"))
    assert json.loads((tmp_path / "m.json").read_text())["tau"] == 0.004
    assert sysid.Model.load(str(tmp_path / "m.json")) == m
    assert sysid.Model.from_json(m.to_json()) == m


def test_tracking_experiment_matches_cli_track(model_file, tmp_path):
    nn = tmp_path / "nn.json"
    run_cli("train", "--train", VIRTUAL / "training.csv", "--hidden", "3", "--max-epochs", "5",
            "-o", nn)
    j = cli_json("track", "--ff", "none,analytic,nn", "--model", model_file, "--nn", nn,
                 "--kp", "3000", "--ki", "104100", "--cycles", "1")
    pi = sysid.stage.PiOptions(kp_v_per_m=3000, ki_v_per_m_s=104100)
    for scheme in j["schemes"]:
        r, limits = sysid.stage.track(feedforward=scheme["ff"], model=str(model_file),
                                      network=str(nn), pi=pi, cycles=1)
        assert r.max_error_m == scheme["max_error_m"], scheme["ff"]
        assert r.rms_error_m == scheme["rms_error_m"] and r.rms_u_v == scheme["rms_u_v"]
        assert limits == scheme["stage_limits"]
        for key, value in json.loads(r.to_json()).items():  # the CLI lists the library's JSON
            assert scheme[key] == value, key
        assert "max |e|" in r.brief_report()


def test_derive_each_filter_matches_cli(tmp_path):
    for method, extra in (("central", {}), ("savgol", {"savgol_window": 31})):
        out = tmp_path / f"{method}.csv"
        args = ["--window", "31"] if method == "savgol" else []
        run_cli("derive", "--method", method, *args, "-o", out, VIRTUAL / "waveform_square.csv")
        cli = sysid.read_recording(out)
        ours = sysid.derive(VIRTUAL / "waveform_square.csv", method=method, **extra)
        np.testing.assert_array_equal(ours["v"], cli["v"])
        np.testing.assert_array_equal(ours["a"], cli["a"])


def test_every_result_has_termination_message_and_report(model_file):
    summary = sysid.dominance(str(model_file), str(VIRTUAL / "waveform_*.csv"))
    sweep = sysid.sweep(VIRTUAL / "training.csv", hidden_sizes=[2], max_epochs=2)
    for r in (summary, sweep, sysid.simulate(sysid.Model.paper(), "paper-sine", t_end_s=0.5),
              sysid.identify_trajectory(VIRTUAL / "training.csv")):
        assert isinstance(r.termination, str) and r.termination
        assert isinstance(r.message, str) and r.message
        assert isinstance(r.brief_report(), str) and r.brief_report()
    assert "6 recordings: dominant velocity" in summary.message
    assert "<- chosen" in sweep.brief_report()


def test_pi_margins_match_cli_margins(tmp_path):
    model = sysid.Model(a1p=104.0154, a1n=117.1441, a2p=3.1023, a2n=6.8216, a3=6, tau_s=0.0035)
    path = tmp_path / "m.json"
    model.save(str(path))
    cli = cli_json("margins", "--model", path, "--kp", "3000", "--ki", "104100")
    py = sysid.pi_margins(model, kp_v_per_m=3000, ki_v_per_m_s=104100)
    assert py == cli
    assert py["directions"][0]["stable"] and py["directions"][0]["phase_margin_deg"] > 20
    # The paper's gains on the delayed model: unstable in both directions.
    assert not any(d["stable"] for d in sysid.pi_margins(path)["directions"])


def test_voltage_loop_matches_cli_loop():
    path = VIRTUAL / "loop_triangle.csv"
    cli = cli_json("loop", path, "--levels", "1.25,-1.75")
    py = sysid.voltage_loop(path, levels_v=[1.25, -1.75])
    assert py == cli
    assert py["levels"][0]["width_mps"] > 0
    assert sysid.voltage_loop(sysid.read_recording(path)) == cli_json("loop", path)
    # The file holds one period: cycles=2 is refused alike (it halved the areas by a period
    # that is not there).
    with pytest.raises(sysid.DataError, match="cycles = 2, but the sweep crosses"):
        sysid.voltage_loop(path, cycles=2)
    assert "cycles = 2, but" in run_cli("loop", path, "--cycles", "2", expect=2).stderr


def test_tune_pi_matches_cli_tune_pi_and_its_margins(tmp_path):
    model = sysid.Model(a1p=104.0, a1n=117.1, a2p=3.10, a2n=6.82, a3=6, tau_s=0.00375)
    path = tmp_path / "m.json"
    model.save(str(path))
    cli = cli_json("tune-pi", "--model", path, "--loop-rate", "2000")
    py = sysid.tune_pi(path, loop_rate_hz=2000)
    assert py == cli
    t = py["tuning"]
    margins = sysid.pi_margins(model, kp_v_per_m=t["kp_v_per_m"], ki_v_per_m_s=t["ki_v_per_m_s"],
                               sample_time_s=t["sample_time_s"])
    assert margins["directions"] == t["margins"]["directions"]
    assert min(d["phase_margin_deg"] for d in margins["directions"]) >= 45 - 1e-6

