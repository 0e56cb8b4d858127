"""libsysid from Python: identification and inverse models of friction-dominated actuators.

The heavy lifting is the C++ library (the extension module ``sysid._sysid``); this layer gives
the workflow Pythonic names, accepts paths, globs and arrays where the library wants recordings,
and turns keyword arguments into the library's option structs (whose defaults are the C++
ones). Units are SI everywhere: t [s], u [V], x [m], v [m/s], a [m/s^2].

    import sysid
    recs = sysid.read_recordings("datasets/virtual/pulses.csv")
    model = sysid.identify_pulses(recs).model
    print(sysid.dominance(model, "datasets/virtual/waveform_*.csv").brief_report())
"""

import copy as _copy
import glob as _glob
import os as _os
import warnings as _warnings

from . import _sysid
from ._sysid import (  # noqa: F401  (re-exported)
    Error, DataError, OptionsError, NumericalError, InternalError,
    ReadOptions, Recording, SamplingReport, analyze_sampling, resample, crop, parse_recording,
    csv_table,
    DerivativeMethod, DerivativeOptions, Derivatives, differentiate, MotionOptions, MotionSignals,
    extract_motion,
    Model, InputSignal, table_input, SineComponent, sines_input, PulseTrainSpec, pulse_train,
    waveform_names, waveform, IntegratorMethod, SimulationOptions, SimulationResult, Trajectory,
    PulseDetectionOptions, PlateauOptions, PulseFitOptions, PulseIdentificationOptions, Pulse,
    PulseEstimate, LinearFit, PulsePoint, read_pulse_table, detect_pulses,
    PulseIdentificationResult, TrajectoryOptions, TrajectoryIdentificationResult,
    SegmentOptions, DelayTuningOptions, DelayTuningResult, RefineOptions, RefineResult,
    CandidateTerm, DominanceOptions, TermStats, DominanceResult, DominanceSummary,
    ScaledVariable, Network, NeuralDataset, make_dataset, read_dataset, mean_squared_error,
    IrreducibleError,
    Trainer, Init, TrainingOptions, TrainingResult, EpochRecord, SweepOptions, SweepRow,
    SweepResult, parse_hidden_sizes, PipelineResult,
    stage, analytic_inverse, network_inverse, unit_warnings, export,
    FitScores, score_fit, normalised_autocorrelation, normalised_cross_correlation,
    CorrelationTest, OutputValidation, Validation, ResidualTestOptions, ValidationOptions,
)

__version__ = "0.1.0"

# ---- Described structs: keyword construction (C++ defaults), repr, to_dict, equality, pickling --

OPTION_TYPES = (
    ReadOptions, DerivativeOptions, MotionOptions, Model, PulseTrainSpec, SimulationOptions,
    PulseDetectionOptions, PlateauOptions, PulseFitOptions, PulseIdentificationOptions,
    TrajectoryOptions, SegmentOptions, DelayTuningOptions, RefineOptions, DominanceOptions,
    TrainingOptions, SweepOptions, stage.PulseProcedure, stage.TrackingProcedure,
    stage.PiOptions, stage.SmoothProfileOptions, ResidualTestOptions, ValidationOptions,
    stage.DriverSettings, stage.RigSettings, stage.IntegratorSettings, PulsePoint,
)


def _bound_classes():
    """Every class of the extension module and its submodule sysid.stage."""
    return [v for module in (_sysid, _sysid.stage) for v in vars(module).values()
            if isinstance(v, type) and v.__module__.startswith("sysid")]


# A result's attributes are read-only: its described fields (__fields__, C++ Serialize order)
# and the members its description leaves out (__extra_fields__, each with its reason). It pickles
# in C++ through the same list (python/src/bind_fields.hpp).
RESULT_TYPES = tuple(c for c in _bound_classes() if "__extra_fields__" in vars(c))


