"""Figures laid out by fixed margins (:class:`pipeline.viz.canvas.Margins`) instead of
constrained layout, and saved in one drawing (:func:`pipeline.viz.saving.tight_png`).

The layout engine puts the panels exactly where the margins in inches say; every figure
kind of the demo run (``workflows/default_case.py``: FE 2D contact, a shaft, dynamics,
rating, the report's figures) is drawn and checked by :func:`figure_layout.layout_problems`:
nothing past the canvas, no text of a panel on another panel, no suptitle or figure legend
on a panel; and each is saved from its first drawing (no ``savefig`` redraw because it
outgrew its canvas). The drawing processes run without the cyclic garbage collector.
"""

from __future__ import annotations

import gc

import numpy as np
import pytest
from figure_layout import layout_problems
from matplotlib.backends.backend_agg import FigureCanvasAgg

from pipeline.parallel import can_fork, process_pool
from pipeline.viz.canvas import Margins, new_figure, panels_with_colorbar
from pipeline.viz.figure_queue import drawing_process
from pipeline.viz.saving import tight_png
from workflows.default_case import DEFAULT

# every matplotlib figure of the demo run (the pyvista load map aside)
DEMO_FIGURES = {
    "line_of_action.png", "tooth_profiles.png", "mesh_stiffness.png",
    "friction_coefficients.png", "contact_cycle.png", "load_map_2d.png", "mode_shapes.png",
    "time_history.png", "dte_spectrum.png", "harmonics.png", "sweep.png",
    "report_stiffness.png", "report_transmission_error.png", "report_line_load.png",
    "report_contact_pressure.png", "report_root_stress.png", "report_shafts.png",
    "report_shaft_dynamics.png", "report_rating.png", "report_rating_local_pitting.png",
    "report_rating_root_face.png",
}


def _inches(ax) -> np.ndarray:
    """x0, y0, x1, y1 of the panel's frame in inches from the figure's lower left corner."""
    fig = ax.figure
    return ax.get_position().extents * np.tile(fig.get_size_inches(), 2)


def test_fixed_margins_place_the_panels_in_inches():
    m = Margins(left=1.0, right=0.5, bottom=0.6, top=0.4, wspace=0.8, hspace=0.7)
    fig = new_figure((8.0, 5.0), m)
    axes = fig.subplots(2, 2)
    FigureCanvasAgg(fig).draw()
    # panels: (8 - 1 - 0.5 - 0.8) / 2 = 2.85 in wide, (5 - 0.6 - 0.4 - 0.7) / 2 = 1.65 high
    np.testing.assert_allclose(_inches(axes[1, 0]), [1.0, 0.6, 3.85, 2.25], atol=1e-12)
    np.testing.assert_allclose(_inches(axes[0, 1]), [4.65, 2.95, 7.5, 4.6], atol=1e-12)


def test_fixed_margins_follow_the_grid_with_most_columns_and_a_resize():
    fig = new_figure((6.0, 3.0), Margins(left=0.5, right=0.5, wspace=0.5))
    a, b, c = fig.subplots(1, 3, width_ratios=(2.0, 1.0, 1.0))
    fig.set_size_inches(10.0, 3.0)  # laid out when drawn, at the size it has then
    FigureCanvasAgg(fig).draw()
    # 10 - 0.5 - 0.5 - 2 x 0.5 = 8 in of panels, shared 2 : 1 : 1
    np.testing.assert_allclose(_inches(a)[[0, 2]], [0.5, 4.5], atol=1e-12)
    np.testing.assert_allclose(_inches(b)[[0, 2]], [5.0, 7.0], atol=1e-12)
    np.testing.assert_allclose(_inches(c)[[0, 2]], [7.5, 9.5], atol=1e-12)


