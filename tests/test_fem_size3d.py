"""3D model size before meshing: the layer integral exactly, the estimate against real
meshes, and the refusal / warning lines.

The estimate's tolerance: it is there to refuse models orders of magnitude too big and
to warn before minutes of work, so within 30 % of the real count is what it promises
(measured 0.80-1.20 on groove bodies, 0.82-1.15 on sectors and whole gears).
"""

from __future__ import annotations

import dataclasses
import math
from pathlib import Path

import numpy as np
import pytest
from scipy.integrate import quad

from pipeline.cache.folder import Cache
from pipeline.config import load_gearbox
from pipeline.fem.groove.mesh import mesh_coaxial_body
from pipeline.fem.groove.size import estimated_size
from pipeline.fem.mesh_settings import SectorSettings3D, meshed_width
from pipeline.fem.sector3d import build_sector_mesh_3d
from pipeline.fem.sector3d_size import estimated_size_3d
from pipeline.fem.size3d import (
    MAX_DOF,
    TET_FILL,
    SizeEstimate,
    SizeWarning,
    check_size_3d,
    graded_layer_cells,
    uniform_cells,
)
from pipeline.geometry.gear import GearSpec
from pipeline.validation import InputError

GROOVE = Path(__file__).resolve().parents[1] / "workflows" / "configs" / \
    "wind_turbine_sun_groove.toml"
TOLERANCE = (0.7, 1.3)


def test_graded_layer_is_the_integral_of_the_size_field():
    """Exact: cells added per unit area = int (1/(c h(d)^3) - 1/(c hb^3)) dd, with h = h0
    up to d_fine and linear to hb over d_grade."""
    h0, hb, d_fine, d_grade = 1e-3, 5e-3, 0.3e-3, 8e-3

    def h(d):
        return h0 if d < d_fine else h0 + (hb - h0) * min(1.0, (d - d_fine) / d_grade)

    exact = quad(lambda d: 1 / (TET_FILL * h(d) ** 3) - 1 / (TET_FILL * hb**3),
                 0, d_fine + d_grade, points=[d_fine], limit=200)[0]
    assert graded_layer_cells(1.0, h0, hb, d_fine, d_grade) == pytest.approx(exact, rel=1e-9)
    assert graded_layer_cells(2.0, hb, hb, d_fine, d_grade) == 0.0
    assert uniform_cells(8.0, 2.0) == pytest.approx(1 / TET_FILL)


def _groove(h: float, bore: float = 0.0):
    base = load_gearbox(GROOVE).groove
    return dataclasses.replace(base, gear=dataclasses.replace(base.gear, bore_radius=bore),
                               mesh_size=h)


@pytest.mark.parametrize(("h", "bore"), [(0.03, 0.0), (0.03, 0.06), (0.02, 0.0)])
def test_groove_estimate_against_real_meshes(h, bore):
    spec = _groove(h, bore)
    body, settings = spec.body(), spec.mesh_settings()
    data = mesh_coaxial_body(body, settings)
    ratio = estimated_size(body, settings).dof / (3 * data.points.shape[1])
    assert TOLERANCE[0] < ratio < TOLERANCE[1], ratio


KW = dict(teeth=30, module=3e-3, pressure_angle=math.radians(20), bore_radius=0.03)


@pytest.mark.parametrize("gear", [
    GearSpec(face_width=6e-3, **KW),
    pytest.param(GearSpec(face_width=6e-3, helix_angle=math.radians(15), hand="right", **KW),
                 marks=pytest.mark.slow)], ids=["spur", "helical"])
def test_sector_estimate_against_real_meshes(gear):
    s = SectorSettings3D.for_gear(gear, 3, 1.0)
    data = build_sector_mesh_3d(gear, s)
    ratio = estimated_size_3d(gear, s, meshed_width(gear)).dof / (3 * data.points.shape[1])
    assert TOLERANCE[0] < ratio < TOLERANCE[1], ratio


@pytest.mark.slow
def test_whole_gear_estimate_against_a_real_mesh():
    from gearsets import spur

    from pipeline.fem.whole3d import build_whole_gear_mesh_3d

    gear = spur(50, "pinion")
    s = SectorSettings3D.whole_gear(gear, (24, 25, 26), 1.0)
    data = build_whole_gear_mesh_3d(gear, s)
    ratio = estimated_size_3d(gear, s, meshed_width(gear)).dof / (3 * data.points.shape[1])
    assert TOLERANCE[0] < ratio < TOLERANCE[1], ratio


def test_refusal_and_warning_lines():
    big = SizeEstimate(MAX_DOF / (3 * 1.6) * 1.5)
    with pytest.raises(InputError) as err:
        check_size_3d("the body", big, "raise x.mesh_size_mm (now 1 mm)")
    text = str(err.value)
    assert text.startswith("the 3D mesh of the body would have about 1.2 million unknowns")
    assert "GiB; the limit is 800 thousand unknowns: raise x.mesh_size_mm (now 1 mm)" in text
    with pytest.warns(SizeWarning, match="about 300 thousand unknowns"):
        check_size_3d("the body", SizeEstimate(300_000 / 4.8), "raise x")
    import warnings

    with warnings.catch_warnings():
        warnings.simplefilter("error")
        check_size_3d("the body", SizeEstimate(100_000 / 4.8), "raise x")


def test_groove_refused_before_meshing(monkeypatch):
    import pipeline.fem.groove.study as study

    monkeypatch.setattr(study, "mesh_coaxial_body", lambda *a: pytest.fail("meshed"))
    with pytest.raises(InputError, match=r"billion unknowns.*groove.mesh_size_mm \(now 0.5 mm\)"):
        study.analyse_groove(_groove(0.5e-3), cache=Cache.off())
    assert np.isfinite(estimated_size(_groove(0.5e-3).body(),
                                      _groove(0.5e-3).mesh_settings()).memory)
