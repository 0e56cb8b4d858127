"""Shared fixtures: the CLI of the same build (SYSID_EXE), the repository (SYSID_SOURCE_DIR)."""
import json
import os
import pathlib
import subprocess

import pytest

ROOT = pathlib.Path(os.environ.get("SYSID_SOURCE_DIR",
                                   pathlib.Path(__file__).resolve().parents[2]))
EXE = os.environ.get("SYSID_EXE", str(ROOT / "build" / "apps" / "sysid"))
VIRTUAL = ROOT / "datasets" / "virtual"


def run_cli(*args, cwd=None, expect=0):
    """Runs `sysid ARGS` (a list of strings, no shell); returns the completed process."""
    proc = subprocess.run([EXE, *map(str, args)], capture_output=True, text=True, cwd=cwd)
    assert proc.returncode == expect, proc.stderr
    return proc


def pulse_only_pipeline_summary():
    """A pipeline summary of a run on pulse recordings alone: no network keys, the skipped steps,
    the tuned gains and the tracking on the model."""
    import sysid
    return {
        "model": json.loads(sysid.Model().to_json()),
        "skipped": ["dominance analysis: needs a training set and a test set"],
        "tracking": [],
        "tuned_pi": {"kp_v_per_m": 1571.7, "ki_v_per_m_s": 26720.0, "sample_time_s": 0.001},
        "model_tracking": [{"frequency_hz": 0.5, "ff": "analytic", "max_error_m": 9.6e-7,
                            "rms_error_m": 4e-7}],
        "steps": [{"name": "identify", "wall_time_s": 0.1}],
    }


def cli_json(*args, cwd=None):
    return json.loads(run_cli(*args, "--json", cwd=cwd).stdout)


@pytest.fixture(scope="session")
def root():
    return ROOT


@pytest.fixture(scope="session")
def virtual():
    return VIRTUAL


@pytest.fixture(scope="session")
def model_file(tmp_path_factory):
    """The model the CLI identifies from the bundled pulse test."""
    path = tmp_path_factory.mktemp("model") / "model.json"
    run_cli("identify", "-o", path, VIRTUAL / "pulses.csv")
    return path
