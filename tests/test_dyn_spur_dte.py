"""The dynamic transmission error of workflows/dynamics_spur_dte.py and its ladder.

The number: the DTE peak-to-peak of the assembly-error paper's spur pair (z 50/50, m 3 mm,
340 N m, 2340 rpm, its 6-DOF lateral-torsional model and table of parameters), condition 1
(no assembly error), mu = 0, analytical potential-energy k(t) at 360 positions, harmonic
balance with H = 25 harmonics: 23.832 um. The rungs below it:

* exact limit: at vanishing speed the DTE is the static deflection F / k(t) with
  F = T_p / r_bp, whose peak-to-peak F (1 / k_min - 1 / k_max) = 9.292 um is computed from the
  stiffness samples alone; the same model approaches it at first order in the speed
  (:func:`test_dte_tends_to_the_static_deflection_at_vanishing_speed`). At 2340 rpm the
  DTE is 2.56 times the static value: the number is a dynamic one.
* independent solution: the paper's equations of motion written out here, reduced by the
  rigid rotation, integrated over one mesh period by scipy's DOP853 (8th-order
  Runge-Kutta, rtol 1e-10) between the samples of k(t), with the periodic state from the
  monodromy matrix (shooting): 23.82708 um. The harmonic balance at H = 200 and the
  pipeline's exact-propagator time integration agree to 1e-6 and 1e-5; the workflow's
  H = 25 value lies 1.9e-4 above
  (:func:`test_dte_agrees_with_an_independent_time_integration`). The same integration,
  with friction torques and a transmission error, confirms the workflow's friction cases
  and the values other tests pin for this pair read from its gearbox file (DTE,
  tests/test_dyn_contact_excitation.py) and for the demo gearbox (dynamic factor,
  tests/test_dyn_dynamic_factor.py).
* convergence: in the harmonics the error falls faster than H^-2 (measured H^-3 to H^-4);
  in the stiffness positions at first order, through where the sampled k(t) puts the
  entry and exit of a tooth pair: 23.827 um at 360 positions, 23.883 um as the positions
  grow (the workflow's value is 0.23 % low on this account)
  (:func:`test_dte_converges_in_harmonics`, :func:`test_dte_converges_in_positions`).
* published reference: none. The assembly-error paper describes its DTE figures in words
  only, with no value for any case. Its three statements about the DTE (at
  condition 1, mu = 0.05 gives the smallest DTE; at mu = 0.05, condition 2 the largest and
  condition 3 a smaller one; at condition 3, friction lowers the DTE) are not reproduced
  by this model, whose DTE peak-to-peak rises with the friction and with the assembly
  error in every case (asserted as regression below). Inputs differ from the paper's:
  foundation correction 1.0 (the paper's 1.1), friction through the friction stiffness and
  torques of Jin et al. (2018) instead of the paper's friction-modified potential energy,
  and the periodic steady state instead of the paper's fourth-order Runge-Kutta run.
* regression: the workflow's table (:func:`test_spur_dte_workflow_coarse`).
"""

from dataclasses import replace

import numpy as np
import pytest
import scipy.linalg as sla
from helpers import load_workflow
from scipy.integrate import solve_ivp

from pipeline.dynamics.harmonic_balance import harmonic_balance
from pipeline.dynamics.integrate import steady_state
from pipeline.dynamics.models.spur_pair import SpurPairModel

DTE_WORKFLOW = 23.832e-6
"""The workflow's DTE peak-to-peak, condition 1, mu = 0, H = 25, 360 positions (m)."""


@pytest.fixture(scope="module")
def workflow():
    return load_workflow("dynamics_spur_dte")


@pytest.fixture(scope="module")
def base_case(workflow) -> SpurPairModel:
    """The workflow's model of condition 1 without friction (360 positions)."""
    return workflow.model_for(1, 0.0, 360)[0]