def test_margins_are_checked():
    with pytest.raises(ValueError, match=r"Margins.wspace: -0.1 in; at least 0"):
        Margins(wspace=-0.1)
    fig = new_figure((1.0, 3.0), Margins(left=0.6, right=0.5))
    fig.subplots()
    # matplotlib's draw ignores a layout engine's ValueError (a window being resized) and
    # keeps the previous layout; the engine itself says why
    with pytest.raises(ValueError, match="no room for the panels"):
        fig.get_layout_engine().execute(fig)


def test_panels_with_colorbar_share_y_and_keep_the_bar_in_its_slot():
    fig = new_figure((8.0, 3.0), Margins(left=0.8, right=0.7, wspace=0.3))
    (a, b), bar = panels_with_colorbar(fig)
    mesh = a.pcolormesh(np.arange(4.0), np.arange(3.0), np.ones((2, 3)))
    b.set_ylim(-1.0, 5.0)
    fig.colorbar(mesh, cax=bar, label="p [MPa]")
    FigureCanvasAgg(fig).draw()
    assert a.get_ylim() == (-1.0, 5.0)  # shared
    assert not any(t.get_visible() for t in b.get_yticklabels())
    # 8 - 0.8 - 0.7 - 2 x 0.3 = 5.9 in of panels: 2 + 0.045 shares of 5.9 / 2.045 in each
    share = 5.9 / 2.045
    np.testing.assert_allclose(_inches(bar)[[0, 2]], [7.3 - 0.045 * share, 7.3], atol=1e-12)
    np.testing.assert_allclose(_inches(b)[2] + 0.3, _inches(bar)[0], atol=1e-12)


@pytest.mark.skipif(not can_fork(), reason="drawing processes are forked (POSIX)")
def test_drawing_processes_run_without_the_cyclic_collector():
    pool = process_pool(1, drawing_process)
    try:
        assert pool.submit(gc.isenabled).result() is False
    finally:
        pool.shutdown()
    assert gc.isenabled()  # this process keeps it


@pytest.fixture(scope="module")
def demo_figures(tmp_path_factory):
    """Every matplotlib figure the demo's ``gearpipe run`` draws, by file name: the drawing
    function and its arguments, queued as the run queues them (nothing drawn yet)."""
    from pipeline.cache.folder import Cache
    from pipeline.cli.run import write_run
    from pipeline.config import gearbox_from_text
    from pipeline.report.writer import prepare_reports
    from pipeline.run.chain import RunOptions
    from pipeline.run.runner import run_pipeline
    from pipeline.viz.figure_cache import FigureCache
    from pipeline.viz.figure_queue import FigureQueue

    root = tmp_path_factory.mktemp("demo")
    out = root / "out"
    out.mkdir()
    result = run_pipeline(gearbox_from_text(DEFAULT, "default_case"),
                          RunOptions(cache=Cache.for_command(root / "cache"),
                                     show_progress=False))
    queue = FigureQueue()
    figures = FigureCache(queue=queue)
    files = write_run(result, out, figures=figures)
    prepare_reports(result, out, figures, command="gearpipe run", written=files)
    drawings = {}
    for path, job in queue.jobs:
        _, _, dpi, draw, args, kwargs = job.args[:6]
        if path.name != "load_map.png":  # pyvista
            drawings[path.name] = (dpi, draw, args, kwargs)
    return drawings


def _figure(drawing):
    dpi, draw, args, kwargs = drawing
    fig = draw(*args, **kwargs)
    return getattr(fig, "figure", fig), dpi  # an Axes: its figure


def test_every_figure_of_the_demo_run_is_laid_out_cleanly(demo_figures):
    assert set(demo_figures) == DEMO_FIGURES
    problems = {}
    for name, drawing in sorted(demo_figures.items()):
        fig, dpi = _figure(drawing)
        found = layout_problems(fig, dpi)
        if found:
            problems[name] = found
    assert problems == {}


def test_every_figure_of_the_demo_run_is_saved_from_one_drawing(demo_figures):
    redrawn = [name for name, drawing in sorted(demo_figures.items())
               if tight_png(*_figure(drawing)) is None]
    assert redrawn == []
