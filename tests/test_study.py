"""Design studies (gearpipe study): study file checks, Dask vs serial, resume after kill -9,
the tip-relief optimum of the assembly-error paper's pair against the classic estimate, and
the results folder (a user's files and other results refused and left byte-identical, an
earlier result of the same study replaced as a unit)."""

import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
import pyarrow.parquet as pq
import pytest

from pipeline.cache.folder import Cache
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
    res = point_result(point_gearbox(doc), cache=Cache(str(tmp_path)))
    row = kpi_row(res, tuple(KPI_BY_NAME[n] for n in names))
    dist = load_distribution(res.contact, res.pair, res.operation)
    root = analyse_root_stress(res.contact, res.pair, res.operation, res.run.gearbox.fe_source,
                               cache=Cache(tmp_path))
    assert row["k_hbeta"] == pytest.approx(1.0, abs=1e-12)
    assert row["contact_pressure_max_MPa"] == pytest.approx(dist.hertz_max.value * 1e-6,
                                                            rel=1e-12)
    worst = max(root.pinion, root.gear, key=lambda g: g.max_stress)
    assert row["root_stress_max_MPa"] == pytest.approx(worst.max_stress * 1e-6, rel=1e-12)
    # below ISO's whole load on one tooth: the tip corners touching beyond the path share
    # it (0.815 measured at 20 positions; within 10 % on the nominal path)
    assert 0.75 < worst.max_stress / worst.iso.sigma_f0 < 0.90
    # the point's FE tables are cached, its contact cycle is not (one file per point)
    assert list(tmp_path.glob("fe2dtable-*")) and not list(tmp_path.glob("contactcycle-*"))


# --- the results folder ---------------------------------------------------------------

# two analytical points of about half a second each: enough for a whole study result
TINY = f"""
name = "{{name}}"
base = "{BASE}"
[set]
"contact.positions" = 10
"contact.render" = false
"contact.tip_relief_length_pinion_mm" = 6.2
[[axes]]
key = "contact.tip_relief_pinion_um"
values = {{values}}
[kpis]
names = ["te_peak_to_peak_um", "mesh_stiffness_mean_N_per_um"]
"""


def tiny(tmp_path: Path, name: str = "tiny", values: str = "[0.0, 10.0]") -> Path:
    p = tmp_path / f"{name}.toml"
    p.write_text(TINY.format(name=name, values=values))
    return p


def study_cli(study: Path, out: Path, *more: str) -> int:
    from pipeline.cli import main

    return main(["study", str(study), "--out", str(out), "--workers", "0", "--no-best-run",
                 "--json", *more])


def tree(folder: Path) -> dict[str, bytes]:
    """Every file under ``folder`` (hidden ones too) by relative path, with its bytes."""
    return {str(p.relative_to(folder)): p.read_bytes() if p.is_file() else b"<dir>"
            for p in sorted(folder.rglob("*"))}


def no_points(monkeypatch) -> None:
    """Fail the test if a point is computed."""
    def refuse(*a, **k):
        raise AssertionError("a point was computed")

    monkeypatch.setattr("pipeline.study.execute.evaluate_point", refuse)


def _user_files(tmp_path: Path) -> tuple[Path, str]:
    out = tmp_path / "mine"
    (out / "parts").mkdir(parents=True)
    (out / "study.csv").write_text("point,my_kpi\n0,1.5\n")
    (out / "summary.json").write_text('{"mine": true}')
    (out / "run.json").write_text('{"outputs": ["study.csv"]}')
    (out / "parts" / "x.parquet").write_bytes(b"PAR1 mine")
    return out, "(parts, run.json, study.csv, summary.json)"


def _stranger_in_parts(tmp_path: Path) -> tuple[Path, str]:
    """An unfinished study of the same name, but parts/ holds a file no study writes."""
    out = tmp_path / "mixed"
    (out / "parts").mkdir(parents=True)
    (out / "manifest.json").write_text('{"study": "tiny", "hash": "0", "points": 2}')
    (out / "parts" / "x.parquet").write_bytes(b"PAR1 mine")
    return out, "(parts/x.parquet)"


def _geometry_result(tmp_path: Path) -> tuple[Path, str]:
    from pipeline.cli import main

    out = tmp_path / "geometry"
    assert main(["geometry", str(BASE), "--out", str(out), "--json"]) == 0
    return out, "run.json"


