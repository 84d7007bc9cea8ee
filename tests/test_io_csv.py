"""CSV files (pipeline.io.write_csv): one header field per data column, whatever the names hold."""

from __future__ import annotations

import csv

import numpy as np
import pytest

from pipeline.io import write_csv

# names as the workflows write them: case labels with commas, an equals sign, quotes
NAMES = ["pinion_angle [rad]", "case0 mu = 0.0 [N/m]",
         "case1 cond 1: e = (10, 10) um, mu = 0.05 [N/m]", 'tip "A" [N]',
         "kind [0 none,1 rigid,2 rot]"]


def _read(path):
    with open(path, newline="", encoding="utf-8") as fh:
        return list(csv.reader(fh))


def test_header_with_commas_round_trips(tmp_path):
    """A header with commas inside names reads back as exactly the given names, and every
    row has as many fields as the header (the old writer gave 10 header fields, 7 per row
    on the assembly-error workflow's curves.csv)."""
    data = np.arange(15.0).reshape(3, 5) / 7.0
    path = write_csv(tmp_path / "c.csv", dict(zip(NAMES, data.T, strict=True)))
    rows = _read(path)
    assert rows[0] == NAMES
    assert all(len(r) == len(NAMES) for r in rows[1:])
    back = np.array(rows[1:], dtype=float)
    assert back == pytest.approx(data, rel=1e-8)  # 9 significant digits
    assert np.genfromtxt(path, delimiter=",", skip_header=1).shape == (3, 5)


def test_text_column_is_quoted_where_needed(tmp_path):
    """A column of case names with commas is one field; numbers keep 9 digits."""
    path = write_csv(tmp_path / "t.csv", {"case": ["a, b", "plain"], "k [N/m]": [1.0 / 3, 2e8]})
    rows = _read(path)
    assert rows == [["case", "k [N/m]"], ["a, b", "0.333333333"], ["plain", "200000000"]]


def test_unequal_columns_are_refused_and_nothing_is_written(tmp_path):
    with pytest.raises(ValueError, match="equal length"):
        write_csv(tmp_path / "bad.csv", {"a [m]": [1.0, 2.0], "b [m]": [1.0]})
    assert list(tmp_path.iterdir()) == []
