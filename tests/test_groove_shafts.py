"""Relief-groove FE chain on shafts with closed-form torsional stiffness.

References (elementary strength of materials, e.g. Timoshenko, *Strength of
Materials* I, ch. IX):

* a round (hollow) shaft twisted between its end faces: k = G J / L with
  J = pi (D^4 - d_i^4) / 32; exact in 3D elasticity for circular sections,
  whether the ends are rigid or loaded by shear proportional to radius;
* a stepped shaft: the series sum 1/k = sum L_i / (G J_i). This neglects the
  Saint-Venant zones at each shoulder, where the shear flow spreads from the
  small into the large section: the large section near the shoulder is not
  fully effective, which adds a fixed compliance per shoulder - an extra length
  dl of the small shaft - independent of the segment lengths. For D/d = 1.67 with
  sharp shoulders the FE gives dl = 0.097 d per shoulder (5.8 mm for d = 60 mm);
  Saint-Venant bounds it by the disturbed zone, about the step height
  (D - d) / 2 = 20 mm. The tests check that the FE excess over the series sum
  is (i) positive, (ii) the same for two sets of lengths (local end effect),
  (iii) below that bound.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from pipeline.fem.groove.body import CoaxialBody, Segment
from pipeline.fem.groove.coupling import couple_two_surfaces
from pipeline.fem.groove.mesh import MeshSettings, mesh_coaxial_body
from pipeline.fem.linear_static import build_model
from pipeline.fem.tetmesh import to_skfem
from pipeline.geometry.gear import Material

MAT = Material()
G = MAT.shear_modulus


def _end_coupling(body, size, coupling, curvature=16):
    sk = to_skfem(mesh_coaxial_body(body, MeshSettings(size, curvature_points=curvature)))
    model = build_model(sk.mesh, MAT)
    return couple_two_surfaces(model, sk.triangles["end:left"], sk.triangles["end:right"],
                               [0, 0, body.z_start], [0, 0, body.z_end], coupling)


@pytest.mark.parametrize("coupling", ["distributed", "rigid"])
@pytest.mark.parametrize("bore", [0.0, 0.02])
def test_cylinder_gj_over_l(coupling, bore):
    """k_t = G J / L within 1 % (measured: 1e-5) for a solid and a hollow shaft."""
    R, L = 0.05, 0.2
    res = _end_coupling(CoaxialBody((Segment("shaft", 0.0, L, R),), bore), 0.04, coupling)
    ref = G * math.pi * (R**4 - bore**4) / 2 / L
    assert res.torsional_stiffness == pytest.approx(ref, rel=1e-2)
    assert res.torsional_stiffness == pytest.approx(ref, rel=1e-4)  # what it really achieves
    # 12 x 12 matrix: symmetric, rigid-body null space of dimension six exactly.
    K = res.matrix
    np.testing.assert_allclose(K, K.T, atol=1e-12 * np.abs(K).max())
    ev = np.sort(np.abs(np.linalg.eigvalsh(K))) / np.abs(K).max()
    assert ev[5] < 1e-10 and ev[6] > 1e-6
    if coupling == "distributed":
        # Axial stiffness E A / L is exact too when the ends may contract freely.
        ea = MAT.youngs_modulus * math.pi * (R**2 - bore**2) / L
        assert 1 / res.relative_flexibility[2, 2] == pytest.approx(ea, rel=1e-3)


def test_stepped_shaft_series_sum_and_saint_venant():
    """Series sum of the segments, with the excess explained by local shoulder effects."""
    D, d = 0.1, 0.06
    J = lambda dia: math.pi * dia**4 / 32  # noqa: E731
    excess_lengths = []
    for lengths in ((0.1, 0.05, 0.1), (0.2, 0.1, 0.2)):
        z = np.concatenate([[0.0], np.cumsum(lengths)])
        body = CoaxialBody(tuple(Segment(n, z[i], z[i + 1], dia / 2) for i, (n, dia) in
                                 enumerate((("a", D), ("b", d), ("c", D)))))
        res = _end_coupling(body, 0.02, "rigid", curvature=24)
        series = sum(L / (G * J(dia)) for L, dia in zip(lengths, (D, d, D), strict=True))
        excess = 1.0 / res.torsional_stiffness - series
        excess_lengths.append(excess * G * J(d) / 2)  # extra length of small shaft per shoulder
    dl = np.array(excess_lengths)
    assert np.all(dl > 0)
    assert dl[0] == pytest.approx(dl[1], rel=0.03)  # local: independent of the lengths
    assert np.all(dl < (D - d) / 2)  # within the Saint-Venant zone bound
    assert dl.mean() / d == pytest.approx(0.097, abs=0.01)  # regression of the measured value