def _other_study(tmp_path: Path) -> tuple[Path, str]:
    out = tmp_path / "other"
    assert study_cli(tiny(tmp_path, "other", "[0.0]"), out) == 0
    return out, "manifest.json"


@pytest.mark.parametrize("make", [_user_files, _stranger_in_parts, _geometry_result,
                                  _other_study])
def test_a_folder_that_is_not_this_study_s_result_is_refused_and_kept(
        tmp_path, capsys, monkeypatch, make):
    """Refused in one line before any point is computed (exit status 1, as every command's
    folder), every file byte-identical, nothing left beside the folder."""
    monkeypatch.setenv("GEARPIPE_CACHE_DIR", str(tmp_path / "cache"))
    out, named = make(tmp_path)
    before = tree(out)
    beside = sorted(os.listdir(tmp_path))
    no_points(monkeypatch)
    capsys.readouterr()
    assert study_cli(tiny(tmp_path), out) == 1
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1, err
    assert err[0].startswith(f"gearpipe study: error: {out} holds files that are not a "
                             "result of the study 'tiny' ")
    assert named in err[0]
    assert tree(out) == before
    assert sorted(os.listdir(tmp_path)) == sorted(beside + ["tiny.toml"])


def test_a_rerun_replaces_the_earlier_result_of_the_same_study_as_a_unit(tmp_path, capsys,
                                                                         monkeypatch):
    """The same study (its name) edited from 2 to 3 points replaces its earlier result: the
    folder then holds only files its run.json lists, the 3 points of the new
    session and no part file of the old one. A rerun that fails at its second point leaves
    the earlier result byte-identical."""
    import json

    from numpy.linalg import LinAlgError

    monkeypatch.setenv("GEARPIPE_CACHE_DIR", str(tmp_path / "cache"))
    out = tmp_path / "out"
    assert study_cli(tiny(tmp_path), out) == 0
    first = json.loads(capsys.readouterr().out)["session"]
    assert study_cli(tiny(tmp_path, values="[0.0, 5.0, 10.0]"), out) == 0
    second = json.loads(capsys.readouterr().out)["session"]
    record = json.loads((out / "run.json").read_text())
    assert set(os.listdir(out)) <= set(record["outputs"] + ["run.json"])
    assert pq.read_table(out / "study.parquet").column("point").to_pylist() == [0, 1, 2]
    parts = sorted(p.name for p in (out / "parts").iterdir())
    assert parts == [f"part-{i:07d}-{second}.parquet" for i in range(3)]
    assert first not in (out / "computed_points.log").read_text()
    assert not [e for e in os.listdir(tmp_path) if e.startswith(".")]  # no staging left

    import pipeline.study.execute as execute

    calls, evaluate = [], execute.evaluate_point

    def fail_second(*a, **k):
        calls.append(1)
        if len(calls) == 2:
            raise LinAlgError("singular")
        return evaluate(*a, **k)

    before = tree(out)
    monkeypatch.setattr(execute, "evaluate_point", fail_second)
    assert study_cli(tiny(tmp_path), out) == 1
    assert "LinAlgError: singular" in capsys.readouterr().err
    assert tree(out) == before and len(calls) == 2
    assert not [e for e in os.listdir(tmp_path) if e.startswith(".")]


def test_an_unfinished_study_is_what_resume_continues(tmp_path, capsys, monkeypatch):
    """A study stopped after its first point keeps it in the folder; a plain rerun is
    refused (exit status 2, the earlier behaviour) and --resume computes the one missing
    point, also for a manifest written before the study's name was recorded in it."""
    import json

    from numpy.linalg import LinAlgError

    import pipeline.study.execute as execute

    monkeypatch.setenv("GEARPIPE_CACHE_DIR", str(tmp_path / "cache"))
    evaluate = execute.evaluate_point
    calls = []

    def stop_second(*a, **k):
        calls.append(1)
        if len(calls) == 2:
            raise LinAlgError("stopped")
        return evaluate(*a, **k)

    out = tmp_path / "out"
    monkeypatch.setattr(execute, "evaluate_point", stop_second)
    assert study_cli(tiny(tmp_path), out) == 1
    monkeypatch.setattr(execute, "evaluate_point", evaluate)
    assert sorted(os.listdir(out)) == ["computed_points.log", "manifest.json", "parts"]
    manifest = json.loads((out / "manifest.json").read_text())
    assert manifest.pop("study") == "tiny"
    (out / "manifest.json").write_text(json.dumps(manifest))  # as older versions wrote it
    capsys.readouterr()
    assert study_cli(tiny(tmp_path), out) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "unfinished study (1 of 2 points)" in err[0]
    assert study_cli(tiny(tmp_path), out, "--resume") == 0
    summary = json.loads(capsys.readouterr().out)
    assert summary["computed_now"] == 1 and summary["points"] == 2
    assert pq.read_table(out / "study.parquet").column("point").to_pylist() == [0, 1]
    record = json.loads((out / "run.json").read_text())
    assert set(os.listdir(out)) <= set(record["outputs"] + ["run.json"])


