"""Saving a matplotlib figure drawn once (:func:`pipeline.viz.saving.tight_png`) gives the
picture ``savefig(bbox_inches="tight")`` gives: the same drawing (the pixels inside the
drawn box equal but for anti-aliased edges shifted by under a pixel), cut to the drawn
pixels and padded by ``savefig.pad_inches`` in the figure's colour, where ``savefig`` pads
the text's line box (a few pixels more); a figure drawn up to its canvas's edge (a legend
beside the axes, a label longer than the figure, even one leaving it between two words) is
left to ``savefig`` (``None``), which grows the canvas to show it."""

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


def _drawn(picture: np.ndarray) -> np.ndarray:
    """The part of an RGB picture (0-255 floats) drawn in another colour than white."""
    rows = np.flatnonzero((picture != 255.0).any(axis=(1, 2)))
    cols = np.flatnonzero((picture != 255.0).any(axis=(0, 2)))
    return picture[rows[0]:rows[-1] + 1, cols[0]:cols[-1] + 1]


def test_drawn_once_equals_savefig_tight():
    dpi = 130
    buf = io.BytesIO()
    _figure().savefig(buf, dpi=dpi, bbox_inches="tight", format="png")
    old = _drawn(_pixels(buf.getvalue()))
    png = tight_png(_figure(), dpi)
    assert png is not None
    picture = _pixels(png)
    new = _drawn(picture)
    # the padding: savefig.pad_inches (0.1 in = 13 px at 130 dpi) of white on every side
    pad = round(0.1 * dpi)
    assert picture.shape[0] == new.shape[0] + 2 * pad
    assert picture.shape[1] == new.shape[1] + 2 * pad
    assert abs(new.shape[0] - old.shape[0]) <= 1 and abs(new.shape[1] - old.shape[1]) <= 1
    h, w = min(old.shape[0], new.shape[0]) - 2, min(old.shape[1], new.shape[1]) - 2

    def diff(i, j, k, m):  # mean |difference| of 255, old shifted by (i, j), new by (k, m)
        return np.abs(old[i:i + h, j:j + w] - new[k:k + h, m:m + w]).mean()

    # the best of the one-pixel shifts: the boxes' corners are rounded differently
    best = min(diff(i, j, k, m) for i in (0, 1) for j in (0, 1) for k in (0, 1)
               for m in (0, 1))
    assert best < 3.0  # anti-aliased edges shifted by under a pixel
    # the measure sees a real difference: the pictures two pixels apart differ by more
    assert diff(2, 2, 0, 0) > 2.0 * best and diff(0, 0, 2, 2) > 2.0 * best
    edge = np.concatenate([picture[0], picture[-1], picture[:, 0], picture[:, -1]])
    assert np.all(edge == 255.0)  # the padding is the figure's white


def test_a_text_wholly_outside_the_canvas_is_left_to_savefig(tmp_path):
    # a text beyond the top edge leaves no pixel on the canvas (as a label leaving it
    # between two words leaves none at the edge): the labels are measured too
    fig = _figure()
    fig.text(0.5, 1.08, "a note above the figure", ha="center")
    assert tight_png(fig, 100) is None
    path = save(fig, tmp_path / "note.png", dpi=100)
    assert Image.open(path).size[1] > 3 * 100  # the canvas grown to hold the note


def test_a_legend_outside_the_canvas_is_left_to_savefig(tmp_path):
    assert tight_png(_figure(legend_outside=True), 100) is None
    path = save(_figure(legend_outside=True), tmp_path / "legend.png", dpi=100)
    width = Image.open(path).size[0]
    assert width > 4 * 100  # the canvas grown to hold the legend


def test_save_writes_the_drawn_once_picture(tmp_path):
    path = save(_figure(), tmp_path / "f.png", dpi=100)
    assert path.read_bytes() == tight_png(_figure(), 100)