def _reduced_matrices(model: SpurPairModel, k: float):
    """Mass and stiffness of the paper's equations, reduced by the rigid rotation.

    Coordinates (x_p, y_p, x_g, y_g, d), x along the line of action, y along its normal n
    (x turned by +90 deg) and d = r_bp theta_p - r_bg theta_g:
    ``m_p x_p'' + c_b x_p' + k_b x_p = -F``, ``m_g x_g'' + c_b x_g' + k_b x_g = F``,
    ``m_p y_p'' + c_b y_p' + k_b y_p = F_f``, ``m_g y_g'' + c_b y_g' + k_b y_g = -F_f`` and,
    from the two rotations with T_g = T_p r_bg / r_bp,
    ``m_e d'' = T_p / r_bp - F + m_e (r_bp T_f1 / I_p - r_bg T_f2 / I_g)`` with
    ``m_e = 1 / (r_bp^2 / I_p + r_bg^2 / I_g)``; ``F = k (delta - e) + c_m (delta' - e')``,
    ``delta = x_p - x_g + d``, and the friction force and torques (each in its gear's sense
    of rotation) ``F_f = K_f (delta - e)``, ``T_fi = KT_fi (delta - e)`` (Jin et al. 2018,
    eqs. 15-17).

    Returns
    -------
    M, K (5 x 5, with mesh stiffness k), v (delta = v . q), m_e.
    """
    rp, rg = model.base_radius_pinion, model.base_radius_gear
    me = 1.0 / (rp**2 / model.inertia_pinion + rg**2 / model.inertia_gear)
    v = np.array([1.0, 0.0, -1.0, 0.0, 1.0])
    M = np.diag([model.mass_pinion, model.mass_pinion, model.mass_gear, model.mass_gear, me])
    kb = model.bearing_stiffness
    K = np.diag([kb, kb, kb, kb, 0.0]) + k * np.outer(v, v)
    return M, K, v, me


def _samples(signal, n: int) -> np.ndarray:
    """Samples of an optional periodic signal (zeros for ``None``), checked to be ``n``."""
    values = np.zeros(n) if signal is None else signal.values
    assert values.size == n
    return values


def _independent_dte(model: SpurPairModel, per_sample: int) -> np.ndarray:
    """Periodic DTE (m) of the paper's equations at ``per_sample`` phases per k(t) sample.

    The state ``y = (q, q')`` of :func:`_reduced_matrices` obeys ``y' = A(t) y + b(t)``.
    Integrating the 10 x 11 matrix ``[Phi | g]`` from ``[I | 0]`` over one mesh period T
    gives the periodic state ``y0 = (I - Phi(T))^-1 g(T)`` and at every phase
    ``y = Phi(t) y0 + g(t)``. Every periodic coefficient is the periodic piecewise-linear
    interpolant of its samples (np.interp), integrated one sample interval at a time so
    that the integrator never steps over a kink. As the pipeline documents for its forcing,
    a transmission error enters through the interpolants of the sampled products
    (k e, K_f e, KT_fi e) and the slope of the interpolant of e.
    """
    kv = model.mesh_stiffness.values
    n, T = kv.size, model.mesh_period
    M, K0, v, me = _reduced_matrices(model, 0.0)
    minv = 1.0 / np.diag(M)
    cm = 2.0 * model.damping_ratio * np.sqrt(kv.mean() * me)
    cb = model.bearing_damping
    C = np.diag([cb, cb, cb, cb, 0.0]) + cm * np.outer(v, v)
    rp, rg = model.base_radius_pinion, model.base_radius_gear
    e = _samples(model.transmission_error, n)
    kf = _samples(model.friction_stiffness, n)
    torque = (rp / model.inertia_pinion * _samples(model.friction_torque_pinion, n)
              - rg / model.inertia_gear * _samples(model.friction_torque_gear, n))
    # rows: accelerations per unit (delta - e) of x_p, y_p, x_g, y_g, d
    gain = np.stack([-kv / M[0, 0], kf / M[1, 1], kv / M[2, 2], -kf / M[3, 3],
                     -kv / me + torque], axis=1)
    gain = np.vstack([gain, gain[:1]])
    gain_e = np.vstack([gain[:-1] * e[:, None], gain[:1] * e[0]])
    slope_e = np.diff(np.append(e, e[0])) * n / T
    b0 = np.zeros(10)
    b0[9] = model.torque / rp / me

    def rhs(t, y):
        x = t / T * n
        i = min(int(x), n - 1)
        w = x - i
        g = (1.0 - w) * gain[i] + w * gain[i + 1]
        ge = (1.0 - w) * gain_e[i] + w * gain_e[i + 1]
        Y = y.reshape(10, 11)
        dY = np.empty_like(Y)
        dY[:5] = Y[5:]
        dY[5:] = -minv[:, None] * (K0 @ Y[:5] + C @ Y[5:]) + np.outer(g, v @ Y[:5])
        dY[:, 10] += b0
        dY[5:, 10] += -ge + minv * v * cm * slope_e[i]
        return dY.ravel()

    y = np.hstack([np.eye(10), np.zeros((10, 1))]).ravel()
    states = []
    for i in range(n):
        t0, t1 = i * T / n, (i + 1) * T / n
        sol = solve_ivp(rhs, (t0, t1), y, method="DOP853", rtol=1e-10, atol=1e-14,
                        t_eval=np.linspace(t0, t1, per_sample + 1))
        states.append(sol.y[:, :-1].T.reshape(-1, 10, 11))
        y = sol.y[:, -1]
    Y = y.reshape(10, 11)
    y0 = np.linalg.solve(np.eye(10) - Y[:, :10], Y[:, 10])
    Ys = np.concatenate(states)
    return (Ys[:, :5, :10] @ y0 + Ys[:, :5, 10]) @ v


