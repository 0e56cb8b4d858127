"""sysid.crop: the rows of a time window, as `--t-start/--t-end` and `--fit-fraction` cut them.
References: a NumPy mask on t, and the CLI's --fit-fraction on the same recording."""
import json

import numpy as np
import pytest

import sysid
from conftest import VIRTUAL, cli_json


def test_crop_keeps_the_rows_of_the_window_as_a_mask_on_t():
    rec = sysid.read_recording(VIRTUAL / "pulses.csv")
    t = rec["t"].copy()
    part = sysid.crop(rec, 1.0, 2.5)
    mask = (t >= 1.0) & (t <= 2.5)
    assert part.rows == int(mask.sum())
    assert part.names == rec.names
    np.testing.assert_array_equal(part.data, rec.data[mask])  # t as recorded, not shifted
    assert part.meta("crop_s") == "1 2.5"
    assert part.source == rec.source
    assert rec.rows == len(t)  # the input is left whole


def test_crop_refuses_windows_outside_reversed_or_empty():
    rec = sysid.read_recording(VIRTUAL / "pulses.csv")
    with pytest.raises(sysid.DataError, match="reaches outside the recording"):
        sysid.crop(rec, 0.0, 1000.0)
    with pytest.raises(sysid.DataError, match="the start before the end"):
        sysid.crop(rec, 2.0, 1.0)
    with pytest.raises(sysid.DataError, match="expected at least 2"):
        sysid.crop(rec, 1.0001, 1.0002)


def test_identify_on_a_cropped_first_part_is_the_cli_fit_fraction():
    rec = sysid.read_recording(VIRTUAL / "pulses.csv")
    t = rec["t"]
    first, last = float(t[0]), float(t[-1])
    part = sysid.crop(rec, first, first + 0.5 * (last - first))
    r = sysid.identify_pulses([part])
    j = cli_json("identify", "--fit-fraction", "0.5", VIRTUAL / "pulses.csv")
    whole = cli_json("identify", VIRTUAL / "pulses.csv")
    assert json.loads(r.to_json())["a1p"] == j["a1p"]
    assert json.loads(r.to_json())["a2n"] == j["a2n"]
    assert j["a1p"] != whole["a1p"]  # fewer pulses, another fit
