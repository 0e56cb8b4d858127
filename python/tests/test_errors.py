"""Library errors as Python exceptions with the library's messages (the CLI prints the same
text after 'sysid: error: ')."""
import pytest

import sysid
from conftest import VIRTUAL, run_cli


def cli_error(*args, expect):
    stderr = run_cli(*args, expect=expect).stderr.strip()
    assert stderr.startswith("sysid: error: ")
    return stderr[len("sysid: error: "):]


def test_bad_cell_is_data_error_with_location(tmp_path):
    bad = tmp_path / "bad.csv"
    bad.write_text("t,u,x\n0,0,0\n0.001,1,2e\n")
    with pytest.raises(sysid.DataError) as info:
        sysid.read_recording(bad)
    e = info.value
    assert (e.file, e.line, e.column) == (str(bad), 3, 9)
    assert str(e) == cli_error("identify", bad, expect=2)
    assert "expected a number, found \"2e\"" in str(e)
    assert isinstance(e, sysid.Error) and isinstance(e, RuntimeError)


def test_missing_file_and_non_increasing_time(tmp_path):
    with pytest.raises(sysid.DataError, match="cannot open"):
        sysid.read_recording(tmp_path / "none.csv")
    back = tmp_path / "back.csv"
    back.write_text("t,u,x\n0,0,0\n0.002,0,0\n0.001,0,0\n")
    with pytest.raises(sysid.DataError) as info:
        sysid.read_recording(back)
    assert info.value.line == 4
    assert str(info.value) == cli_error("identify", back, expect=2)


def test_from_arrays_uses_the_reader_rules():
    rec = sysid.recording(t=[0.0, 0.001, 0.002], u=[0, 1, 1], x=[0.0, 1e-6, 3e-6], source="mine")
    assert rec.rows == 3 and rec.names == ["t", "u", "x"] and rec.source == "mine"
    with pytest.raises(sysid.DataError, match="mine:.*'x'"):
        sysid.recording(t=[0.0, 0.001], u=[0, 1], x=[0.0, float("nan")], source="mine")
    with pytest.raises(sysid.DataError, match="increasing"):
        sysid.recording(t=[0.0, 0.0], u=[0, 1], x=[0.0, 0.0])
    with pytest.raises(sysid.DataError, match="has 1 values"):
        sysid.recording(t=[0.0, 0.001], u=[0], x=[0.0, 0.0])
    with pytest.raises(sysid.DataError, match="column"):
        rec["nope"]


def test_options_error_names_field_and_rule(model_file):
    with pytest.raises(sysid.OptionsError) as info:
        sysid.dominance(str(model_file), VIRTUAL / "pulses.csv", min_speed_mps=-1)
    assert str(info.value) == cli_error("dominance", "--model", model_file, "--min-speed", "-1",
                                        VIRTUAL / "pulses.csv", expect=1)
    with pytest.raises(sysid.OptionsError, match="a1p"):
        sysid.Model(a1p=-1.0).validate()
    with pytest.raises(sysid.OptionsError, match="'lm' or 'ceres'"):
        sysid.TrainingOptions(trainer="adam")


def test_unknown_keyword_is_type_error():
    with pytest.raises(TypeError, match="unknown option 'min_speed'"):
        sysid.DominanceOptions(min_speed=1e-3)
    with pytest.raises(TypeError, match="unknown option"):
        sysid.tune_delay(sysid.Model.paper(), VIRTUAL / "pulses.csv", tau_max=0.1)


def test_numerical_error_names_parameters():
    points = [sysid.PulsePoint(1.5, 0.05), sysid.PulsePoint(2.0, 0.09)]
    with pytest.raises(sysid.NumericalError, match="a1n, a2n"):
        sysid.identify_pulses(points)


def test_options_defaults_come_from_cpp():
    # The values below are the C++ structs' initialisers; nothing in Python repeats them.
    d = sysid.DominanceOptions()
    assert d.min_speed_mps == 1e-3 and d.negligible_ratio == 0.1 and d.threads == 0
    assert str(d.motion.derivative.method) == "central"
    t = sysid.TrajectoryOptions()
    assert str(t.motion.derivative.method) == "butterworth"  # TrajectoryOptions::DefaultMotion
    assert sysid.TrainingOptions().hidden == 24
    assert sysid.DelayTuningOptions(tau_max_s=0.05).to_dict()["tau_max_s"] == 0.05


def test_sizes_are_bounded_before_allocation():
    # A typo'd size is refused at once with the CLI's limit and message (the checks live in the
    # library: tests/robustness/resource_limits.sh), not attempted until a MemoryError.
    with pytest.raises(sysid.OptionsError, match=r"repeats .*<= 20000000 table rows") as info:
        sysid.pulse_train(sysid.PulseTrainSpec(amplitudes_v=[1.0], repeats=2_000_000_000))
    assert str(info.value) == cli_error("simulate", "--paper-model", "--pulses", "1",
                                        "--pulse-repeats", "2000000000", expect=1)
    with pytest.raises(sysid.OptionsError, match=r"hidden = 1000000000\. .*1 <= hidden <= 100000"):
        sysid.Network([sysid.ScaledVariable("v")], sysid.ScaledVariable("u"), 10**9)
    assert sysid.Network([sysid.ScaledVariable("v")], sysid.ScaledVariable("u"), 2).hidden_size == 2


