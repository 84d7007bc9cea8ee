"""The on-disk cache cannot block or fool a run: every damaged entry is reported once,
deleted and rebuilt; an unwritable folder only costs the saving; the folder follows
``--cache-dir`` > ``GEARPIPE_CACHE_DIR`` > the source checkout's ``meshes/`` > the user
cache folder; identical gears share one entry."""

from __future__ import annotations

import errno
import os
import stat
import tempfile
from pathlib import Path

import numpy as np
import pytest

from pipeline.cache import entries as cache
from pipeline.cache.folder import (
    CACHE_ENV,
    Cache,
    CacheWarning,
    default_cache_dir,
    source_checkout_cache,
    user_cache_dir,
    writable_cache_dir,
)
from pipeline.fem import mesh_cache
from pipeline.fem.gmsh_session import TetMeshData

POINTS = np.array([[0.0, 0, 0], [1e-3, 0, 0], [0, 1e-3, 0], [0, 0, 1e-3]])
MESH = TetMeshData(POINTS, np.array([[0, 1, 2, 3]]), {"face": np.array([[0, 1, 2]])}, {})


def _entry(tmp_path: Path) -> tuple[Path, list]:
    """One mesh entry in ``tmp_path`` and the list counting its builds."""
    calls: list = []
    _, path, hit = mesh_cache.cached_tet_mesh("t", {"a": 1}, lambda: calls.append(1) or MESH,
                                         cache=Cache(tmp_path))
    assert not hit and path is not None and len(calls) == 1
    return path, calls


def _scaled_points(path: Path) -> None:
    """Rewrite the entry with its points scaled by 1.0001, keeping the stored digest
    (a payload changed behind the cache's back)."""
    with np.load(path) as z:
        arrays = {k: z[k] for k in z.files}
    arrays["points"] = arrays["points"] * 1.0001
    np.savez(path, **arrays)


def _no_digest(path: Path) -> None:
    """An entry of the previous format: valid archive, no checksum."""
    with np.load(path) as z:
        arrays = {k: z[k] for k in z.files if k != cache.DIGEST}
    np.savez(path, **arrays)


