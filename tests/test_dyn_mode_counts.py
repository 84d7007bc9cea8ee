"""Mode counts and pair mode kinds (pipeline.dynamics.modal.classify_by_energy).

* One count everywhere: ``gearpipe run`` on a spur pair writes the same number of modes,
  the same rigid-body count and the same elastic frequencies up to the stated cut in its
  log, ``modes.csv``, ``summary.json`` and the report (json and csv).
* Exact: a torsional pair (two inertias joined by the mesh spring k along the line of
  action) has one rigid rotation and one elastic mode, the mesh mode at
  ``sqrt(k (r_1^2 / I_1 + r_2^2 / I_2)) / 2 pi`` (e.g. Kahraman and Singh 1991's
  definitional model; the 2-inertia limit of the assembly-error paper's 6-DOF pair),
  purely rotational.
* Exact: the lateral-torsional pair of equal gears (mass m, inertia I, base radius r,
  bearings k_b, mesh k along x) splits into a triple bearing mode sqrt(k_b / m) (no
  rotation), a rigid rotation and two mesh modes of the antisymmetric motion
  u = x_p = -x_g, phi = theta_p = -theta_g (each theta in its own sense):
  ``[k_b + 2k, 2kr; 2kr, 2kr^2] - w^2 diag(m, I)`` singular.
"""

from __future__ import annotations

import csv
import json
import math
import re
import sys
from pathlib import Path

import numpy as np

from pipeline.dynamics.analysis import analyse_modes
from pipeline.dynamics.models.spur_pair import SpurPairModel
from pipeline.signals import PeriodicSignal

sys.path.insert(0, str(Path(__file__).parent))
from gearsets import SMALL  # noqa: E402

K_MESH = 3.9e8  # N/m


def test_torsional_pair_has_one_rotational_mesh_mode():
    m = SpurPairModel(PeriodicSignal(np.full(8, K_MESH)), base_radius_pinion=0.03,
                      base_radius_gear=0.07, inertia_pinion=1.2e-3, inertia_gear=2.9e-2,
                      torsional_only=True)
    res = analyse_modes(m)
    f = math.sqrt(K_MESH * (0.03**2 / 1.2e-3 + 0.07**2 / 2.9e-2)) / (2 * math.pi)
    assert res.frequencies.size == 2 and res.frequencies[0] == 0.0
    assert abs(res.frequencies[1] - f) <= 1e-9 * f  # 2330.3 Hz
    assert res.kinds == ("rigid", "rotational")
    assert res.energy_shares()["rotation"][1] == 1.0


def test_lateral_torsional_equal_pair_kinds_follow_the_exact_shares():
    mass, inertia, r, kb = 2.52, 7.4e-3, 0.0705, 1.0e8
    m = SpurPairModel(PeriodicSignal(np.full(8, K_MESH)), base_radius_pinion=r,
                      base_radius_gear=r, mass_pinion=mass, mass_gear=mass,
                      inertia_pinion=inertia, inertia_gear=inertia, bearing_stiffness=kb)
    res = analyse_modes(m)
    Kr = np.array([[kb + 2 * K_MESH, 2 * K_MESH * r], [2 * K_MESH * r, 2 * K_MESH * r**2]])
    s = np.diag(np.array([mass, inertia]) ** -0.5)
    w2, vec = np.linalg.eigh(s @ Kr @ s)
    f_mesh = np.sqrt(w2) / (2 * np.pi)
    f_bearing = math.sqrt(kb / mass) / (2 * math.pi)
    rot_share = vec[1] ** 2  # energy-normalised: (sqrt(I) phi)^2 over the total
    f = res.frequencies
    assert f[0] == 0.0 and res.kinds[0] == "rigid"
    np.testing.assert_allclose(f[1:], np.sort(np.r_[f_mesh, [f_bearing] * 3]), rtol=1e-9)
    shares = res.energy_shares()["rotation"]
    for fm, share in zip(f_mesh, rot_share, strict=True):
        k = int(np.argmin(abs(f - fm)))
        assert abs(shares[k] - share) < 1e-9
        assert res.kinds[k] == ("rotational" if share >= 0.5 else "translational")
    bearing = np.abs(f - f_bearing) <= 1e-9 * f_bearing
    assert bearing.sum() == 3 and np.all(shares[bearing] < 1e-12)
    assert all(res.kinds[k] == "translational" for k in np.flatnonzero(bearing))
    assert res.kinds.count("rotational") == 1  # measured rotation shares 0.40 and 0.60


