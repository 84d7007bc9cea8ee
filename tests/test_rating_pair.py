"""The whole rating of a pair (pipeline.rating.pair_rating) against a commercial report.

KISSsoft Release 03/2017 A, "ISO 6336:2006 Method B", its report of the NREL 5 MW
reference gearbox's parallel helical stage (``@NREL_5MW/stage_03.rtf`` of the public
repository gfsReboucas/Drivetrain, commit 4a88df34), from its inputs alone (the face load
factor K_Hbeta 1.150 is the report's own input): 40953.0 N m at 1165.9 rpm, K_A 1.25,
175 200 h, grade 6, ISO VG 220, case-carburized 18CrNiMo7-6 (sigma_Hlim 1500, sigma_Flim
430 N/mm^2), R_z 4.8 / 20 um, S_Hmin 1.25, S_Fmin 1.56, C_R 0.898, steel 7830 kg/m^3,
bores 179.10 / 1193.32 mm.
"""

from __future__ import annotations

import nrel_gearbox as nrel
import pytest

from pipeline.geometry.pair import GearPair
from pipeline.rating.pair_rating import GearRatingInputs, RatingInputs, rate_pair
from pipeline.validation import InputError

MPA = 1e6


@pytest.fixture(scope="module")
def stage_3() -> GearPair:
    return nrel.stage_3()


def test_kisssoft_helical_stage_from_its_inputs(stage_3):
    """Printed: K_v 1.092, K_Halpha = K_Falpha 1.069, K_Fbeta 1.136, sigma_H 739.61
    N/mm^2, S_H 1.81 / 1.88, sigma_F 195.64 / 211.85 N/mm^2, S_F 3.26 / 3.09. Here: K_v
    1.0913 (-0.06 %, tests/test_rating_dynamic.py), K_Halpha 1.0694, K_Fbeta 1.1365,
    sigma_H 739.33 (-0.04 %), S_H 1.810 / 1.876, sigma_F 195.36 / 211.56 (-0.14 %: also
    sigma_F0's -0.08 %, tests/test_rating_bending.py), S_F 3.261 / 3.095 - S_H and S_F at
    their printed digits."""
    gear = GearRatingInputs(sigma_hlim=1500 * MPA, sigma_flim=430 * MPA,
                            flank_roughness=4.8e-6, root_roughness=20e-6)
    inputs = RatingInputs(application_factor=1.25, life_hours=175_200.0, accuracy_grade=6,
                          viscosity_40=220e-6, k_hbeta=1.150, blank_factor=0.898,
                          minimum_safety_pitting=1.25, minimum_safety_bending=1.56)
    r = rate_pair(stage_3, 40953.0, 1165.9, inputs, (gear, gear))
    assert r.dynamic.factor == pytest.approx(1.092, rel=1e-3)
    assert r.transverse.k_halpha == pytest.approx(1.069, abs=1e-3)
    assert r.k_fbeta == pytest.approx(1.136, abs=6e-4)
    assert r.contact.stress[0] == pytest.approx(739.61 * MPA, rel=1e-3)
    assert [p.safety for p in r.pitting] == pytest.approx([1.81, 1.88], abs=5e-3)
    assert [b.stress / MPA for b in r.bending] == pytest.approx([195.64, 211.85], rel=3e-3)
    assert [b.safety for b in r.bending] == pytest.approx([3.26, 3.09], abs=5e-3)
    assert r.safety_pitting_min == r.pitting[0].safety
    assert r.safety_bending_min == min(b.safety for b in r.bending)


def test_internal_pairs_refused_for_now():
    from gearsets import spur

    ring = GearPair(spur(24, "planet"), spur(72, "ring", internal=True, bore_radius=0.13))
    gear = GearRatingInputs(sigma_hlim=1500 * MPA, sigma_flim=430 * MPA)
    inputs = RatingInputs(application_factor=1.0, life_hours=1e4, accuracy_grade=6,
                          viscosity_40=220e-6, k_hbeta=1.1)
    with pytest.raises(InputError, match="bending rating of an internal gear is not built"):
        rate_pair(ring, 100.0, 1000.0, inputs, (gear, gear))
