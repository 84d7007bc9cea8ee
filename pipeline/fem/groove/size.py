"""Size of a coaxial-body model before meshing (:mod:`pipeline.fem.size3d`).

Mirrors the size field of :mod:`.mesh`: a plain segment is meshed at ``size``, or at
the curvature size ``2 pi r / curvature_points`` of its outer cylinder when that is
smaller (never below ``min_size_factor size``); a bore of radius ``r_b`` is meshed at
its own curvature size, graded to the segment's size at the outer radius; a toothed
segment has its teeth (half the annulus between root and tip) at the tooth size
``min(size, tooth_size_factor m_n)``, graded to ``size`` between ``0.5 m_n`` and
``3 m_n`` below the root cylinder.
"""

from __future__ import annotations

import math

from pipeline.fem.groove.body import CoaxialBody
from pipeline.fem.groove.mesh import MeshSettings
from pipeline.fem.size3d import SizeEstimate, graded_layer_cells, uniform_cells


def _curvature_size(radius: float, settings: MeshSettings) -> float:
    h = settings.size
    if settings.curvature_points <= 0:
        return h
    return min(h, max(settings.min_size_factor * h,
                      2 * math.pi * radius / settings.curvature_points))


def estimated_size(body: CoaxialBody, settings: MeshSettings) -> SizeEstimate:
    """Estimated cells and unknowns of the P2 model of ``body`` meshed with ``settings``."""
    toothed = any(s.teeth is not None for s in body.segments)
    rb, h = body.bore_radius, settings.size
    cells = 0.0
    for seg in body.segments:
        r, length = seg.outer_radius, seg.length
        if seg.teeth is not None:
            m = seg.teeth.gear.module
            ht = min(h, settings.tooth_size_factor * m)
            ra = seg.teeth.gear.tip_radius_
            cells += uniform_cells(0.5 * math.pi * (ra**2 - r**2) * length, ht)
            cells += uniform_cells(math.pi * (r**2 - rb**2) * length, h)
            cells += graded_layer_cells(2 * math.pi * r * length, ht, h, 0.5 * m, 2.5 * m)
            continue
        hs = h if toothed else _curvature_size(r, settings)
        cells += uniform_cells(math.pi * (r**2 - rb**2) * length, hs)
        if rb > 0 and not toothed:
            cells += graded_layer_cells(2 * math.pi * rb * length, _curvature_size(rb, settings),
                                        hs, 0.0, r - rb)
    return SizeEstimate(cells)
