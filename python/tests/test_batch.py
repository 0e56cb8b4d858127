"""sysid.batch and sysid.sweep_grid: a thread pool of 2 gives the table of 1 thread, and a Dask
LocalCluster of 2 worker processes gives the table of the serial run."""
import pandas
import pytest

import sysid
from conftest import VIRTUAL

WAVEFORMS = str(VIRTUAL / "waveform_*.csv")


@pytest.fixture(scope="module")
def model():
    return sysid.identify_pulses(VIRTUAL / "pulses.csv").model


def test_batch_dominance_matches_per_recording_and_threads(model):
    serial = sysid.batch(WAVEFORMS, model=model, threads=1)
    two = sysid.batch(WAVEFORMS, model=model, threads=2)
    pandas.testing.assert_frame_equal(serial, two)
    files = sysid.expand_paths(WAVEFORMS)
    assert list(serial["source"]) == files and len(files) == 6
    for row, path in zip(serial.to_dict("records"), files):
        single = sysid.dominance(model, path)
        assert row["dominant"] == single.dominant and row["margin"] == single.margin
    # Recording objects work as well as paths.
    recs = sysid.read_recordings(WAVEFORMS)
    pandas.testing.assert_frame_equal(sysid.batch(recs, model=model, threads=2), serial)


def test_one_chunk_call_reusing_buffers_equals_one_call_per_file(model, tmp_path):
    """A chunk is one C++ call reusing one reader and one workspace over its files: every row
    (all columns, exactly) is the one-file call's, across files of different lengths and a
    failing file in between."""
    files = sysid.expand_paths(WAVEFORMS)
    short = sysid.read_recording(files[0])
    cut = tmp_path / "short.csv"
    cut.write_text("t,u,x\n" + "".join(f"{t!r},{u!r},{x!r}\n" for t, u, x in
                   zip(short["t"][:700], short["u"][:700], short["x"][:700])))
    bad = tmp_path / "bad.csv"
    bad.write_text("t,u,x\n0,1,2\n0.001,1,oops\n")
    chunk = [files[0], str(cut), str(bad), files[1], files[0], files[2]]
    opts = sysid.DominanceOptions(threads=1)
    rows = sysid._sysid.dominance_rows_files(model, chunk, opts)
    for path, row in zip(chunk, rows):
        if path == str(bad):
            assert row["error_type"] == "DataError" and "bad.csv:3:" in row["error"]
            continue
        single = sysid._sysid.analyze_dominance(model, sysid.read_recording(path), opts).row()
        assert repr(row) == repr(single)  # exact, not approximate
    recs = [sysid.read_recording(p) for p in chunk if p != str(bad)]
    in_memory = sysid._sysid.dominance_rows(model, recs, opts)
    assert repr(in_memory) == repr([r for r in rows if "error" not in r])


def test_batch_other_tasks_and_errors(model, tmp_path):
    ident = sysid.batch([VIRTUAL / "pulses.csv"], task="identify_pulses", threads=2)
    assert ident.loc[0, "a1p"] == sysid.identify_pulses(VIRTUAL / "pulses.csv").model.a1p
    tuned = sysid.batch([VIRTUAL / "pulses.csv"], task="tune_delay", model=model, threads=1,
                        max_evaluations=20)
    assert tuned.loc[0, "tau_s"] == sysid.tune_delay(model, VIRTUAL / "pulses.csv",
                                                     max_evaluations=20).tau_s
    bad = tmp_path / "bad.csv"
    bad.write_text("t,u,x\n0,0,0\n0.001,1,abc\n")
    with pytest.raises(sysid.DataError, match="bad.csv:3:"):
        sysid.batch([bad], model=model)
    table = sysid.batch([VIRTUAL / "waveform_square.csv", bad], model=model, errors="record")
    assert pandas.isna(table.loc[0, "error"]) and "DataError" in table.loc[1, "error"]
    with pytest.raises(sysid.OptionsError, match="task"):
        sysid.batch([bad], task="nope")
    with pytest.raises(sysid.DataError, match="no file matches"):
        sysid.batch(str(tmp_path / "none_*.csv"), model=model)


