"""The herringbone groove study and gearpipe run on a herringbone sun with its groove (slow:
groove FE).

The study's coarse run must give the groove geometries of the paper's K_j range and the
directions workflows/herringbone_groove_study.py states (torque leaving at the right half:
the left half loses load and peak unit load as K_j falls, the right gains; the left's mesh
with the groove in series softens by about 11 %); ``gearpipe run`` must drive the sun
meshes of the herringbone model from the contact through the groove.
"""

from __future__ import annotations

import csv
import sys
from pathlib import Path

import numpy as np
import pytest

ROOT = Path(__file__).resolve().parents[1]

pytestmark = pytest.mark.slow


@pytest.fixture(scope="module")
def study(tmp_path_factory):
    sys.path.insert(0, str(ROOT / "workflows"))
    import herringbone_groove_study as w

    out = tmp_path_factory.mktemp("study")
    return w.run(out=out, show_progress=False), out


def test_study_grooves_and_directions(study):
    res, out = study
    kj = [g.equivalent_Kj for _, g in res["grooves"]]
    np.testing.assert_allclose(kj, [5.2e7, 4.9e7, 4.6e7, 4.3e7, 4.0e7], rtol=0.03)
    assert np.all(np.diff(kj) < 0)
    c = res["cases"]
    share = [c[f"K{j}"].load_left.mean() / c[f"K{j}"].load for j in range(1, 6)]
    assert np.all(np.diff(share) < 0) and 0.3 < share[-1] < share[0] < 0.5
    assert c["K5"].left.max_unit_load.max() < c["K1"].left.max_unit_load.max()
    assert c["K5"].right.max_unit_load.max() > c["K1"].right.max_unit_load.max()
    series = [c[f"K{j}"].series_mesh_stiffness("left").max() for j in (1, 5)]
    assert series[1] / series[0] - 1 == pytest.approx(-0.1206, abs=0.01)
    # torque entering at the left swaps the sides (mirror image), up to the FE groove's small
    # twist-stretch coupling (C_tz / sqrt(C_tt C_zz) ~ 2e-6, which changes sign in the mirror)
    np.testing.assert_allclose(c["K1 torque left"].load_right, c["K1"].load_left, rtol=1e-5)
    assert c["K1 slide +1 mm"].load_left.max() == 0.0
    assert 0.05e-3 < res["slide_match"] < 0.12e-3
    rows = list(csv.reader(open(out / "comparison.csv", encoding="utf-8")))
    assert rows[0][:5] == ["figure", "quantity", "unit", "Xu et al. (2020)", "computed"]
    assert len(rows) > 30
    for name in ("fig5_mesh_stiffness.png", "fig9_sweep.png", "fig8_K1_left.png",
                 "fig8_K5_right.vtu", "fig8_K1_slide_p1_mm_right.png", "run.json"):
        assert (out / name).stat().st_size > 0


def test_run_excites_the_sun_meshes_from_the_herringbone_contact(tmp_path):
    from pipeline.cache.folder import Cache
    from pipeline.config import load_gearbox
    from pipeline.run.chain import RunOptions
    from pipeline.run.dynamics import dynamic_model
    from pipeline.run.runner import run_pipeline

    box = load_gearbox(ROOT / "workflows/configs/wind_turbine_herringbone_planetary.toml")
    res = run_pipeline(box, RunOptions(show_progress=False, cache=Cache(tmp_path)))
    hb = res.meshes["sun_planet"].herringbone
    assert hb.groove.equivalent_Kj == pytest.approx(5.98e7, rel=0.01)
    s = res.summary()["meshes"]["sun_planet"]["herringbone_contact"]
    # 40.1 % on the nominal path; the sun's tip corners touching beyond it: 39.6 %
    assert s["left"]["load_share_mean"] == pytest.approx(0.396, abs=0.005)
    model, _ = dynamic_model(box, res.meshes)
    assert isinstance(model.k_sun_mesh, tuple) and model.sun_load_side == "R"
    assert model.phase_lr == 0.0 and np.shape(model.groove) == (12, 12)
    mean = res.dynamics.response.summary()["meshes"]
    # the model's static split follows the contact (its planets also slide axially): 1.5 %
    cb = np.cos(box.planetary.sun.base_helix_angle)
    assert mean["s-p1L"]["mean_force_N"] == pytest.approx(s["left"]["load_mean_N"] / cb,
                                                          rel=0.015)
