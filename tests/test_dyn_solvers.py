"""Time integration, Floquet steady state and harmonic balance on the spur pair of the
assembly-error paper.

The reference for the harmonic balance is the time integration of the same
equations (independent method); the reference for the Woodbury solve is the dense
solve of the same harmonic system.
"""

import numpy as np
import pytest

from pipeline.dynamics.excitation import harmonic_signal, rectangular_mesh_stiffness
from pipeline.dynamics.harmonic_balance import harmonic_balance
from pipeline.dynamics.integrate import integrate, steady_state
from pipeline.dynamics.models.spur_pair import SpurPairModel
from pipeline.validation import InputError


@pytest.fixture(scope="module")
def rect_pair():
    """The base case of the assembly-error paper with a rectangular stiffness (2.0/3.4e8 N/m,
    contact ratio 1.65)."""
    k = rectangular_mesh_stiffness(2.0e8, 3.4e8, 1.65, 360)
    return SpurPairModel(k).assembly().assemble()


def test_harmonic_balance_agrees_with_time_integration_within_1_percent(rect_pair):
    """Stiffness jumps: HB (H = 40) vs converged Floquet time integration (1440 segments)."""
    ti = steady_state(rect_pair, segments=1440)
    hb = harmonic_balance(rect_pair, 40).response
    for stat in (
        lambda r: np.ptp(r.dte[0]),
        lambda r: r.dte[0].mean(),
        lambda r: r.rms_mesh_force()[0],
        lambda r: np.sqrt(np.mean(r.q[:, 2] ** 2)),
    ):
        assert stat(hb) == pytest.approx(stat(ti), rel=0.01)
    # and pointwise on the DTE over the period, relative to its peak-to-peak
    dte_ti = np.interp(hb.time, ti.time, ti.dte[0])
    assert np.abs(hb.dte[0] - dte_ti).max() < 0.01 * np.ptp(ti.dte[0])


def test_harmonic_balance_exact_for_smooth_stiffness():
    """Smooth stiffness: HB (H = 12) and fine time integration agree to ~1e-5."""
    k = harmonic_signal(2.7e8, [3e7, 1e7], [0.3, 1.0], samples=2048)
    s = SpurPairModel(k).assembly().assemble()
    ti = steady_state(s, segments=2048)
    hb = harmonic_balance(s, 12, samples=2048).response
    assert np.abs(hb.dte[0] - ti.dte[0]).max() < 2e-5 * np.abs(ti.dte[0]).max()


def test_woodbury_equals_dense(rect_pair):
    """The low-rank (Woodbury) solves, real form and complex form, reproduce the dense
    harmonic system."""
    b = harmonic_balance(rect_pair, 15, method="dense").coefficients
    for method in ("woodbury", "woodbury_complex"):
        a = harmonic_balance(rect_pair, 15, method=method).coefficients
        assert np.abs(a - b).max() < 1e-10 * np.abs(b).max()


def test_first_order_error_is_second_order_in_the_fluctuation():
    """First-order method of Jin et al. (2018): its error against Hill's method scales as
    amplitude^2."""
    amps = np.array([0.01, 0.02, 0.04])
    err = []
    for amp in amps:
        k = harmonic_signal(2.7e8, [amp * 2.7e8], samples=256)
        s = SpurPairModel(k).assembly().assemble()
        full = harmonic_balance(s, 10).response.dte[0]
        first = harmonic_balance(s, 10, coupling="first_order").response.dte[0]
        err.append(np.abs(full - first).max())
    slope = np.polyfit(np.log(amps), np.log(err), 1)[0]
    assert slope == pytest.approx(2.0, abs=0.1)


def test_transient_reaches_floquet_steady_state(rect_pair):
    """Period-by-period integration detects the steady state and lands on the Floquet orbit."""
    r = integrate(rect_pair, periods=5000, tol=1e-6, stop_when_steady=True, keep_last=1)
    assert r.steady_from == 0 and r.time[0] > 0
    fl = steady_state(rect_pair)
    assert np.abs(r.dte[0] - fl.dte[0]).max() < 1e-4 * np.ptp(fl.dte[0])


def test_static_mesh_force_equals_torque_over_base_radius():
    """Constant stiffness: steady mesh force = T_p / r_bp exactly."""
    m = SpurPairModel(harmonic_signal(3e8, [0.0], samples=16))
    r = harmonic_balance(m.assembly().assemble(), 3).response
    assert r.mesh_force[0].mean() == pytest.approx(m.torque / m.base_radius_pinion, rel=1e-12)


def test_unbalanced_load_is_rejected():
    """A net torque on the rigid-body rotation has no steady state."""
    from dataclasses import replace

    from pipeline.dynamics.couplings import Load

    a = SpurPairModel(harmonic_signal(3e8, [1e7], samples=16)).assembly()
    bad = replace(a, loads=(Load("pinion", "theta", 10.0),))
    with pytest.raises(InputError, match="unbalanced"):
        steady_state(bad.assemble())


def test_invalid_inputs_name_the_field():
    with pytest.raises(InputError, match="pinion_teeth"):
        SpurPairModel(harmonic_signal(3e8, [1e7], samples=16), pinion_teeth=2)
    with pytest.raises(InputError, match="contact_ratio"):
        rectangular_mesh_stiffness(1e8, 2e8, 2.5)
