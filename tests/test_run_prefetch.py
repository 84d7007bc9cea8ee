"""The FE 2D tables of a run built side by side (pipeline.run.prefetch): the run's numbers
and its cache entries bit for bit those of a run that builds every table in its stages, the
jobs those the stages read, and a warm cache that forks nothing."""

from __future__ import annotations

from contextlib import contextmanager

import numpy as np
import pytest

from pipeline.cache.entries import load_arrays
from pipeline.cache.folder import Cache
from pipeline.config.gearbox import gearbox_from_text
from pipeline.run import runner
from pipeline.run.chain import RunOptions
from pipeline.run.prefetch import CONTACT, ROOT, TablePrefetch, prefetch_tables, table_jobs
from pipeline.run.runner import run_pipeline

# a small spur pair (z 19/31) with FE 2D contact at coarse [fe] settings: two compliance
# tables and two fillet stress tables (the gears differ)
PAIR = """\
[pinion]
teeth = 19
module_mm = 2.0
pressure_angle_deg = 20.0
face_width_mm = 10.0
bore_radius_mm = 8.0
[gear]
teeth = 31
module_mm = 2.0
pressure_angle_deg = 20.0
face_width_mm = 10.0
bore_radius_mm = 12.0
[operation]
torque_Nm = 40.0
speed_rpm = 1500.0
[contact]
compliance = "fe2d"
positions = 8
[fe]
points = 8
refinement = 0.5
"""


@contextmanager
def _no_prefetch(box, options):
    yield TablePrefetch()


def _without_timing(summary: dict) -> dict:
    return {k: v for k, v in summary.items() if k != "timing"}


@pytest.mark.filterwarnings("ignore::pipeline.validation.PhysicsWarning")
def test_prefetched_tables_give_the_same_run_bit_for_bit(tmp_path, monkeypatch):
    box = gearbox_from_text(PAIR)
    side = RunOptions(show_progress=False, cache=Cache(tmp_path / "side"))
    jobs = table_jobs(box, side)
    # pinion and gear: a compliance table before the contact, a fillet table before the
    # root stress, each in its own cache entry
    assert sorted(j.needed_by for j in jobs) == [("mesh", CONTACT)] * 2 + [("mesh", ROOT)] * 2
    assert len({j.entry for j in jobs}) == 4
    started = []

    @contextmanager
    def spy(box, options):
        with prefetch_tables(box, options) as tables:
            started.append(tables)
            yield tables

    monkeypatch.setattr(runner, "prefetch_tables", spy)
    fast = run_pipeline(box, side)
    # the pinion's compliance table here, the three others in the pool
    assert started[0].pool is not None
    assert sum(len(f) for f in started[0].futures.values()) == 3
    assert started[0].here == {}  # built when the loaded contact waited for it
    assert all(j.entry.is_file() for j in jobs)
    assert table_jobs(box, side) == []  # warm: nothing left to build
    monkeypatch.setattr(runner, "prefetch_tables", _no_prefetch)
    alone = RunOptions(show_progress=False, cache=Cache(tmp_path / "serial"))
    serial = run_pipeline(box, alone)
    # the stages alone wrote every entry the jobs name: the jobs are the tables they read
    assert table_jobs(box, alone) == []
    assert len(list((tmp_path / "serial").glob("fe2dtable-*.npz"))) == 2
    assert len(list((tmp_path / "serial").glob("filletstress-*.npz"))) == 2
    assert _without_timing(fast.summary()) == _without_timing(serial.summary())
    for a, b in ((fast.distributions["mesh"].root_stress, serial.distributions["mesh"]
                  .root_stress),):
        for ga, gb in ((a.pinion, b.pinion), (a.gear, b.gear)):
            np.testing.assert_array_equal(ga.envelope, gb.envelope)
    np.testing.assert_array_equal(fast.meshes["mesh"].contact.point_load,
                                  serial.meshes["mesh"].contact.point_load)
    for job in jobs:  # the entries the stages wrote themselves: the same arrays
        a, b = load_arrays(job.entry), load_arrays(tmp_path / "serial" / job.entry.name)
        for name in ("fe", "local", "stress", "arc"):
            if name in a:
                np.testing.assert_array_equal(a[name], b[name])


def test_identical_gears_share_one_fillet_table(tmp_path):
    """Two identical gears: one fillet stress entry serves both (two jobs, one entry); the
    compliance tables differ by their loaded teeth (pinion mid - k, gear mid + k)."""
    text = PAIR.replace("teeth = 31", "teeth = 19").replace("bore_radius_mm = 12.0",
                                                              "bore_radius_mm = 8.0")
    jobs = table_jobs(gearbox_from_text(text), RunOptions(cache=Cache(tmp_path)))
    root = [j.entry for j in jobs if j.needed_by[1] == ROOT]
    contact = [j.entry for j in jobs if j.needed_by[1] == CONTACT]
    assert len(root) == 2 and root[0] == root[1]
    assert len(contact) == 2 and contact[0] != contact[1]


def test_nothing_to_prefetch_without_cache_or_fe2d(tmp_path):
    box = gearbox_from_text(PAIR)
    assert table_jobs(box, RunOptions(cache=Cache.off())) == []
    analytical = gearbox_from_text(PAIR.replace('"fe2d"', '"analytical"'))
    assert table_jobs(analytical, RunOptions(cache=Cache(tmp_path))) == []