def test_sweep_grid_threads():
    kw = dict(hidden_sizes=[2, 3], seeds=[1, 2], max_epochs=4)
    one = sysid.sweep_grid(str(VIRTUAL / "training.csv"), threads=1, **kw)
    two = sysid.sweep_grid(str(VIRTUAL / "training.csv"), threads=2, **kw)
    pandas.testing.assert_frame_equal(one.drop(columns="wall_time_s"),
                                      two.drop(columns="wall_time_s"))
    assert list(zip(one.hidden, one.seed)) == [(2, 1), (2, 2), (3, 1), (3, 2)]
    r = sysid.train(VIRTUAL / "training.csv", hidden=3, seed=2, max_epochs=4, threads=1)
    assert one.train_mse[3] == r.train_mse


def test_dask_local_cluster_of_two_processes_equals_serial(model):
    distributed = pytest.importorskip("distributed")
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                                  dashboard_address=":0") as cluster, \
            distributed.Client(cluster) as client:
        table = sysid.batch(WAVEFORMS, model=model, client=client)
        # With progress the chunks are collected as they finish (as_completed), else in one
        # gather: same table.
        shown = sysid.batch(WAVEFORMS, model=model, client=client, chunksize=1, progress=True)
        grid = sysid.sweep_grid(str(VIRTUAL / "training.csv"), hidden_sizes=[2, 3], seeds=[1],
                                max_epochs=4, client=client)
        assert len(client.scheduler_info()["workers"]) == 2
    pandas.testing.assert_frame_equal(table, sysid.batch(WAVEFORMS, model=model, threads=1))
    pandas.testing.assert_frame_equal(shown, table)
    serial = sysid.sweep_grid(str(VIRTUAL / "training.csv"), hidden_sizes=[2, 3], seeds=[1],
                              max_epochs=4, threads=1)
    pandas.testing.assert_frame_equal(grid.drop(columns="wall_time_s"),
                                      serial.drop(columns="wall_time_s"))


def test_user_thread_pool_of_two_equals_one(model):
    # Long calls release the GIL: a plain concurrent.futures pool runs them side by side, and
    # the results are those of the serial loop.
    import concurrent.futures
    recs = sysid.read_recordings(WAVEFORMS) * 3
    serial = [sysid.dominance(model, r).to_dict() for r in recs]
    with concurrent.futures.ThreadPoolExecutor(max_workers=2) as pool:
        pooled = list(pool.map(lambda r: sysid.dominance(model, r).to_dict(), recs))
    assert pooled == serial
    with concurrent.futures.ThreadPoolExecutor(max_workers=2) as pool:
        tuned = list(pool.map(lambda r: sysid.tune_delay(model, r, threads=1).tau_s,
                              recs[:2]))
    assert tuned == [sysid.tune_delay(model, r, threads=1).tau_s for r in recs[:2]]


def test_progress_on_stderr(model, capsys):
    sysid.batch(WAVEFORMS, model=model, threads=2, chunksize=2, progress=True)
    err = capsys.readouterr().err
    assert "sysid batch: 2/6" in err and err.endswith("sysid batch: 6/6\n")
    sysid.batch(WAVEFORMS, model=model, threads=2, progress=False)
    assert capsys.readouterr().err == ""


def test_batch_irreducible_row_per_recording_equals_single_calls():
    paths = [str(VIRTUAL / "training.csv"), str(VIRTUAL / "test.csv")]
    table = sysid.batch(paths, task="irreducible", threads=2, neighbours=12)
    assert list(table["source"]) == paths
    for row, path in zip(table.to_dict("records"), paths):
        for inputs in ("v", "v,a"):
            single = sysid.irreducible_error(path, inputs=inputs, neighbours=12)
            assert row[f"irreducible_mse[{inputs}]"] == single.mse  # same seed: bit for bit
        assert row["rows"] == single.rows
        assert row["output_variance"] == single.output_variance
    with pytest.raises(sysid.OptionsError, match="takes inputs"):
        sysid.batch(paths, task="irreducible", k=3)