@pytest.fixture(scope="module")
def independent(base_case) -> np.ndarray:
    """Independent DTE (m) of the base case over one period, 5760 phases (16 per sample)."""
    return _independent_dte(base_case, 16)


@pytest.fixture(scope="module")
def reference(independent) -> float:
    """Independent DTE peak-to-peak of the base case, m."""
    return float(np.ptp(independent))


def test_dte_tends_to_the_static_deflection_at_vanishing_speed(base_case):
    """Exact limit: at speed -> 0 the DTE peak-to-peak is F (1 / k_min - 1 / k_max).

    With the speed scaled by 1e-3, 3e-4, 1e-4 (0.23 rpm at the last) the pipeline's
    exact-propagator time integration (16 segments per k sample) of the workflow's model
    approaches the static 9.2918 um from above: +2.4 %, +0.34 %, +0.088 %. Each stiffness jump is a
    ramp one sample (T_m / 360) wide; the free vibration it leaves in a mode of angular
    frequency omega is at most 2 / (omega t_r) of the jump of the static deflection, so the
    error falls at least in proportion to the speed (asserted; measured order 1.2-1.6) and
    stays below that bound for the lowest mode (783 Hz; bound 2.9 % at 1e-4).
    At 2340 rpm the DTE is 2.56 times the static value (mesh frequency 1950 Hz, the
    torsional mode at 3600-4900 Hz).
    """
    kv = base_case.mesh_stiffness.values
    force = base_case.torque / base_case.base_radius_pinion
    static = force * (1.0 / kv.min() - 1.0 / kv.max())
    assert static == pytest.approx(9.2918e-6, rel=1e-4)
    factors = np.array([1e-3, 3e-4, 1e-4])
    err = []
    for f in factors:
        slow = replace(base_case, speed=base_case.speed * f)
        r = steady_state(slow.assembly().assemble(), segments=16 * kv.size)
        err.append(r.peak_to_peak_dte()[0] / static - 1.0)
    err = np.array(err)
    assert np.all(err > 0)
    assert np.all(err[:-1] / err[1:] >= factors[:-1] / factors[1:])
    M, K, _, _ = _reduced_matrices(base_case, kv.min())
    omega_1 = np.sqrt(sla.eigh(K, M, eigvals_only=True).min())
    ramp = base_case.mesh_period / factors[-1] / kv.size
    assert err[-1] < 2.0 / (omega_1 * ramp)
    nominal = harmonic_balance(base_case.assembly().assemble(), 25).response
    assert nominal.peak_to_peak_dte()[0] / static == pytest.approx(2.565, rel=1e-3)