def fields(obj_or_type):
    """Names of the fields of a bound struct, in declaration order: a described struct's
    __fields__ (its C++ Serialize list), else its writable properties."""
    cls = obj_or_type if isinstance(obj_or_type, type) else type(obj_or_type)
    if "__fields__" in vars(cls):
        return list(cls.__fields__)
    return [n for n, v in vars(cls).items()
            if isinstance(v, property) and v.fset is not None and not n.startswith("_")]


def _to_plain(value):
    if "__fields__" in vars(type(value)) or type(value) in OPTION_TYPES:
        return {n: _to_plain(getattr(value, n)) for n in fields(value)}
    if isinstance(value, (list, tuple)):
        return type(value)(_to_plain(v) for v in value)
    if hasattr(type(value), "__members__"):  # a bound enum: its name
        return next(k for k, v in type(value).__members__.items() if v == value)
    if hasattr(value, "tolist"):  # a NumPy array (an Eigen vector or matrix): nested lists
        return value.tolist()
    return value


def _to_dict(self):
    """The fields as a plain dict (nested described structs as dicts, enums as names, arrays as
    lists)."""
    return _to_plain(self)


def _same(a, b):
    """a == b, with NaN equal to NaN (a result's quantity that does not exist)."""
    if isinstance(a, dict) and isinstance(b, dict):
        return a.keys() == b.keys() and all(_same(a[k], b[k]) for k in a)
    if isinstance(a, (list, tuple)) and isinstance(b, (list, tuple)):
        return len(a) == len(b) and all(_same(x, y) for x, y in zip(a, b))
    if isinstance(a, float) and isinstance(b, float) and a != a and b != b:
        return True
    return a == b


def _rebuild(cls, state):
    obj = cls()
    for name, value in state.items():
        setattr(obj, name, value)
    return obj


def _reduce(self):
    return (_rebuild, (type(self), {n: getattr(self, n) for n in fields(self)}))


def _repr(self):
    body = ", ".join(f"{n}={getattr(self, n)!r}" for n in fields(self))
    return f"{type(self).__name__}({body})"


def _eq(self, other):
    return type(self) is type(other) and _same(_to_plain(self), _to_plain(other))


for _cls in OPTION_TYPES:
    _cls.to_dict = _to_dict
    _cls.__eq__ = _eq
    _cls.__hash__ = None  # mutable, compared by value
    _cls.__reduce__ = _reduce
    _cls.__repr__ = _repr

for _cls in RESULT_TYPES:
    _cls.__eq__ = _eq
    _cls.__hash__ = None  # compared by value
    for _name, _method in (("to_dict", _to_dict), ("__repr__", _repr)):
        if _name not in vars(_cls):  # a result's own summary (the CLI's JSON object) stays
            setattr(_cls, _name, _method)

def _enum_name(value):
    return next(k for k, v in type(value).__members__.items() if v == value).replace("_", "-")


for _enum in (DerivativeMethod, IntegratorMethod, Trainer, Init, stage.AntiWindup):
    _enum.__reduce__ = lambda self: (type(self), (int(self),))
    _enum.__str__ = _enum_name  # the name the CLI and the parsers use: 'butterworth', 'lm'



def _recording_state(rec):
    return (_recording_from_state,
            (rec.source, list(rec.names), rec.data.copy(), list(rec.metadata)))


def _recording_from_state(source, names, data, metadata):
    rec = Recording()
    rec.source = source
    for i, name in enumerate(names):
        rec.set_column(name, data[:, i])
    rec.metadata = metadata
    return rec


Recording.__reduce__ = _recording_state
Recording.columns = property(lambda self: list(self.names))


def _recording_to_dict(self):
    """{column: NumPy view}; pandas.DataFrame(rec.to_dict()) gives the table."""
    return {name: self[name] for name in self.names}


Recording.to_dict = _recording_to_dict