TRAINING = str(VIRTUAL / "training.csv")


@pytest.mark.parametrize("run", ["batch", "sweep_grid", "hysteresis"])
@pytest.mark.parametrize("kw, message", [
    ({"chunksize": -1}, "chunksize: expected an integer >= 1 or None (the default), found -1"),
    ({"chunksize": -3}, "chunksize: expected an integer >= 1 or None (the default), found -3"),
    ({"chunksize": 0}, "chunksize: expected an integer >= 1 or None (the default), found 0"),
    ({"chunksize": 1.5}, "found 1.5"),
    ({"threads": -1}, "threads: expected an integer in [0, 1024] (0: all cores) or None, "
                      "found -1"),
    ({"threads": 10**9}, f"found {10**9}"),
    ({"threads": 1.5}, "found 1.5"),
    ({"threads": "2"}, "threads: expected an integer in [0, 1024] (0: all cores) or None, "
                       "found '2'"),
    ({"threads": True}, "found True"),
    ({"client": "tcp://localhost:8786"}, "client: expected a dask.distributed.Client or None, "
                                         "found str"),
    ({"client": object()}, "client: expected a dask.distributed.Client or None, found object"),
])
def test_run_arguments_are_checked_before_any_work(model, run, kw, message):
    calls = {"batch": lambda: sysid.batch(WAVEFORMS, model=model, **kw),
             "hysteresis": lambda: sysid.batch(WAVEFORMS, task="hysteresis", models=["pi"], **kw),
             "sweep_grid": lambda: sysid.sweep_grid(TRAINING, hidden_sizes=[2], max_epochs=2,
                                                    **kw)}
    # The wrong Python kind (a float, a string, a bool, not a Client) is a TypeError, a value
    # out of range an OptionsError (docs/python.md, "Conventions").
    wrong_kind = any(isinstance(v, (float, str, bool)) or
                     (k == "client" and v is not None) for k, v in kw.items())
    with pytest.raises(TypeError if wrong_kind else sysid.OptionsError) as e:
        calls[run]()
    assert message in str(e.value)


def test_threads_bounds_and_chunksize_none_are_accepted(model):
    serial = sysid.batch(WAVEFORMS, model=model, threads=1)
    for kw in ({"threads": 0}, {"threads": 1024}, {"chunksize": None}, {"chunksize": 100}):
        pandas.testing.assert_frame_equal(sysid.batch(WAVEFORMS, model=model, **kw), serial)


def test_empty_inputs_are_errors_not_empty_tables(model, tmp_path):
    with pytest.raises(sysid.DataError, match="recordings: no recordings"):
        sysid.batch([], model=model)
    with pytest.raises(sysid.DataError, match="recordings: no recordings"):
        sysid.batch([], task="hysteresis")
    for pattern in (str(tmp_path / "*.csv"), [str(tmp_path / "*.csv")]):
        with pytest.raises(sysid.DataError) as e:
            sysid.batch(pattern, model=model)
        assert str(e.value) == f"{tmp_path / '*.csv'}: no file matches the pattern"
    with pytest.raises(sysid.OptionsError, match=r"^models: expected a non-empty list, found \[\]"):
        sysid.batch(WAVEFORMS, task="hysteresis", models=[])
    with pytest.raises(sysid.OptionsError, match=r"^hidden_sizes: expected a non-empty list"):
        sysid.sweep_grid(TRAINING, hidden_sizes=[])
    with pytest.raises(sysid.OptionsError, match=r"^seeds: expected a non-empty list"):
        sysid.sweep_grid(TRAINING, hidden_sizes=[2], seeds=[])
