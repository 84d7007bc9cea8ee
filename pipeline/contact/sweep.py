"""Loaded tooth contact over many mesh positions (a mesh cycle, a load sweep).

Each position is an independent small convex problem (``n`` of a few to a few
hundred points), so positions are solved one after the other, each started from
the loads of the previous position: neighbouring positions share most of their
contact set, which saves most active-set changes. Inputs are validated once for
the whole stack.
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np
from numpy.typing import ArrayLike

from pipeline.contact.complementarity import _check_gaps, _check_options, _solve
from pipeline.contact.hertz import LocalCompliance
from pipeline.contact.results import ContactSweep
from pipeline.progress import progress
from pipeline.validation import InputError


def _hertz_at(hertz, k: int, m: int):
    """The local-compliance model of position ``k``."""
    if hertz is None:
        return None
    if isinstance(hertz, Sequence):
        return hertz[k]
    if getattr(hertz, "n_positions", None) == m:
        return hertz.for_position(k)
    return hertz


def solve_positions(
    G_stack: ArrayLike,
    eps_stack: ArrayLike,
    P: ArrayLike,
    hertz: LocalCompliance | Sequence[LocalCompliance] | None = None,
    *,
    tol: float = 1e-10,
    max_iter: int = 100,
    warm_start: bool = True,
    labels: Sequence[str] | None = None,
    show_progress: bool = False,
) -> ContactSweep:
    """Solve the contact problem of ``m`` mesh positions with ``n`` candidate points each.

    Parameters
    ----------
    G_stack : (m, n, n) compliance per position, m/N, or one (n, n) matrix for all.
    eps_stack : (m, n) initial separations, m; ``+inf`` marks a point out of mesh
        at that position.
    P : total normal load, N: a scalar or (m,) per position, >= 0.
    hertz : None (linear), one local-compliance model for all positions, a model
        with (m, n) arrays (e.g. :class:`~pipeline.contact.hertz.HertzLineContact`,
        split with ``for_position``), or a sequence of m models.
    tol, max_iter : as in :func:`~pipeline.contact.complementarity.solve_contact`.
    warm_start : start each position from the loads of the previous one.
    labels : m names used in error messages; default ``"mesh position k"``.
    show_progress : progress bar on stderr.

    Returns
    -------
    ContactSweep with (m, n) and (m,) arrays.

    Raises
    ------
    InputError for invalid inputs; ContactConvergenceError (naming the position)
    if any position misses its residual bound.
    """
    eps = np.asarray(eps_stack, dtype=float)
    if eps.ndim != 2:
        raise InputError(f"eps_stack has shape {eps.shape}; expected (positions, n)")
    m, n = eps.shape
    G = np.asarray(G_stack, dtype=float)
    if G.shape == (n, n):
        G = np.broadcast_to(G, (m, n, n))
    if G.shape != (m, n, n):
        raise InputError(f"G_stack has shape {G.shape}; expected ({m}, {n}, {n}) or ({n}, {n})")
    loads = np.broadcast_to(np.asarray(P, dtype=float), (m,))
    bad = ~np.isfinite(loads) | (loads < 0.0)
    if bad.any():
        k = int(np.flatnonzero(bad)[0])
        raise InputError(f"P[{k}] = {loads[k]!r} N is outside the allowed range [0, inf) N")
    if isinstance(hertz, Sequence) and len(hertz) != m:
        raise InputError(f"hertz has {len(hertz)} models; expected one per position ({m})")
    if labels is not None and len(labels) != m:
        raise InputError(f"labels has {len(labels)} entries; expected {m}")
    _check_options(tol, max_iter)
    names = [f"mesh position {k}" if labels is None else str(labels[k]) for k in range(m)]

    out = []
    prev = None
    for k in progress(range(m), "contact", total=m, enabled=show_progress):
        lab = f"{names[k]}: "
        e = _check_gaps(eps[k], lab)
        start = prev if warm_start and prev is not None and prev.total_load > 0.0 else None
        sol = _solve(G[k], e, float(loads[k]), _hertz_at(hertz, k, m), tol, max_iter, lab,
                     None if start is None else start.loads)
        out.append(sol)
        prev = sol
    return ContactSweep.from_solutions(out)

