"""Every bound struct's Python attributes come from its one description (C++ Serialize):
a described type's properties are its __fields__ plus the extras it lists with their reasons,
and every type still bound field by field is named below. Real results (from the bundled data)
pickle, compare and print through that list, and their attributes read the values the C++ JSON
writer (which visits the fields by address, not through Python) writes."""
import json
import math
import pickle

import numpy as np
import pytest

import sysid
from sysid import _sysid
from conftest import ROOT, VIRTUAL, pulse_only_pipeline_summary

# Types still bound field by field (no Serialize), each with its reason.
UNDESCRIBED = {
    # Traces and per-sample signals, never written as a described object.
    "Recording", "Derivatives", "MotionSignals", "Trajectory", "SimulationResult",
    "NeuralDataset", "PositionReference", "StageRun",
    # A report over several results, written by its own JSON (sysid dominance --json).
    "DominanceSummary",
    # A sampling report printed as text by `sysid info`.
    "SamplingReport",
    # Model objects with a file format of their own (read and written by their own code).
    "Network", "HysteresisModel", "StageParameters",
    # The virtual stage's limits, read back as text.
    "StageStatus",
    # An options struct bound with its computed duration (PulseTrainSpec.duration_s).
    "PulseTrainSpec",
}


def _properties(cls):
    return {n for n, v in vars(cls).items()
            if isinstance(v, property) and not n.startswith("_")}


def _bound_classes():
    return [c for c in sysid._bound_classes() if not hasattr(c, "__members__")]  # not enums


def test_described_types_show_their_fields_and_listed_extras_only():
    checked = 0
    for cls in _bound_classes():
        if "__fields__" not in vars(cls):
            continue
        extras = dict(vars(cls).get("__extra_fields__", {}))
        assert all(isinstance(r, str) and r for r in extras.values()), cls.__name__
        assert not set(extras) & set(cls.__fields__), cls.__name__
        assert _properties(cls) == set(cls.__fields__) | set(extras), cls.__name__
        checked += 1
    assert checked >= 40


def test_every_type_bound_field_by_field_is_listed_as_undescribed():
    readonly = {c.__name__ for c in _bound_classes()
                if "__fields__" not in vars(c)
                and any(v.fset is None for n, v in vars(c).items()
                        if isinstance(v, property) and not n.startswith("_"))}
    assert readonly == UNDESCRIBED


def test_python_names_are_the_member_names():
    # tau_s where the file says "tau"; training_rms where it says "training_rms_m".
    assert "tau_s" in sysid.DelayTuningResult.__fields__
    assert "training_rms" in _sysid.HysteresisFitSummary.__fields__
    assert "input_names" in sysid.IrreducibleError.__fields__
    assert "stop" in sysid.TrainingResult.__fields__
    # A result is read-only.
    r = sysid.identify_pulses(VIRTUAL / "pulses.csv")
    with pytest.raises(AttributeError):
        r.fit.rows = 3


def _pipeline():
    return sysid.PipelineResult.from_json(json.dumps(pulse_only_pipeline_summary()), "p.json")


@pytest.fixture(scope="module")
def results():
    """One real instance of each described result, by class name."""
    pulses = sysid.identify_pulses(VIRTUAL / "pulses.csv")
    model = pulses.model
    dominance = sysid.dominance(model, VIRTUAL / "waveform_square.csv")
    simulation = sysid.simulate(sysid.Model.paper(), "paper-pulses", t_end_s=0.5)
    [validation] = sysid.validate(model, VIRTUAL / "waveform_square.csv", max_lag=8)
    training = sysid.train(VIRTUAL / "training.csv", hidden=2, seed=2, max_epochs=2, threads=1)
    sweep = sysid.sweep(VIRTUAL / "training.csv", hidden_sizes=[2], max_epochs=2, threads=1)
    tracking, _ = sysid.stage.track(cycles=1, frequency_hz=2.0)
    pipeline = _pipeline()
    fit = sysid.hysteresis.fit(ROOT / "datasets" / "piezo_aye_ang" / "piezo.csv", model="pi",
                               operators=4)
    out = [pulses, pulses.fit, pulses.pulses[0], pulses.pulses[0].pulse,
           sysid.identify_trajectory(VIRTUAL / "training.csv"),
           sysid.tune_delay(model, VIRTUAL / "pulses.csv", threads=1),
           sysid.refine(model, VIRTUAL / "pulses.csv", max_iterations=1, threads=1),
           dominance, dominance.ranking[0], simulation.summary, simulation.events[0],
           validation, validation.outputs[0], validation.outputs[0].autocorrelation,
           validation.outputs[0].scores, training, training.history[0], sweep, sweep.rows[0],
           sysid.irreducible_error(VIRTUAL / "training.csv"), tracking, pipeline,
           pipeline.model_tracking[0], fit.summary, fit.parameters[0]]
    return {type(r).__name__: r for r in out}


