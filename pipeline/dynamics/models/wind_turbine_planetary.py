"""The herringbone planetary case of Xu et al. (2020) as model inputs (1.5 MW wind-turbine stage).

Sun 21, planet 37, ring 95 teeth, m_n 15 mm, alpha_n 25 deg, beta 8 deg, 4
planets; face widths 185/175/185 mm with relief grooves 40/50/40 mm; groove
torsional stiffness K_j from 5.2e7 to 4.0e7 N m^2 (Xu et al. 2020, sec. 3.1). The
paper gives no masses or support stiffnesses: masses and inertias are those of steel
discs of the gear dimensions, supports and mesh stiffness are typical values for
this size (stated below); they set where the peaks fall, not the trends.
Planet angles and meshing phases (eqs. 10a-c, 11) come from
:class:`pipeline.geometry.planetary.PlanetarySet`. Damping: mesh damping ratio
0.05 plus a constant modal damping of 0.02 (Xu et al. 2020, sec. 2.3 uses a constant
modal damping without giving its value).

Groove stiffness and mesh stiffness (Xu et al. 2020, eqs. 1, 11, 14-15): K_j sets the
twist of the sun halves, hence the right meshes' phase lambda_LR; ring-planet meshes
keep their stiffness (eq. 15). As a comparison with the paper,
``groove_mesh=XU2020_GROOVE_MESH`` also applies its published left/right sun-planet
mesh stiffness change (+9.79 % / -11.23 % from K_1 to K_5,
:mod:`pipeline.dynamics.models.groove_mesh`); by default both sides are equal. The
computed effect of the groove (its FE stiffness and the contact of both halves through
it) is :mod:`pipeline.contact.herringbone` and :mod:`pipeline.dynamics.herringbone_excitation`.
"""

from __future__ import annotations

import math

from pipeline.dynamics.excitation import contact_line_stiffness
from pipeline.dynamics.models.groove_mesh import (
    GrooveMeshRelation,
    side_factors,
)
from pipeline.dynamics.models.herringbone_planetary import HalfSignal, HerringbonePlanetaryModel
from pipeline.fem.groove.result import GrooveStiffness
from pipeline.geometry.gear import GearSpec
from pipeline.geometry.planetary import PlanetarySet, dec
from pipeline.signals import PeriodicSignal
from pipeline.validation import check_range

Z_S, Z_P, Z_R = 21, 37, 95
M_N = 15e-3
ALPHA_N = math.radians(25.0)
BETA = math.radians(8.0)
HALF_WIDTH = 0.0625  # m, toothed width of one half in mesh (planet (175 - 50) / 2 mm)
L_LR = 0.0725 + 0.040  # m, distance between the half centres of the sun (72.5 + 40 mm)
# Torsional length in eq. 1: Xu et al. (2020) measure the twist from the torsion centre O_T,
# l_LT = 657.5 mm from O_L; we use it as the beam length of the groove torsion.
L_TORSION = 0.6575
K_J = (5.2e7, 4.9e7, 4.6e7, 4.3e7, 4.0e7)  # N m^2, Xu et al. (2020) K_1..K_5
RHO = 7850.0
C_GAMMA = 2.0e10  # N/m per m of face width (ISO 6336-1 mesh stiffness order, 20 N/(mm um))
POWER = 1.5e6  # W
RATED_CARRIER_RPM = 18.0  # rotor speed of a 1.5 MW turbine (sets the torque, not the sweep)


def _disc(r_out: float, r_in: float, width: float) -> tuple[float, float]:
    m = RHO * math.pi * (r_out**2 - r_in**2) * width
    return m, 0.5 * m * (r_out**2 + r_in**2)


def wind_turbine_planetary_set(n_planets: int = 4) -> PlanetarySet:
    """The gears of Xu et al. (2020) (Table 1) as a :class:`PlanetarySet` (phases of eq. 10)."""
    common = dict(module=M_N, pressure_angle=ALPHA_N, helix_angle=BETA, herringbone=True)
    sun = GearSpec(Z_S, face_width=0.370, hand="right", groove_width=0.040, name="sun", **common)
    planet = GearSpec(
        Z_P, face_width=0.350, hand="left", groove_width=0.050, name="planet", **common
    )
    ring = GearSpec(
        Z_R,
        face_width=0.370,
        hand="left",
        groove_width=0.040,
        internal=True,
        bore_radius=Z_R * M_N / math.cos(BETA) / 2 + 0.08,
        name="ring",
        **common,
    )
    return PlanetarySet(sun, planet, ring, n_planets)


