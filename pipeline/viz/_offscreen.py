"""Off-screen pyvista plotters that render on a machine without a display, quietly.

On Linux, VTK's default render window is an X window. Without a display, VTK (9.4 and
later) logs ``vtkXOpenGLRenderWindow ... WARN| bad X server connection. DISPLAY=`` on
stderr when a process makes its first window (each figure-drawing child process again),
and only then falls back to an EGL window, which renders the same picture.
:func:`offscreen_plotter` asks VTK for the EGL window directly, through the variable VTK
documents for the choice (``VTK_DEFAULT_OPENGL_WINDOW``, "Runtime settings" of the VTK
documentation), while the plotter's window is made; the variable is put back as it was
afterwards, so nothing outside this module sees it. It does so only on Linux with
no ``DISPLAY`` (a Wayland-only session draws through EGL as well), when the user has not
chosen a window class, and when libEGL can be found; otherwise VTK's own choice stands.

Matplotlib needs nothing of the kind: the figures are pyplot-free, and matplotlib itself
falls back to Agg when no display is present.
"""

from __future__ import annotations

import ctypes.util
import os
import sys
from collections.abc import Callable, Iterator, Mapping
from contextlib import contextmanager
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    import pyvista

WINDOW_VARIABLE = "VTK_DEFAULT_OPENGL_WINDOW"
"""Environment variable naming the class of VTK's OpenGL render window."""
HEADLESS_WINDOW = "vtkEGLRenderWindow"
"""VTK's render window without a display server (EGL)."""


def headless_window(env: Mapping[str, str], platform: str,
                    find_library: Callable[[str], str | None] = ctypes.util.find_library
                    ) -> str | None:
    """The render window class to ask VTK for, or None to leave VTK's choice alone.

    Parameters
    ----------
    env : the process environment (``DISPLAY`` and ``VTK_DEFAULT_OPENGL_WINDOW`` are read).
    platform : ``sys.platform``.
    find_library : finds a shared library by name (asked for "EGL" only when it matters).
    """
    if not platform.startswith("linux") or env.get("DISPLAY") or env.get(WINDOW_VARIABLE):
        return None
    return HEADLESS_WINDOW if find_library("EGL") else None


@contextmanager
def _window_class(name: str | None) -> Iterator[None]:
    """Set ``VTK_DEFAULT_OPENGL_WINDOW`` to ``name`` inside the block (nothing for None)."""
    if name is None:
        yield
        return
    os.environ[WINDOW_VARIABLE] = name
    try:
        yield
    finally:
        os.environ.pop(WINDOW_VARIABLE, None)


def offscreen_plotter(**kwargs) -> pyvista.Plotter:
    """A new off-screen ``pyvista.Plotter(off_screen=True, **kwargs)`` whose render window
    needs no display (module docstring); close it after use (:func:`pipeline.viz.save`
    does)."""
    name = headless_window(os.environ, sys.platform)
    import pyvista as pv

    with _window_class(name):  # VTK picks the window class when the window is made
        return pv.Plotter(off_screen=True, **kwargs)