def test_every_result_type_has_an_instance(results):
    assert set(results) == {c.__name__ for c in sysid.RESULT_TYPES}


def _plain(value):
    if isinstance(value, sysid.Network):  # a file of its own, compared as its text
        return value.to_json()
    if isinstance(value, list):
        return [_plain(v) for v in value]
    return sysid._to_plain(value)


@pytest.mark.parametrize("name", sorted(c.__name__ for c in sysid.RESULT_TYPES))
def test_result_pickles_compares_and_prints_by_value(results, name):
    a = results[name]
    b = pickle.loads(pickle.dumps(a))
    assert type(b) is type(a) and b == a and not (b != a)
    # The members the description leaves out travel too (arrays, nested results, enums).
    for extra in type(a).__extra_fields__:
        assert sysid._same(_plain(getattr(b, extra)), _plain(getattr(a, extra))), extra
    assert repr(b) == repr(a)
    d = a.to_dict()
    assert isinstance(d, dict) and (name in ("DominanceResult", "Validation")
                                    or list(d) == list(type(a).__fields__))
    json.dumps(d, allow_nan=True)  # plain data: numbers, strings, lists, dicts


def test_a_changed_field_is_unequal(results):
    a = results["PulseIdentificationResult"]
    b = sysid.identify_pulses(VIRTUAL / "pulses.csv", a3=7.0)
    assert a != b and a == sysid.identify_pulses(VIRTUAL / "pulses.csv")


def _json_value(v):
    return math.nan if v is None else v


def _json_cases(results):
    """(attribute holder, the JSON object its writer wrote it into)."""
    p = results["PulseIdentificationResult"]
    d = json.loads(p.to_json())["diagnostics"]
    v = results["Validation"]
    jv = json.loads(v.to_json())
    out = [(p.fit, d), (p.pulses[0], d["pulses"][0]), (p.pulses[0].pulse, d["pulses"][0]),
           (v.outputs[0], jv["outputs"][0]), (v.outputs[0].scores, jv["outputs"][0]),
           (v.outputs[0].autocorrelation, jv["outputs"][0]["autocorrelation"]), (v, jv)]
    for name in ("DelayTuningResult", "RefineResult", "TrackingResult", "DominanceResult",
                 "TrajectoryIdentificationResult"):
        r = results[name]
        j = json.loads(r.to_json())
        out += [(r, o) for o in [j] + [x for x in j.values() if isinstance(x, dict)]]
    return out


def test_attributes_read_what_the_json_writer_writes(results):
    """The JSON writer visits each field at its address; each attribute whose JSON key is its
    name holds that value (an attribute at a wrong offset, or named after the wrong field,
    reads another)."""
    compared = set()
    for holder, j in _json_cases(results):
        for field in type(holder).__fields__:
            if field in j and not isinstance(j[field], (dict, list)):
                value = _plain(getattr(holder, field))
                assert sysid._same(value, _json_value(j[field])), (type(holder).__name__, field)
                compared.add((type(holder).__name__, field))
    assert {("LinearFit", "condition_number"), ("PulseEstimate", "v_stderr_mps"),
            ("Pulse", "duration_s"), ("FitScores", "nrmse_range"), ("CorrelationTest", "bound"),
            ("TrackingResult", "saturated_samples"), ("DelayTuningResult", "rms_error_mps"),
            ("DominanceResult", "pointwise_ratio_max")} <= compared
    assert len(compared) >= 40


def test_renamed_fields_read_their_file_keys(results):
    delay = results["DelayTuningResult"]
    assert delay.tau_s == json.loads(delay.to_json())["tau"] > 0
    irr = results["IrreducibleError"]
    j = json.loads(irr.to_json()) if hasattr(irr, "to_json") else None
    assert irr.mse > 0 and irr.input_names == ["v"] and irr.output_name == "u"
    assert j is None or j["irreducible_mse_estimate"] == irr.mse
    t = results["TrainingResult"]
    assert t.stop == t.stop_reason and t.termination in ("converged", "budget-exhausted",
                                                         "budget_exhausted")
    c = results["CorrelationTest"]
    assert getattr(c, "pass") is c.passed