def test_dte_agrees_with_an_independent_time_integration(base_case, reference):
    """Independent solution (module docstring): 23.82708 um.

    * harmonic balance, H = 200, same 5760 phases: within 1e-6 (its truncation error from
      the convergence test, 1.5e-7; the integrator's rtol 1e-10);
    * the pipeline's exact-propagator time integration, 2880 segments: within 1e-5
      (second order in the segment length: -1.1e-5 at 1440 segments, -1.5e-6 at 2880);
    * the workflow's setting (H = 25, 512 phases): within 3e-4, the truncation error of
      H = 25 (2.4e-4 on 5760 phases, see :func:`test_dte_converges_in_harmonics`; 1.9e-4 on
      the workflow's 512).
    """
    assert reference == pytest.approx(23.8271e-6, rel=1e-5)
    system = base_case.assembly().assemble()
    hb = harmonic_balance(system, 200, samples=5760).response
    assert hb.peak_to_peak_dte()[0] == pytest.approx(reference, rel=1e-6)
    assert np.abs(hb.q[:, [1, 4]]).max() < 1e-12 * reference  # y: no force without friction
    ti = steady_state(system, segments=2880)
    assert ti.peak_to_peak_dte()[0] == pytest.approx(reference, rel=1e-5)
    wf = harmonic_balance(system, 25).response.peak_to_peak_dte()[0]
    assert wf == pytest.approx(reference, rel=3e-4)


@pytest.mark.parametrize("excitation, dte_ptp, dte_mean, tol_fine, tol_pinned", [
    ("analytical", 24.9963e-6, 13.8636e-6, 1e-6, 2.4e-4 * (25 / 40) ** 2),
    ("contact", 8.33545e-6, 13.6973e-6, 4e-6, 1.2e-4)])
def test_gearbox_file_dte_agrees_with_an_independent_time_integration(
        workflow, excitation, dte_ptp, dte_mean, tol_fine, tol_pinned):
    """The same pair read from the gearbox file (bodies derived from the 21 mm bore, 2.543 kg,
    7.72e-3 kg m^2), excited by the analytical k(t) or by the loaded contact (tangent k(t)
    and static transmission error e(t), 360 positions, the tip corners touching beyond the
    path): the values test_dyn_contact_excitation pins at H = 40 (24.996 and 8.335 um
    peak-to-peak, 13.864 and 13.697 um mean).

    The independent solution (with e(t) for the contact): 24.9963 / 8.33545 um peak-to-peak,
    13.8636 / 13.6973 um mean. Analytical: the harmonic balance at H = 200 agrees within 1e-6
    (measured 5e-8); at H = 40 on 512 phases, as that test runs, within 1e-4: the error bound
    of H = 25 (2.4e-4) carried to H = 40 at the guaranteed second order (measured 6e-6 and
    6e-5). Contact: the corners closing put kinks into k(t) and e(t), and the series
    converges more slowly: on 5760 phases -1.4e-4, -7.1e-5, +1.5e-5, -7.5e-6, +3.6e-6 at
    H = 25, 40, 80, 160, 200 (order about 1.5), -9.8e-5 at H = 40 on 512 phases; asserted
    within 4e-6 (H = 200) and 1.2e-4 (H = 40).
    """
    from pipeline.config import gearbox_from_text
    from pipeline.run.runner import gearbox_dynamic_model

    text = workflow.CONFIG.read_text(encoding="utf-8") + "[contact]\npositions = 360\n"
    box = gearbox_from_text(text.replace(
        "damping_ratio = 0.07", f'damping_ratio = 0.07\nexcitation = "{excitation}"'))
    model = gearbox_dynamic_model(box)
    assert model.friction_stiffness is None
    assert (model.transmission_error is None) == (excitation == "analytical")
    dte = _independent_dte(model, 16)
    assert np.ptp(dte) == pytest.approx(dte_ptp, rel=1e-5)
    assert dte.mean() == pytest.approx(dte_mean, rel=1e-5)
    system = model.assembly().assemble()
    fine = harmonic_balance(system, 200, samples=5760).response
    assert fine.peak_to_peak_dte()[0] == pytest.approx(np.ptp(dte), rel=tol_fine)
    pinned = harmonic_balance(system, 40).response.peak_to_peak_dte()[0]
    assert pinned == pytest.approx(np.ptp(dte), rel=tol_pinned)