def _options(cls, options, kwargs):
    """`options` (copied) with `kwargs` applied, or cls(**kwargs); unknown keys raise TypeError."""
    if options is None:
        return cls(**kwargs)
    if not isinstance(options, cls):
        raise TypeError(f"options: expected sysid.{cls.__name__}, got {type(options).__name__}")
    options = _copy.copy(options)
    for name, value in kwargs.items():
        if name not in fields(cls):
            raise TypeError(f"{cls.__name__}: unknown option '{name}'")
        setattr(options, name, value)
    return options


# ---- Recordings ------------------------------------------------------------------------------

def expand_paths(paths):
    """A path, glob pattern or list of them -> sorted list of paths (a pattern matching nothing
    is a DataError naming it)."""
    if isinstance(paths, (str, _os.PathLike)):
        paths = [paths]
    out = []
    for p in paths:
        p = _os.fspath(p)
        if _glob.has_magic(p):
            matched = sorted(_glob.glob(p, recursive=True))
            if not matched:
                raise DataError(f"{p}: no file matches the pattern")
            out.extend(matched)
        else:
            out.append(p)
    return out


class UnitWarning(UserWarning):
    """A recording's speeds or travel are implausible in SI units (x in mm read as metres)."""


def _checked_units(rec):
    for message in unit_warnings(rec):
        _warnings.warn(message, UnitWarning, stacklevel=3)
    return rec


def _pairs(value, name):
    """{column: value}, [(column, value)] or "a=b,c=d" -> [(column, value)]."""
    if value is None:
        return []
    if isinstance(value, str):
        out, depth, part = [], 0, ""
        for ch in value + ",":
            depth += ch == "["
            depth -= ch == "]"
            if ch == "," and depth == 0:
                if "=" not in part:
                    raise ValueError(f"{name}: expected COLUMN=VALUE, found '{part}'")
                k, v = part.split("=", 1)
                out.append((k, v))
                part = ""
            else:
                part += ch
        return out
    if isinstance(value, dict):
        return list(value.items())
    return list(value)


def _mapping(var, rate, scale):
    return dict(var=[(k, str(v)) for k, v in _pairs(var, "var")], rate=float(rate or 0),
                scale=[(k, float(v)) for k, v in _pairs(scale, "scale")])


def read_recording(path, options=None, var=None, rate=None, scale=None, **kwargs):
    """Reads a recording: CSV with the strict reader (DataError 'FILE:LINE:COLUMN: ...'), or a
    MATLAB MAT (v4, v5, v7.3) or HDF5 file. ``var`` maps columns to variables
    ({"u": "/multisine/u"} or "u=/multisine/u,x=data[:,2]", matrix columns 1-based), ``rate`` [Hz]
    gives t = k / rate when there is no time variable, ``scale`` ({"x": 1e-6}) converts to SI.
    A UnitWarning when its speeds or travel look like mm or um read as metres."""
    return _checked_units(_sysid.read_recording(
        _os.fspath(path), _options(ReadOptions, options, kwargs), **_mapping(var, rate, scale)))


def read_recordings(paths, options=None, var=None, rate=None, scale=None, **kwargs):
    """Reads every file of a path, glob or list of them, in sorted order per pattern (CSV, MAT or
    HDF5, with the same ``var``, ``rate``, ``scale`` as read_recording)."""
    opts = _options(ReadOptions, options, kwargs)
    mapping = _mapping(var, rate, scale)
    return [_checked_units(_sysid.read_recording(p, opts, **mapping))
            for p in expand_paths(paths)]


def list_variables(path):
    """The variables of a MAT or HDF5 file: dicts of name, type, dims, complex, sparse and, for
    numeric vectors, length, min, max."""
    import json
    return json.loads(_sysid.list_variables_json(_os.fspath(path)))["variables"]