def test_hysteresis_fit_sizes_are_bounded_before_allocation(tmp_path):
    # nn-operators: the operator count and the hidden units are refused by their bounds, and a
    # fit whose feature matrices pass the 4 GB training limit (200 operators on 1e6 samples,
    # about 4.8 GB) is an OptionsError before allocating, not a MemoryError (std::bad_alloc).
    import numpy as np
    import sysid.hysteresis as hy
    t = np.arange(400) * 5e-3
    u = np.sin(2 * np.pi * t)
    rec = sysid.recording(t=t, u=u, x=1e-6 * u)
    path = tmp_path / "h.csv"
    rec.save(str(path))
    for kw, flag, match in [({"operators": 10**9}, "--operators", r"operators = 1000000000\. .*<= 200"),
                            ({"hidden": 10**9}, "--hidden", r"hidden = 1000000000\. .*<= 200")]:
        with pytest.raises(sysid.OptionsError, match=match) as info:
            hy.fit([rec], model="nn-operators", **kw)
        # The CLI gives the same limit and text, after the flag's name.
        assert cli_error("hysteresis", "fit", "--model", "nn-operators", flag, "1000000000",
                         path, "-o", tmp_path / "m.json", expect=1) == f"{flag}: {info.value}"
    n = 1_000_000
    t = np.arange(n) * 1e-3
    long = sysid.recording(t=t, u=np.zeros(n), x=np.zeros(n))
    with pytest.raises(sysid.OptionsError, match=r"operators = 200\. .*1000000 samples .*GB"):
        hy.fit([long], model="nn-operators", operators=200, hidden=1)


def test_hysteresis_invert_far_reference_names_the_reach_not_nan():
    # y = 0.25 u + F_1[u] (r = 1 V, w = 1) on [0, 2] V + 5 %: at x = 1e308 m the inverse's sum
    # overflows (inf - inf) and the message said "it needs u = -nan V". By hand the model
    # reaches 0.25 * 2.1 + (2.1 - 1) = 1.625 m at u = 2.1 V from rest after u_0 = 0.
    import sysid.hysteresis as hy
    model = sysid._sysid.hysteresis_model_from_json(
        '{"kind": "pi", "thresholds": [1.0], "weights": [1.0], "polynomial": [0.25], '
        '"offset_m": 0.0, "initial_input_v": 0.0, "initial_state": [0.0], '
        '"input_min_v": 0.0, "input_max_v": 2.0, "range_margin": 0.05}')
    with pytest.raises(sysid.DataError) as info:
        hy.invert(model, [0.0, 1e308, 0.0], dt_s=0.1)
    message = str(info.value)
    assert "reference sample 1 (t = 0.1 s): x = 1e+308 m" in message
    assert "above the output 1.625 m at u = 2.1 V" in message
    assert "nan" not in message and "inf" not in message


def test_set_column_keeps_a_recording_save_can_write(tmp_path):
    """Issue 38: set_column took NaN, a decreasing t and names with ',', ESC, a newline or
    nothing; `save` then wrote a CSV that sysid refuses. The reader's rules now apply here."""
    rec = sysid.recording(t=[0.0, 0.001, 0.002], u=[0, 1, 1], x=[0.0, 1e-6, 3e-6])
    for name in ["a,b", "e\x1b[2J", "a\nb", "", "1x", " x", "#x"]:
        with pytest.raises(sysid.DataError, match="column name"):
            rec.set_column(name, [1.0, 2.0, 3.0])
    with pytest.raises(sysid.DataError, match=r"'v'\[1\]: expected a finite number, found nan"):
        rec.set_column("v", [0.0, float("nan"), 0.0])
    with pytest.raises(sysid.DataError, match="time must be strictly increasing"):
        rec.set_column("t", [0.0, 0.002, 0.001])
    with pytest.raises(sysid.DataError, match="time must be strictly increasing"):
        rec.set_column("t", [0.0, 1e-320, 2e-320])
    assert rec.names == ["t", "u", "x"]  # nothing was added by the refused calls
    rec.set_column("v", [0.0, 1e-3, 2e-3])
    path = tmp_path / "ok.csv"
    rec.save(str(path))
    back = sysid.read_recording(path)
    assert back.names == ["t", "u", "x", "v"]


def test_hysteresis_simulate_of_none_is_a_type_error():
    import sysid.hysteresis as hy
    for call in (lambda: hy.simulate(None, [0.0, 1.0], 1e-3), lambda: hy.invert(None, [0.0], 1e-3),
                 lambda: hy.simulate(3, [0.0, 1.0], 1e-3)):
        with pytest.raises(TypeError, match="expected a HysteresisModel"):
            call()