@pytest.mark.parametrize("condition, mu, dte_ptp", [(1, 0.1, 24.1216e-6), (3, 0.1, 26.9971e-6)])
def test_workflow_friction_cases_agree_with_an_independent_time_integration(
        workflow, condition, mu, dte_ptp):
    """With friction (Jin et al. 2018): the workflow's cases condition 1 and 3 at mu = 0.1.
    The friction force acts along the normal to the line of action and moves only y, which
    the DTE does not see; the friction torques change the DTE (+1.2 % at condition 1).

    Independent solution 24.1216 and 26.9971 um; the harmonic balance at H = 200 within
    1e-6 (measured 2e-7 and 8e-8), the workflow's H = 25 within 3e-4, the truncation error of
    H = 25 (:func:`test_dte_agrees_with_an_independent_time_integration`; measured -2.5e-4
    and 5.6e-5).
    """
    model = workflow.model_for(condition, mu, 360)[0]
    assert model.friction_stiffness is not None
    ref = np.ptp(_independent_dte(model, 16))
    assert ref == pytest.approx(dte_ptp, rel=1e-5)
    system = model.assembly().assemble()
    fine = harmonic_balance(system, 200, samples=5760).response.peak_to_peak_dte()[0]
    assert fine == pytest.approx(ref, rel=1e-6)
    assert harmonic_balance(system, 25).response.peak_to_peak_dte()[0] == pytest.approx(
        ref, rel=3e-4)


def test_demo_dynamic_factor_agrees_with_an_independent_time_integration():
    """The demo gearbox (analytical compliance, 360 positions, friction, loaded-contact
    transmission error): the dynamic factor max k (delta - e) / mean k (delta - e) that
    test_dyn_dynamic_factor pins at H = 40 (1.26935; 2.3699 with contact confined to the
    nominal path: with the tip corners touching the stiffness no longer jumps where a pair
    enters).

    Independent solution 1.26934. The maximum sits where a tooth pair enters and k jumps,
    where the series converges at its guaranteed second order only, not at the faster rate
    of the DTE's smooth extremes: the harmonic balance at H = 200 on the same 5760 phases
    lies within 2.4e-4 (25 / 200)^2 = 3.8e-6 (measured 1.7e-6); at H = 40, as pinned,
    within 5e-4 (that test's convergence table moves it 2e-4 from 40 to 160 harmonics;
    measured -2.1e-4).
    """
    from pipeline.config import gearbox_from_text
    from pipeline.run.runner import gearbox_dynamic_model
    from workflows.default_case import PAPER_CASE as DEFAULT

    text = DEFAULT.replace('compliance = "fe2d"', 'compliance = "analytical"').replace(
        "positions = 60", "positions = 360")
    model = gearbox_dynamic_model(gearbox_from_text(text))
    assert model.friction_stiffness is not None and model.transmission_error is not None
    dte = _independent_dte(model, 16)
    tau = np.arange(dte.size) / dte.size
    elastic = model.mesh_stiffness(tau) * (dte - model.transmission_error(tau))
    ref = elastic.max() / elastic.mean()
    assert ref == pytest.approx(1.26934, rel=1e-5)
    system = model.assembly().assemble()
    fine = harmonic_balance(system, 200, samples=dte.size).response.dynamic_factor()[0]
    assert fine == pytest.approx(ref, rel=2.4e-4 * (25 / 200) ** 2)
    assert harmonic_balance(system, 40).response.dynamic_factor()[0] == pytest.approx(
        ref, rel=5e-4)


