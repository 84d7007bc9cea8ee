"""Periodic signals with jumps at known phases (:func:`pipeline.signals.resample_with_jumps`)
and the spur pair's tooth-pair jumps (:func:`pipeline.dynamics.mesh_input.tooth_pair_jumps`).

References
----------
* Exact: a signal linear between its jumps is reproduced exactly at every phase of the
  finer grid (each piece's interpolant extended by its end lines is that line).
* Convergence: for a smooth signal between jumps the largest error of the resampled
  signal falls at second order in the sample interval (linear interpolation, error
  ``h^2 max|s''| / 8``), where the plain interpolant keeps an O(1) error next to a jump.
* ISO 21771:2007, sec. 5.4 (transverse contact ratio): a spur pair's tooth pairs enter at
  the start of the path of contact and leave ``eps_alpha - floor(eps_alpha)`` of a base
  pitch later in the mesh cycle.
"""

import math

import numpy as np
import pytest

from pipeline.config import gearbox_from_text
from pipeline.dynamics.mesh_input import tooth_pair_jumps
from pipeline.signals import Jump, PeriodicSignal, resample_with_jumps
from pipeline.validation import InputError
from workflows.default_case import PAPER_CASE as DEFAULT

LEAVE = 0.6180339887


def _piecewise(tau: np.ndarray) -> np.ndarray:
    """1 + tau on [0, LEAVE], -1 - tau after it: jumps at 0 (up by 3) and LEAVE (down by
    3.24)."""
    return np.where(tau <= LEAVE, 1.0 + tau, -1.0 - tau)


def test_piecewise_linear_signal_is_reproduced_exactly():
    """60 samples -> 360 phases: every value within 1e-13 of the exact signal, the
    jump at LEAVE falling between two samples of the fine grid and the one at 0 on a
    sample; the plain interpolant misses by up to 2.6 (a ramp across the interval)."""
    coarse = PeriodicSignal(_piecewise(np.arange(60) / 60))
    jumps = (Jump(0.0, "after"), Jump(LEAVE, "before"))
    fine = resample_with_jumps(coarse, jumps, 360)
    exact = _piecewise(fine.tau)
    np.testing.assert_allclose(fine.values, exact, rtol=0, atol=1e-13)
    assert np.abs(coarse(fine.tau) - exact).max() > 2.5


def test_a_sample_on_a_jump_holds_the_side_it_names():
    """A jump at 0.25 with 8 samples: sample 2 lies on it. 'before' keeps it on the left
    piece (value 0.25 of the rising line), 'after' on the right (value 5)."""
    tau = np.arange(8) / 8
    values = np.where(tau <= 0.25, tau, 5.0 + 0 * tau)
    left = resample_with_jumps(PeriodicSignal(values), (Jump(0.0, "after"),
                                                        Jump(0.25, "before")), 16)
    assert left.values[4] == pytest.approx(0.25, abs=1e-14)
    assert left.values[5] == pytest.approx(5.0, abs=1e-14)
    values = np.where(tau < 0.25, tau, 5.0 + 0 * tau)
    right = resample_with_jumps(PeriodicSignal(values), (Jump(0.0, "after"),
                                                         Jump(0.25, "after")), 16)
    assert right.values[4] == pytest.approx(5.0, abs=1e-14)
    assert right.values[3] == pytest.approx(3 / 16, abs=1e-14)


def test_smooth_pieces_converge_at_second_order():
    """s = sin(2 pi tau) + (1 on [0.31, 0.81]), jumps between samples. Linear
    interpolation or extension over at most one interval h misses a smooth piece by at
    most ``h^2 max|s''|`` (``max|s''| = 4 pi^2``); the largest error at 2560 phases stays
    below that bound for n = 40, 80, 160 (0.42, 0.66, 0.41 of it) and falls 16.1x from 40
    to 160 samples (second order: 16; first order would give 4). The plain interpolant's
    error stays at about half the jump (0.56-0.78)."""
    jumps = (Jump(0.31, "after"), Jump(0.81, "before"))

    def exact(t):
        return np.sin(2 * np.pi * t) + ((t >= 0.31) & (t <= 0.81))

    errors, plain = [], []
    for n in (40, 80, 160):
        coarse = PeriodicSignal(exact(np.arange(n) / n))
        fine = resample_with_jumps(coarse, jumps, 2560)
        errors.append(np.abs(fine.values - exact(fine.tau)).max())
        plain.append(np.abs(coarse(fine.tau) - exact(fine.tau)).max())
        assert errors[-1] < 4 * np.pi**2 / n**2
    assert errors[0] / errors[-1] > 12.0
    assert min(plain) > 0.4


def test_without_jumps_or_with_an_empty_piece_it_is_the_plain_interpolant():
    """No jump, or two jumps closer than a sample interval (no sample between them): the
    result is the linear interpolant at the finer phases."""
    coarse = PeriodicSignal(np.cos(2 * np.pi * np.arange(12) / 12))
    t = np.arange(48) / 48
    np.testing.assert_array_equal(resample_with_jumps(coarse, (), 48).values, coarse(t))
    close = (Jump(0.51, "after"), Jump(0.52, "before"))
    np.testing.assert_array_equal(resample_with_jumps(coarse, close, 48).values, coarse(t))


@pytest.mark.parametrize("phase, side", [(1.0, "after"), (-0.1, "after"), (0.5, "left")])
def test_a_jump_outside_one_period_or_with_an_unknown_side_is_refused(phase, side):
    with pytest.raises(InputError, match="a jump needs a phase in"):
        Jump(phase, side)


def test_spur_pair_jumps_sit_at_the_ends_of_the_path():
    """Demo pair (z 50/50, m 3 mm, alpha 20 deg, x 0): eps_alpha = 1.7547 (ISO 21771
    sec. 5.4, from the tip and base circles); the leaving pair drops out at 0.7547 of the
    mesh cycle. A helical pair's contact lines enter gradually: no jumps."""
    pair = gearbox_from_text(DEFAULT).pair
    (enter, leave) = tooth_pair_jumps(pair)
    eps = pair.transverse_contact_ratio
    assert (enter.phase, enter.sample_side) == (0.0, "after")
    assert leave.sample_side == "before"
    assert leave.phase == pytest.approx(eps - math.floor(eps), abs=1e-12)
    ra, rb = pair.pinion.tip_radius_, pair.pinion.base_radius
    g = 2 * math.sqrt(ra**2 - rb**2) - pair.operating_centre_distance * math.sin(
        pair.operating_pressure_angle)
    assert eps == pytest.approx(g / pair.base_pitch, rel=1e-12)
    assert eps == pytest.approx(1.7547, abs=5e-5)
    helical = gearbox_from_text(DEFAULT.replace(
        "[pinion]\n", '[pinion]\nhelix_angle_deg = 15.0\nhand = "right"\n').replace(
        "[gear]\n", '[gear]\nhelix_angle_deg = 15.0\nhand = "left"\n')).pair
    assert tooth_pair_jumps(helical) == ()
