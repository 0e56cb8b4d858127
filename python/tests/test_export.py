"""sysid.export: the same files as `sysid export` (byte for byte), from objects in Python."""
import hashlib
import pytest

import sysid
from conftest import run_cli

MODEL_JSON = '{"a1p": 104.0154, "a1n": 117.1441, "a2p": 3.1023, "a2n": 6.8216, "a3": 6, "tau": 0.00379}'


def test_friction_export_matches_the_cli(tmp_path):
    path = tmp_path / "m.json"
    path.write_text(MODEL_JSON)
    model = sysid.Model.load(str(path))
    out = sysid.export(model, str(tmp_path / "py"), prefix="ff", dt_s=1e-4)
    assert out["kind"] == "friction" and out["bound_v"] == 0.0
    assert out["inputs"] == ["v", "a"]
    run_cli("export", "--model", path, "--dt", "1e-4", "--prefix", "ff", "-o", tmp_path / "cli")
    # The C and the vectors are the CLI's; the header differs only in the provenance line (an
    # object has no file name: its hash is that of its JSON text, not of the file's bytes).
    for name in ("ff.c", "ff_vectors.csv", "ff_check.c"):
        assert (tmp_path / "py" / name).read_text() == (tmp_path / "cli" / name).read_text()
    header = (tmp_path / "py" / "ff.h").read_text()
    assert hashlib.sha256(model.to_json().encode()).hexdigest() in header
    assert "a FrictionModel from Python" in header


def test_export_refuses_what_it_cannot_generate(tmp_path):
    path = tmp_path / "m.json"
    path.write_text(MODEL_JSON)
    model = sysid.Model.load(str(path))
    with pytest.raises(Exception, match="dt_s"):
        sysid.export(model, str(tmp_path / "a"))
    with pytest.raises(Exception, match="C99 keyword"):
        sysid.export(model, str(tmp_path / "b"), prefix="int", dt_s=1e-3)
    assert not (tmp_path / "a").exists() and not (tmp_path / "b").exists()


BW_JSON = ('{"kind": "bouc-wen-piezo", "parameters": {"d": 1.87e-05, "alpha": 0.479, '
           '"beta": 0.499, "gamma": 0.0938, "offset": -1.3e-04}}')


def test_bouc_wen_export_matches_the_cli(tmp_path):
    path = tmp_path / "bw.json"
    path.write_text(BW_JSON)
    model = sysid.hysteresis.read(path)
    for precision in ("double", "float"):
        out = sysid.export(model, str(tmp_path / ("py_" + precision)), precision=precision,
                           prefix="bw")
        assert out["kind"] == "bouc-wen-piezo" and out["inputs"] == ["x_ref"]
        assert out["bound_v"] > 0
        run_cli("export", "--hysteresis", path, "--dt", "1e-3", "--precision", precision,
                "--prefix", "bw", "-o", tmp_path / ("cli_" + precision))
        for name in ("bw.c", "bw_vectors.csv", "bw_check.c"):
            assert ((tmp_path / ("py_" + precision) / name).read_text()
                    == (tmp_path / ("cli_" + precision) / name).read_text())
