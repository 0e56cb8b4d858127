"""sysid.csv_table: the one CSV writer of the library (the report's tables, the CLI's, Python's).
Reference: Python's csv module, an independent RFC 4180 reader, reads back what it writes."""
import csv
import io
import math
import shutil

import pytest

import sysid
from conftest import VIRTUAL

TRICKY = ["plain", "", "a,b", 'say "hi"', '"', '""', "two\nlines", "cr\rlf\r\n", ",", " lead",
          "trail ", "tab\there", "é ünïcode", "x'y", "#not a comment", "=1+2", ";"]


def read_back(text):
    return list(csv.reader(io.StringIO(text, newline=""), strict=True))


def test_tricky_text_fields_read_back_unchanged():
    rows = [[a, b] for a in TRICKY for b in reversed(TRICKY)]
    text = sysid.csv_table(["first", "second, with a comma"], rows)
    back = read_back(text)
    assert back[0] == ["first", "second, with a comma"]
    assert back[1:] == rows
    # Every line ends in LF (not CRLF) outside quoted fields: the documented dialect.
    assert text.endswith("\n") and not text.endswith("\r\n")


def test_numbers_read_back_to_the_same_double_with_17_digits():
    values = [0.1, 1 / 3, -2.5e-310, 6.02214076e23, 1e308, -0.0, 123456789.0, math.pi]
    rows = [[v, i, None, True] for i, v in enumerate(values)]
    back = read_back(sysid.csv_table(["v", "i", "empty", "flag"], rows))
    assert [float(r[0]) for r in back[1:]] == values
    assert [int(r[1]) for r in back[1:]] == list(range(len(values)))
    assert all(r[2] == "" and r[3] == "1" for r in back[1:])
    # Fewer digits: as printf's %.6g, which Python's "%.6g" also is.
    six = read_back(sysid.csv_table(["v"], [[v] for v in values], digits=6))
    assert [r[0] for r in six[1:]] == ["%.6g" % v for v in values]


def test_rows_must_be_as_wide_as_the_header():
    with pytest.raises(ValueError, match="row 1 has 1 fields, the header 2"):
        sysid.csv_table(["a", "b"], [["x", "y"], ["z"]])
    with pytest.raises(TypeError, match="expected str, int, float or None"):
        sysid.csv_table(["a"], [[[1, 2]]])


def test_the_dominance_table_quotes_a_file_name_with_a_comma_quote_and_newline(tmp_path):
    # A library table reaching Python (table_csv, the CLI's -o) through the same writer.
    name = tmp_path / 'we,"ird"\nname.csv'
    shutil.copy(VIRTUAL / "test.csv", name)
    model = sysid.identify_pulses(sysid.read_recordings(str(VIRTUAL / "pulses.csv"))).model
    text = sysid.dominance(model, [str(name)]).table_csv()
    rows = read_back("".join(l for l in io.StringIO(text, newline="") if not l.startswith("#")))
    assert rows[0][:3] == ["source", "rank", "variable"]
    assert len(rows) > 1 and all(r[0] == str(name) and len(r) == len(rows[0]) for r in rows[1:])