def test_dte_converges_in_harmonics(base_case, reference):
    """Convergence in H against the independent solution (5760 phases).

    The jumps of k(t) make the acceleration jump, so the DTE's Fourier coefficients fall
    as h^-3 and a truncation at H errs by O(H^-2) at most; each doubling of H must then
    divide the error by 4 or more. Measured: 2.4e-4, 2.9e-5, 1.9e-6, 1.5e-7 at
    H = 25, 50, 100, 200 (ratios 8.2, 15, 13).
    """
    system = base_case.assembly().assemble()
    err = np.array([abs(harmonic_balance(system, h, samples=5760).response
                        .peak_to_peak_dte()[0] / reference - 1.0) for h in (25, 50, 100, 200)])
    assert err[0] == pytest.approx(2.4e-4, rel=0.05)
    assert np.all(err[:-1] / err[1:] > 4.0)


def test_dte_converges_in_positions(workflow):
    """Convergence in the positions of the stiffness stage (H = 200, 5760 phases).

    Sampled k(t) ramps across the sample interval that holds a tooth pair's entry or exit,
    so the double-contact time is off by up to one interval (8.8e-4 of a mesh period at
    360 positions, 1.9e-4 at 1440, 1.4e-5 at 5760 and 23040): the DTE converges at first
    order in 1/positions, each fourfold refinement dividing the difference to the finest
    by 4 or more. Measured: 23.8271, 23.8720, 23.88302, 23.88308 um at 360, 1440, 5760,
    23040 positions; the workflow's 360 positions are 0.23 % low.
    """
    p = np.array([
        harmonic_balance(workflow.model_for(1, 0.0, n)[0].assembly().assemble(), 200,
                         samples=5760).response.peak_to_peak_dte()[0]
        for n in (360, 1440, 5760, 23040)])
    diff = np.abs(p[:-1] - p[-1])
    assert diff[0] / diff[1] > 4.0 and diff[1] / diff[2] > 4.0
    assert p[-1] == pytest.approx(23.8831e-6, rel=1e-5)
    assert p[0] / p[-1] - 1.0 == pytest.approx(-2.3e-3, abs=1e-4)


def test_spur_dte_workflow_coarse(workflow, independent, tmp_path):
    """Regression: the workflow's table (coarse: 360 positions, H = 25).

    23.832 um (condition 1, mu = 0) sits 1.9e-4 above the independent solution of its
    equations (23.8271 um, the harmonics' truncation) and 0.23 % below the value its
    stiffness converges to with the positions (23.883 um); the paper gives no value. The
    band, 1e-3, is below that positions error, so that a change of the stiffness sampling
    shows, and far above round-off. Its mean DTE, 13.8224 um, is the independent
    solution's within 1e-4 (the mean of one period's samples without the repeated end
    point; measured 5e-6).

    This model's trends (regression; the paper reports otherwise, see the module
    docstring): larger assembly errors shorten the contact path (smaller contact ratio)
    and raise the DTE peak-to-peak at every friction level; friction raises the DTE
    peak-to-peak and the RMS mesh force at every condition.
    """
    cols = workflow.run(False, tmp_path)
    ptp = cols["dte peak-to-peak [m]"].reshape(3, 3)  # condition x friction
    eps = cols["contact ratio [-]"].reshape(3, 3)[:, 0]
    assert np.all(np.diff(eps) < 0) and np.all(np.diff(ptp, axis=0) > 0)
    assert np.all(np.diff(ptp, axis=1) > 0)
    assert np.all(np.diff(cols["rms mesh force [N]"].reshape(3, 3), axis=1) > 0)
    assert ptp[0, 0] == pytest.approx(DTE_WORKFLOW, rel=1e-3)
    assert cols["dte mean [m]"][0] == pytest.approx(independent.mean(), rel=1e-4)
    assert (tmp_path / "dte_conditions.png").is_file()
