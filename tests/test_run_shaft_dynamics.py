"""The shafts in the pair's dynamics: the torsion between the gears and the motor and the
driven machine, and the modes and sweep beside the same pair on rigid supports."""

from __future__ import annotations

import json
import math
from pathlib import Path

import numpy as np
import pytest
import scipy.linalg

from pipeline.cache.folder import Cache
from pipeline.config.gearbox import gearbox_from_text, load_gearbox
from pipeline.dynamics.analysis import analyse_modes
from pipeline.dynamics.models.spur_pair import SpurPairModel, spur_pair_model
from pipeline.dynamics.options import PairDynamicsOptions
from pipeline.run.chain import RunOptions
from pipeline.run.runner import run_pipeline
from pipeline.run.shafts import support_stiffness
from pipeline.signals import PeriodicSignal
from pipeline.validation import InputError
from workflows.default_case import DEMO_PAIR

EXAMPLE = Path(__file__).parents[1] / "workflows" / "configs" / "shaft_straddle_pinion.toml"
FAST = '[contact]\ncompliance = "analytical"\npositions = 24\nslices = 20\n'


def _polar(d: float) -> float:
    return math.pi * d**4 / 32.0


def test_torsional_stiffness_of_the_example_shafts_is_g_j_over_l():
    """Saint-Venant torsion of round shafts, k = G J / L per segment in series (exact in the
    beam element): the pinion's integral seat centre (80 mm) to its coupling (0 mm) through
    70 mm of 35 mm journal and 10 mm of the 142.5 mm body; the gear's rigid hub (70-90 mm)
    to its coupling at 250 mm through 160 mm of 50 mm shaft."""
    box = load_gearbox(EXAMPLE)
    _, (k_p, k_g) = support_stiffness(box)
    mat = box.shafts["pinion"][1].material
    g = mat.youngs_modulus / (2.0 * (1.0 + mat.poisson_ratio))
    want_p = 1.0 / (0.070 / (g * _polar(0.035)) + 0.010 / (g * _polar(0.1425)))
    want_g = g * _polar(0.050) / 0.160
    assert k_p == pytest.approx(want_p, rel=1e-9)
    assert k_g == pytest.approx(want_g, rel=1e-9)


def _chain_frequencies(j, k_d, k_l, k_m, r_p, r_g):
    """Natural frequencies (Hz) of the torsional chain motor - pinion - mesh - gear - load,
    assembled here by hand: energy k_d (t_d - t_p)^2 + k_m (r_p t_p - r_g t_g)^2 + k_l
    (t_g - t_l)^2 over 2 (each gear's angle in its own sense of rotation)."""
    K = np.zeros((4, 4))
    for (a, b), k in (((0, 1), k_d), ((2, 3), k_l)):
        K[np.ix_([a, b], [a, b])] += k * np.array([[1.0, -1.0], [-1.0, 1.0]])
    v = np.array([0.0, r_p, -r_g, 0.0])
    K += k_m * np.outer(v, v)
    w2 = scipy.linalg.eigh(K, np.diag(j), eigvals_only=True)
    return np.sqrt(np.clip(w2, 0.0, None)) / (2 * math.pi)


def test_drive_and_load_inertias_make_the_torsional_chain():
    """The torsional pair model with a motor and a driven machine behind the shafts has the
    natural frequencies of the hand-assembled four-inertia chain (to 1e-9); with a mesh
    far stiffer than the shaft, its first frequency tends to the two-inertia one,
    sqrt(k_t (J_1 + J_2) / (J_1 J_2)) / 2 pi, J_2 the gears' inertia seen at the pinion."""
    box = load_gearbox(EXAMPLE)
    pair = box.pair
    lateral, torsion = support_stiffness(box)
    k_m = 4.0e8
    opts = PairDynamicsOptions(dofs="torsional", drive_inertia=0.05, load_inertia=0.5,
                               mesh_stiffness=PeriodicSignal(np.full(8, k_m)))
    model = spur_pair_model(pair, (box.bodies["pinion"], box.bodies["gear"]), box.operation,
                            opts, None, lateral, torsion)
    got = np.sort(analyse_modes(model).frequencies)
    j = np.array([0.05, model.inertia_pinion, model.inertia_gear, 0.5])
    r_p, r_g = pair.pinion.base_radius, pair.gear.base_radius
    want = _chain_frequencies(j, torsion[0], torsion[1], k_m, r_p, r_g)
    assert got[1:] == pytest.approx(want[1:], rel=1e-9)
    # the mesh far stiffer than the pinion's shaft, no driven machine: two inertias
    stiff = PairDynamicsOptions(dofs="torsional", drive_inertia=0.05,
                                mesh_stiffness=PeriodicSignal(np.full(8, 1e16)))
    two = spur_pair_model(pair, (box.bodies["pinion"], box.bodies["gear"]), box.operation,
                          stiff, None, lateral, (torsion[0], None))
    f_two = np.sort(analyse_modes(two).frequencies)
    j2 = model.inertia_pinion + model.inertia_gear * (r_p / r_g) ** 2
    f2 = math.sqrt(torsion[0] * (0.05 + j2) / (0.05 * j2)) / (2 * math.pi)
    assert f_two[1] == pytest.approx(f2, rel=1e-6)


