"""Batch analysis over many recordings and the hidden-size x seed sweep, on Dask when given.

Each task is one recording (or one (hidden size, seed) pair) and runs the C++ library with the
GIL released, so the local thread pool uses every core; with a ``dask.distributed.Client`` the
tasks go to its workers instead (a LocalCluster or a lab's scheduler). Nothing here schedules:
the executor is concurrent.futures or Dask. The result is one pandas.DataFrame in input order.
"""

import concurrent.futures as _futures
import numbers as _numbers
import os as _os
import sys as _sys

from . import _sysid

TASKS = ("dominance", "identify_pulses", "identify_trajectory", "tune_delay", "hysteresis",
         "irreducible")

# The keywords of task "irreducible" (sysid.irreducible_error's) and their defaults.
_IRREDUCIBLE_DEFAULTS = {"inputs": ("v", "v,a"), "output": "u", "neighbours": 10, "seed": 1}

# The fit options a hysteresis model spec may set (sysid.hysteresis.fit's keywords).
_HYSTERESIS_KEYS = ("kind", "label", "operators", "offset", "degree", "hidden", "epochs", "seed")


def _model_row(prefix, model):
    return {f"{prefix}{k}": getattr(model, k) for k in ("a1p", "a1n", "a2p", "a2n", "a3", "tau_s")}


def _run_one(item, task, model, options, mapping=None):
    """One recording -> one row (a dict). Runs in a worker thread or a Dask worker process.
    `mapping` (var, rate, scale) reads MAT/HDF5 files or renamed CSV columns."""
    import sysid  # in a fresh Dask worker process
    rec = item if isinstance(item, sysid.Recording) else sysid.read_recording(item,
                                                                              **(mapping or {}))
    row = {"source": rec.source}
    if task == "dominance":
        row.update(_sysid.analyze_dominance(model, rec, options).row())
    elif task == "identify_pulses":
        r = _sysid.identify_pulses_recordings([rec], options)
        row.update(_model_row("", r.model))
        row.update({"equations": r.fit.rows, "rank": r.fit.rank,
                    "rms_residual_mps2": r.fit.rms_residual, "termination": r.termination})
    elif task == "identify_trajectory":
        r = _sysid.identify_trajectory_recordings([rec], options)
        row.update(_model_row("", r.model))
        row.update({"samples_used": r.samples_used, "relative_error": r.relative_error,
                    "termination": r.termination})
    elif task == "irreducible":
        for inputs in options["inputs"]:
            e = sysid.irreducible_error(rec, inputs=inputs, output=options["output"],
                                        neighbours=options["neighbours"], seed=options["seed"])
            row[f"irreducible_mse[{','.join(e.input_names)}]"] = e.mse
            row.update({"rows": e.rows, "output_variance": e.output_variance})
    elif task == "tune_delay":
        r = _sysid.tune_delay_recordings(model, [rec], options)
        row.update({"tau_s": r.tau_s, "cost": r.cost, "rms_error_mps": r.rms_error_mps,
                    "evaluations": r.evaluations, "termination": r.termination,
                    "message": r.message})
    return row


def _guarded(item, task, model, options, errors, mapping=None):
    try:
        return _run_one(item, task, model, options, mapping)
    except _sysid.Error as e:
        if errors == "raise":
            raise
        source = item.source if isinstance(item, _sysid.Recording) else _os.fspath(item)
        return {"source": source, "error": f"{type(e).__name__}: {e}"}