def test_counts_and_frequencies_agree_in_log_csv_summary_and_report(tmp_path, capsys):
    from pipeline.cli import main

    cfg = tmp_path / "small.toml"
    cfg.write_text(SMALL, encoding="utf-8")
    out = tmp_path / "out"
    assert main(["run", str(cfg), "--out", str(out), "--cache-dir", str(tmp_path / "c")]) == 0
    log = capsys.readouterr().err
    with open(out / "modes.csv", newline="", encoding="utf-8") as fh:
        rows = list(csv.reader(fh))[1:]
    f_csv = np.array([float(r[0]) for r in rows])
    kinds_csv = [int(r[2]) for r in rows]
    dyn = json.loads((out / "summary.json").read_text())["dynamics"]
    rep = json.loads((out / "report.json").read_text())["sections"]["dynamics"]["quantities"]
    n_rigid = kinds_csv.count(1)
    assert n_rigid == int(np.count_nonzero(f_csv == 0.0)) == dyn["rigid_body_modes"] == \
        rep["rigid_body_modes"]["value"] == 1
    assert dyn["independent_dofs"] == f_csv.size == 6 and dyn["coordinates"] == 6
    line = re.search(r"modes: .*", log).group(0)
    assert line.endswith("6 coordinates, 6 independent DOF (1 rigid-body mode)")
    assert rep["model_size"]["value"].startswith("6 coordinates, 6 independent DOF")
    cut = dyn["natural_frequency_cut_Hz"]
    assert rep["natural_frequency_cut"]["value"] == cut
    listed_csv = f_csv[(f_csv > 0.0) & (f_csv <= cut)]
    listed = np.array(dyn["natural_frequencies_Hz"])
    np.testing.assert_allclose(listed, listed_csv, rtol=1e-8)  # csv: 9 digits
    rep_f = []
    for key, q in rep.items():
        if key.startswith("natural_frequency_mode_"):
            modes = q["label"].split("(repeated)")[0] if "repeated" in q["label"] else \
                q["label"].split(",")[0]
            rep_f += [q["value"]] * len(re.findall(r"\d+", modes))
    np.testing.assert_allclose(rep_f, listed, rtol=1e-12)
    assert listed.size + dyn["elastic_modes_above_cut"] + n_rigid == f_csv.size
    assert rep["elastic_modes_above_cut"]["value"] == dyn["elastic_modes_above_cut"]
    assert [d["kind"] for d in dyn["modes_listed"]] == \
        ["translational", "translational", "translational", "translational", "rotational"]


def test_pair_layout_puts_both_base_circles_on_the_line_of_action():
    """Default pair (z 50/50, m 3 mm, 20 deg): the base circles touch the line of action
    (the x axis direction) at T1 and T2, T1 T2 = a_w sin(alpha_w) = 150 sin 20 deg mm, and
    the centres are a_w = 150 mm apart."""
    from pipeline.dynamics.layout import model_layout

    a, alpha = 0.150, math.radians(20.0)
    rb = 0.075 * math.cos(alpha)
    m = SpurPairModel(PeriodicSignal(np.full(8, K_MESH)), t1t2=a * math.sin(alpha))
    lay = model_layout(m)
    p, g = lay.place("pinion"), lay.place("gear")
    (x1, y1), (x2, y2) = lay.line_of_action
    assert y1 == y2 == p.centre[1] - rb and x1 == p.centre[0]
    assert abs(g.centre[1] + rb - y2) < 1e-15 and x2 == g.centre[0]
    assert abs(math.dist(p.centre, g.centre) - a) < 1e-12
    assert g.spin == -1 and p.spin == 1
