"""The gap the shafts open across the face (pipeline.shaft.misalignment), on the beam model,
against closed forms written here (Euler-Bernoulli with Timoshenko shear where it enters,
the section rotation for a rigid seat)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from pipeline.geometry.gear import Material
from pipeline.shaft.beam import BeamShaft
from pipeline.shaft.layout import Bearing, ShaftLayout, ShaftSegment
from pipeline.shaft.misalignment import shaft_gap
from pipeline.validation import InputError

E, NU = 206e9, 0.3
G = E / (2 * (1 + NU))
D = 0.040
I_ = math.pi * D**4 / 64
J = 2 * I_
B = 0.020   # face width
RB = 0.0705  # base radius
Z = (np.arange(10) + 0.5) * B / 10  # slice centres
W = np.full(10, 2.3e5)  # N/m: F = 4600 N
F = float(W.sum() * B / 10)


def _layout(gear_position, bearings, torque_position=0.0, hub="rigid", length=0.3):
    return ShaftLayout((ShaftSegment(0.0, length, D),), gear_position, B, bearings,
                       torque_position, hub, Material(E, NU))


def test_straddle_mounted_rigid_seat_opens_no_misalignment():
    """A rigid seat at mid-span between two rigid bearings, under a uniform line load, moves
    without tilting: the gap is the same at every face point (to 1e-12 of its size); its
    twist part is r_b^2 F L_t / (G J) with L_t the shaft from the torque point to the seat."""
    lay = _layout(0.15, (Bearing(0.02, axial=True), Bearing(0.28)))
    gap, (ret,) = shaft_gap([BeamShaft(lay)], [RB], Z, W)
    assert np.ptp(gap) <= 1e-12 * abs(gap).max()
    l_t = 0.15 - B / 2
    assert ret.twist == pytest.approx(np.full(10, RB**2 * F * l_t / (G * J)), rel=1e-9)


def test_overhung_rigid_seat_tilts_by_its_section_rotation():
    """A rigid seat overhung beyond the second bearing: the gap grows linearly across the
    face (second differences 0 to 1e-12 of the range), its slope the section rotation at the
    seat: F c^2 / (2 E I) + F (b / 2) c / (E I) from the overhang's bending, and the span's
    rotation at the bearing under the overhang's moment M = F (c + b / 2), M a / (3 E I) +
    M / (kappa G A a) with its shear (Cowper's kappa of a solid section, 6 (1 + nu) / (7 + 6
    nu)); a the span, c the flexible overhang to the seat's start (the shear strain of the
    overhang does not turn the rigid seat; a free stub beyond the seat carries nothing). The
    twist is uniform over a rigid seat."""
    a, c = 0.2, 0.03
    lay = _layout(a + c + B / 2, (Bearing(0.0, axial=True), Bearing(a)),
                  length=a + c + B + 0.01)
    gap, (ret,) = shaft_gap([BeamShaft(lay)], [RB], Z, W)
    d2 = np.diff(ret.translation, 2)
    assert np.abs(d2).max() <= 1e-12 * np.ptp(ret.translation)
    kappa, area = 6 * (1 + NU) / (7 + 6 * NU), math.pi * D**2 / 4
    slope = (F * c**2 / (2 * E * I_) + F * (B / 2) * c / (E * I_)
             + F * (c + B / 2) * (a / (3 * E * I_) + 1 / (kappa * G * area * a)))
    assert np.diff(ret.translation).mean() / (B / 10) == pytest.approx(slope, rel=1e-9)
    assert np.ptp(ret.twist) <= 1e-12 * abs(ret.twist).max()


def test_integral_seat_twists_across_the_face():
    """A pinion cut on its shaft (integral seat), torque held at the shaft's first end: the
    flank's twist grows across the face as the torque carried through each section, r_b
    theta(z) = r_b^2 / (G J) [ F L_0 + integral of the torque still to come ], L_0 the shaft
    up to the face; checked at every slice centre by the discrete sum."""
    lay = _layout(0.15, (Bearing(0.02, axial=True), Bearing(0.28)), hub="integral")
    gap, (ret,) = shaft_gap([BeamShaft(lay)], [RB], Z, W)
    start = 0.15 - B / 2
    dz = B / 10
    # the torque through the section at z: the slices beyond z (each F_j r_b at its centre)
    want = []
    for zj in Z:
        theta = F * RB * start / (G * J)
        beyond = [(zk, W[k] * dz) for k, zk in enumerate(Z)]
        theta += sum(fk * RB * min(zk, zj) for zk, fk in beyond) / (G * J)
        want.append(RB * theta)
    assert ret.twist == pytest.approx(want, rel=1e-9)
    assert ret.twist[-1] > ret.twist[0]


def test_helical_refused():
    lay = _layout(0.15, (Bearing(0.02, axial=True), Bearing(0.28)))
    with pytest.raises(InputError, match="helical mesh's axial force"):
        shaft_gap([BeamShaft(lay)], [RB], Z, W, helix_angle=0.2)