def _default_options(task, options, kwargs):
    import sysid
    if task == "irreducible":
        given = dict(options or {}, **kwargs)
        unknown = set(given) - set(_IRREDUCIBLE_DEFAULTS)
        if unknown:
            raise sysid.OptionsError(
                f"batch: task 'irreducible' takes {', '.join(_IRREDUCIBLE_DEFAULTS)}; got "
                f"{', '.join(sorted(unknown))}")
        opts = {**_IRREDUCIBLE_DEFAULTS, **given}
        if isinstance(opts["inputs"], str):
            opts["inputs"] = (opts["inputs"],)
        opts["inputs"] = [list(i.split(",")) if isinstance(i, str) else list(i)
                          for i in opts["inputs"]]
        return opts
    cls = {"dominance": sysid.DominanceOptions, "identify_pulses": sysid.PulseIdentificationOptions,
           "identify_trajectory": sysid.TrajectoryOptions,
           "tune_delay": sysid.DelayTuningOptions}[task]
    opts = sysid._options(cls, options, kwargs)
    # One task per recording: the parallelism is across recordings, so each task uses one
    # thread (results do not depend on the thread count).
    if "threads" in sysid.fields(cls):
        opts.threads = 1
    return opts


def _run_chunk(chunk, fn, kw):
    if fn is _guarded and kw["task"] == "dominance":
        return _dominance_chunk(chunk, **kw)
    return [fn(item, **kw) for item in chunk]


def _dominance_chunk(chunk, task, model, options, errors, mapping=None):
    """A chunk of dominance tasks in one C++ call (files read there too) with the GIL released,
    so threads scale; a failing recording is re-run alone to raise its own exception."""
    import sysid  # in a fresh Dask worker process
    if mapping:  # the files are read through the mapping in Python, then analysed in one call
        chunk = [i if isinstance(i, sysid.Recording) else _guarded_read(i, mapping, errors)
                 for i in chunk]
        if any(isinstance(i, dict) for i in chunk):
            return [i if isinstance(i, dict) else _guarded(i, task, model, options, errors)
                    for i in chunk]
    paths = [i for i in chunk if not isinstance(i, sysid.Recording)]
    if len(paths) == len(chunk):
        rows = _sysid.dominance_rows_files(model, paths, options)
    elif not paths:
        rows = _sysid.dominance_rows(model, chunk, options)
    else:
        return [_guarded(i, task, model, options, errors) for i in chunk]
    for item, row in zip(chunk, rows):
        if "error" in row:
            if errors == "raise":
                _run_one(item, task, model, options)  # raises the recording's sysid.Error
            del row["error_type"]
    return rows


def _guarded_read(path, mapping, errors):
    """The recording at `path` through `mapping`, or (errors='record') an error row."""
    import sysid
    try:
        return sysid.read_recording(path, **mapping)
    except _sysid.Error as e:
        if errors == "raise":
            raise
        return {"source": _os.fspath(path), "error": f"{type(e).__name__}: {e}"}

# The CLI's bounds on --threads (0: all cores).
_MAX_THREADS = 1024


def _check_run_args(client, threads, chunksize, **lists):
    """Checks the arguments that say how a batch runs, before any work: client (None or a
    dask.distributed.Client), threads (None or an integer in [0, 1024], as the CLI), chunksize
    (None or an integer >= 1), and each of `lists` (name -> value) non-empty. TypeError for
    the wrong kind, OptionsError for a value breaking the rule, each naming the argument, the
    rule and the value."""
    import sysid

    def integer(v):
        return isinstance(v, _numbers.Integral) and not isinstance(v, bool)

    # The package's convention (docs/python.md): the wrong Python kind is a TypeError, a value
    # of the right kind breaking the rule an OptionsError.
    for name, value, rule, ok in (
            ("threads", threads, f"an integer in [0, {_MAX_THREADS}] (0: all cores) or None",
             lambda v: 0 <= v <= _MAX_THREADS),
            ("chunksize", chunksize, "an integer >= 1 or None (the default)", lambda v: v >= 1)):
        if value is None:
            continue
        if not integer(value):
            raise TypeError(f"{name}: expected {rule}, found {value!r}")
        if not ok(value):
            raise sysid.OptionsError(f"{name}: expected {rule}, found {value!r}")
    if client is not None:
        try:
            from distributed import Client
        except ImportError:
            Client = ()
        if not isinstance(client, Client):
            raise TypeError(f"client: expected a dask.distributed.Client or None, "
                            f"found {type(client).__name__}")
    for name, value in lists.items():
        if isinstance(value, (list, tuple)) and not value:
            raise sysid.OptionsError(f"{name}: expected a non-empty list, found {value!r}")


