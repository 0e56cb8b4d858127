"""Options and the pipeline summary through the library's JSON: to_json / from_json are the C++
ToJson / XFromJson (every key optional, validated, positioned errors)."""
import json

import pytest

import sysid
from conftest import pulse_only_pipeline_summary


@pytest.mark.parametrize("cls, changes", [
    (sysid.MotionOptions, {"velocity_column": "vm", "max_relative_jitter": 0.05}),
    (sysid.PulseDetectionOptions, {"min_duration_s": 0.35}),
    (sysid.PlateauOptions, {"window_fraction": 0.4, "max_speed_mps": 0.8}),
    (sysid.PulseFitOptions, {"a3": 5.5}),
    (sysid.PulseIdentificationOptions, {}),
    (sysid.TrajectoryOptions, {"decimation": 4, "offset": True}),
    (sysid.SegmentOptions, {"rest_speed_mps": 4e-3}),
    (sysid.DelayTuningOptions, {"tau_max_s": 0.015, "curve_points": 25}),
    (sysid.RefineOptions, {"refine_a3": False, "max_iterations": 7}),
    (sysid.DominanceOptions, {"negligible_ratio": 0.2}),
    (sysid.TrainingOptions, {"hidden": 7, "momentum": 0.25, "seed": 2**64 - 1}),
    (sysid.SweepOptions, {"hidden_sizes": [4, 9, 13], "threads": 5}),
    (sysid.stage.PiOptions, {"kp_v_per_m": 3000.0, "u_max_v": 8.0}),
    (sysid.stage.SmoothProfileOptions, {"frequency_hz": 2.0, "cycles": 3}),
    (sysid.stage.PulseProcedure, {"amplitudes_v": [-1.0, 1.5], "on_s": 0.5}),
])
def test_options_round_trip(cls, changes):
    options = cls(**changes)
    text = options.to_json()
    back = cls.from_json(text, "o.json")
    for name, value in changes.items():
        assert getattr(back, name) == value
    assert back.to_json() == text
    # An empty object is the defaults.
    assert cls.from_json("{}").to_json() == cls().to_json()


def test_options_errors_name_the_place():
    with pytest.raises(sysid.DataError) as info:
        sysid.PlateauOptions.from_json('{\n  "window_fraction": 0}', "p.json")
    assert (info.value.file, info.value.line, info.value.column) == ("p.json", 2, 3)
    assert "window_fraction: expected 0 < window_fraction <= 1" in str(info.value)
    with pytest.raises(sysid.DataError, match="unknown key 'hiden' in 'training'"):
        sysid.SweepOptions.from_json('{"training": {"hiden": 3}}')
    with pytest.raises(sysid.DataError, match="solve_output_layer needs trainer = lm"):
        sysid.TrainingOptions.from_json('{"trainer": "ceres", "solve_output_layer": true}')


