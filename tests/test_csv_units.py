"""The commands' CSV files: SI units as the README says, ``dte_spectrum.csv`` in mesh orders with
its order 0 the DTE mean."""

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
    order, amp = cols["mesh order [-]"], cols["DTE amplitude [m]"] * 1e6
    np.testing.assert_allclose(order[:4], [0.0, 1.0, 2.0, 3.0], atol=1e-12)
    expected = np.zeros_like(amp)
    expected[[0, 1, 3]] = [17.0, 3.0, 1.0]
    np.testing.assert_allclose(amp, expected, atol=1e-9)


CSVS = ("contact_cycle.csv", "contact_points.csv", "report_face.csv", "report_cycle.csv",
        "dte_spectrum.csv", "time_history.csv", "sweep.csv", "mesh_stiffness.csv")


@pytest.fixture(scope="module")
def report_run(tmp_path_factory):
    """``gearpipe report`` on the assembly-error spur pair (every stage writes its CSVs)."""
    from pipeline.cli import main

    out = tmp_path_factory.mktemp("report")
    cfg = ROOT / "workflows/configs/spur_pair_assembly_errors.toml"
    assert main(["report", str(cfg), "--out", str(out)]) == 0
    return out


def _header(path: Path) -> list[str]:
    with open(path, newline="") as fh:
        return next(csv.reader(fh))


def _readme_si_units() -> set[str]:
    """The units after "SI units only:" in the README (back-quoted, in brackets)."""
    text = " ".join((ROOT / "README.md").read_text().split())
    listed = text.split("SI units only:", 1)[1].split(".", 1)[0]
    return set(re.findall(r"`\[([^`]*)\]`", listed))


@pytest.mark.parametrize("name", CSVS)
def test_csv_columns_are_in_the_readme_units(report_run, name):
    """Every column of the file names one unit, and that unit is one of the README's SI list
    (no N/mm beside m in one file)."""
    units = _readme_si_units()
    assert {"m", "N/m", "N", "-"} <= units and "N/mm" not in units
    for column in _header(report_run / name):
        found = re.findall(r"\[([^\]]*)\]", column)
        assert len(found) == 1 and found[0] in units, (name, column)


def test_dte_spectrum_csv(report_run):
    """``dte_spectrum.csv`` has the README's columns, integer mesh orders and an order-0 row
    equal to the time mean of the DTE: the mean of ``time_history.csv`` over one period (its
    last row repeats the first) and ``dte_mean_m`` of ``summary.json``."""
    rows = list(csv.reader(open(report_run / "dte_spectrum.csv", newline="")))
    assert tuple(rows[0]) == _readme_columns("dte_spectrum") == DTE_SPECTRUM_COLUMNS
    data = np.array(rows[1:], dtype=float)
    np.testing.assert_allclose(data[:, 0], np.arange(len(data)), atol=1e-9)
    history = np.loadtxt(report_run / "time_history.csv", delimiter=",", skiprows=1)
    assert history[0, 1] == history[-1, 1]
    mean = history[:-1, 1].mean()
    assert mean > 1e-6  # a loaded pair: the mean is micrometres, not round-off
    assert data[0, 1] == pytest.approx(mean, rel=1e-6)
    summary = json.loads((report_run / "summary.json").read_text())
    at_speed = summary["dynamics"]["response_at_operating_speed"]["meshes"]["mesh"]
    assert data[0, 1] == pytest.approx(at_speed["dte_mean_m"], rel=1e-6)
