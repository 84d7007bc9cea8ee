"""Layout checks of a drawn matplotlib figure: everything inside the canvas, no panel's
decorations on another panel, no figure-level text on a panel's decorations."""

from __future__ import annotations

from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.transforms import Bbox


def _overlap(a: Bbox, b: Bbox, tol: float) -> bool:
    """Whether ``a`` and ``b`` (pixels) overlap by more than ``tol`` pixels both ways."""
    return (min(a.x1, b.x1) - max(a.x0, b.x0) > tol
            and min(a.y1, b.y1) - max(a.y0, b.y0) > tol)


def _figure_texts(fig) -> list:
    found = [*fig.texts, *fig.legends]
    found += [t for t in (fig._suptitle, fig._supxlabel, fig._supylabel) if t is not None]
    for sub in fig.subfigs:
        found += _figure_texts(sub)
    return [t for t in found if t.get_visible() and getattr(t, "get_text", lambda: "x")()]


def _decorations(ax, r) -> list[Bbox]:
    """Boxes (pixels) of the texts round a panel: titles, axis labels, the tick labels in
    view, its legend."""
    texts = [ax.title, ax._left_title, ax._right_title]
    axes = (ax.xaxis, ax.yaxis) if ax.axison else ()  # set_axis_off: none drawn
    texts += [axis.label for axis in axes]
    for axis in axes:
        lo, hi = sorted(axis.get_view_interval())
        for tick in axis.get_major_ticks():
            if lo - 1e-9 * abs(hi - lo) <= tick.get_loc() <= hi + 1e-9 * abs(hi - lo):
                texts += [tick.label1, tick.label2]
    texts += [axis.offsetText for axis in axes]  # "1e6" at an axis's end
    boxes = [t.get_window_extent(r) for t in texts if t.get_visible() and t.get_text()]
    if ax.get_legend() is not None and ax.get_legend().get_visible():
        boxes.append(ax.get_legend().get_window_extent(r))
    return boxes


def _frame(ax, r) -> Bbox:
    """The panel's frame, or for a panel without axes (``set_axis_off``: no frame drawn) the
    box of what is drawn in it (its patches and lines)."""
    if ax.axison:
        return ax.bbox
    drawn = [a.get_window_extent(r) for a in [*ax.patches, *ax.lines] if a.get_visible()]
    return Bbox.union(drawn) if drawn else Bbox.null()


def layout_problems(fig, dpi: int = 130, tol: float = 1.0) -> list[str]:
    """What is wrong with the layout of ``fig`` drawn at ``dpi`` (empty if nothing):

    * the tight box of the figure (every text artist's, tick labels included) reaches
      past the canvas;
    * a text round a panel (title, axis label, tick label in view, legend) overlaps
      another panel's frame or texts (panels on one frame, twins, count as one; a colour
      bar is a panel);
    * a figure-level text (suptitle, figure legend, figure text) overlaps a panel's frame
      or texts.

    Boxes are the texts' line boxes, so two texts one pixel apart in ink may still count.
    """
    fig.set_dpi(dpi)
    canvas = FigureCanvasAgg(fig)
    canvas.draw()
    r = canvas.get_renderer()
    w, h = canvas.get_width_height()
    problems = []
    box = fig.get_tightbbox(r).transformed(fig.dpi_scale_trans)
    if box.x0 < -tol or box.y0 < -tol or box.x1 > w + tol or box.y1 > h + tol:
        problems.append(f"drawing {box.extents.round()} px past the canvas 0 0 {w} {h}")
    panels: dict[tuple, list] = {}  # twins share a frame: one panel
    for ax in fig.get_axes():
        if ax.get_visible():
            panels.setdefault(tuple(ax.bbox.extents.round(1)), []).append(ax)
    groups = list(panels.values())
    texts = [[b for ax in g for b in _decorations(ax, r)] for g in groups]
    frames = [_frame(g[0], r) for g in groups]
    names = [g[0].get_label() or g[0].get_title() or f"axes {i}" for i, g in enumerate(groups)]
    for i in range(len(groups)):
        for j in range(len(groups)):
            if i == j:
                continue
            if any(_overlap(b, frames[j], tol) for b in texts[i]):
                problems.append(f"a text of {names[i]!r} on the frame of {names[j]!r}")
            if i < j and any(_overlap(a, b, tol) for a in texts[i] for b in texts[j]):
                problems.append(f"texts of {names[i]!r} and {names[j]!r} overlap")
    for t in _figure_texts(fig):
        tb = t.get_window_extent(r)
        what = t.get_text() if hasattr(t, "get_text") else "figure legend"
        for i in range(len(groups)):
            if _overlap(tb, frames[i], tol) or any(_overlap(tb, b, tol) for b in texts[i]):
                problems.append(f"figure text {what!r} on {names[i]!r}")
    return problems
