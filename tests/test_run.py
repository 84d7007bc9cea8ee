"""``gearpipe run``: the chain of stages, its cache and its one results folder.

The chain's numbers are the stages' own (each tested in its module's tests); here:
every step runs in order and hands its result on, a rerun takes the expensive
intermediates from the cache and gives identical numbers, a changed input misses the
cache exactly where it should, and the run's failure paths are one line.
"""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest
from gearsets import SMALL

from pipeline.cache.folder import Cache, CacheWarning
from pipeline.cli import main as cli
from pipeline.config import gearbox_from_text
from pipeline.output_folder import LONGEST_FILE_NAME
from pipeline.run import RunOptions, run_pipeline

CONFIGS = Path(__file__).resolve().parents[1] / "workflows" / "configs"



def _run(text: str, cache_dir: Path):
    return run_pipeline(gearbox_from_text(text, "small"),
                        RunOptions(cache=Cache(cache_dir), show_progress=False))


def test_rerun_reads_the_contact_cycle_from_the_cache(tmp_path):
    first = _run(SMALL, tmp_path)
    second = _run(SMALL, tmp_path)
    step = "loaded contact (analytical)"
    assert not first.log.cached[step] and second.log.cached[step]
    a, b = first.meshes["mesh"].contact, second.meshes["mesh"].contact
    for name in ("transmission_error", "mesh_stiffness", "pair_loads", "point_load"):
        np.testing.assert_array_equal(getattr(a, name), getattr(b, name))
    assert a.load == b.load and a.local_contact == b.local_contact
    fa = first.dynamics.response.response.mesh_force
    np.testing.assert_array_equal(fa, second.dynamics.response.response.mesh_force)
    assert len(list(tmp_path.glob("contactcycle-*.npz"))) == 1


def test_dynamics_option_changes_only_the_dynamics(tmp_path):
    first = _run(SMALL, tmp_path)
    second = _run(SMALL.replace("damping_ratio = 0.07", "damping_ratio = 0.10"), tmp_path)
    assert second.log.cached["loaded contact (analytical)"]
    f1 = first.dynamics.response.response.mesh_force
    f2 = second.dynamics.response.response.mesh_force
    assert np.ptp(f2) < np.ptp(f1)  # more damping, smaller force swing at the same speed


@pytest.mark.parametrize("change", [
    ("positions = 24", "positions = 30"),                 # [contact]
    ("friction = 0.05", "friction = 0.06"),               # [stiffness] friction
    ("torque_Nm = 340.0", "torque_Nm = 300.0"),           # [operation]
    ("[gear]\nteeth = 50", "[gear]\nteeth = 51"),         # geometry
])
def test_a_changed_input_misses_the_cache(tmp_path, change):
    _run(SMALL, tmp_path)
    again = _run(SMALL.replace(*change), tmp_path)
    assert not again.log.cached["loaded contact (analytical)"]
    assert len(list(tmp_path.glob("contactcycle-*.npz"))) == 2


def test_unreadable_cache_file_is_rebuilt(tmp_path):
    first = _run(SMALL, tmp_path)
    (path,) = tmp_path.glob("contactcycle-*.npz")
    path.write_bytes(path.read_bytes()[:100])  # truncated, as by a full disk
    with pytest.warns(CacheWarning, match="not a complete archive"):
        again = _run(SMALL, tmp_path)
    assert not again.log.cached["loaded contact (analytical)"]
    np.testing.assert_array_equal(first.meshes["mesh"].contact.transmission_error,
                                  again.meshes["mesh"].contact.transmission_error)


def test_static_stages_hand_on_their_results(tmp_path):
    """The run's contact load is the driving torque over the base radius, its dynamic
    mean force equals that load, and the sweep covers the file's range."""
    res = _run(SMALL, tmp_path)
    st = res.meshes["mesh"]
    rb = 0.075 * np.cos(np.radians(20.0))
    assert st.contact.load == pytest.approx(340.0 / rb, rel=1e-12)
    s = res.summary()
    mesh = s["dynamics"]["response_at_operating_speed"]["meshes"]["mesh"]
    # mean dynamic mesh force = static load (a periodic steady state carries the torque)
    assert mesh["mean_force_N"] == pytest.approx(st.contact.load, rel=2e-3)
    assert s["dynamics"]["sweep"]["f_min_Hz"] == 500.0
    assert s["dynamics"]["sweep"]["points"] == 12
    assert mesh["dynamic_factor"] > 1.0


def test_cli_writes_one_folder_with_one_summary(tmp_path, capsys):
    cfg = tmp_path / "small.toml"
    cfg.write_text(SMALL, encoding="utf-8")
    out = tmp_path / "out"
    assert cli(["run", str(cfg), "--out", str(out), "--cache-dir", str(tmp_path / "c"),
                "--json"]) == 0
    summary = json.loads(capsys.readouterr().out)
    assert summary == json.loads((out / "summary.json").read_text())
    for name in ("mesh_stiffness.csv", "contact_cycle.csv", "load_map_2d.png", "modes.csv",
                 "time_history.csv", "sweep.csv", "sweep.png", "tooth_profiles.png",
                 "run.json"):
        assert (out / name).is_file(), name
    # the output folder's length check counts on names of at most LONGEST_FILE_NAME bytes
    assert max(len(p.name) for p in out.iterdir()) <= LONGEST_FILE_NAME
    record = json.loads((out / "run.json").read_text())
    assert str(tmp_path / "c") in record["arguments"] and record["options"] == {"full": False}
    # the report's FE root-stress tables go to the run's cache folder, like every FE table
    assert sorted(p.name.split("-")[0] for p in (tmp_path / "c").rglob("filletstress*")), \
        "no root-stress table in --cache-dir"


def test_run_refuses_a_single_gear(tmp_path, capsys):
    rc = cli(["run", str(CONFIGS / "wind_turbine_sun_groove.toml"), "--out", str(tmp_path)])
    err = capsys.readouterr().err.strip().splitlines()
    assert rc == 2 and len(err) == 1
    assert "gearpipe run: error:" in err[0] and "single gear" in err[0]


def test_report_step_lines_name_the_report_command(tmp_path, capsys):
    """``gearpipe report`` runs the same chain as ``gearpipe run``; its step lines on stderr
    say ``[gearpipe report]``, the command the user typed."""
    cfg = tmp_path / "small.toml"
    cfg.write_text(SMALL.split("[dynamics]")[0], encoding="utf-8")
    assert cli(["report", str(cfg), "--out", str(tmp_path / "out"), "--cache-dir",
                str(tmp_path / "c")]) == 0
    steps = [line for line in capsys.readouterr().err.splitlines() if line.startswith("[")]
    assert steps and all(line.startswith("[gearpipe report] ") for line in steps), steps
