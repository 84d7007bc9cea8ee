"""Design studies (gearpipe study): study file checks, Dask vs serial, resume after kill -9,
and the tip-relief optimum of the assembly-error paper's pair against the classic estimate."""

import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
import pyarrow.parquet as pq
import pytest

from pipeline.study.execute import StudyOptions, run_study
from pipeline.study.spec import study_from_file
from pipeline.validation import InputError

ROOT = Path(__file__).resolve().parents[1]
BASE = ROOT / "workflows" / "configs" / "spur_pair_assembly_errors.toml"

STUDY = f"""
name = "relief"
base = "{BASE}"
[set]
"contact.compliance" = "fe2d"
"contact.positions" = 30
"contact.render" = false
"contact.tip_relief_length_pinion_mm" = 6.2
"contact.tip_relief_length_gear_mm" = 6.2
[[axes]]
keys = ["contact.tip_relief_pinion_um", "contact.tip_relief_gear_um"]
range = [0.0, 24.0]
points = {{points}}
[kpis]
names = ["te_peak_to_peak_um", "mesh_stiffness_mean_N_per_um", "te_order1_um"]
[execution]
batch_points = 2
"""


def write_study(tmp_path: Path, points: int = 13, extra: str = "") -> Path:
    p = tmp_path / "relief.toml"
    p.write_text(STUDY.format(points=points) + extra)
    return p


def quiet(**kw) -> StudyOptions:
    return StudyOptions(show_progress=False, **kw)


@pytest.fixture(scope="module")
def dask_and_serial(tmp_path_factory):
    tmp = tmp_path_factory.mktemp("study")
    spec = study_from_file(write_study(tmp))
    a, fa = run_study(spec, tmp / "dask", quiet(workers=2))
    b, fb = run_study(spec, tmp / "serial", quiet(workers=0))
    return a, b, fa, fb


def test_local_cluster_with_two_workers_equals_serial(dask_and_serial):
    a, b, fa, fb = dask_and_serial
    assert fa["scheduler"] == "LocalCluster" and fa["workers"] == 2 and fb["workers"] == 0
    assert fa["fe_geometries"] == 1  # one geometry: its FE tables built once for 13 points
    assert a.num_rows == 13 and a.equals(b)
    assert a.column_names[:2] == ["point", "contact.tip_relief_pinion_um"]


def test_tip_relief_optimum_near_the_combined_tooth_deflection(dask_and_serial):
    """Classic estimate of the best linear long relief: the combined tooth deflection at the
    operating load, F / (b c_gamma_alpha) with ISO 6336-1's mesh stiffness: F = 340 N m /
    r_b1 = 4824 N, c_gamma_alpha = 22.0 N/(mm um), b = 20 mm -> 10.96 um. The TE p-p
    minimum of the FE 2D study (2 um grid, parabola through the three lowest points) must
    lie within 20 % of it (measured: 12.0 um, +10 %), and the relief must cut the TE p-p
    of the unmodified pair (5.24 um) by more than 4x."""
    from pipeline.config import load_gearbox
    from pipeline.stiffness.analysis import analyse_stiffness

    box = load_gearbox(BASE)
    F = box.operation.torque / box.pair.pinion.base_radius
    iso = analyse_stiffness(box.pair, box.operation, box.stiffness).summary()["iso6336"]
    estimate = F / (iso["c_gamma_alpha_N_per_mm_um"] * box.pinion.face_width * 1e3)  # um
    assert estimate == pytest.approx(10.96, abs=0.05)
    t = dask_and_serial[0].to_pydict()
    x, y = np.array(t["contact.tip_relief_pinion_um"]), np.array(t["te_peak_to_peak_um"])
    i = int(np.clip(np.argmin(y), 1, y.size - 2))
    c = np.polyfit(x[i - 1:i + 2], y[i - 1:i + 2], 2)
    best = -c[1] / (2 * c[0])
    assert abs(best - estimate) < 0.2 * estimate
    assert y.min() < y[0] / 4


