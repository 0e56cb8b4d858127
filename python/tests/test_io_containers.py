"""MAT and HDF5 recordings from Python: sysid.read_recording with var/rate/scale returns what
the CLI's import wrote (the bundled Bouc-Wen CSVs, themselves checked bit for bit in tests/io)."""
import os

import numpy as np
import pytest

import sysid

ROOT = os.path.join(os.path.dirname(__file__), "..", "..")
BW = os.path.join(ROOT, "datasets", "boucwen")


def test_read_recording_from_hdf5_and_mat_equals_the_imported_csv():
    train = sysid.read_recording(os.path.join(BW, "train.h5"),
                                 var={"u": "/multisine/u", "x": "/multisine/y"}, rate=750)
    csv = sysid.read_recording(os.path.join(BW, "train.csv"))
    assert list(train.names) == ["t", "u", "x"]
    np.testing.assert_array_equal(train.data, csv.data)  # bit for bit
    test = sysid.read_recording(os.path.join(BW, "uval_multisine.mat"),
                                var="u=uval_multisine,x=uval_multisine", rate=750,
                                scale={"x": 2.0})
    np.testing.assert_array_equal(test["x"], 2.0 * test["u"])


def test_list_variables_and_errors():
    v = sysid.list_variables(os.path.join(BW, "uval_multisine.mat"))
    assert v[0]["name"] == "uval_multisine" and v[0]["dims"] == [1, 8192]
    with pytest.raises(sysid.DataError, match=r"no dataset '/multisine/q'"):
        sysid.read_recording(os.path.join(BW, "train.h5"), var={"u": "/multisine/q"}, rate=750)
    with pytest.raises(sysid.DataError, match=r"--rate"):
        sysid.read_recording(os.path.join(BW, "train.h5"),
                             var={"u": "/multisine/u", "x": "/multisine/y"})


def test_save_mat_round_trip(tmp_path):
    rec = sysid.read_recording(os.path.join(BW, "test_multisine.csv"))
    rec.save(str(tmp_path / "r.mat"))
    back = sysid.read_recording(str(tmp_path / "r.mat"))
    np.testing.assert_array_equal(back.data, rec.data)


def test_batch_reads_mat_files_through_var(tmp_path):
    csv = os.path.join(ROOT, "datasets", "virtual", "pulses.csv")
    rec = sysid.read_recording(csv)
    rec.save(str(tmp_path / "p.mat"))
    a = sysid.batch([csv], task="identify_pulses", threads=1)
    b = sysid.batch([str(tmp_path / "p.mat")], task="identify_pulses", threads=1,
                 var={"t": "t", "u": "u", "x": "x"})
    # Same samples bit for bit; the MAT file lacks the CSV's '# key: value' lines (the pulse
    # schedule), so the pulse windows may differ in rounding only: 1e-12 relative.
    for k in ("a1p", "a1n", "a2p", "a2n"):
        assert a[k][0] == pytest.approx(b[k][0], rel=1e-12)
    bad = sysid.batch([str(tmp_path / "p.mat")], task="dominance", model=sysid.Model.paper(),
                   threads=1, errors="record", var={"t": "t", "u": "missing"})
    assert "no variable 'missing'" in bad["error"][0]
