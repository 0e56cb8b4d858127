"""The example scripts in experiments/ run on small data and write what they promise."""
import os
import shutil
import subprocess
import sys

import pandas

import sysid
from conftest import ROOT, VIRTUAL


def run_script(name, *args, cwd):
    proc = subprocess.run([sys.executable, str(ROOT / "experiments" / name), *map(str, args)],
                          capture_output=True, text=True, cwd=cwd, env=os.environ.copy())
    assert proc.returncode == 0, proc.stderr
    return proc


def test_batch_dominance_script(tmp_path):
    data = tmp_path / "data"
    data.mkdir()
    for name in ("pulses.csv", "waveform_square.csv", "waveform_triangle.csv"):
        shutil.copy(VIRTUAL / name, data / name)
    out = tmp_path / "out"
    run_script("batch_dominance.py", data, "-o", out, "--threads", "2", cwd=tmp_path)
    table = pandas.read_csv(out / "dominance.csv", float_precision="round_trip")
    assert [os.path.basename(s) for s in table["source"]] == ["waveform_square.csv",
                                                             "waveform_triangle.csv"]
    # The script's model is pulse least squares + delay tuning: the same table from the API.
    recs = [sysid.read_recording(data / "pulses.csv")]
    model = sysid.tune_delay(sysid.identify_pulses(recs).model, recs).model
    expected = sysid.dominance(model, data / "waveform_square.csv")
    assert table.loc[0, "dominant"] == expected.dominant
    assert table.loc[0, "margin"] == expected.margin
    assert (out / "dominance.png").read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


def test_sweep_dask_script(tmp_path):
    out = tmp_path / "sweep.csv"
    run_script("sweep_dask.py", "--train", VIRTUAL / "training.csv", "--test",
               VIRTUAL / "test.csv", "--hidden", "2,3", "--seeds", "1,2", "--max-epochs", "3",
               "--workers", "2", "-o", out, cwd=tmp_path)
    table = pandas.read_csv(out, float_precision="round_trip")
    assert list(zip(table.hidden, table.seed)) == [(2, 1), (2, 2), (3, 1), (3, 2)]
    r = sysid.train(VIRTUAL / "training.csv", hidden=3, seed=2, max_epochs=3)
    assert table.train_mse[3] == r.train_mse