def _recording_items(recordings):
    """Paths (str), glob patterns and Recordings, or a list of them -> the items in order, each
    a path (globs expanded: a pattern matching nothing is a DataError naming it) or a Recording;
    DataError when there are none."""
    import sysid
    if isinstance(recordings, (str, _os.PathLike, sysid.Recording)):
        recordings = [recordings]
    items = []
    for r in recordings:
        items.extend([r] if isinstance(r, sysid.Recording) else sysid.expand_paths(r))
    if not items:
        raise sysid.DataError("recordings: no recordings; expected a Recording, a path, a glob "
                              "or a non-empty list of them")
    return items


def _map(fn, items, client, threads, chunksize=None, progress=None, **kw):
    """fn(item, **kw) for every item, in order: on the Dask client's workers, else on a local
    thread pool. Items go in chunks (default: about 4 per worker) so that per-task overhead
    (a Dask round trip is about a millisecond) stays small beside the work. Progress ("k/n")
    goes to stderr when asked, or by default when stderr is a terminal."""
    if client is not None:
        workers = max(1, sum(client.nthreads().values()))
    else:
        workers = max(1, threads or _os.cpu_count() or 1)
    if chunksize is None:
        chunksize = max(1, -(-len(items) // (4 * workers)))
    chunks = [items[i:i + chunksize] for i in range(0, len(items), chunksize)]
    if progress is None:
        progress = _sys.stderr.isatty()
    results = [None] * len(chunks)
    done = 0

    def report(k):
        nonlocal done
        done += len(chunks[k])
        if progress:
            print(f"\rsysid batch: {done}/{len(items)}", end="" if done < len(items) else "\n",
                  file=_sys.stderr, flush=True)

    if client is not None:
        from distributed import as_completed
        futures = client.map(_run_chunk, chunks, fn=fn, kw=kw, pure=False)
        if not progress:
            # One gather for all chunks (batched per worker), not a blocking round trip from
            # this thread into the client's event loop per chunk.
            results = client.gather(futures)
        else:
            index = {f.key: k for k, f in enumerate(futures)}
            for future, result in as_completed(futures, with_results=True):
                k = index[future.key]
                results[k] = result
                report(k)
    elif workers == 1:
        for k, c in enumerate(chunks):
            results[k] = _run_chunk(c, fn, kw)
            report(k)
    else:
        with _futures.ThreadPoolExecutor(max_workers=workers) as pool:
            futures = {pool.submit(_run_chunk, c, fn, kw): k for k, c in enumerate(chunks)}
            for future in _futures.as_completed(futures):
                k = futures[future]
                results[k] = future.result()
                report(k)
    return [row for chunk in results for row in chunk]


def _hysteresis_specs(models):
    """Model specs (dicts with kind, label and fit keywords) from kinds, dicts, or None (the
    pipeline's stack models)."""
    import sysid
    if models is None:
        return [dict(s) for s in _sysid.stack_model_specs()]
    if isinstance(models, (str, dict)):
        models = [models]
    specs = []
    for m in models:
        spec = {"kind": m} if isinstance(m, str) else dict(m)
        unknown = set(spec) - set(_HYSTERESIS_KEYS)
        if "kind" not in spec or unknown:
            raise sysid.OptionsError(
                f"batch: hysteresis model spec {m!r}: expected a kind or a dict with 'kind' and "
                f"any of {', '.join(_HYSTERESIS_KEYS[1:])}")
        spec.setdefault("label", spec["kind"])
        specs.append(spec)
    return specs


def _hysteresis_one(pair, train_fraction, errors, mapping=None):
    """One (recording, model spec) -> one row: the model fitted on the recording's first part
    and scored on the rest (sysid/compare_stack.hpp)."""
    import sysid  # in a fresh Dask worker process
    item, spec = pair
    source = item.source if isinstance(item, _sysid.Recording) else _os.fspath(item)
    try:
        rec = item if isinstance(item, sysid.Recording) else sysid.read_recording(
            item, **(mapping or {}))
        kw = {k: v for k, v in spec.items() if k != "kind"}
        row = _sysid.fit_and_score_hysteresis([rec], spec["kind"], train_fraction=train_fraction,
                                              threads=1, **kw)
    except _sysid.Error as e:
        if errors == "raise":
            raise
        return {"recording": source, "model": spec["label"], "kind": spec["kind"],
                "error": f"{type(e).__name__}: {e}"}
    return {"recording": rec.source, **row}


def hysteresis_batch(recordings, models=None, client=None, threads=None, train_fraction=0.4,
                     errors="raise", chunksize=1, progress=None, var=None, rate=None,
                     scale=None):
    """Hysteresis models x recordings into one pandas.DataFrame, a row per (recording, model)
    in recordings-major order: each model fitted on the first `train_fraction` of the
    recording's rows and scored on the rest, as the pipeline's stack table (docs/hysteresis.md):
    recording, model (label), kind, parameters, fit_time_s [s], train_samples, test_samples,
    forward_rms_m [m], forward_nrmse_std (/ std x), inverse_rms_v [V], inverse_nrmse_std (/ std u),
    inverse_error (the model's reason when it cannot invert, else ''), fit_error.

    models: kinds ('pi', ...) or dicts {kind, label, operators, offset, degree, hidden, epochs,
            seed}; None: the pipeline's six stack models (sysid._sysid.stack_model_specs()).
    client, threads, errors, chunksize, progress, var/rate/scale: as in `batch` (one task per
            (recording, model) pair; each task fits on one thread).
    """
    import pandas
    import sysid
    _check_run_args(client, threads, chunksize, models=models)
    if errors not in ("raise", "record"):
        raise sysid.OptionsError("batch: errors must be 'raise' or 'record'")
    items = _recording_items(recordings)
    specs = _hysteresis_specs(models)
    pairs = [(item, spec) for item in items for spec in specs]
    mapping = sysid._mapping(var, rate, scale) if (var or rate or scale) else None
    rows = _map(_hysteresis_one, pairs, client, threads, chunksize or 1, progress,
                train_fraction=train_fraction, errors=errors, mapping=mapping)
    return pandas.DataFrame.from_records(rows)


def batch(recordings, task="dominance", model=None, client=None, threads=None, options=None,
          errors="raise", chunksize=None, progress=None, var=None, rate=None, scale=None,
          models=None, train_fraction=0.4, **kwargs):
    """Runs `task` on every recording and returns one pandas.DataFrame, a row per recording in
    input order.

    recordings: a glob pattern, a path, or a list of paths / sysid.Recording objects (paths
                are read where the task runs, so Dask workers read their own files).
    task:       'dominance' (needs `model`), 'identify_pulses', 'identify_trajectory',
                'tune_delay' (needs `model`), 'hysteresis' (hysteresis `models` x recordings,
                fitted on the first `train_fraction` of each: see hysteresis_batch),
                'irreducible' (the least MSE any model of `output` on each input set can reach,
                sysid.irreducible_error: columns irreducible_mse[v], irreducible_mse[v,a], ...,
                rows, output_variance; keywords inputs=("v", "v,a"), output="u",
                neighbours=10, seed=1).
    model:      sysid.Model or a model JSON path.
    client:     a dask.distributed.Client: tasks run on its workers; None: a local thread pool
                of `threads` (None or 0: all cores; at most 1024, as the CLI).
    options:    the task's option struct; keywords set its fields (e.g. min_speed_mps=2e-3).
    errors:     'raise' (a failing recording raises its sysid.Error) or 'record' (the
                row gets an 'error' column with the message and the batch goes on).
    chunksize:  recordings per task, an integer >= 1 (None: about 4 tasks per worker thread).
                A bad client, threads or chunksize is an OptionsError before any work; no
                recordings (or a pattern matching no file) a DataError.
    progress:   print "k/n" to stderr as tasks finish (default: when stderr is a terminal).
    var, rate, scale: how files are read, as in sysid.read_recording (MAT and HDF5 files, or
                renamed CSV columns; e.g. var={"u": "/multisine/u", "x": "/multisine/y"},
                rate=750).
    """
    import pandas
    import sysid
    if task not in TASKS:
        raise sysid.OptionsError(f"batch: task '{task}': expected one of {', '.join(TASKS)}")
    _check_run_args(client, threads, chunksize)
    if task == "hysteresis":
        return hysteresis_batch(recordings, models, client, threads, train_fraction, errors,
                                chunksize, progress, var, rate, scale)
    if errors not in ("raise", "record"):
        raise sysid.OptionsError("batch: errors must be 'raise' or 'record'")
    if task in ("dominance", "tune_delay"):
        if model is None:
            raise sysid.OptionsError(f"batch: task '{task}' needs a model")
        model = sysid._as_model(model)
    items = _recording_items(recordings)
    opts = _default_options(task, options, kwargs)
    mapping = sysid._mapping(var, rate, scale) if (var or rate or scale) else None
    rows = _map(_guarded, items, client, threads, chunksize, progress, task=task, model=model,
                options=opts, errors=errors, mapping=mapping)
    return pandas.DataFrame.from_records(rows)


def _train_one(pair, train, validation, test, inputs, output, options):
    import sysid
    hidden, seed = pair
    opts = sysid._options(sysid.TrainingOptions, options, {})
    opts.hidden, opts.seed, opts.threads = int(hidden), int(seed), 1
    tr = sysid._as_dataset(train, inputs, output)
    va = sysid._as_dataset(validation, inputs, output)
    r = _sysid.train_dataset(tr, va, opts)
    te = sysid._as_dataset(test, inputs, output)
    return {"hidden": int(hidden), "seed": int(seed), "epochs": r.epochs,
            "train_mse": r.train_mse, "validation_mse": r.validation_mse,
            "test_mse": _sysid.mean_squared_error(r.network, te) if te is not None else
            float("nan"),
            "termination": r.termination, "wall_time_s": r.wall_time_s}


def sweep_grid(train, hidden_sizes, seeds=(1,), validation=None, test=None, inputs=("v",),
               output="u", client=None, threads=None, options=None, chunksize=1, progress=None,
               **kwargs):
    """Trains one network per (hidden size, seed) and returns one pandas.DataFrame (hidden,
    seed, epochs, train/validation/test MSE [output unit^2], termination, wall time), rows in
    sizes-major order. Data are CSV paths (read where the task runs) or Recordings."""
    import pandas
    import sysid
    if isinstance(hidden_sizes, str):
        hidden_sizes = sysid.parse_hidden_sizes(hidden_sizes)
    hidden_sizes, seeds = list(hidden_sizes), list(seeds)
    _check_run_args(client, threads, chunksize, hidden_sizes=hidden_sizes, seeds=seeds)
    if isinstance(inputs, str):
        inputs = inputs.split(",")
    opts = sysid._options(sysid.TrainingOptions, options, kwargs)
    pairs = [(h, s) for h in hidden_sizes for s in seeds]
    rows = _map(_train_one, pairs, client, threads, chunksize, progress, train=train,
                validation=validation, test=test, inputs=list(inputs), output=output,
                options=opts)
    return pandas.DataFrame.from_records(rows)
