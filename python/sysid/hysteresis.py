"""Hysteresis models from Python (docs/hysteresis.md): Prandtl–Ishlinskii (pi, gpi, rdpi),
Bouc–Wen and the operator-input network, fitted by kind, simulated and inverted.

    import sysid.hysteresis as hy
    fit = hy.fit("datasets/piezo_aye_ang/piezo.csv", model="pi", operators=20)
    print(fit.fit_time_s, fit.parameters[0])
    x_model = hy.simulate(fit.model, u, dt_s=0.005)
    u_ff = hy.invert(fit.model, x_desired, dt_s=0.005)
    table = hy.compare(["pi.json", "gpi.json"], "piezo.csv")   # as `sysid compare --hysteresis`

Units: u [V], x [m], dt_s [s]; parameters carry their SI unit and standard error (NaN when the
fit gives none).
"""

from dataclasses import dataclass, field

from . import _sysid


@dataclass
class HysteresisFit:
    """What `fit` returns: the model, its parameters with standard errors, and the fit's
    summary (samples, fit time [s], training RMS [m], converged, message)."""
    model: object
    summary: object
    parameters: list = field(default_factory=list)

    @property
    def fit_time_s(self):
        return self.summary.fit_time_s

    @property
    def training_rms_m(self):
        return self.summary.training_rms

    @property
    def std_errors(self):
        return {p.name: p.std_error for p in self.parameters}

    def to_dict(self):
        return {p.name: (p.value, p.std_error, p.unit) for p in self.parameters}


def kinds():
    """The model kinds `fit` accepts."""
    return list(_sysid.hysteresis_kinds())


def fit(recordings, model="pi", operators=10, offset=True, degree=3, hidden=10, epochs=300,
        seed=1):
    """Fits a hysteresis model of kind `model` to recordings (paths, globs, Recording objects;
    columns t [s], u [V], x [m])."""
    from . import _as_recordings
    recs = _as_recordings(recordings)
    m, s = _sysid.fit_hysteresis(model, recs, operators, offset, degree, hidden, epochs, seed)
    return HysteresisFit(model=m, summary=s, parameters=list(m.parameters))


def read(path):
    """Reads a model file written by `sysid hysteresis fit` or `model.to_json()`."""
    return _sysid.read_hysteresis_model(str(path))


def _model(model, function):
    """A HysteresisModel from a model or a model file's path; TypeError for anything else."""
    import os
    if isinstance(model, (str, os.PathLike)):
        return read(model)
    if not isinstance(model, _sysid.HysteresisModel):
        raise TypeError(f"hysteresis.{function}: model: expected a HysteresisModel (from fit or "
                        f"read) or a model file's path, got {type(model).__name__}")
    return model


def simulate(model, u_v, dt_s, periodic=False):
    """x [m] for the input samples u [V] spaced dt_s [s]; `periodic`: u is one period, the
    result the periodic steady state's last period."""
    model = _model(model, "simulate")
    return model.simulate_periodic(u_v, dt_s) if periodic else model.simulate(u_v, dt_s)


def invert(model, x_m, dt_s):
    """The input u [V] that makes the model follow x [m]."""
    return _model(model, "invert").invert(x_m, dt_s)


def compare(models, recordings, trim_samples=5):
    """Each model's inverse on each recording's x scored against its u, as `sysid compare
    --hysteresis` does: one pandas.DataFrame row per (recording, model) with recording (the
    file stem), model (the label), kind, rmse_v [V], peak_error_v [V], nrmse_range (RMSE / range of
    u), r2, samples (scored, after dropping `trim_samples` at each end).

    models: model file paths (labelled KIND:FILE_STEM, as the CLI labels them), or a dict
            {label: model or path}. recordings: paths, globs or Recordings (t, u, x)."""
    import os
    import pandas
    from . import _as_recordings
    if isinstance(models, dict):
        named = [(label, read(m) if isinstance(m, (str, os.PathLike)) else m)
                 for label, m in models.items()]
    else:
        named = []
        for path in ([models] if isinstance(models, (str, os.PathLike)) else models):
            m = read(path)
            named.append((f"{m.kind}:{os.path.splitext(os.path.basename(os.fspath(path)))[0]}", m))
    rows = []
    for rec in _as_recordings(recordings):
        t, _, scored = _sysid.compare_hysteresis_inverses(rec, named, trim_samples)
        stem = os.path.splitext(os.path.basename(rec.source))[0]
        for r in scored:
            rows.append({"recording": stem, "model": r["label"], "kind": r["kind"],
                         "rmse_v": r["rmse_v"], "peak_error_v": r["peak_error_v"],
                         "nrmse_range": r["nrmse_range"], "r2": r["r2"], "samples": len(t)})
    return pandas.DataFrame.from_records(rows)