def test_pipeline_summary_round_trip():
    net = sysid.Network.from_json(json.dumps({
        "inputs": [{"name": "v", "min": -0.1, "max": 0.1}],
        "output": {"name": "u", "min": -10, "max": 10},
        "hidden": 2, "W1": [0.5, -0.25], "b1": [0.1, 0.2], "W2": [1.5, -2.0], "b2": 0.3}))
    summary = {
        "model": json.loads(sysid.Model().to_json()),
        "dominant": "velocity", "nn_inputs": ["v"], "hidden": 2,
        "network": json.loads(net.to_json()), "nn_test_mse": 0.25,
        "typical_train_mse": 0.01, "typical_test_mse": 0.4,
        "tracking": [{"frequency_hz": 0.5, "ff": "nn", "max_error_m": 2e-6,
                      "rms_error_m": 1e-6}],
        "margins": [{"direction": "forward", "crossover_rad_s": 330.0, "phase_margin_deg": 2.0,
                     "gain_margin": 1.2, "stable": True},
                    {"direction": "backward", "crossover_rad_s": 331.0,
                     "phase_margin_deg": -3.0, "gain_margin": None, "stable": False}],
        "facts": [{"id": "F1", "required": True, "met": True},
                  {"id": "F7", "required": False, "met": False}],
        "facts_required_met": True,
        "steps": [{"name": "train", "wall_time_s": 2.0}, {"name": "identify", "wall_time_s": 0.5}],
    }
    text = json.dumps(summary, indent=2) + "\n"
    r = sysid.PipelineResult.from_json(text, "p.json")
    assert r.dominant == "velocity"
    assert r.network.to_json() == net.to_json()
    assert r.typical_train_mse == 0.01 and r.typical_test_mse == 0.4
    assert r.tracking[0].scheme == "nn" and r.tracking[0].result.max_error_m == 2e-6
    assert r.facts_required_met is True
    assert r.margins["forward"]["stable"] and not r.margins["backward"]["stable"]
    assert r.margins["backward"]["phase_margin_deg"] == -3.0
    assert r.step_seconds == [("train", 2.0), ("identify", 0.5)]  # run order kept
    assert json.loads(r.to_json()) == summary
    assert sysid.PipelineResult.from_json(r.to_json()).to_json() == r.to_json()
    summary["hidden"] = 3
    with pytest.raises(sysid.DataError, match="hidden: expected 2"):
        sysid.PipelineResult.from_json(json.dumps(summary))
    assert r.skipped == [] and r.model_tracking == [] and r.tuned_pi is None


def test_pulse_only_pipeline_summary_round_trips():
    summary = pulse_only_pipeline_summary()
    r = sysid.PipelineResult.from_json(json.dumps(summary), "p.json")
    assert r.skipped == summary["skipped"]
    assert r.tuned_pi.kp_v_per_m == 1571.7 and r.tuned_pi.ki_v_per_m_s == 26720.0
    assert r.tuned_pi.sample_time_s == 0.001
    assert r.model_tracking[0].scheme == "analytic"
    assert r.model_tracking[0].result.max_error_m == 9.6e-7


# Python attributes that are not fields of the file, each with its reason.
NOT_FILE_FIELDS = {
    # Whether a3 was set (setting a3 sets it; a file gives a3 by naming it).
    "PulseFitOptions": {"a3_given"},
}


# Types whose JSON is a file format of its own, each with its reason.
OWN_FORMAT = {
    # The model file's published form: "tau" [s] and a "units" object (docs/identification.md).
    "Model",
}


@pytest.mark.parametrize("cls", [c for c in sysid.OPTION_TYPES
                                 if hasattr(c, "to_json") and c.__name__ not in OWN_FORMAT],
                         ids=lambda c: c.__name__)
def test_python_attributes_are_the_json_fields(cls):
    """Each options type's Python attributes, in order, are its JSON keys: the C++ field list
    the JSON writer walks; for a described type both come from its one Serialize."""
    keys = list(json.loads(cls().to_json()))
    attributes = [n for n in sysid.fields(cls) if n not in NOT_FILE_FIELDS.get(cls.__name__, ())]
    assert attributes == keys


@pytest.mark.parametrize("cls", [c for c in sysid.OPTION_TYPES if "__fields__" in vars(c)],
                         ids=lambda c: c.__name__)
def test_described_types_compare_copy_and_pickle_by_value(cls):
    import copy
    import pickle
    a = cls()
    assert a == cls() and a == copy.deepcopy(a) and a == pickle.loads(pickle.dumps(a))
    assert repr(a).startswith(cls.__name__ + "(")
    first = sysid.fields(cls)[0]
    b = cls()
    value = getattr(b, first)
    if isinstance(value, bool):
        setattr(b, first, not value)
    elif isinstance(value, (int, float)) and not isinstance(value, bool):
        setattr(b, first, value + 1)
    else:
        return  # a nested struct or an enum first: the equality above is the check
    assert b != a
