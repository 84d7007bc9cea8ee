"""Saving a matplotlib figure drawn once (:func:`pipeline.viz.saving.tight_png`) gives the
picture ``savefig(bbox_inches="tight")`` gives: the same size within the rounding of the
box's corners (one pixel), the same pixels but for the sub-pixel shift of the box's corner
(anti-aliased edges), the figure's colour in the padding; a figure with a legend outside
its canvas is left to ``savefig`` (``None``), which grows the canvas to show it."""

from __future__ import annotations

import io

import numpy as np
from matplotlib.figure import Figure
from PIL import Image

from pipeline.viz.saving import save, tight_png


def _figure(legend_outside: bool = False) -> Figure:
    # constrained layout would shrink the axes to fit the legend: none with it outside
    fig = Figure(figsize=(4, 3), layout=None if legend_outside else "constrained")
    ax = fig.subplots()
    ax.plot(np.linspace(0, 1, 50), np.linspace(0, 1, 50) ** 2, label="a curve")
    ax.set_xlabel("x [m]")
    ax.set_ylabel("y [m]")
    ax.set_title("a title")
    if legend_outside:
        ax.legend(loc="upper left", bbox_to_anchor=(1.02, 1.0))
    return fig


def _pixels(png: bytes) -> np.ndarray:
    return np.asarray(Image.open(io.BytesIO(png)).convert("RGB")).astype(float)


def test_drawn_once_equals_savefig_tight():
    dpi = 130
    buf = io.BytesIO()
    _figure().savefig(buf, dpi=dpi, bbox_inches="tight", format="png")
    old = _pixels(buf.getvalue())
    png = tight_png(_figure(), dpi)
    assert png is not None
    new = _pixels(png)
    assert abs(new.shape[0] - old.shape[0]) <= 1 and abs(new.shape[1] - old.shape[1]) <= 1
    h, w = min(old.shape[0], new.shape[0]) - 2, min(old.shape[1], new.shape[1]) - 2

    def diff(i, j, k, m):  # mean |difference| of 255, old shifted by (i, j), new by (k, m)
        return np.abs(old[i:i + h, j:j + w] - new[k:k + h, m:m + w]).mean()

    # the best of the one-pixel shifts: the boxes' corners are rounded differently
    best = min(diff(i, j, k, m) for i in (0, 1) for j in (0, 1) for k in (0, 1)
               for m in (0, 1))
    assert best < 3.0  # anti-aliased edges shifted by under a pixel (measured 1.6)
    # the measure sees a real difference: the pictures two pixels apart differ by more
    assert diff(2, 2, 0, 0) > 2.0 * best and diff(0, 0, 2, 2) > 2.0 * best
    edge = np.concatenate([new[0], new[-1], new[:, 0], new[:, -1]])
    assert np.all(edge == 255.0)  # the padding is the figure's white


def test_a_legend_outside_the_canvas_is_left_to_savefig(tmp_path):
    assert tight_png(_figure(legend_outside=True), 100) is None
    path = save(_figure(legend_outside=True), tmp_path / "legend.png", dpi=100)
    width = Image.open(path).size[0]
    assert width > 4 * 100  # the canvas grown to hold the legend


def test_save_writes_the_drawn_once_picture(tmp_path):
    path = save(_figure(), tmp_path / "f.png", dpi=100)
    assert path.read_bytes() == tight_png(_figure(), 100)