def recording(source="arrays", metadata=(), options=None, **columns):
    """A recording from 1-D arrays of real numbers, checked by the reader's rules:
    ``sysid.recording(t=t, u=u, x=x)``. A ``("units", "x=mm")`` metadata entry converts as
    in a file. DataError for another dtype, unequal lengths or an empty array."""
    return _checked_units(Recording.from_arrays(columns, source,
                                                _options(ReadOptions, options, {}),
                                                list(metadata)))


def _as_recordings(recordings, name="recordings"):
    """Recording(s), path(s) or glob(s) -> a non-empty list of Recording (DataError when
    empty, TypeError for anything else)."""
    out = _flatten_recordings(recordings, name)
    if not out:
        raise DataError(f"{name}: no recordings; expected a Recording, a path, a glob or a "
                        f"non-empty list of them")
    return out


def _flatten_recordings(recordings, name):
    if isinstance(recordings, Recording):
        return [recordings]
    if isinstance(recordings, (str, _os.PathLike)):
        return read_recordings(recordings)
    if not isinstance(recordings, (list, tuple)):
        raise TypeError(f"{name}: expected a Recording, a path, a glob or a list of them, got "
                        f"{type(recordings).__name__}")
    out = []
    for r in recordings:
        out.extend(_flatten_recordings(r, name))
    return out


def _as_model(model):
    if isinstance(model, Model):
        return model
    if isinstance(model, (str, _os.PathLike)):
        return Model.load(_os.fspath(model))
    if isinstance(model, dict):
        return Model(**model)
    raise TypeError(f"model: expected sysid.Model, a model file path or a dict, got "
                    f"{type(model).__name__}")


def derive(recording, options=None, max_relative_jitter=0.01, **kwargs):
    """The recording with v [m/s] and a [m/s^2] derived from x by the chosen filter
    (method='central' | 'butterworth' | 'savgol'), as ``sysid derive``."""
    rec = _as_recordings(recording, "recording")
    if len(rec) != 1:
        raise TypeError(f"derive: expected one recording, got {len(rec)}")
    return _sysid.derive(rec[0], _options(DerivativeOptions, options, kwargs),
                         max_relative_jitter)


# ---- Model, simulation, identification --------------------------------------------------------

def simulate(model, input, options=None, **kwargs):
    """Simulates the friction model. `input`: a waveform name ('paper-pulses', ...; its natural
    duration is the default t_end_s), an InputSignal, or a (t [s], u [V]) pair held
    zero-order."""
    model = _as_model(model)
    if isinstance(input, str):
        signal, duration = waveform(input)
        if options is None and "t_end_s" not in kwargs:
            kwargs["t_end_s"] = duration
        input = signal
    elif isinstance(input, tuple):
        if len(input) != 2:
            raise TypeError(f"simulate: input: expected a (t_s, u_v) pair, got a tuple of "
                            f"{len(input)}")
        input = table_input(input[0], input[1])
    return _sysid.simulate_input(model, input, _options(SimulationOptions, options, kwargs))


def identify_pulses(recordings, options=None, a3=None, **kwargs):
    """Pulse-test least squares (the paper's method) over the pulses of every recording.
    `recordings`: Recording(s), path(s) or glob(s); or a list of PulsePoint."""
    opts = _options(PulseIdentificationOptions, options, kwargs)
    if a3 is not None:
        opts.fit.a3 = a3
    if isinstance(recordings, (list, tuple)) and recordings and isinstance(recordings[0],
                                                                           PulsePoint):
        return _sysid.fit_pulse_table(list(recordings), opts.fit)
    return _sysid.identify_pulses_recordings(_as_recordings(recordings), opts)


def identify_trajectory(recordings, options=None, **kwargs):
    """Trajectory (inverse-model) least squares: a3, a1p, a1n, a2p, a2n (and tau)."""
    return _sysid.identify_trajectory_recordings(_as_recordings(recordings),
                                                 _options(TrajectoryOptions, options, kwargs))