DAMAGE = [
    ("zero-byte", lambda p: p.write_bytes(b""), "empty"),
    ("truncated", lambda p: p.write_bytes(p.read_bytes()[:100]), "not a complete archive"),
    ("half", lambda p: p.write_bytes(p.read_bytes()[: p.stat().st_size // 2]),
     "not a complete archive"),
    ("not an archive", lambda p: p.write_text("hello"), "not a complete archive"),
    ("points scaled 1.0001", _scaled_points, "do not match their SHA-256"),
    ("no checksum", _no_digest, "no checksum"),
]


@pytest.mark.parametrize(("case", "damage", "why"), DAMAGE, ids=[d[0] for d in DAMAGE])
def test_damaged_entry_is_reported_deleted_and_rebuilt(tmp_path, case, damage, why):
    path, calls = _entry(tmp_path)
    damage(path)
    with pytest.warns(CacheWarning, match=why) as record:
        data, again, hit = mesh_cache.cached_tet_mesh(
            "t", {"a": 1}, lambda: calls.append(1) or MESH, cache=Cache(tmp_path))
    assert len(record) == 1 and "deleted and rebuilt" in str(record[0].message)
    assert not hit and again == path and len(calls) == 2
    np.testing.assert_array_equal(data.points, POINTS)
    # the rebuilt entry is whole again: the next call reads it without a warning
    _, _, hit = mesh_cache.cached_tet_mesh("t", {"a": 1}, lambda: calls.append(1) or MESH,
                                      cache=Cache(tmp_path))
    assert hit and len(calls) == 2
    assert [p.name for p in tmp_path.iterdir()] == [path.name]  # no temporary files left


def test_digest_covers_names_dtypes_shapes_and_bytes():
    a = {"x": np.arange(6.0)}
    variants = [{"y": np.arange(6.0)}, {"x": np.arange(6.0).astype(np.float32)},
                {"x": np.arange(6.0).reshape(2, 3)}, {"x": np.arange(6.0) * (1 + 1e-16) + 1e-12}]
    assert len({cache.arrays_digest(v) for v in [a, *variants]}) == 5
    assert cache.arrays_digest(a) == cache.arrays_digest({"x": np.arange(6.0)})


def test_reserved_digest_name_is_refused(tmp_path):
    with pytest.raises(ValueError, match="reserved"):
        cache.save_arrays(tmp_path / "x.npz", {cache.DIGEST: np.zeros(1)})


@pytest.fixture
def read_only(monkeypatch):
    """Make a folder read-only: by its mode, and for a user whom modes do not stop (root)
    by refusing new files in it as a read-only mount would."""
    made: list[Path] = []

    def make(folder: Path) -> None:
        folder.chmod(stat.S_IRUSR | stat.S_IXUSR)
        made.append(folder)
        if os.access(folder, os.W_OK):
            real = tempfile.mkstemp

            def refuse(*args, dir=None, **kwargs):
                if dir is not None and Path(dir).resolve() in {f.resolve() for f in made}:
                    raise PermissionError(errno.EACCES, os.strerror(errno.EACCES), str(dir))
                return real(*args, dir=dir, **kwargs)

            monkeypatch.setattr(tempfile, "mkstemp", refuse)

    yield make
    for folder in made:
        folder.chmod(stat.S_IRWXU)


def test_read_only_folder_runs_uncached_with_one_warning(tmp_path, read_only):
    folder = tmp_path / "ro"
    folder.mkdir()
    read_only(folder)
    calls: list = []
    with pytest.warns(CacheWarning, match="cannot be written") as record:
        for _ in range(3):
            data, path, hit = mesh_cache.cached_tet_mesh(
                "t", {"a": 1}, lambda: calls.append(1) or MESH, cache=Cache(folder))
            assert path is None and not hit
            np.testing.assert_array_equal(data.points, POINTS)
    assert len(calls) == 3 and len({str(r.message) for r in record}) == 1
    assert "Permission denied" in str(record[0].message)
    with pytest.warns(CacheWarning, match="Permission denied"):
        assert writable_cache_dir(folder) is None
    assert list(folder.iterdir()) == []


def test_a_file_in_place_of_the_folder_degrades(tmp_path):
    blocker = tmp_path / "cache"
    blocker.write_text("not a folder")
    with pytest.warns(CacheWarning, match="cannot be written"):
        _, path, hit = mesh_cache.cached_tet_mesh("t", {"a": 1}, lambda: MESH,
                                                  cache=Cache(blocker))
    assert path is None and not hit
    with pytest.warns(CacheWarning):
        assert writable_cache_dir(blocker / "sub") is None


def test_damaged_entry_in_read_only_folder_is_rebuilt_without_saving(tmp_path, read_only):
    path, calls = _entry(tmp_path)
    path.write_bytes(b"")
    read_only(tmp_path)
    with pytest.warns(CacheWarning) as record:
        data, again, hit = mesh_cache.cached_tet_mesh(
            "t", {"a": 1}, lambda: calls.append(1) or MESH, cache=Cache(tmp_path))
    assert again is None and not hit and len(calls) == 2
    np.testing.assert_array_equal(data.points, POINTS)
    assert [("empty" in str(r.message), "cannot be written" in str(r.message))
            for r in record] == [(True, False), (False, True)]


@pytest.mark.parametrize(("env", "expected"), [
    ({CACHE_ENV: "/data/gp"}, Path("/data/gp")),
    ({CACHE_ENV: "", "XDG_CACHE_HOME": "/xdg"}, "checkout or /xdg/gearpipe"),
    ({"XDG_CACHE_HOME": "/xdg"}, "checkout or /xdg/gearpipe"),
    ({"XDG_CACHE_HOME": "relative"}, "checkout or ~/.cache/gearpipe"),
])
def test_default_cache_dir(env, expected):
    got = default_cache_dir(env)
    if isinstance(expected, Path):
        assert got == expected
        return
    checkout = source_checkout_cache()
    user = {"/xdg/gearpipe": Path("/xdg/gearpipe"),
            "~/.cache/gearpipe": Path.home() / ".cache" / "gearpipe"}[expected.split(" or ")[1]]
    assert got == (checkout or user)
    assert user_cache_dir(env) == user


def test_source_checkout_uses_its_meshes_folder():
    root = Path(cache.__file__).resolve().parents[2]
    assert source_checkout_cache() == root / "meshes"
    assert (root / "meshes" / "README.md").is_file()


def test_installed_package_uses_the_user_cache(tmp_path, monkeypatch):
    """A copy of the package outside a checkout (as in site-packages) has no meshes/."""
    import pipeline.cache.folder as cd

    fake = tmp_path / "site-packages" / "pipeline" / "cache" / "folder.py"
    monkeypatch.setattr(cd, "__file__", str(fake))
    assert cd.source_checkout_cache() is None
    assert cd.default_cache_dir({"XDG_CACHE_HOME": str(tmp_path / "xdg")}) == \
        tmp_path / "xdg" / "gearpipe"


def test_identical_pinion_and_gear_are_meshed_once(tmp_path, monkeypatch):
    """Names (of the gears and their materials) are labels: the twin gear's sector mesh (as
    ``gearpipe fe`` builds it) comes from the pinion's cache entry, bit for bit; a real
    difference (0.1 mm more bore) still gives its own entry."""
    from gearsets import STEEL, spur

    import pipeline.fem.sector2d as sector2d
    from pipeline.geometry import Material

    meshed: list[str] = []
    real = sector2d.build_sector_mesh_2d

    def counting(gear, *args, **kwargs):
        meshed.append(gear.name)
        return real(gear, *args, **kwargs)

    monkeypatch.setattr(sector2d, "build_sector_mesh_2d", counting)
    relabelled = Material(STEEL.youngs_modulus, STEEL.poisson_ratio, STEEL.density, name="x")
    pinion = spur(20, "pinion", bore_radius=0.012)
    wheel = spur(20, "wheel", bore_radius=0.012, material=relabelled)
    other = spur(20, "other", bore_radius=0.0121)
    meshes = [sector2d.sector_mesh_2d(g, sector2d.SectorSettings.for_gear(g, 3, 0.3),
                                      cache=Cache(tmp_path)) for g in (pinion, wheel, other)]
    assert meshed == ["pinion", "other"]
    assert len(list(tmp_path.glob("sector2d-*.npz"))) == 2
    assert np.array_equal(meshes[0].mesh.p, meshes[1].mesh.p)
    assert meshes[1].gear.name == "wheel"  # the result still carries its own gear


FIGURE_DAMAGE = [
    ("zero-byte", lambda p: p.write_bytes(b"")),
    ("truncated", lambda p: p.write_bytes(p.read_bytes()[:-20])),
    ("not a png", lambda p: p.write_bytes(b"x" * 5000)),
]


def _counted_line(drawn: list):
    """A drawing of a line that appends to ``drawn`` each time it draws."""
    import matplotlib.pyplot as plt

    def draw(y):
        drawn.append(1)
        fig, ax = plt.subplots()
        ax.plot(y)
        return fig

    return draw


@pytest.mark.parametrize(("case", "damage"), FIGURE_DAMAGE, ids=[d[0] for d in FIGURE_DAMAGE])
def test_damaged_cached_figure_is_redrawn(tmp_path, case, damage):
    from pipeline.viz.figure_cache import FigureCache, without_key

    drawn: list = []
    draw = _counted_line(drawn)
    figures = FigureCache(tmp_path / "figures", dpi=40)
    first = figures.save(tmp_path / "a.png", draw, np.arange(3.0))
    (cached,) = (tmp_path / "figures").iterdir()
    figures.save(tmp_path / "b.png", draw, np.arange(3.0))
    assert len(drawn) == 1 and (tmp_path / "b.png").read_bytes() == first.read_bytes()
    damage(cached)
    with pytest.warns(CacheWarning, match="not a whole PNG of this figure"):
        out = figures.save(tmp_path / "c.png", draw, np.arange(3.0))
    assert len(drawn) == 2 and out.read_bytes()[-8:] == b"IEND\xaeB`\x82"
    # the cache holds the whole figure again (with its key)
    assert without_key(cached.read_bytes()) == out.read_bytes()


def test_a_cached_figure_moved_onto_another_name_is_redrawn(tmp_path):
    """Two figures of different data; the second's cached PNG copied over the first's (a
    swap on disk): the first is redrawn with one warning, never replaced by the other
    (each cached PNG carries its key in a tEXt chunk)."""
    from pipeline.viz.figure_cache import FigureCache, stored_key, without_key

    drawn: list = []
    draw = _counted_line(drawn)
    figures = FigureCache(tmp_path / "figures", dpi=40)
    a = figures.save(tmp_path / "a.png", draw, np.arange(3.0)).read_bytes()
    b = figures.save(tmp_path / "b.png", draw, np.arange(4.0)).read_bytes()
    entries = list((tmp_path / "figures").iterdir())
    cache_a, cache_b = (next(f for f in entries if without_key(f.read_bytes()) == png)
                        for png in (a, b))
    assert a != b and len(entries) == 2
    assert stored_key(cache_a) == cache_a.stem.removeprefix("fig-") != stored_key(cache_b)
    cache_a.write_bytes(cache_b.read_bytes())
    with pytest.warns(CacheWarning, match="another figure's"):
        again = figures.save(tmp_path / "a2.png", draw, np.arange(3.0))
    assert len(drawn) == 3 and again.read_bytes() == a


def test_the_test_session_caches_outside_the_checkout(tmp_path_factory):
    """The suite's own cache folder (conftest) is a temporary one: neither the checkout's
    meshes/ nor the user's cache folder receives anything from a test run."""
    folder = default_cache_dir().resolve()
    assert folder.is_relative_to(tmp_path_factory.getbasetemp().resolve())
    assert folder != source_checkout_cache()


def test_an_entry_moved_onto_another_name_is_rebuilt(tmp_path):
    """Two entries of different inputs; the second's file copied over the first's (a swap on
    disk): reading the first warns that the file holds another entry, rebuilds it and
    returns the first's own result, never the other's."""
    other = TetMeshData(2 * POINTS, MESH.cells, MESH.surfaces, {})
    path_a, calls = _entry(tmp_path)
    _, path_b, _ = mesh_cache.cached_tet_mesh("t", {"a": 2}, lambda: other, cache=Cache(tmp_path))
    path_a.write_bytes(path_b.read_bytes())
    with pytest.warns(CacheWarning, match="holds another entry") as record:
        data, _, hit = mesh_cache.cached_tet_mesh("t", {"a": 1}, lambda: calls.append(1) or MESH,
                                             cache=Cache(tmp_path))
    assert len(record) == 1 and not hit and len(calls) == 2
    np.testing.assert_array_equal(data.points, POINTS)


def test_the_key_follows_the_producing_code(tmp_path, monkeypatch):
    """A changed line in the code an entry names gives another key (no version to bump); the
    same code, the same key; code it does not name changes nothing."""
    pkg = tmp_path / "producer_pkg"
    pkg.mkdir()
    (pkg / "__init__.py").write_text("")
    (pkg / "solve.py").write_text("FACTOR = 1.0\n")
    (tmp_path / "unrelated_mod.py").write_text("X = 1\n")
    monkeypatch.syspath_prepend(str(tmp_path))
    cache.code_digest.cache_clear()
    key = cache.entry_key("t", {"a": 1}, ("producer_pkg",))
    assert cache.entry_key("t", {"a": 1}, ("producer_pkg",)) == key
    (tmp_path / "unrelated_mod.py").write_text("X = 2\n")
    cache.code_digest.cache_clear()
    assert cache.entry_key("t", {"a": 1}, ("producer_pkg",)) == key
    (pkg / "solve.py").write_text("FACTOR = 1.0 + 1e-12\n")
    cache.code_digest.cache_clear()
    assert cache.entry_key("t", {"a": 1}, ("producer_pkg",)) != key
    cache.code_digest.cache_clear()
    with pytest.raises(ValueError, match="no module or package named 'no_such_pkg'"):
        cache.entry_key("t", {}, ("no_such_pkg",))


def test_one_cache_object_reaches_every_step(tmp_path):
    """``Cache`` is the one cache argument: off builds every time and writes nothing; a
    command's cache is off with --no-cache and its folder otherwise; and the dynamics
    commands' model (``gearbox_dynamic_model``, which once ignored the folder) keeps its
    loaded contact cycle in the folder it is given, then reads it back."""
    from pipeline.config import gearbox_from_text
    from pipeline.run.runner import gearbox_dynamic_model
    from workflows.default_case import DEMO_PAIR

    calls: list[int] = []
    for _ in range(2):
        _, path, hit = cache.cached_file("t", {"a": 1}, lambda: calls.append(1) or {},
                                         dict, dict, code=("pipeline.io",), cache=Cache.off())
        assert path is None and not hit
    assert len(calls) == 2
    assert Cache.for_command(tmp_path / "c", disabled=True) == Cache.off()
    assert Cache.for_command(tmp_path / "c") == Cache(tmp_path / "c")
    assert Cache().root == default_cache_dir() and Cache().subfolder("figures") is not None
    assert Cache.off().subfolder("figures") is None
    from pipeline.viz.figure_cache import FigureCache

    assert FigureCache.within(Cache.off()) == FigureCache()
    assert FigureCache.within(Cache(tmp_path / "c")).folder == tmp_path / "c" / "figures"

    box = gearbox_from_text(DEMO_PAIR + '[contact]\npositions = 8\n'
                            '[dynamics]\nexcitation = "contact"\n')
    folder = tmp_path / "dyn"
    gearbox_dynamic_model(box, Cache(folder))
    cycles = sorted(folder.glob("contactcycle-*.npz"))
    assert len(cycles) == 1
    stamp = cycles[0].stat().st_mtime_ns
    gearbox_dynamic_model(box, Cache(folder))
    assert sorted(folder.glob("contactcycle-*.npz")) == cycles
    assert cycles[0].stat().st_mtime_ns == stamp  # read back, not rewritten
