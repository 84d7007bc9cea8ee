"""A normal run without a display prints only the command's own lines.

``gearpipe`` called directly (not through ``dev.sh``, which sets ``PYVISTA_OFF_SCREEN``,
``MPLBACKEND`` and ``VTK_DEFAULT_OPENGL_WINDOW``) on a machine without a display renders
its 3D load map through EGL with no "bad X server connection" warning from VTK, and a step
shorter than a second shows no progress bar (:mod:`pipeline.progress`).
"""

from __future__ import annotations

import os
import re
import struct
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from pipeline.viz._offscreen import HEADLESS_WINDOW, WINDOW_VARIABLE, headless_window

ROOT = Path(__file__).resolve().parents[1]
SPUR = ROOT / "workflows" / "configs" / "spur_pair_assembly_errors.toml"
PNG_SIGNATURE = b"\x89PNG\r\n\x1a\n"


def _found(name: str) -> str:
    return f"lib{name}.so.1"


def _missing(name: str) -> None:
    return None


WINDOWS = [  # (case, environment, sys.platform, find_library, window class asked for)
    ("no display", {}, "linux", _found, HEADLESS_WINDOW),
    ("Wayland only", {"WAYLAND_DISPLAY": "wayland-0"}, "linux", _found, HEADLESS_WINDOW),
    ("X display", {"DISPLAY": ":0"}, "linux", _found, None),
    ("user's choice", {WINDOW_VARIABLE: "vtkOSOpenGLRenderWindow"}, "linux", _found, None),
    ("no libEGL", {}, "linux", _missing, None),
    ("macOS", {}, "darwin", _found, None),
    ("Windows", {}, "win32", _found, None),
]


@pytest.mark.parametrize(("case", "env", "platform", "find", "expected"), WINDOWS,
                         ids=[w[0] for w in WINDOWS])
def test_window_class_asked_for(case, env, platform, find, expected):
    assert headless_window(env, platform, find) == expected


def test_offscreen_plotter_leaves_the_environment_as_it_was(monkeypatch):
    if headless_window({}, sys.platform) is None:
        pytest.skip("EGL rendering is chosen on Linux with libEGL only")
    monkeypatch.delenv("DISPLAY", raising=False)
    monkeypatch.delenv(WINDOW_VARIABLE, raising=False)
    from pipeline.viz._offscreen import offscreen_plotter

    plotter = offscreen_plotter(window_size=[16, 8])
    try:
        assert plotter.render_window.GetClassName() == HEADLESS_WINDOW
    finally:
        plotter.close()
    assert WINDOW_VARIABLE not in os.environ


def _clean_environment(cache: Path) -> dict[str, str]:
    """What a user's shell passes: no DISPLAY, no PYVISTA_*, MPLBACKEND or VTK_* settings."""
    return {"PATH": os.environ.get("PATH", "/usr/bin:/bin"), "HOME": str(Path.home()),
            "PYTHONPATH": str(ROOT), "GEARPIPE_CACHE_DIR": str(cache),
            "OMP_NUM_THREADS": "1"}


def test_contact_without_display_prints_no_library_noise(tmp_path):
    cfg = tmp_path / "spur.toml"
    # 12 positions: the contact loop takes a few hundredths of a second, far below 1 s
    cfg.write_text(SPUR.read_text() + "\n[contact]\npositions = 12\nrender = true\n")
    out = tmp_path / "out"
    proc = subprocess.run([sys.executable, "-m", "pipeline.cli", "contact", str(cfg),
                           "--out", str(out), "--no-cache"],
                          env=_clean_environment(tmp_path / "cache"), capture_output=True,
                          text=True, timeout=300, check=False)
    assert proc.returncode == 0, proc.stderr
    own = re.compile(r"^(\[gearpipe contact\] |gearpipe contact: warning: )")
    noise = [line for line in proc.stderr.splitlines() if line.strip() and not own.match(line)]
    assert noise == [], proc.stderr
    assert "bad X server" not in proc.stderr and "\r" not in proc.stderr

    png = (out / "load_map.png").read_bytes()
    assert png[:8] == PNG_SIGNATURE and png[12:16] == b"IHDR"
    width, height = struct.unpack(">II", png[16:24])
    assert width == 1400 and 500 < height < 3000  # render_load_map's default window width
    from matplotlib.image import imread

    pixels = imread(out / "load_map.png")[..., :3]
    assert pixels.shape[:2] == (height, width)
    # a drawn picture, not a blank window: the viridis flanks and the grey teeth give
    # hundreds of colours
    assert len(np.unique(pixels.reshape(-1, 3), axis=0)) > 200