def tune_delay(model, recordings, options=None, **kwargs):
    """The delay tau [s] that makes simulated and measured velocity agree best."""
    return _sysid.tune_delay_recordings(_as_model(model), _as_recordings(recordings),
                                        _options(DelayTuningOptions, options, kwargs))


def refine(model, recordings, options=None, **kwargs):
    """Output-error refinement of all parameters (Ceres) from `model`."""
    return _sysid.refine_recordings(_as_model(model), _as_recordings(recordings),
                                    _options(RefineOptions, options, kwargs))


def dominance(model, recordings, options=None, **kwargs):
    """Dominant-variable analysis. One Recording (or one file path) gives a DominanceResult;
    a list or glob gives a DominanceSummary over all of them (parallel threads).
    ``pandas.DataFrame(result.records())`` is the CLI's CSV table."""
    model = _as_model(model)
    opts = _options(DominanceOptions, options, kwargs)
    single = isinstance(recordings, Recording) or (
        isinstance(recordings, (str, _os.PathLike)) and not _glob.has_magic(
            _os.fspath(recordings)))
    recs = _as_recordings(recordings)
    if single:
        return _sysid.analyze_dominance(model, recs[0], opts)
    return _sysid.analyze_dominance_batch(model, recs, opts)


# ---- Neural inverse models --------------------------------------------------------------------

def _as_dataset(data, inputs, output):
    if data is None or isinstance(data, NeuralDataset):
        return data
    if isinstance(data, Recording):
        return make_dataset(data, list(inputs), output)
    if isinstance(data, (str, _os.PathLike)):
        return read_dataset(_os.fspath(data), list(inputs), output)
    raise TypeError(f"expected a NeuralDataset, Recording or CSV path, got {type(data).__name__}")


def train(train, validation=None, inputs=("v",), output="u", options=None, **kwargs):
    """Trains a tanh network (trainer='lm' | 'ceres') on `train` (a CSV path, Recording or
    NeuralDataset with the input and output columns); early-stopped on `validation` if given."""
    if isinstance(inputs, str):
        inputs = inputs.split(",")
    return _sysid.train_dataset(_as_dataset(train, inputs, output),
                                _as_dataset(validation, inputs, output),
                                _options(TrainingOptions, options, kwargs))


def irreducible_error(data, inputs=("v",), output="u", neighbours=10, seed=1, jackknife_groups=20):
    """An estimate of the least MSE any model of `output` on `inputs` can reach on `data` (a CSV
    path, Recording or NeuralDataset), without a model: the output's variance among each row's
    `neighbours` nearest rows in the standardised inputs, averaged (docs/neural.md,
    "Irreducible error"). Biased upward. Returns an IrreducibleError (mse, interval95: the 95 %
    interval from a delete-a-group jackknife over `jackknife_groups` row blocks, output_variance,
    unexplained_share)."""
    if isinstance(inputs, str):
        inputs = inputs.split(",")
    return _sysid.estimate_irreducible_error(_as_dataset(data, inputs, output), neighbours, seed,
                                             jackknife_groups)


def sweep(train, validation=None, test=None, inputs=("v",), output="u", hidden_sizes=None,
          options=None, **kwargs):
    """Trains one network per hidden size (parallel threads), as ``sysid sweep``.
    Training options go in `options` (a TrainingOptions) or as keywords."""
    if isinstance(inputs, str):
        inputs = inputs.split(",")
    so = SweepOptions()
    so.training = _options(TrainingOptions, options, kwargs)
    if hidden_sizes is not None:
        so.hidden_sizes = (parse_hidden_sizes(hidden_sizes) if isinstance(hidden_sizes, str)
                           else list(hidden_sizes))
    return _sysid.sweep_datasets(_as_dataset(train, inputs, output),
                                 _as_dataset(validation, inputs, output),
                                 _as_dataset(test, inputs, output), so)


