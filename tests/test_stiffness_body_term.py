"""Sainsot's body term outside its fitted range (1.4 <= h_f = r_f / r_int <= 7).

The seed 001 pair (z 50/50, m 3 mm, r_f 71.25 mm) over bores 0..21 mm: the body of a
smaller bore is no softer than that of a larger one (the torsion of the annulus inside
r_f / 7 belongs to the shaft seat), the mesh stiffness is continuous and monotonic in
the bore, and a bore -> 0 tends to the solid gear. Extrapolated, it fell from 3.76e8 N/m
(21 mm) to 7.35e7 (5 mm) and jumped back to 2.07e8 for the solid gear.
"""

from __future__ import annotations

import warnings

import numpy as np
import pytest
from gearsets import spur

from pipeline.geometry import GearPair
from pipeline.operation import OperatingPoint
from pipeline.stiffness.analysis import analyse_stiffness
from pipeline.stiffness.foundation import H_F_RANGE, body_term_warnings, foundation_coefficients
from pipeline.stiffness.options import StiffnessOptions
from pipeline.validation import PhysicsWarning

OPERATION = OperatingPoint(torque=340.0, speed=245.0)
R_F = 0.07125  # root radius of the seed 001 gears, m


def _mean_stiffness(bore_mm: float) -> float:
    b = bore_mm * 1e-3
    pair = GearPair(spur(50, "pinion", bore_radius=b), spur(50, "gear", bore_radius=b))
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", PhysicsWarning)
        return analyse_stiffness(pair, OPERATION, StiffnessOptions(friction=0.0)).mesh.mean


def test_seed_pair_stiffness_is_monotonic_and_continuous_in_the_bore():
    bores = np.arange(0.0, 21.01, 0.5)
    k = np.array([_mean_stiffness(b) for b in bores])
    assert np.all(np.diff(k) >= -1e-9 * k[:-1])  # a larger bore is never stiffer-bodied
    # no jump: at most the slope of the fitted range (5.5 % per mm from 10.2 to 21 mm)
    assert np.max(np.abs(np.diff(k)) / k[:-1]) < 0.06
    kink = R_F / 7 * 1e3  # where h_f reaches the fit's end
    below, above = _mean_stiffness(kink - 1e-6), _mean_stiffness(kink + 1e-6)
    assert above >= below and (above - below) / below < 1e-5
    assert k[1] == k[0]  # bore -> 0 is the solid gear
    assert k[0] == pytest.approx(2.07e8, rel=2e-3)  # the solid gear, unchanged
    assert k[-1] == pytest.approx(3.76e8, rel=2e-3)  # 21 mm, inside the fit: unchanged


@pytest.mark.parametrize(("bore_mm", "h_f", "inside"), [
    (0.0, 7.0, True),        # solid: the fit's upper end by definition
    (5.0, 7.0, False),       # h_f 14.3: held at 7 as the solid gear
    (R_F / 7 * 1e3, 7.0, True),
    (21.0, R_F / 0.021, True),
    (R_F / 1.45 * 1e3, 1.45, True),
    (60.0, 1.4, False),      # h_f 1.19: held at 1.4
])
def test_h_f_is_held_inside_the_fit(bore_mm, h_f, inside):
    c = foundation_coefficients(R_F, bore_mm * 1e-3, 0.05)
    assert c.h_f == pytest.approx(h_f, rel=1e-12) and c.in_fit_range == inside
    assert H_F_RANGE[0] <= c.h_f <= H_F_RANGE[1]


@pytest.mark.parametrize(("bore_mm", "theta_f", "words"), [
    (21.0, 0.05, []),
    (0.0, 0.05, []),
    (5.0, 0.05, ["bore radius 5 mm is below r_f / 7 = 10.18 mm", "solid gear"]),
    (60.0, 0.05, ["thinner than Sainsot's fit (h_f = 1.19 < 1.4)", "more compliant"]),
    (21.0, 0.2, ["theta_f = 0.2 rad is outside Sainsot's fit"]),
])
def test_body_term_warnings(bore_mm, theta_f, words):
    lines = body_term_warnings("pinion", R_F, bore_mm * 1e-3, theta_f)
    assert len(lines) == (1 if words else 0)
    for w in words:
        assert w in lines[0], lines


def test_small_bore_warns_once_through_the_stiffness_stage():
    pair = GearPair(spur(50, "pinion", bore_radius=0.005), spur(50, "gear", bore_radius=0.021))
    with pytest.warns(PhysicsWarning, match="pinion: bore radius 5 mm") as record:
        res = analyse_stiffness(pair, OPERATION, StiffnessOptions(friction=0.0))
    assert all("gear:" not in str(r.message) for r in record)
    assert res.summary()["sainsot_fit_range_ok"] == {"pinion": False, "gear": True}