def test_resume_after_kill_minus_9(tmp_path):
    """kill -9 part way, then --resume: the table equals an uninterrupted run and no point
    that had finished was computed again (the computed-point log names each session)."""
    study = write_study(tmp_path, points=25)
    env = dict(os.environ, PYTHONPATH=str(ROOT), OMP_NUM_THREADS="1", MPLBACKEND="Agg")
    cmd = [sys.executable, "-m", "pipeline.cli", "study", str(study), "--workers", "0",
           "--no-best-run", "--json"]
    out = tmp_path / "killed"
    proc = subprocess.Popen(cmd + ["--out", str(out)], env=env, stdout=subprocess.DEVNULL,
                            stderr=subprocess.DEVNULL)
    parts = out / "parts"
    t0 = time.time()
    while len(list(parts.glob("part-*.parquet")) if parts.is_dir() else []) < 3:
        assert proc.poll() is None and time.time() - t0 < 240
        time.sleep(0.05)
    os.kill(proc.pid, signal.SIGKILL)
    proc.wait()
    saved = set()
    for p in parts.glob("part-*.parquet"):
        saved |= set(pq.read_table(p).column("point").to_pylist())
    assert 0 < len(saved) < 25
    assert not (out / "study.parquet").exists()
    # not resuming an unfinished study is refused, so nothing is lost
    r = subprocess.run(cmd + ["--out", str(out)], env=env, capture_output=True, text=True)
    assert r.returncode == 2 and "--resume" in r.stderr and len(r.stderr.splitlines()) == 1
    r = subprocess.run(cmd + ["--out", str(out), "--resume"], env=env, capture_output=True,
                       text=True)
    assert r.returncode == 0, r.stderr
    lines = [ln.split() for ln in (out / "computed_points.log").read_text().splitlines()]
    sessions = list(dict.fromkeys(s for s, _ in lines))
    assert len(sessions) == 2
    resumed = [int(p) for s, p in lines if s == sessions[1]]
    assert not saved & set(resumed)
    assert len(resumed) == len(set(resumed)) == 25 - len(saved)
    full = tmp_path / "full"
    r = subprocess.run(cmd + ["--out", str(full)], env=env, capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
    assert pq.read_table(out / "study.parquet").equals(pq.read_table(full / "study.parquet"))


def test_resume_refused_when_axes_or_base_change(tmp_path):
    study = write_study(tmp_path, points=2)
    out = tmp_path / "out"
    run_study(study_from_file(study), out, quiet(workers=0))
    changed = write_study(tmp_path, points=3)
    with pytest.raises(InputError, match="another axes"):
        run_study(study_from_file(changed), out, quiet(workers=0, resume=True))
    base = tmp_path / "base.toml"
    base.write_text(BASE.read_text().replace("torque_Nm = 340.0", "torque_Nm = 300.0"))
    other = tmp_path / "other.toml"
    other.write_text(STUDY.format(points=2).replace(str(BASE), str(base)))
    with pytest.raises(InputError, match="another base_sha256"):
        run_study(study_from_file(other), out, quiet(workers=0, resume=True))


@pytest.mark.parametrize("extra, match", [
    ('[[axes]]\nkey = "contact.tip_relif_gear_um"\nvalues = [1.0]\n',
     r"point 0 .*'tip_relif_gear_um' is not known \(did you mean 'tip_relief_gear_um'\?\)"),
    ('[[axes]]\nkey = "operation.torque_Nm"\nvalues = [-5.0]\n',
     r"operation.torque_Nm = -5.0\): operation.torque_Nm = -5 N m is outside"),
    ("[sampling]\nmethod = \"latin_hypercube\"\nsamples = 4\n[[axes]]\n"
     'key = "operation.torque_Nm"\nvalues = [1.0]\n', "a Latin hypercube samples ranges"),
    ('[plot]\ntradeoff = ["a", "b"]\n', "'plot' is not known"),
])
def test_study_file_errors_name_the_key(tmp_path, extra, match):
    with pytest.raises(InputError, match=match):
        run_study(study_from_file(write_study(tmp_path, 2, extra)), tmp_path / "o",
                  quiet(workers=0))
    assert not (tmp_path / "o" / "manifest.json").exists()


def test_latin_hypercube_points_are_reproducible(tmp_path):
    from pipeline.study.points import design_points

    extra = ('[sampling]\nmethod = "latin_hypercube"\nsamples = 8\nseed = 3\n')
    text = STUDY.format(points=2).replace("\npoints = 2\n", "\n", 1) + extra
    p = tmp_path / "lhs.toml"
    p.write_text(text)
    a = design_points(study_from_file(p))
    b = design_points(study_from_file(p))
    x = np.array([q.values["contact.tip_relief_pinion_um"] for q in a])
    assert [q.values for q in a] == [q.values for q in b]
    # one sample in each eighth of the range
    assert sorted(np.floor(x / 3.0).astype(int).tolist()) == list(range(8))


def test_load_distribution_kpis_are_the_reports(tmp_path):
    """K_Hbeta, the largest Hertz pressure and the largest root stress of a study point are
    the report's numbers for the same gearbox (one function serves both), and on the
    assembly-error paper's spur pair they are what the report's checks establish: K_Hbeta
    exactly 1 (one slice across the face: a uniform line load), and the FE root stress
    within 10 % of ISO 6336-3's nominal sigma_F0 for the same load (measured -3 %)."""
    import tomllib

    from pipeline.contact.distribution import load_distribution
    from pipeline.contact.root_stress import analyse_root_stress
    from pipeline.study.evaluate import point_gearbox, point_result
    from pipeline.study.kpis import KPI_BY_NAME, kpi_row

    doc = tomllib.loads(BASE.read_text())
    doc["contact"] = {"compliance": "fe2d", "positions": 20, "render": False}
    names = ("k_hbeta", "contact_pressure_max_MPa", "root_stress_max_MPa")
    res = point_result(point_gearbox(doc), cache_dir=str(tmp_path))
    row = kpi_row(res, tuple(KPI_BY_NAME[n] for n in names))
    dist = load_distribution(res.contact, res.pair, res.operation)
    root = analyse_root_stress(res.contact, res.pair, res.operation, res.run.gearbox.fe_source,
                               cache_dir=tmp_path)
    assert row["k_hbeta"] == pytest.approx(1.0, abs=1e-12)
    assert row["contact_pressure_max_MPa"] == pytest.approx(dist.hertz_max.value * 1e-6,
                                                            rel=1e-12)
    worst = max(root.pinion, root.gear, key=lambda g: g.max_stress)
    assert row["root_stress_max_MPa"] == pytest.approx(worst.max_stress * 1e-6, rel=1e-12)
    assert abs(worst.max_stress / worst.iso.sigma_f0 - 1.0) < 0.10
    # the point's FE tables are cached, its contact cycle is not (one file per point)
    assert list(tmp_path.glob("fe2dtable-*")) and not list(tmp_path.glob("contactcycle-*"))
