"""Cases of the dynamics layer: Lin and Parker (1999)'s planetary natural frequencies, the
two-inertia torsional pair and the exact monodromy of a piecewise-constant stiffness.
"""

from __future__ import annotations

import math

import numpy as np

from pipeline.verification.context import Context
from pipeline.verification.model import Convergence, Outcome, Plot, Quantity, Series

LIN_PARKER_1999_TABLE_2 = {
    3: {"rotational": (1475.7, 1930.3, 2658.3, 7462.8, 11775.3),
        "translational": (743.2, 1102.4, 1896.0, 2276.4, 6986.3, 9647.9),
        "planet": ()},
    4: {"rotational": (1536.6, 1970.6, 2625.7, 7773.6, 13071.1),
        "translational": (727.0, 1091.0, 1892.8, 2342.5, 7189.9, 10437.6),
        "planet": (1808.2, 5963.8, 6981.7)},
    5: {"rotational": (1567.4, 2006.1, 2614.8, 8065.4, 14253.1),
        "translational": (710.0, 1072.0, 1888.1, 2425.3, 7382.4, 11172.3),
        "planet": (1808.2, 5963.8, 6981.7)},
}
"""Lin and Parker (1999), Table 2: natural frequencies (Hz) of the example system for 3,
4 and 5 planets by mode type (the rigid rotation at 0 Hz left out); translational modes
are double, planet modes have multiplicity N - 3."""


def case_lin_parker_1999(context: Context) -> Outcome:
    """Every elastic natural frequency of Lin and Parker's example planetary set, 3, 4
    and 5 planets, with its mode type."""
    from pipeline.dynamics.modal import modal_analysis
    from pipeline.dynamics.models.planetary import PlanetaryModel

    reason = ("Table 2 prints 0.1 Hz and Table 1's inputs are rounded (N = 4 differs most, "
              "1536.5 against 1536.6 Hz, by hand-written reduced models); the tests hold "
              "5e-4")
    quantities = []
    for n, table in LIN_PARKER_1999_TABLE_2.items():
        m = PlanetaryModel(n_planets=n)
        res = m.classify(modal_analysis(m.assembly().assemble()))
        kinds = np.array(res.kinds)
        for kind, values in table.items():
            got = np.sort(res.frequencies[kinds == kind])
            mult = {"rotational": 1, "translational": 2, "planet": n - 3}[kind]
            if got.size != mult * len(values):
                raise ValueError(f"{n} planets: {got.size} {kind} modes, Table 2 has "
                                 f"{len(values)} of multiplicity {mult}")
            for i, f_ref in enumerate(values):
                quantities.append(Quantity(f"N = {n}, {kind} mode {i + 1}", "Hz", f_ref,
                                           got[i * mult], "relative", 5e-4, reason))
    inputs = (("masses m_s, m_r, m_c, m_p", "0.4, 2.35, 5.43, 0.66 kg"),
              ("I / r^2 of sun, ring, carrier, planet", "0.39, 3.00, 6.29, 0.61 kg"),
              ("mesh stiffness k_sp = k_rp", "5e8 N/m"),
              ("bearings k_p; ring k_ru; k_su = k_cu", "1e8 N/m; 1e9 N/m; 0"),
              ("pressure angle", "24.6 deg"), ("planets", "3, 4, 5, equally spaced"))
    return Outcome("Lin and Parker (1999), J. Vib. Acoust. 121, 316-321, Table 1 (inputs) "
                   "and Table 2 (natural frequencies)", inputs, tuple(quantities))


TWO_INERTIA = {"k_N_per_m": 3.1e8, "r1_m": 0.04, "r2_m": 0.09, "I1_kgm2": 2.0e-3,
               "I2_kgm2": 3.5e-2}


def case_two_inertia_pair(context: Context) -> Outcome:
    """Torsional spur pair: f = sqrt(k (r1^2 / I1 + r2^2 / I2)) / (2 pi)."""
    from pipeline.dynamics.modal import modal_analysis
    from pipeline.dynamics.models.spur_pair import SpurPairModel
    from pipeline.signals import PeriodicSignal

    k, r1, r2, i1, i2 = TWO_INERTIA.values()
    m = SpurPairModel(PeriodicSignal(np.full(16, k)), base_radius_pinion=r1,
                      base_radius_gear=r2, inertia_pinion=i1, inertia_gear=i2,
                      torsional_only=True)
    f = modal_analysis(m.assembly().assemble()).frequencies
    exact = math.sqrt(k * (r1**2 / i1 + r2**2 / i2)) / (2 * math.pi)
    quantities = (Quantity("elastic natural frequency", "Hz", exact, f[1], "relative", 1e-12,
                           "closed form: round-off only"),
                  Quantity("rigid-body frequency", "Hz", 0.0, f[0], "absolute", 0.0,
                           "one rigid rotation, exactly zero"))
    inputs = (("mesh stiffness k", f"{k:g} N/m"), ("base radii", f"{r1 * 1e3:g}, "
                                                   f"{r2 * 1e3:g} mm"),
              ("polar inertias", f"{i1:g}, {i2:g} kg m^2"))
    return Outcome("two inertias on a spring: f = sqrt(k (r1^2/I1 + r2^2/I2)) / (2 pi) "
                   "(textbook)", inputs, quantities)


MONODROMY = {"k1": 30.0, "k2": 50.0, "samples": 16}
"""Unit inertia, period 1 s, stiffness k1 for half the period and k2 for the other half
(N m/rad)."""