def test_drive_inertia_needs_its_shaft():
    """A motor's inertia on a pinion without a shaft has no torsion to sit behind: one line
    naming the key."""
    with pytest.raises(InputError, match=r"dynamics.drive_inertia_kgm2 needs \[pinion.shaft\]"):
        gearbox_from_text(DEMO_PAIR + FAST + "[dynamics]\ndrive_inertia_kgm2 = 0.05\n")
    with pytest.raises(InputError, match=r"dynamics.drive_inertia.*0 kg m\^2"):
        PairDynamicsOptions(drive_inertia=0.0)


@pytest.mark.filterwarnings("ignore::pipeline.validation.PhysicsWarning")
def test_run_shows_the_dynamics_with_and_without_the_shafts(tmp_path):
    """gearpipe run of the straddle-mounted example: summary.json and the report carry the
    natural frequencies and the sweep's largest dynamic factor with the shafts and on rigid
    supports; the lowest elastic mode with the shafts is the motor and the machine turning
    against the gears through the shafts' torsion (below the rigid pair's mesh mode, the
    only elastic mode of the rigidly supported pair, torsional)."""
    from pipeline.cli import main as cli

    out = tmp_path / "run"
    assert cli(["run", str(EXAMPLE), "--out", str(out), "--cache-dir", str(tmp_path / "c")]) == 0
    dyn = json.loads((out / "summary.json").read_text())["dynamics"]
    rigid = dyn["without_shafts"]
    assert len(rigid["natural_frequencies_Hz"]) == 1
    box = load_gearbox(EXAMPLE)
    pair = box.pair
    # the rigid pair's mesh mode: sqrt(k_mean / m_e), m_e = 1 / (r_p^2/J_p + r_g^2/J_g)
    r = run_pipeline(box, RunOptions(show_progress=False, cache=Cache(tmp_path / "c")))
    k_mean = float(np.mean(r.meshes["mesh"].shafts.rigid.mesh_stiffness))
    jp, jg = box.bodies["pinion"].inertia_, box.bodies["gear"].inertia_
    m_e = 1.0 / (pair.pinion.base_radius**2 / jp + pair.gear.base_radius**2 / jg)
    assert rigid["natural_frequencies_Hz"][0] == pytest.approx(
        math.sqrt(k_mean / m_e) / (2 * math.pi), rel=0.02)
    assert dyn["natural_frequencies_Hz"][0] < 0.2 * rigid["natural_frequencies_Hz"][0]
    report = json.loads((out / "report.json").read_text())["sections"]
    rows = report["shaft_dynamics"]["quantities"]
    assert rows["mode_1"]["values"]["with the shafts"] == pytest.approx(
        dyn["natural_frequencies_Hz"][0])
    assert rows["max_dynamic_factor_mesh"]["values"]["rigid supports"] == pytest.approx(
        rigid["max_dynamic_factor"]["mesh"])
    assert (out / "report_shaft_dynamics.png").is_file()


def test_a_lumped_pair_takes_the_motor_with_its_shaft():
    """In a [lumped_model] spur pair the motor's inertia and its shaft's torsional stiffness
    are given together or not at all (one line naming both)."""
    k = PeriodicSignal(np.full(8, 4.0e8))
    with pytest.raises(InputError, match="inertia_drive and kt_drive go together"):
        SpurPairModel(k, inertia_drive=0.05)
    model = SpurPairModel(k, inertia_drive=0.05, kt_drive=1.0e5, torsional_only=True)
    assert [b.name for b in model.assembly().bodies] == ["pinion", "gear", "drive"]