def _sweep_rows(self):
    """One dict per hidden size (pandas.DataFrame takes the list)."""
    return [{"hidden": r.hidden, "epochs": r.epochs, "train_mse": r.train_mse,
             "validation_mse": r.validation_mse, "test_mse": r.test_mse,
             "termination": r.termination, "stop_reason": r.stop_reason,
             "wall_time_s": r.wall_time_s, "chosen": i == self.chosen} for i, r in enumerate(self.rows)]


SweepResult.records = _sweep_rows
SweepResult.termination = property(lambda self: "chosen" if self.chosen >= 0 else "none")
SweepResult.message = property(
    lambda self: (f"H = {self.rows[self.chosen].hidden} by {self.rule}" if self.chosen >= 0
                  else "no network trained"))
SweepResult.brief_report = lambda self: "".join(
    f"H {r['hidden']:>4}  epochs {r['epochs']:>5}  train MSE {r['train_mse']:.6g}  "
    f"validation MSE {r['validation_mse']:.6g}  test MSE {r['test_mse']:.6g}  "
    f"{r['termination']}{'  <- chosen' if r['chosen'] else ''}\n" for r in self.records())
SweepResult.__extra_fields__.update(
    termination="whether a network was chosen (the termination every result states)",
    message="the chosen size and rule in words")
DominanceSummary.termination = property(lambda self: "analysed")
DominanceSummary.message = property(
    lambda self: f"{len(self.results)} recordings: dominant {self.dominant}, margin min "
                 f"{self.min_margin:.3g}, median {self.median_margin:.3g}")


def voltage_loop(recording, levels_v=(), half_window=10, moving_speed_mps=1e-3, motion=None,
                 cycles=1):
    """The voltage-velocity loop of a slow open-loop sweep (the paper's triangle test), as a dict
    (the JSON of ``sysid loop --json``): velocity [m/s] where |u| passes each level [V] going up
    and going down, the loop's width, the start / stop voltages, and the area [V m/s] the loop
    encloses per direction per period (``cycles``: whole periods of u in the recording) with its
    mean width [m/s]. ``recording``: a Recording or a path; ``levels_v`` empty: six per
    direction past the start voltage."""
    import json as _json
    rec = _as_recordings(recording, "recording")
    if len(rec) != 1:
        raise TypeError(f"voltage_loop: expected one recording, got {len(rec)}")
    return _json.loads(_sysid.voltage_loop_json(
        rec[0], levels_v, int(half_window), float(moving_speed_mps), int(cycles),
        _options(MotionOptions, motion, {})))


def pi_margins(model, pi=None, extra_delay_s=0.0, **kwargs):
    """The PI loop's linear gain and phase margins on a rough model, per direction, as a dict
    (the JSON of ``sysid margins --json``). ``pi``: a ``sysid.stage.PiOptions`` (its
    ``sample_time_s`` is the controller's period [s]) or keywords for one; ``extra_delay_s``
    [s]: actuator delay beyond the sample-and-hold."""
    import json as _json
    opts = _options(stage.PiOptions, pi, kwargs)
    return _json.loads(_sysid.pi_margins_json(_as_model(model), opts, float(extra_delay_s)))