def test_kill_minus_9_during_a_rerun_leaves_the_earlier_result(tmp_path):
    """A rerun over a finished result computes in the hidden staging folder: kill -9 after
    three of its part files leaves the earlier result byte-identical, and the next run
    removes the dead run's staging folder and replaces the result."""
    values = "[" + ", ".join(f"{0.5 * i:.1f}" for i in range(16)) + "]"
    study = tiny(tmp_path, values=values)
    env = dict(os.environ, PYTHONPATH=str(ROOT), OMP_NUM_THREADS="1", MPLBACKEND="Agg",
               GEARPIPE_CACHE_DIR=str(tmp_path / "cache"))
    out = tmp_path / "out"
    cmd = [sys.executable, "-m", "pipeline.cli", "study", str(study), "--workers", "0",
           "--no-best-run", "--json", "--out", str(out)]
    r = subprocess.run(cmd, env=env, capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
    before = tree(out)
    proc = subprocess.Popen(cmd, env=env, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    t0 = time.time()
    while len(list(tmp_path.glob(".out.staging-*/parts/part-*.parquet"))) < 3:
        assert proc.poll() is None and time.time() - t0 < 120
        time.sleep(0.02)
    os.kill(proc.pid, signal.SIGKILL)
    proc.wait()
    assert tree(out) == before
    assert len(list(tmp_path.glob(".out.staging-*"))) == 1
    r = subprocess.run(cmd, env=env, capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
    assert not list(tmp_path.glob(".out.*"))
    assert pq.read_table(out / "study.parquet").num_rows == 16
    assert (out / "run.json").read_bytes() != before["run.json"]


def test_sensitivity_and_tradeoff_axes_carry_the_kpi_labels(tmp_path):
    """Every panel of the sensitivity plot, the right-hand column included, reads its KPI by
    name and unit from the one table of KPI labels; the trade-off plot likewise. The x
    axes name the study's keys in words with the unit of their suffix."""
    from pipeline.config.units import key_label
    from pipeline.study.kpis import kpi_label
    from pipeline.study.plots import plot_sensitivity, plot_tradeoff
    from pipeline.study.points import design_points

    text = STUDY.format(points=3).replace(
        '"contact.tip_relief_length_gear_mm" = 6.2\n', "") + (
        '[[axes]]\nkeys = ["contact.tip_relief_length_gear_mm"]\nrange = [5.0, 7.0]\n'
        'points = 3\n')
    p = tmp_path / "two_axes.toml"
    p.write_text(text)
    spec = study_from_file(p)
    points = design_points(spec)
    kpis = ["te_peak_to_peak_um", "mesh_stiffness_mean_N_per_um"]
    table: dict[str, list] = {"point": [q.index for q in points]}
    for a in spec.axes:
        table[a.label] = [q.values[a.keys[0]] for q in points]
    for k in kpis:
        table[k] = [float(i) for i in range(len(points))]
    fig = plot_sensitivity(spec, table, kpis)
    axs = np.array(fig.axes).reshape(len(kpis), len(spec.axes))
    assert axs.shape == (2, 2)
    for i, k in enumerate(kpis):
        assert [ax.get_ylabel() for ax in axs[i]] == [kpi_label(k)] * 2
    assert kpi_label("te_peak_to_peak_um") == "TE peak to peak (um)"
    assert kpi_label("mesh_stiffness_mean_N_per_um") == "mean mesh stiffness (N/um)"
    assert kpi_label("k_hbeta") == "face load factor K_H\u03b2"
    assert [ax.get_xlabel() for ax in axs[-1]] == [
        "contact: tip relief pinion (um) (+1 tied)", "contact: tip relief length gear (mm)"]
    assert key_label("contact.tip_relief_length_gear_mm") == (
        "contact: tip relief length gear (mm)")
    assert key_label("pinion.teeth") == "pinion: teeth"
    assert key_label("operation.torque_Nm") == "operation: torque (N m)"
    trade = plot_tradeoff(table, kpis[0], kpis[1], 0, "relief")
    ax = trade.axes[0]
    assert (ax.get_xlabel(), ax.get_ylabel()) == (kpi_label(kpis[0]), kpi_label(kpis[1]))


def test_best_point_folder_is_a_run_folder_with_its_report(tmp_path):
    """The best point gets what ``gearpipe run`` writes, report.html included, under the
    best point's name (not the base file's)."""
    from pipeline.cli.study import report_best_point

    spec = study_from_file(write_study(tmp_path, 2))
    values = {spec.axes[0].label: 12.0}
    files = report_best_point(spec, values, tmp_path / "best_point")
    run = tmp_path / "best_point" / "run"
    assert files == [tmp_path / "best_point" / "gearbox.toml", run]
    html = (run / "report.html").read_text()
    assert "best point of study relief" in html
    assert "contact.tip_relief_pinion_um = 12.0" in (files[0]).read_text()


# --- checks before the first point ----------------------------------------------------

GRID_1E10 = ('[[axes]]\nkey = "operation.torque_Nm"\nrange = [100.0, 400.0]\npoints = 100000\n'
             '[[axes]]\nkey = "operation.speed_rpm"\nrange = [500.0, 3000.0]\n'
             'points = 100000\n')


def study_with(tmp_path: Path, extra: str) -> Path:
    p = tiny(tmp_path)
    p.write_text(p.read_text() + extra)
    return p


@pytest.mark.parametrize("options, extra, status, message", [
    (["--scheduler", "not a url"], "", 2,
     "--scheduler not a url: expected a Dask scheduler address tcp://host:port"),
    (["--scheduler", "http://127.0.0.1:8787"], "", 2,
     "http:// is the dashboard's address, the scheduler's is tcp://host:8786"),
    (["--scheduler", "inproc://x"], "", 2, "(schemes tcp, tls, ws, wss)"),
    (["--scheduler", "tcp://127.0.0.1:0"], "", 2, "a port in 1..65535"),
    (["--scheduler", "tcp://127.0.0.1:1"], "", 2,
     "--scheduler tcp://127.0.0.1:1: no Dask scheduler answered (Connection refused; waited "
     "at most 5 s)"),
    (["--scheduler", "tcp://127.0.0.1:1", "--workers", "2"], "", 2,
     "--workers 2 with --scheduler"),
    (["--workers", "-1"], "", 2, "--workers -1: expected 0 (serial) or more"),
    (["--resume"], "", 2, "holds no study to resume"),
    ([], '[best]\nkpi = "te_pp_um"\n', 2,
     "best.kpi = 'te_pp_um' is not a KPI of this study; its KPIs: te_peak_to_peak_um, "
     "mesh_stiffness_mean_N_per_um"),
    ([], '[best]\nkpi = "k_hbeta"\n', 2, "best.kpi = 'k_hbeta' is not a KPI of this study"),
    ([], '[plots]\ntradeoff = ["te_peak_to_peak_um", "k_hbeta"]\n', 2,
     "plots.tradeoff = 'k_hbeta' is not a KPI of this study"),
    ([], '[plots]\ntradeoff = ["te_peak_to_peak_um", "te_peak_to_peak_um"]\n', 2,
     "expected two different KPIs"),
    ([], '[sampling]\nseed = 3\n', 2, "sampling.seed applies to method = \"latin_hypercube\""),
    ([], GRID_1E10, 2, "the study has 20000000000 points (grid 2 x 100000 x 100000); at most "
                       "100000 are run"),
])
def test_a_bad_option_or_study_value_is_one_line_before_anything(
        tmp_path, capsys, monkeypatch, options, extra, status, message):
    """Each is one line, the documented exit status, no point computed, and nothing
    written: the --out folder (two levels new) is not made, nothing appears beside it."""
    from pipeline.cli import main

    monkeypatch.setenv("GEARPIPE_CACHE_DIR", str(tmp_path / "cache"))
    study = study_with(tmp_path, extra)
    before = sorted(os.listdir(tmp_path))
    no_points(monkeypatch)
    capsys.readouterr()
    serial = [] if "--scheduler" in options else ["--workers", "0"]
    t0 = time.perf_counter()
    assert main(["study", str(study), "--out", str(tmp_path / "new" / "out"), "--no-best-run",
                 "--json", *serial, *options]) == status
    assert time.perf_counter() - t0 < 4.0  # the size is counted, never built
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and err[0].startswith("gearpipe study: error: "), err
    assert message in err[0]
    assert sorted(os.listdir(tmp_path)) == before


@pytest.mark.parametrize("target, message", [
    ("afile", "is a file, not a folder"),
    ("/", "/ holds files that are not a result of the study 'tiny'"),
])
def test_out_naming_a_file_or_the_root_is_one_line(tmp_path, capsys, monkeypatch, target,
                                                   message):
    monkeypatch.setenv("GEARPIPE_CACHE_DIR", str(tmp_path / "cache"))
    (tmp_path / "afile").write_text("mine")
    out = Path(target) if target == "/" else tmp_path / target
    study = tiny(tmp_path)
    before = tree(tmp_path)
    no_points(monkeypatch)
    capsys.readouterr()
    assert study_cli(study, out) == 1
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and message in err[0], err
    assert tree(tmp_path) == before


def test_a_read_only_out_folder_is_one_line(tmp_path, capsys, monkeypatch):
    """An existing empty folder the study cannot write into (read-only: chmod, or, for
    root, whom chmod does not stop, the permission check answering no) is refused with
    exit status 1 before any point."""
    monkeypatch.setenv("GEARPIPE_CACHE_DIR", str(tmp_path / "cache"))
    out = tmp_path / "ro"
    out.mkdir()
    out.chmod(0o555)
    if os.access(out, os.W_OK):
        access = os.access
        monkeypatch.setattr(os, "access", lambda p, mode, **k: Path(p) != out
                            and access(p, mode, **k))
    no_points(monkeypatch)
    capsys.readouterr()
    try:
        assert study_cli(tiny(tmp_path), out) == 1
    finally:
        out.chmod(0o755)
    err = capsys.readouterr().err.strip().splitlines()
    assert err == [f"gearpipe study: error: {out} is not writable, so the study cannot be "
                   "written there; give --out another folder"]
    assert os.listdir(out) == []


def test_an_unreachable_scheduler_fails_at_once_and_a_plain_rerun_works(tmp_path, capsys,
                                                                         monkeypatch):
    """A closed local port is refused at once (it waited 20 s before), leaves no
    manifest or parts, so the same command without --scheduler then runs the study."""
    from pipeline.cli import main

    monkeypatch.setenv("GEARPIPE_CACHE_DIR", str(tmp_path / "cache"))
    out = tmp_path / "out"
    study = tiny(tmp_path)
    t0 = time.perf_counter()
    assert main(["study", str(study), "--out", str(out), "--no-best-run", "--json",
                 "--scheduler", "tcp://127.0.0.1:1"]) == 2
    assert time.perf_counter() - t0 < 3.0
    assert "Connection refused" in capsys.readouterr().err
    assert not out.exists() and sorted(os.listdir(tmp_path)) == ["tiny.toml"]
    assert study_cli(study, out) == 0
    assert pq.read_table(out / "study.parquet").num_rows == 2


def test_a_silent_scheduler_is_waited_for_at_most_the_connect_timeout(tmp_path, monkeypatch):
    """A port that accepts the connection but never answers (a listening socket nobody
    reads; dask.distributed's own handshake would wait on past its timeout): the study
    gives up after the connect timeout (set to 0.5 s here) and writes nothing."""
    import socket

    import pipeline.study.execute as execute

    monkeypatch.setattr(execute, "CONNECT_TIMEOUT_S", 0.5)
    silent = socket.socket()
    silent.bind(("127.0.0.1", 0))
    silent.listen()
    address = f"tcp://127.0.0.1:{silent.getsockname()[1]}"
    spec = study_from_file(tiny(tmp_path))
    no_points(monkeypatch)
    t0 = time.perf_counter()
    try:
        with pytest.raises(InputError, match=r"no Dask scheduler answered \(.*waited at most "
                                             r"0.5 s\)"):
            run_study(spec, tmp_path / "out", quiet(scheduler=address))
    finally:
        silent.close()
    assert 0.5 <= time.perf_counter() - t0 < 3.0
    assert not (tmp_path / "out").exists()


def test_a_running_scheduler_is_used(tmp_path, monkeypatch):
    """The connection check lets a real scheduler through: a cluster started at a tcp://
    address gives the serial table."""
    from dask.distributed import LocalCluster

    monkeypatch.setenv("GEARPIPE_CACHE_DIR", str(tmp_path / "cache"))
    spec = study_from_file(tiny(tmp_path))
    with LocalCluster(n_workers=1, threads_per_worker=1, processes=False,
                      dashboard_address=None, protocol="tcp://") as cluster:
        a, facts = run_study(spec, tmp_path / "dask", quiet(scheduler=cluster.scheduler_address))
    b, _ = run_study(spec, tmp_path / "serial", quiet(workers=0))
    assert facts["scheduler"].startswith("tcp://127.0.0.1:") and facts["workers"] == 1
    assert a.equals(b)


def test_the_point_count_is_the_number_of_points_built(tmp_path):
    """point_count multiplies the axis lengths without building the points: equal to
    len(design_points) for a grid with a deduplicated integer range (1..4 over 7 points:
    4 values) x 3 values = 12, and a Latin hypercube of 5 samples; at MAX_POINTS a study
    runs; above it a study is refused, with 0.06 s and 4.5 kB a point: 50001 x 2 = 100002
    points -> 6000 s = 1.67 h, 450 MB."""
    from pipeline.study.points import design_points
    from pipeline.study.size import MAX_POINTS, check_size, point_count

    grid = study_with(tmp_path, '[[axes]]\nkey = "pinion.teeth"\nrange = [47, 50]\n'
                                'points = 7\n[[axes]]\nkey = "operation.torque_Nm"\n'
                                'values = [100.0, 200.0, 300.0]\n')
    spec = study_from_file(grid)
    assert point_count(spec) == len(design_points(spec)) == 2 * 4 * 3
    lhs = tmp_path / "lhs.toml"
    lhs.write_text(STUDY.format(points=2).replace("\npoints = 2\n", "\n", 1)
                   + '[sampling]\nmethod = "latin_hypercube"\nsamples = 5\n')
    spec = study_from_file(lhs)
    assert point_count(spec) == len(design_points(spec)) == 5
    edge = ('[[axes]]\nkey = "operation.torque_Nm"\nrange = [100.0, 400.0]\n'
            'points = {n}\n')
    p = tmp_path / "edge.toml"
    p.write_text(STUDY.format(points=2).split("[[axes]]")[0] + edge.format(n=MAX_POINTS))
    assert check_size(study_from_file(p)) == MAX_POINTS
    p.write_text(p.read_text() + '[[axes]]\nkey = "operation.speed_rpm"\n'
                 'values = [1000.0, 2000.0]\n')
    p.write_text(p.read_text().replace(f"points = {MAX_POINTS}", "points = 50001"))
    with pytest.raises(InputError, match=r"has 100002 points \(grid 50001 x 2\); at most "
                                         r"100000 are run: at 0.06 s a point .* at least "
                                         r"1.67 h on one worker and 450 MB of memory"):
        check_size(study_from_file(p))


def test_a_study_of_one_kpi_has_no_tradeoff_plot(tmp_path, capsys, monkeypatch):
    """One KPI: the study runs, the summary says why there is no trade-off plot, and the
    folder holds no tradeoff.png (nor does run.json list one)."""
    import json

    monkeypatch.setenv("GEARPIPE_CACHE_DIR", str(tmp_path / "cache"))
    study = tiny(tmp_path)
    study.write_text(study.read_text().replace(', "mesh_stiffness_mean_N_per_um"', ""))
    out = tmp_path / "out"
    capsys.readouterr()
    assert study_cli(study, out) == 0
    summary = json.loads(capsys.readouterr().out)
    assert summary["tradeoff"] == ("none: the study has one KPI (te_peak_to_peak_um), a "
                                   "trade-off needs two")
    te = np.genfromtxt(out / "study.csv", delimiter=",", names=True)
    column = next(n for n in te.dtype.names if n.startswith("te_peak_to_peak_um"))
    assert summary["best"]["kpi"] == "te_peak_to_peak_um"
    assert summary["best"]["point"] == int(te["point"][np.argmin(te[column])])
    assert (out / "sensitivity.png").is_file() and not (out / "tradeoff.png").exists()
    assert "tradeoff.png" not in json.loads((out / "run.json").read_text())["outputs"]
