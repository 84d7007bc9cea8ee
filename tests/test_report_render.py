"""The HTML report as a browser shows it and prints it (slow: installs and runs Chromium).

Debian's ``chromium`` is installed by the project's own set-up when missing
(``./dev.sh chromium``); the report of a small case is rendered headless to a screenshot
that must not be blank (ink in every 100-pixel band down the page; the report's figures
bring thousands of colours) and printed to PDF (several A4 pages).
"""

from __future__ import annotations

import re
import subprocess
from pathlib import Path

import numpy as np
import pytest
from helpers import small_report

ROOT = Path(__file__).resolve().parents[1]
FLAGS = ("--headless", "--no-sandbox", "--disable-gpu", "--disable-background-networking",
         "--disable-component-update", "--disable-sync", "--no-first-run")


@pytest.fixture(scope="module")
def chromium() -> str:
    done = subprocess.run(["bash", str(ROOT / "dev.sh"), "chromium"], capture_output=True,
                          text=True, timeout=1200)
    assert done.returncode == 0, done.stderr[-2000:]
    return done.stdout.strip().splitlines()[-1]


@pytest.fixture(scope="module")
def report_html(tmp_path_factory) -> Path:
    return small_report(tmp_path_factory.mktemp("render")) / "report.html"


def _chromium(chromium: str, tmp: Path, *args: str) -> None:
    cmd = [chromium, *FLAGS, f"--user-data-dir={tmp / 'profile'}", *args]
    done = subprocess.run(cmd, capture_output=True, text=True, timeout=180)
    assert done.returncode == 0, done.stderr[-2000:]


@pytest.mark.slow
def test_screenshot_is_not_blank(chromium, report_html, tmp_path):
    from PIL import Image

    shot = tmp_path / "report.png"
    _chromium(chromium, tmp_path, f"--screenshot={shot}", "--window-size=1100,2600",
              "--hide-scrollbars", report_html.as_uri())
    img = np.asarray(Image.open(shot).convert("RGB"))
    assert img.shape[0] >= 2000 and img.shape[1] >= 1000
    ink = ~(img > 245).all(axis=2)  # measured: 7.8 % of the first 2600 px, every band inked
    bands = [ink[i:i + 100].mean() for i in range(0, img.shape[0], 100)]
    assert min(bands) > 0.005  # content all the way down, no blank stretch
    assert ink.mean() > 0.04
    colours = np.unique(img.reshape(-1, 3), axis=0).shape[0]
    assert colours > 2000  # the embedded figures were drawn (measured 3690)
    # the heading is rendered in the top band (dark text)
    assert (img[:120] < 100).all(axis=2).mean() > 0.005


@pytest.mark.slow
def test_prints_to_pdf(chromium, report_html, tmp_path):
    pdf = tmp_path / "report.pdf"
    _chromium(chromium, tmp_path, f"--print-to-pdf={pdf}", "--no-pdf-header-footer",
              report_html.as_uri())
    data = pdf.read_bytes()
    assert data.startswith(b"%PDF")
    pages = len(re.findall(rb"/Type\s*/Page[^s]", data))
    assert 4 <= pages <= 20
