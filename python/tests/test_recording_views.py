"""rec[name] and rec.data are NumPy views into the recording's storage (docs/python.md,
"Recordings"). Appending a column grows that storage and may move it; a view taken before must
then stay valid (detached, with the values it had), never point into freed memory: before the
fix, writing through such a view corrupted the heap (`double free or corruption`, exit 134)."""
import os
import subprocess
import sys
import textwrap

import numpy as np

import sysid


def _recording(n=7100):
    t = np.arange(n) * 1e-3
    return sysid.recording(t=t, u=np.sin(t), x=1e-3 * np.cos(t))


def _address(a):
    return a.__array_interface__["data"][0]


def test_views_track_the_recording_until_a_column_is_appended():
    rec = _recording(100)
    x = rec["x"]
    x[0] = 0.5  # a view: writes reach the recording
    assert rec["x"][0] == 0.5 and rec.data[0, 2] == 0.5
    rec.set_column("x", np.zeros(100))  # replacing writes in place: the view sees it
    assert np.all(x == 0.0)


def test_views_taken_before_appending_keep_their_values_and_memory():
    rec = _recording()
    x, data = rec["x"], rec.data
    expected_x, expected_data = x.copy(), data.copy()
    moved = False
    for k in range(40):  # until the storage moves (realloc may grow in place a few times)
        before = _address(rec.data)
        rec.set_column(f"z{k}", np.full(rec.rows, float(k)))
        moved = moved or _address(rec.data) != before
    assert moved
    # Allocate recordings of the freed size: they would land on the old buffer if it were freed.
    others = [_recording() for _ in range(20)]
    np.testing.assert_array_equal(x, expected_x)
    np.testing.assert_array_equal(data, expected_data)
    x[:] = 4.2e9  # detached: the write stays in the view's own buffer
    data[:, 0] = -1.0
    np.testing.assert_array_equal(rec["x"], expected_x)
    np.testing.assert_array_equal(rec["t"], expected_data[:, 0])
    assert rec.names[:3] == ["t", "u", "x"] and rec.data.shape == (7100, 43)
    np.testing.assert_array_equal(rec["z39"], 39.0)
    for o in others:
        assert not np.any(o.data == 4.2e9) and not np.any(o.data[:, 0] == -1.0)
    # A view taken after appending tracks the recording again.
    y = rec["x"]
    y[0] = 7.0
    assert rec["x"][0] == 7.0


def test_a_view_outlives_its_recording():
    rec = _recording(50)
    x, data = rec["x"], rec.data
    expected = x.copy()
    del rec  # the view keeps the storage (and the recording) alive
    np.testing.assert_array_equal(x, expected)
    rec = _recording(50)
    x = rec["x"]
    rec.set_column("z", np.zeros(50))
    del rec  # detached: the view owns the old buffer, the recording may go
    np.testing.assert_array_equal(x, expected)
    assert data.shape == (50, 3)


def test_the_audit_reproduction_exits_cleanly():
    # The audit's script, in a child process whose allocator scribbles over freed memory
    # (MALLOC_PERTURB_): a view into a freed buffer would read the scribble, write into another
    # recording or abort the child.
    script = textwrap.dedent("""
        import numpy as np, sysid
        n = 7100
        t = np.arange(n) * 1e-3
        rec = sysid.recording(t=t, u=np.sin(t), x=1e-3 * np.cos(t))
        x = rec["x"]
        for k in range(3):
            rec.set_column("z%d" % k, np.zeros(n))
        assert np.array_equal(x, 1e-3 * np.cos(t)), "the view lost its values"
        x[:] = 4.2e9
        cols = {c: np.zeros(n) for c in ["u", "x", "c0", "c1", "c2", "c3"]}
        cols["t"] = t
        others = [sysid.recording(**cols) for _ in range(50)]
        assert not any(np.any(o.data == 4.2e9) for o in others), "another recording changed"
        print("ok")
    """)
    env = dict(os.environ, MALLOC_PERTURB_="165")
    proc = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True, env=env,
                          timeout=120)
    assert proc.returncode == 0 and proc.stdout.strip() == "ok", proc.stderr