def validate(model, recordings, options=None, **kwargs):
    """Validates a model on held-out recordings as ``sysid validate``: the model simulated
    free-run from each recording's u and scored as MATLAB's compare and resid do. `model`: a
    ``sysid.Model`` (or a friction model file, or a dict) simulated by the delayed stick-slip
    simulator and scored on v and x, or a hysteresis model (``sysid.hysteresis.read``, or its
    file: one with a "kind" key) scored on x. Keywords: ``max_lag`` (L, default 25), ``z``,
    ``motion``, ``sim_rtol``, ``sim_atol`` (``ValidationOptions``). Returns one
    ``Validation`` per recording: ``outputs[i].scores`` (fit_percent, rmse, nrmse_std,
    nrmse_range), ``outputs[i].autocorrelation`` and ``.cross_correlation`` (r, bound,
    passed, verdict); ``to_dict()`` gives the JSON of ``sysid validate --json``."""
    import json as _json
    residual = {k: kwargs.pop(k) for k in ("max_lag", "z", "lag_probability", "test_level")
                if k in kwargs}
    opts = _options(ValidationOptions, options, kwargs)
    if residual:
        opts.residual = _options(ResidualTestOptions, opts.residual, residual)
    if isinstance(model, (str, _os.PathLike)):
        with open(model, encoding="utf-8") as f:
            is_hysteresis = "kind" in _json.load(f)
        model = hysteresis.read(model) if is_hysteresis else _as_model(model)
    if isinstance(model, _sysid.HysteresisModel):
        run = _sysid.validate_hysteresis
    else:
        model, run = _as_model(model), _sysid.validate_friction
    return [run(rec, model, opts) for rec in _as_recordings(recordings)]


def _validation_to_dict(self):
    import json as _json
    return _json.loads(self.to_json())


_sysid.Validation.to_dict = _validation_to_dict


def tune_pi(model, loop_rate_hz=1000.0, phase_margin_deg=45.0, gain_margin_db=6.0,
            crossover_per_integral_corner=5.0, extra_delay_s=0.0, u_max_v=10.0):
    """PI gains for a rough model, as a dict (the JSON of ``sysid tune-pi --json``): the highest
    crossover at which both directions meet the phase margin [deg] and gain margin [dB] at the
    loop rate [Hz], with Ki/Kp = crossover / ``crossover_per_integral_corner``; "tuning" holds
    the gains and their margins (``pi_margins``' dict), "behaviour" their step and sine on the
    model. ``model``: a Model or a model file's path."""
    import json as _json
    plant = _os.fspath(model) if isinstance(model, (str, _os.PathLike)) else "model"
    return _json.loads(_sysid.tune_pi_json(
        _as_model(model), str(plant), float(loop_rate_hz), float(phase_margin_deg),
        float(gain_margin_db), float(crossover_per_integral_corner), float(extra_delay_s),
        float(u_max_v)))


def _track(parameters=None, reference=None, feedforward="none", model=None, network=None,
           pi=None, seed=1, **profile):
    """The tracking experiment of ``sysid track``: PI position control of the virtual stage
    with feedforward 'none', 'analytic' (needs `model`), 'nn' (needs `network`) or an array of
    voltages [V] per sample. `reference`: a PositionReference, else the smooth profile from the
    keywords (frequency_hz, amplitude_m, cycles, ...). Returns (TrackingResult, limits text)."""
    parameters = parameters or stage.StageParameters.default()
    if reference is None:
        options = _options(stage.SmoothProfileOptions, None, profile)
        options.sample_rate_hz = 1.0 / parameters.sample_time_s
        reference = stage.smooth_profile(options)
    elif profile:
        raise TypeError("track: profile keywords only without a reference")
    pi = _options(stage.PiOptions, pi, {})
    if isinstance(feedforward, str):
        if feedforward not in ("none", "analytic", "nn"):
            raise OptionsError(f"track: feedforward '{feedforward}' is not one of none, "
                               f"analytic, nn")
        if feedforward == "analytic" and model is None:
            raise OptionsError("track: feedforward 'analytic' needs a model")
        if feedforward == "nn" and network is None:
            raise OptionsError("track: feedforward 'nn' needs a network")
        if network is not None and not isinstance(network, Network):
            network = Network.load(_os.fspath(network))
        # The loop sysid track runs, with the inverse stepped inside it.
        return stage.track_scheme(parameters, reference, pi, feedforward,
                                  None if model is None else _as_model(model), network, seed)
    return stage.track_stage(parameters, reference, pi, feedforward, seed)


stage.track = _track

from .batch import batch, hysteresis_batch, sweep_grid  # noqa: E402,F401
from . import hysteresis  # noqa: E402,F401