def wind_turbine_herringbone_model(
    groove_Kj: float = K_J[0],
    axial_slide: float = 0.0,
    mesh_frequency: float = 1440.0,
    damping_ratio: float = 0.05,
    half_coupling: tuple | None = None,
    samples: int = 180,
    stagger: float = 0.0,
    groove: GrooveStiffness | None = None,
    modal_damping_ratio: float = 0.02,
    groove_mesh: GrooveMeshRelation | None = None,
) -> HerringbonePlanetaryModel:
    """The herringbone planetary model of Xu et al. (2020) at one mesh frequency.

    Parameters
    ----------
    groove_Kj : K_j in N m^2; the groove torsional stiffness is K_j / l (Xu et al. 2020, eq. 1,
        l = L_TORSION). Ignored when ``groove`` is given.
    axial_slide : sun axial slide z_a in m (+ to the output/right side).
    mesh_frequency : Hz; carrier speed = 2 pi f / z_r (ring fixed).
    damping_ratio : mesh damping ratio (-).
    half_coupling : (kx, ky, kz, ktheta) joining planet/ring/carrier halves; ``None`` ties them.
    samples : samples per mesh period of the stiffness.
    stagger : left/right tooth stagger of the herringbone in mesh periods (Xu et al. 2020 give
        none); added to the twist phase lambda_LR of the right sun meshes.
    groove : FE groove stiffness (:class:`GrooveStiffness`): its 12 x 12 coupling
        matrix joins the sun halves and its ``phase_shift`` gives lambda_LR; ``None`` uses
        the beam value ``groove_Kj / L_TORSION`` with stiff translations.
    modal_damping_ratio : constant modal damping (-) of Xu et al. (2020) (sec. 2.3).
    groove_mesh : a comparison with the paper: its published left/right sun-planet mesh
        stiffness change against K_j as input data (Xu et al. 2020, eq. 14, Fig. 5;
        ``XU2020_GROOVE_MESH`` and ``side_factors`` of
        :mod:`pipeline.dynamics.models.groove_mesh`),
        evaluated at ``groove_Kj`` (or ``groove.equivalent_Kj``), which must then lie in
        [K_5, K_1]; ``None`` (default): both sides keep the nominal stiffness at every K_j.
        The computed left/right excitation through the groove is
        :mod:`pipeline.dynamics.herringbone_excitation` (the herringbone contact).
    """
    ps = wind_turbine_planetary_set(4)
    mt = M_N / math.cos(BETA)
    at = math.atan(math.tan(ALPHA_N) / math.cos(BETA))
    bb = math.atan(math.tan(BETA) * math.cos(at))
    rs, rp, rr = Z_S * mt / 2, Z_P * mt / 2, Z_R * mt / 2
    ms, Is = _disc(rs, 0.06, 0.185)
    mp, Ip = _disc(rp, 0.10, 0.175)
    mr, Ir = _disc(rr + 0.08, rr, 0.185)
    mc, Ic = _disc(rs + rp + 0.15, 0.20, 0.30)
    eps_a = 1.55
    eps_b = HALF_WIDTH * math.sin(BETA) / (math.pi * M_N)
    k = contact_line_stiffness(C_GAMMA * HALF_WIDTH / math.cos(bb), eps_a, eps_b, samples)
    check_range("mesh_frequency", mesh_frequency, 1e-3, 1e6, unit="Hz")
    omega_c = 2 * math.pi * mesh_frequency / Z_R
    t_c = POWER / (RATED_CARRIER_RPM * 2 * math.pi / 60)
    t_s = t_c / (1 + Z_R / Z_S)
    if groove is None:
        k_groove: float | GrooveStiffness = groove_Kj / L_TORSION
        lam_lr = ps.left_right_phase(t_s / k_groove)
        translational = (5e9, 5e9, 5e9)
    else:
        k_groove = groove
        lam_lr = float(dec(groove.phase_shift(t_s).lambda_LR))
        translational = None
    lam_lr = float(dec(stagger + lam_lr))
    k_sun: HalfSignal = k
    if groove_mesh is not None:
        kj = groove_Kj if groove is None else groove.equivalent_Kj
        sf = side_factors(kj, groove_mesh)
        k_sun = (
            PeriodicSignal(k.values * sf.left, k.period),
            PeriodicSignal(k.values * sf.right, k.period),
        )
    return HerringbonePlanetaryModel(
        n_planets=4,
        mass_sun=ms,
        mass_ring=mr,
        mass_carrier=mc,
        mass_planet=mp,
        inertia_sun=Is,
        inertia_ring=Ir,
        inertia_carrier=Ic,
        inertia_planet=Ip,
        base_radius_sun=rs * math.cos(at),
        base_radius_ring=rr * math.cos(at),
        base_radius_planet=rp * math.cos(at),
        carrier_radius=ps.carrier_radius,
        pressure_angle_sun=at,
        pressure_angle_ring=at,
        base_helix_angle=bb,
        k_sun_mesh=k_sun,
        k_ring_mesh=k,
        k_sun=2e9,
        k_ring=5e9,
        k_carrier=5e9,
        kz_sun=1e9,
        kz_ring=5e9,
        kz_carrier=5e9,
        k_planet=3e9,
        kz_planet=2e9,
        kt_sun=0.0,
        kt_ring=5e10,
        kt_carrier=0.0,
        groove=k_groove,
        groove_translational=translational,
        half_coupling=half_coupling,
        axial_slide=axial_slide,
        engaged_width=HALF_WIDTH,
        sun_load_side="R",
        planet_angles=tuple(ps.angles),
        phase_sun=tuple(ps.sun_phases),
        phase_ring=tuple(dec(ps.ring_phases + ps.ring_sun_phase)),
        phase_lr=lam_lr,
        damping_ratio=damping_ratio,
        modal_damping_ratio=modal_damping_ratio,
        sun_torque=t_s,
        carrier_speed=omega_c,
        mesh_period=1.0 / mesh_frequency,
    )