def case_piecewise_monodromy(context: Context) -> Outcome:
    """Floquet multipliers of a square-wave stiffness against the product of the
    closed-form maps [[cos w h, sin(w h)/w], [-w sin w h, cos w h]]."""
    from pipeline.dynamics.assembly import Assembly
    from pipeline.dynamics.bodies import Body
    from pipeline.dynamics.couplings import GearMesh
    from pipeline.dynamics.integrate import floquet_multipliers
    from pipeline.signals import PeriodicSignal

    k1, k2, n = MONODROMY["k1"], MONODROMY["k2"], MONODROMY["samples"]
    sig = PeriodicSignal(np.r_[np.full(n // 2, k1), np.full(n // 2, k2)])
    body = Body("b", inertia=1.0, dofs=("theta",))
    system = Assembly([body], [GearMesh("k", {("b", "theta"): 1.0}, sig)],
                      period=1.0).assemble()
    h, km = 1.0 / n, 0.5 * (k1 + k2)
    phi = np.eye(2)
    # the linear interpolant ramps over one sample at each jump: its segment means are k1,
    # the mean, k2, the mean
    for k, count in ((k1, n // 2 - 1), (km, 1), (k2, n // 2 - 1), (km, 1)):
        w = math.sqrt(k)
        phi = np.array([[math.cos(w * count * h), math.sin(w * count * h) / w],
                        [-w * math.sin(w * count * h), math.cos(w * count * h)]]) @ phi
    mu = np.sort_complex(floquet_multipliers(system, segments=n))
    exact = np.sort_complex(np.linalg.eigvals(phi))
    reason = "exact propagator over constant segments: round-off only (the tests: 1e-12)"
    quantities = []
    for i in range(2):
        quantities.append(Quantity(f"Floquet multiplier {i + 1}, real part", "-",
                                   exact[i].real, mu[i].real, "absolute", 1e-12, reason))
        quantities.append(Quantity(f"Floquet multiplier {i + 1}, imaginary part", "-",
                                   exact[i].imag, mu[i].imag, "absolute", 1e-12, reason))
    inputs = (("stiffness k1 / k2 over each half period", f"{k1:g} / {k2:g} N m/rad"),
              ("inertia, period", "1 kg m^2, 1 s"), ("samples", str(n)))
    return Outcome("Meissner-type equation: monodromy = product of closed-form maps "
                   "(Nayfeh and Mook 1979, sec. 5.2)", inputs, tuple(quantities))


MATHIEU = {"a2": 1.0, "eps": 0.2, "samples": 4096, "segments": (32, 64, 128, 256),
           "reference_segments": 4096}
"""x'' + w0^2 (1 + eps cos 2 pi t) x = 0, period 1 s, (2 w0 / 2 pi)^2 = a2 (the centre of
the principal instability tongue)."""


def case_mathieu_convergence(context: Context) -> Outcome:
    """The largest Floquet multiplier of the Mathieu equation by the segment-mean
    propagator: its error falls as h^2."""
    from pipeline.dynamics.assembly import Assembly
    from pipeline.dynamics.bodies import Body
    from pipeline.dynamics.couplings import GearMesh
    from pipeline.dynamics.integrate import floquet_multipliers
    from pipeline.signals import PeriodicSignal

    m = MATHIEU
    w0 = math.pi * math.sqrt(m["a2"])
    tau = np.arange(m["samples"]) / m["samples"]
    sig = PeriodicSignal(w0**2 * (1 + m["eps"] * np.cos(2 * np.pi * tau)))
    body = Body("b", inertia=1.0, dofs=("theta",))
    system = Assembly([body], [GearMesh("k", {("b", "theta"): 1.0}, sig)],
                      period=1.0).assemble()
    ref = float(np.abs(floquet_multipliers(system, segments=m["reference_segments"])).max())
    segs = np.array(m["segments"])
    vals = [float(np.abs(floquet_multipliers(system, segments=int(s))).max()) for s in segs]
    errs = np.abs(np.array(vals) - ref)
    h = 1.0 / segs
    rate = float(np.polyfit(np.log(h), np.log(errs), 1)[0])
    why = ("the segment-mean propagator is second-order accurate in the segment length "
           "(midpoint rule of the stiffness); 0.15 for the fit against a 4096-segment "
           "reference")
    conv = Convergence("segment length h [s]", tuple(h), "largest |Floquet multiplier| [-]",
                       tuple(vals), tuple(errs), "|mu_h - mu_4096| [-]", rate, 2.0, why)
    q = (Quantity("fitted convergence rate", "-", 2.0, rate, "absolute", 0.15, why),
         Quantity("largest multiplier > 1 (inside the tongue: unstable)", "-", 1.0, ref,
                  "lower_bound", 0.0, "a2 = 1 lies inside the principal tongue "
                  "1 +- eps / 2 (Nayfeh and Mook 1979)"))
    plot = Plot("Mathieu equation: error of the largest Floquet multiplier",
                "segment length h [s]", "|mu_h - mu_4096| [-]",
                (Series("segment-mean propagator", h, errs),
                 Series("h^2", h, errs[0] * (h / h[0]) ** 2, "--")), loglog=True)
    inputs = (("equation", "x'' + w0^2 (1 + eps cos 2 pi t) x = 0, period 1 s"),
              ("a2 = (2 w0 / 2 pi)^2, eps", f"{m['a2']:g}, {m['eps']:g}"),
              ("segments", ", ".join(str(s) for s in segs) + f" (reference "
                                                             f"{m['reference_segments']})"))
    return Outcome("Mathieu equation, principal tongue (Nayfeh and Mook 1979, sec. 5.2); "
                   "convergence of the propagator", inputs, q, conv, (plot,))
