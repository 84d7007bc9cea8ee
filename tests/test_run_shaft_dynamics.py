"""The shafts in the pair's dynamics: the torsion between the gears and the motor and the
driven machine, and the modes and sweep beside the same pair on rigid supports."""

from __future__ import annotations

import dataclasses
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


def without_shafts(text: str) -> str:
    """A gearbox file without its shaft tables ([<gear>.shaft] and its [[...]] rows) and the
    keys that need them (the motor and the machine)."""
    out, skipping = [], False
    for line in text.splitlines():
        if line.lstrip().startswith("["):
            skipping = ".shaft" in line.split("#")[0]
        if not skipping and not line.startswith(("drive_inertia", "load_inertia")):
            out.append(line)
    return "\n".join(out) + "\n"


SWEEP = "[dynamics.sweep]\nf_min_Hz = 400.0\nf_max_Hz = 8000.0\npoints_coarse = 60\n"


@pytest.mark.filterwarnings("ignore::pipeline.validation.PhysicsWarning")
def test_run_shows_the_dynamics_with_and_without_the_shafts(tmp_path):
    """gearpipe run of the straddle-mounted example: summary.json and the report carry the
    natural frequencies and the sweep's largest dynamic factor with the shafts and without
    them; "without" is the same file without its shaft tables run on its own (natural
    frequencies and the sweep's largest dynamic factor to 1e-9 over the same sweep). The
    lowest elastic mode with the shafts is the motor and the machine turning against the
    gears through the shafts' torsion, far below every mode of the pair without them."""
    from pipeline.cli import main as cli

    text = EXAMPLE.read_text() + SWEEP
    path = tmp_path / "box.toml"
    path.write_text(text)
    out = tmp_path / "run"
    assert cli(["run", str(path), "--out", str(out), "--cache-dir", str(tmp_path / "c")]) == 0
    dyn = json.loads((out / "summary.json").read_text())["dynamics"]
    alone = run_pipeline(gearbox_from_text(without_shafts(text)),
                         RunOptions(show_progress=False, cache=Cache(tmp_path / "c")))
    ref = alone.dynamics.summary()
    without = dyn["without_shafts"]
    assert without["natural_frequencies_Hz"] == pytest.approx(ref["natural_frequencies_Hz"],
                                                              rel=1e-9)
    assert without["max_dynamic_factor"]["mesh"] == pytest.approx(
        ref["sweep"]["max_dynamic_factor"]["mesh"], rel=1e-9)
    assert dyn["natural_frequencies_Hz"][0] < 0.3 * without["natural_frequencies_Hz"][0]
    report = json.loads((out / "report.json").read_text())["sections"]
    rows = report["shaft_dynamics"]["quantities"]
    assert rows["mode_1"]["values"]["with the shafts"] == pytest.approx(
        dyn["natural_frequencies_Hz"][0])
    assert rows["max_dynamic_factor_mesh"]["values"]["without the shafts"] == pytest.approx(
        without["max_dynamic_factor"]["mesh"])
    assert (out / "report_shaft_dynamics.png").is_file()


PLANETARY = Path(__file__).parents[1] / "workflows" / "configs" / "shaft_planetary.toml"


@pytest.mark.filterwarnings("ignore::pipeline.validation.PhysicsWarning")
def test_the_sun_shaft_ties_the_motor_to_the_sun(tmp_path):
    """A planetary set with its sun on a shaft and [dynamics] drive_inertia_kgm2: the motor
    is tied to the sun by the shaft's torsion, G J / L of the 112.5 mm sun body between its
    seat's centre (120 mm) and the coupling (0 mm) (1e-9); a shaft far stiffer than the
    rest makes the motor part of the sun (the frequencies of the model with the sun's
    inertia plus the motor's, 1e-6); the run compares with the same file without shafts
    (natural frequencies to 1e-9); a drive inertia without [sun.shaft] is refused."""
    from pipeline.dynamics.models.planetary import PlanetaryModel
    from pipeline.progress import Steps
    from pipeline.run.chain import mesh_stages
    from pipeline.run.dynamics import dynamic_model

    dyn = '[dynamics]\nexcitation = "analytical"\ndrive_inertia_kgm2 = 0.02\n' + SWEEP
    text = PLANETARY.read_text() + dyn
    box = gearbox_from_text(text)
    meshes = mesh_stages(box, RunOptions(show_progress=False, cache=Cache(tmp_path)),
                         Steps("", enabled=False), contact=False)
    model, _ = dynamic_model(box, meshes)
    mat = box.shafts["sun"][1].material
    assert model.kt_drive == pytest.approx(mat.shear_modulus * _polar(0.1125) / 0.120,
                                           rel=1e-9)
    assert "drive" in [b.name for b in model.assembly().bodies]
    # the motor on a shaft of 1e12 N m/rad: its own mode at 2.6e6 Hz, the others moved by
    # about (f / 2.6e6 Hz)^2
    stiff = dataclasses.replace(model, kt_drive=1e12)
    joined = dataclasses.replace(model, inertia_drive=None, kt_drive=None,
                                 inertia_sun=model.inertia_sun + 0.02)
    f_stiff = np.sort(analyse_modes(stiff).frequencies)
    f_joined = np.sort(analyse_modes(joined).frequencies)
    assert isinstance(stiff, PlanetaryModel)
    assert f_stiff.size == f_joined.size + 1
    j_s = model.inertia_sun  # the motor against the sun: two inertias on the stiff shaft
    assert f_stiff[-1] == pytest.approx(
        math.sqrt(1e12 * (0.02 + j_s) / (0.02 * j_s)) / (2 * math.pi), rel=1e-4)
    assert f_stiff[:-1] == pytest.approx(f_joined, rel=1e-5, abs=1e-6)
    r = run_pipeline(box, RunOptions(show_progress=False, cache=Cache(tmp_path)))
    alone = run_pipeline(gearbox_from_text(without_shafts(text)),
                         RunOptions(show_progress=False, cache=Cache(tmp_path)))
    assert r.dynamics.summary()["without_shafts"]["natural_frequencies_Hz"] == pytest.approx(
        alone.dynamics.summary()["natural_frequencies_Hz"], rel=1e-9)
    with pytest.raises(InputError, match=r"dynamics.drive_inertia_kgm2 needs \[sun.shaft\]"):
        gearbox_from_text(without_shafts(PLANETARY.read_text()) + dyn)


def test_a_lumped_pair_takes_the_motor_with_its_shaft():
    """In a [lumped_model] spur pair the motor's inertia and its shaft's torsional stiffness
    are given together or not at all (one line naming both)."""
    k = PeriodicSignal(np.full(8, 4.0e8))
    with pytest.raises(InputError, match="inertia_drive and kt_drive go together"):
        SpurPairModel(k, inertia_drive=0.05)
    model = SpurPairModel(k, inertia_drive=0.05, kt_drive=1.0e5, torsional_only=True)
    assert [b.name for b in model.assembly().bodies] == ["pinion", "gear", "drive"]
