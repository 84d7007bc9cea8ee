"""Transverse load factors of ISO 6336-1 method B (pipeline.rating.transverse) against the
KISSsoft 03/2017 A reports of the NREL 5 MW reference gearbox (gfsReboucas/Drivetrain,
commit 4a88df34, ``@NREL_5MW/stage_03.rtf`` and ``stage_02.rtf``)."""

from __future__ import annotations

import math

import pytest

from pipeline.rating.transverse import transverse_load_factors


def test_helical_stage():
    """Stage 3: c_gamma_alpha 18.632 N/(mm um), f_pb 13.1 / 15.9 um, f_falpha 18 / 22 um
    (grade 6), y_alpha 1.2 um (0.075 f_pb), F_t 240064.4 N, b 360 mm, K_A 1.25, K_v 1.092,
    K_Hbeta 1.150, eps_alpha 1.463, eps_gamma 2.884, Z_eps 0.827. Printed K_Halpha = K_Falpha
    1.069 (the larger deviation, f_falpha 22 um, enters; f_pb alone would give 1.020)."""
    line_load = 240064.4 * 1.25 * 1.092 * 1.150 / 0.36
    kw = dict(mesh_stiffness=18.632e9, allowance=0.075 * 15.9e-6, line_load_h=line_load,
              transverse_contact_ratio=1.463, total_contact_ratio=2.884,
              contact_ratio_factor=0.827)
    f = transverse_load_factors(base_pitch_deviation=15.9e-6, form_deviation=22e-6, **kw)
    assert f.k_halpha == pytest.approx(1.069, abs=5e-4)
    assert f.k_falpha == f.k_halpha
    only_pitch = transverse_load_factors(base_pitch_deviation=15.9e-6, form_deviation=0.0,
                                         **kw)
    assert only_pitch.k_halpha == pytest.approx(1.020, abs=5e-4)


@pytest.mark.parametrize(("cga", "fpb", "ffa", "ya", "kv", "khb", "ea", "zeps"), [
    (15.640e9, 17.9e-6, 23e-6, 1.342e-6, 1.061, 2.059767, 1.370, 0.936),  # sun-planet
    (20.563e9, 20.7e-6, 27e-6, 3.142e-6, 1.061, 1.15, 1.618, 0.891),  # planet-ring
])
def test_spur_planetary_meshes_are_at_the_floor(cga, fpb, ffa, ya, kv, khb, ea, zeps):
    """Stage 2's spur meshes (eps_gamma = eps_alpha < 2): printed K_Halpha = K_Falpha =
    1.00, the floor of the formula's eps_gamma / 2 (0.9 + ...) < 1 (F_t 285900.438 N per
    planet, b 550 mm, K_A 1.25, K_gamma 1.10)."""
    line_load = 285900.438 * 1.25 * 1.10 * kv * khb / 0.55
    f = transverse_load_factors(mesh_stiffness=cga, base_pitch_deviation=fpb,
                                form_deviation=ffa, allowance=ya, line_load_h=line_load,
                                transverse_contact_ratio=ea, total_contact_ratio=ea,
                                contact_ratio_factor=zeps)
    assert f.unlimited < 1.0
    assert (f.k_halpha, f.k_falpha) == (1.0, 1.0)


def test_limits():
    """A large deviation is capped at eps_gamma / (eps_alpha Z_eps^2) (K_Halpha) and
    eps_gamma / (0.25 eps_alpha + 0.75) (K_Falpha); a spur pair's Z_eps^2 = (4 - eps_alpha)
    / 3 makes the first 3 / (4 - eps_alpha)."""
    ea = 1.6
    zeps = math.sqrt((4 - ea) / 3)
    f = transverse_load_factors(mesh_stiffness=20e9, base_pitch_deviation=200e-6,
                                form_deviation=0.0, allowance=0.0, line_load_h=1e5,
                                transverse_contact_ratio=ea, total_contact_ratio=ea,
                                contact_ratio_factor=zeps)
    assert f.k_halpha == pytest.approx(3 / (4 - ea), rel=1e-12)
    assert f.k_falpha == pytest.approx(ea / (0.25 * ea + 0.75), rel=1e-12)
