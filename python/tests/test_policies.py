"""Honest defaults and one policy from Python (issue 29): a3 says whether it was given, x in mm
draws a UnitWarning (and '# units: x=mm' converts), and v, a columns are used when present."""
import numpy as np
import pytest

import sysid
from conftest import VIRTUAL

DEFAULT_A3 = "a3 = 6 (default: the paper's HR-8 data sheet; give --a3 for your stage)"


def test_a3_default_is_said():
    pulses = sysid.read_recording(VIRTUAL / "pulses.csv")
    default = sysid.identify_pulses(pulses)
    assert not default.a3_given and DEFAULT_A3 in default.brief_report()
    given = sysid.identify_pulses(pulses, a3=6.0)
    assert given.a3_given and "a3 = 6 (given)" in given.brief_report()
    assert sysid.PulseFitOptions(a3=5.0).a3_given and not sysid.PulseFitOptions().a3_given
    # The same parameters either way: only the words differ.
    assert default.model == given.model


def test_mm_positions_warn_and_units_metadata_converts():
    t = np.arange(200) * 1e-3
    x_mm = 50.0 * t  # 50 mm/s, written in mm: 50 "m/s" read as metres
    with pytest.warns(sysid.UnitWarning, match=r"'# units: x=mm'"):
        sysid.recording(t=t, u=np.ones(200), x=x_mm)
    import warnings
    with warnings.catch_warnings():
        warnings.simplefilter("error", sysid.UnitWarning)
        rec = sysid.recording(t=t, u=np.ones(200), x=x_mm, metadata=[("units", "x=mm")])
    np.testing.assert_allclose(rec["x"], x_mm * 1e-3, rtol=1e-15)  # converted exactly
    assert sysid.unit_warnings(rec) == []


def test_v_a_columns_are_used_when_present():
    t = np.arange(100) * 1e-3
    rec = sysid.recording(t=t, u=np.zeros(100), x=0.5 * t ** 2, v=3 * t, a=np.full(100, 5.0))
    m = sysid.extract_motion(rec)
    assert m.velocity_from == "columns v, a"
    np.testing.assert_array_equal(m.a_mps2, 5.0)
    m = sysid.extract_motion(rec, sysid.MotionOptions(prefer_velocity_column=False))
    assert m.velocity_from == "x (central)"
    assert m.a_mps2[50] == pytest.approx(1.0, rel=1e-6)  # x'' of t^2 / 2
