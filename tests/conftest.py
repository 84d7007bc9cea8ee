"""Shared fixtures: the published gear pairs used across the tests."""

from __future__ import annotations

import math
import os

import pytest

os.environ.setdefault("MPLBACKEND", "Agg")
os.environ.setdefault("PYVISTA_OFF_SCREEN", "true")

from gearsets import STEEL, spur  # noqa: E402

from pipeline.geometry import GearPair, GearSpec  # noqa: E402


@pytest.fixture(scope="session")
def spur_pair_z50() -> GearPair:
    """The base case of the assembly-error paper: z 50/50, m 3 mm, 20 deg, b 20 mm, E 200 GPa."""
    return GearPair(spur(50, "pinion"), spur(50, "gear"))


@pytest.fixture(scope="session")
def helical_traction_pair() -> GearPair:
    """Traction pair of Yang et al. (2026), Table 2 (beta 4 deg, a 495 mm; face width assumed 130
    mm)."""
    kw = dict(module=7.35e-3, pressure_angle=math.radians(20), helix_angle=math.radians(4.0),
              addendum_coef=1.2, dedendum_coef=1.55, face_width=0.13, material=STEEL)
    p = GearSpec(teeth=31, hand="right", profile_shift=0.27807, bore_radius=0.045,
                 name="pinion", **kw)
    g = GearSpec(teeth=104, hand="left", profile_shift=-0.59026, bore_radius=0.15, name="gear",
                 **kw)
    return GearPair(p, g)


@pytest.fixture(autouse=True)
def _one_blas_thread_in_dynamics_tests(request):
    """Dynamics tests: one BLAS thread (their matrices are at most a few hundred rows).

    With dev.sh's two BLAS threads on cores shared with other jobs, the spinning
    threads made these small solves 5-20x slower (test_sweep_methods_agree: 15.4 s
    against 0.82 s); the FE tests keep their threads.
    """
    if not request.module.__name__.startswith("test_dyn_"):
        yield
        return
    from threadpoolctl import threadpool_limits

    with threadpool_limits(limits=1):
        yield


@pytest.fixture(scope="session", autouse=True)
def _temporary_cache_folder(tmp_path_factory):
    """Every test caches into one temporary folder of the session (GEARPIPE_CACHE_DIR, which
    subprocesses inherit), never into the checkout's meshes/ or the user's cache: a user's
    first run after the tests stays cold, and no test depends on what an earlier run left.
    A test that names its own --cache-dir or sets the variable itself still wins."""
    from pipeline.cache.folder import CACHE_ENV

    with pytest.MonkeyPatch.context() as mp:
        mp.setenv(CACHE_ENV, str(tmp_path_factory.mktemp("gearpipe-cache")))
        yield
