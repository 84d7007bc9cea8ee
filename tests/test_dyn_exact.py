"""Exact checks of the dynamics framework: 2-inertia pair, Meissner/Mathieu stability, energy.

References
----------
* 2-inertia torsional pair: f = sqrt(k (r1^2/I1 + r2^2/I2)) / (2 pi) (textbook).
* Piecewise-constant (Meissner-type) stiffness: the monodromy is the product of
  the closed-form maps [[cos w h, sin(w h)/w], [-w sin w h, cos w h]].
* Mathieu equation x'' + w0^2 (1 + eps cos(2 pi t / T)) x = 0: first-order
  boundaries of the principal instability tongue (2 w0 T / 2 pi)^2 = 1 +- eps/2
  (Nayfeh and Mook, Nonlinear Oscillations, 1979, sec. 5.2).
"""

import math

import numpy as np
import pytest

from pipeline.dynamics.assembly import Assembly
from pipeline.dynamics.bodies import Body
from pipeline.dynamics.couplings import GearMesh
from pipeline.dynamics.integrate import floquet_multipliers, integrate
from pipeline.dynamics.modal import modal_analysis
from pipeline.dynamics.models.planetary import PlanetaryModel
from pipeline.dynamics.models.spur_pair import SpurPairModel
from pipeline.dynamics.reduction import reduce_rigid_body_modes
from pipeline.signals import PeriodicSignal


def test_two_inertia_torsional_pair_frequency():
    """Torsional spur pair: one rigid mode and f = sqrt(k (r1^2/I1 + r2^2/I2)) / 2 pi."""
    k, r1, r2, I1, I2 = 3.1e8, 0.04, 0.09, 2.0e-3, 3.5e-2
    m = SpurPairModel(
        PeriodicSignal(np.full(16, k)),
        base_radius_pinion=r1,
        base_radius_gear=r2,
        inertia_pinion=I1,
        inertia_gear=I2,
        torsional_only=True,
    )
    f = modal_analysis(m.assembly().assemble()).frequencies
    exact = math.sqrt(k * (r1**2 / I1 + r2**2 / I2)) / (2 * math.pi)
    assert f[0] == 0.0
    assert f[1] == pytest.approx(exact, rel=1e-12)


def _single_dof(signal: PeriodicSignal, period: float = 1.0, inertia: float = 1.0):
    b = Body("b", inertia=inertia, dofs=("theta",))
    mesh = GearMesh("k", {("b", "theta"): 1.0}, signal)
    return Assembly([b], [mesh], period=period).assemble()


def _map(w: float, h: float) -> np.ndarray:
    return np.array(
        [[math.cos(w * h), math.sin(w * h) / w], [-w * math.sin(w * h), math.cos(w * h)]]
    )


@pytest.mark.parametrize("k1,k2", [(30.0, 50.0), (8.0, 14.0)])
def test_piecewise_constant_stiffness_monodromy_is_exact(k1, k2):
    """Square-wave stiffness on aligned segments: monodromy equals the closed-form product.

    With n samples (n/2 at k1, n/2 at k2) the linear interpolant ramps over one
    sample at each jump; its segment means are k1 (n/2-1 segments), (k1+k2)/2,
    k2 (n/2-1 segments), (k1+k2)/2, so the exact monodromy is the product of
    four closed-form maps.
    """
    n = 16
    sig = PeriodicSignal(np.r_[np.full(n // 2, k1), np.full(n // 2, k2)])
    h = 1.0 / n
    km = 0.5 * (k1 + k2)
    parts = [(k1, n // 2 - 1), (km, 1), (k2, n // 2 - 1), (km, 1)]
    Phi = np.eye(2)
    for k, count in parts:
        Phi = _map(math.sqrt(k), count * h) @ Phi
    mu = np.sort_complex(floquet_multipliers(_single_dof(sig), segments=n))
    exact = np.sort_complex(np.linalg.eigvals(Phi))
    np.testing.assert_allclose(mu, exact, rtol=0, atol=1e-12)
    # stability is decided by |trace| of the exact monodromy
    stable = abs(np.trace(Phi)) < 2
    assert (np.abs(mu).max() <= 1 + 1e-12) == stable


def _mathieu(a2: float, eps: float, samples: int = 4096):
    """x'' + w0^2 (1 + eps cos 2 pi t) x = 0 with T = 1 and (2 w0 / 2 pi)^2 = a2."""
    w0 = math.pi * math.sqrt(a2)
    tau = np.arange(samples) / samples
    return _single_dof(PeriodicSignal(w0**2 * (1 + eps * np.cos(2 * np.pi * tau))))


@pytest.mark.parametrize(
    "a2,unstable",
    [(1.0, True), (0.97, True), (1.03, True), (0.85, False), (1.15, False), (0.25, False)],
)
def test_mathieu_principal_tongue(a2, unstable):
    """eps = 0.2: the principal tongue spans about a2 in (0.9, 1.1); outside is stable."""
    mu = floquet_multipliers(_mathieu(a2, 0.2), segments=1024)
    assert (np.abs(mu).max() > 1 + 1e-6) == unstable


def test_mathieu_multiplier_converges_second_order():
    """Segment-mean propagator: error of the largest multiplier falls as h^2."""
    sys_ = _mathieu(1.0, 0.2)
    ref = np.abs(floquet_multipliers(sys_, segments=4096)).max()
    segs = np.array([32, 64, 128, 256])
    err = [abs(np.abs(floquet_multipliers(sys_, segments=s)).max() - ref) for s in segs]
    slope = np.polyfit(np.log(1.0 / segs), np.log(err), 1)[0]
    assert slope == pytest.approx(2.0, abs=0.15)


def test_energy_conserved_without_damping_with_gyroscopic_terms():
    """Planetary set spinning at 300 rad/s, constant meshes, no damping: energy constant."""
    m = PlanetaryModel(n_planets=4, carrier_speed=300.0, mesh_period=1e-3)
    red = reduce_rigid_body_modes(m.assembly().assemble())
    assert np.abs(red.G).max() > 0 and red.carrier_speed == 300.0
    rng = np.random.default_rng(1)
    x0 = rng.normal(size=2 * red.n) * np.r_[np.full(red.n, 1e-5), np.full(red.n, 1e-2)]
    r = integrate(red, periods=50, x0=x0, segments=64)
    p = np.linalg.lstsq(red.basis, r.q.T, rcond=None)[0]
    pd = np.linalg.lstsq(red.basis, r.qd.T, rcond=None)[0]
    K = red.mean_stiffness()  # constant meshes: K(t) = mean, including -Omega^2 K_Omega
    E = 0.5 * np.einsum("it,ij,jt->t", pd, red.M, pd) + 0.5 * np.einsum("it,ij,jt->t", p, K, p)
    # 3200 exact steps: only round-off accumulates (RK4 at this step drifts ~1e-5)
    assert np.ptp(E) / E.mean() < 1e-8
