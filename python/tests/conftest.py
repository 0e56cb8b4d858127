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
