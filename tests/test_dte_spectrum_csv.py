"""``dte_spectrum.csv``: mesh order and um as the README's figure table says, order 0 the mean."""

import csv
import json
import re
from pathlib import Path

import numpy as np
import pytest

from pipeline.dynamics.results import DTE_SPECTRUM_COLUMNS, Response

ROOT = Path(__file__).resolve().parents[1]


def _readme_columns(name: str) -> tuple[str, ...]:
    """The back-quoted column names after "columns" in the README table row of ``name``."""
    row = next(line for line in (ROOT / "README.md").read_text().splitlines()
               if line.startswith(f"| `{name}"))
    return tuple(re.findall(r"`([^`]*\[[^`]*\])`", row.split("columns", 1)[1]))


def test_spectrum_of_a_known_signal():
    """d(t) = 17 + 3 cos(2 pi t/T) + 1 sin(6 pi t/T) um over one period of 60 samples (plus
    the repeated end sample): order 0 is the mean 17 um, orders 1 and 3 their amplitudes
    3 and 1 um (exact discrete Fourier series), every other order 0."""
    period, n = 2.5e-4, 60
    t = np.linspace(0.0, period, n + 1)
    d = 1e-6 * (17.0 + 3.0 * np.cos(2 * np.pi * t / period) + np.sin(6 * np.pi * t / period))
    zero = np.zeros((n + 1, 1))
    resp = Response(t, zero, zero, d[None, :], d[None, :], ("x",), ("mesh",), period)
    cols = resp.dte_spectrum_columns(0)
    assert tuple(cols) == DTE_SPECTRUM_COLUMNS
    order, amp = cols["mesh order [-]"], cols["DTE amplitude [um]"]
    np.testing.assert_allclose(order[:4], [0.0, 1.0, 2.0, 3.0], atol=1e-12)
    expected = np.zeros_like(amp)
    expected[[0, 1, 3]] = [17.0, 3.0, 1.0]
    np.testing.assert_allclose(amp, expected, atol=1e-9)


def test_response_command_writes_readme_columns(tmp_path, capsys):
    """The CSV of ``gearpipe response`` on the assembly-error pair has the README's columns,
    integer mesh orders and an order-0 row equal to the time mean of the DTE in
    ``summary.json`` (to the CSV's printed digits)."""
    from pipeline.cli import main

    cfg = ROOT / "workflows/configs/spur_pair_assembly_errors.toml"
    assert main(["response", str(cfg), "--out", str(tmp_path)]) == 0
    with open(tmp_path / "dte_spectrum.csv", newline="") as fh:
        rows = list(csv.reader(fh))
    assert tuple(rows[0]) == _readme_columns("dte_spectrum") == DTE_SPECTRUM_COLUMNS
    data = np.array(rows[1:], dtype=float)
    np.testing.assert_allclose(data[:, 0], np.arange(len(data)), atol=1e-9)
    summary = json.loads((tmp_path / "summary.json").read_text())
    mean_um = summary["meshes"]["mesh"]["dte_mean_m"] * 1e6
    assert mean_um > 1.0  # a loaded pair: the mean is micrometres, not round-off
    assert data[0, 1] == pytest.approx(mean_um, rel=1e-6)
