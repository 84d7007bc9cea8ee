"""Left/right excitation of the herringbone planetary model from the contact through the groove.

The static limit is the check: the herringbone model of the wind-turbine set of Xu et al.
(2020), excited by the left/right k_h(t), e_h(t) of the herringbone contact and joined by
the same groove matrix, must carry the contact's loads on each half at zero speed when
it holds the same assumptions (planets in phase, planets axially fixed, the sun's axial
support the contact's).
"""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest

from pipeline.config import load_gearbox
from pipeline.contact import analytical_compliance
from pipeline.contact.groove_flank import GrooveFlankCoupling
from pipeline.contact.herringbone import HerringboneOptions, herringbone_mesh_cycle
from pipeline.dynamics.herringbone_excitation import excitation_from_herringbone
from pipeline.dynamics.models.planetary_gears import (
    helical_half,
    herringbone_planetary_model_from_gears,
    mesh_operations,
)
from pipeline.dynamics.quasi_static import quasi_static_response
from pipeline.run.chain import mesh_cases
from pipeline.run.dynamics import mesh_excitation
from pipeline.validation import InputError

CONFIG = "workflows/configs/wind_turbine_herringbone_planetary.toml"
K_AXIAL = 1.0e9  # N/m, the sun's axial support in the contact and the model


def groove_matrix(kt: float, kz: float = 5.6e10) -> np.ndarray:
    """12 x 12 of a groove with torsion kt, axial kz and the FE's other stiffnesses (N/m,
    N m/rad)."""
    K = np.zeros((12, 12))
    for i, k in ((0, 2.7e10), (1, 2.7e10), (2, kz), (3, 6.5e8), (4, 6.5e8), (5, kt)):
        K[np.ix_([i, i + 6], [i, i + 6])] += k * np.array([[1.0, -1.0], [-1.0, 1.0]])
    return K


@pytest.fixture(scope="module")
def setup():
    box = load_gearbox(CONFIG)
    ps = box.planetary
    pair = helical_half(ps.sun_planet)
    op = mesh_operations(ps, box.operation, 1)[0]
    half = dataclasses.replace(op, torque=op.torque / 2)
    src = analytical_compliance(pair, half, box.contact, box.stiffness)
    # axially rigid groove: the model puts half the sun's axial bearing on each half, the
    # contact holds the sun at its torque end (with the FE's axial stretch the splits differ
    # by 8e-4 of the load)
    K12 = groove_matrix(5.98e7 / 0.225, kz=5.6e16)
    cycle = herringbone_mesh_cycle(src, op.torque / pair.pinion.base_radius,
                                   GrooveFlankCoupling.from_matrix(K12), ps.n_planets,
                                   options=HerringboneOptions(axial_support_stiffness=K_AXIAL),
                                   positions=12)
    return box, pair, op, cycle, K12


def test_excitation_reproduces_the_contact_state(setup):
    box, pair, op, cycle, _ = setup
    left, right = excitation_from_herringbone(cycle, pair, op)
    for exc, side in ((left, "left"), (right, "right")):
        half, load = cycle.half(side), cycle.half_load(side)
        k = exc.stiffness.values
        np.testing.assert_allclose(k * (half.transmission_error - exc.transmission_error.values),
                                   load, rtol=1e-12)
        assert exc.load == pytest.approx(load.mean())
        # one mesh period of the sun relative to the carrier
        assert exc.mesh_period == pytest.approx(2 * math.pi / (op.speed * pair.pinion.teeth))
    assert left.load < right.load  # torque leaves at the right: the left half carries less


def test_model_static_limit_carries_the_contact_loads(setup):
    """Zero speed: the model's left/right sun-mesh forces equal the contact's P_h / cos(beta_b)
    at every sample to 1e-6."""
    box, pair, op, cycle, K12 = setup
    ps = box.planetary
    exc = excitation_from_herringbone(cycle, pair, op)
    ring = mesh_excitation(next(s for s in _ring_stages(box)), box.stiffness.friction_model,
                           "analytical")
    opts = dataclasses.replace(box.dynamics, sun_axial_stiffness=K_AXIAL,
                               planet_axial_stiffness=1e14, carrier_axial_stiffness=1e14,
                               ring_axial_stiffness=1e14)
    model = herringbone_planetary_model_from_gears(ps, box.bodies, box.carrier, box.operation,
                                                   opts, exc, ring, groove=K12,
                                                   sun_load_side="R")
    model = dataclasses.replace(model, phase_sun=(0.0,) * 4, phase_ring=(0.0,) * 4)
    system = model.assembly().assemble()
    n = len(cycle)
    resp = quasi_static_response(system, np.arange(n) / n)
    cb = math.cos(pair.pinion.base_helix_angle)
    for name, load in (("s-p1L", cycle.load_left), ("s-p1R", cycle.load_right)):
        f = resp.mesh_force[resp.mesh_names.index(name)]
        np.testing.assert_allclose(f, load / cb, rtol=1e-6)


def _ring_stages(box):
    """The planet-ring mesh's analytical stiffness stage (for its excitation)."""
    from pipeline.progress import Steps
    from pipeline.run.chain import RunOptions, static_stages

    case = mesh_cases(box)[1]
    yield static_stages(box, case, RunOptions(show_progress=False), Steps("", enabled=False),
                        contact=False)


def test_unloaded_half_is_refused(setup):
    box, pair, op, _, K12 = setup
    src = analytical_compliance(pair, op, box.contact, box.stiffness)
    lifted = herringbone_mesh_cycle(src, op.torque / pair.pinion.base_radius,
                                    GrooveFlankCoupling.from_matrix(K12), 4,
                                    options=HerringboneOptions(axial_slide=1e-3), positions=6)
    with pytest.raises(InputError, match="the left half carries 0 N"):
        excitation_from_herringbone(lifted, pair, op)
    with pytest.raises(InputError, match="needs >= 4"):
        excitation_from_herringbone(
            herringbone_mesh_cycle(src, 1e5, GrooveFlankCoupling.rigid(), 4, positions=3),
            pair, op)
