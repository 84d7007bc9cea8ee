"""A run's folder holds the previous complete result or the new one, never a mix.

Each case is a way a run can fail or be pointed wrong (a full or read-only disk, a file
where a folder should be, a folder holding other files, an input refused after the
work began, a name inside the file that tries to leave ``results/``); each checks the
one-line error, the exit status and that nothing partial is left. Files get the
permissions the umask gives, and temporary files of dead processes are removed. Runs
writing into one folder at the same time leave one whole result, the last one's.
"""

from __future__ import annotations

import errno
import json
import os
import subprocess
import sys
from pathlib import Path

import pytest

from pipeline.cli import main as cli
from pipeline.io import atomic_write_text, remove_stale_temps
from pipeline.output_folder import OutputError, staged_output

CONFIG = Path(__file__).resolve().parents[1] / "workflows" / "configs" / \
    "spur_pair_assembly_errors.toml"


def small(tmp_path: Path, friction: float = 0.05, name: str = "pair") -> Path:
    """The assembly-error paper's pair with 60 stiffness positions (a run of about 1 s)."""
    text = CONFIG.read_text().replace("positions = 360", "positions = 60")
    text = text.replace("friction = 0.0 ", f"friction = {friction} ")
    path = tmp_path / f"{name}.toml"
    path.write_text(text, encoding="utf-8")
    return path


def snapshot(folder: Path) -> dict[str, bytes]:
    return {p.name: p.read_bytes() for p in sorted(folder.iterdir())}


def hidden(folder: Path) -> list[str]:
    return sorted(p.name for p in folder.iterdir() if p.name.startswith("."))


def one_line(capsys) -> str:
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1, err
    return err[0]


def _reaped_pid() -> int:
    """The id of a process that has exited (and been reaped)."""
    p = subprocess.Popen([sys.executable, "-c", "pass"])
    p.wait()
    return p.pid


def test_a_rerun_removes_the_files_of_the_earlier_run(tmp_path):
    out = tmp_path / "out"
    assert cli(["stiffness", str(small(tmp_path, 0.05)), "--out", str(out)]) == 0
    assert (out / "friction_coefficients.png").is_file()
    assert cli(["stiffness", str(small(tmp_path, 0.0)), "--out", str(out)]) == 0
    record = json.loads((out / "run.json").read_text())
    assert sorted(os.listdir(out)) == sorted(record["outputs"] + ["run.json"])
    assert "friction_coefficients.png" not in record["outputs"]
    assert hidden(tmp_path) == []


@pytest.mark.parametrize(("code", "after"), [
    (errno.ENOSPC, 1),   # disk full at the second file: the CSV is written, the PNG is not
    (errno.ENOSPC, 3),
    (errno.EROFS, 0),    # the filesystem went read-only
    (errno.EDQUOT, 2),   # quota exceeded
])
def test_a_disk_error_keeps_the_previous_result(tmp_path, capsys, monkeypatch, code, after):
    out = tmp_path / "out"
    assert cli(["stiffness", str(small(tmp_path, 0.05)), "--out", str(out)]) == 0
    before = snapshot(out)
    capsys.readouterr()
    real, calls = os.fsync, []

    def fsync(fd):
        calls.append(fd)
        if len(calls) > after:
            raise OSError(code, os.strerror(code))
        return real(fd)

    monkeypatch.setattr(os, "fsync", fsync)
    assert cli(["stiffness", str(small(tmp_path, 0.0)), "--out", str(out)]) == 1
    line = one_line(capsys)
    assert line.startswith("gearpipe stiffness: error: cannot write the results to")
    assert os.strerror(code) in line and "the folder holds the previous result" in line
    monkeypatch.undo()
    assert snapshot(out) == before
    assert hidden(tmp_path) == []


def test_a_disk_error_on_a_first_run_leaves_no_folder(tmp_path, capsys, monkeypatch):
    def fsync(fd):
        raise OSError(errno.ENOSPC, os.strerror(errno.ENOSPC))

    monkeypatch.setattr(os, "fsync", fsync)
    out = tmp_path / "results" / "pair" / "stiffness"
    assert cli(["stiffness", str(small(tmp_path)), "--out", str(out)]) == 1
    assert "nothing was written" in one_line(capsys)
    assert sorted(os.listdir(tmp_path)) == ["pair.toml"]  # no results/pair/ either


def _file(tmp_path: Path) -> tuple[Path, Path]:
    (tmp_path / "f").write_text("keep")
    return tmp_path / "f", tmp_path / "f"


def _under_file(tmp_path: Path) -> tuple[Path, Path]:
    (tmp_path / "f").write_text("keep")
    return tmp_path / "f" / "out", tmp_path / "f"


def _foreign(tmp_path: Path) -> tuple[Path, Path]:
    (tmp_path / "project").mkdir()
    (tmp_path / "project" / "notes.txt").write_text("keep")
    return tmp_path / "project", tmp_path / "project" / "notes.txt"


def _mixed(tmp_path: Path) -> tuple[Path, Path]:
    """An earlier result with a file its run.json does not list (as left by old versions)."""
    out = tmp_path / "out"
    out.mkdir()
    (out / "run.json").write_text(json.dumps({"outputs": ["mesh_stiffness.csv"]}))
    (out / "mesh_stiffness.csv").write_text("1\n")
    (out / "friction_coefficients.png").write_text("png")
    return out, out / "friction_coefficients.png"


@pytest.mark.parametrize(("make", "message"), [
    (_file, "is a file, not a folder"),
    (_under_file, "is a file, so the folder"),
    (_foreign, "holds files that are not one gearpipe result (notes.txt)"),
    (_mixed, "(friction_coefficients.png)"),
])
def test_a_target_that_cannot_be_a_result_folder_is_refused(tmp_path, capsys, make, message):
    out, kept = make(tmp_path)
    before = kept.read_bytes() if kept.is_file() else None
    assert cli(["stiffness", str(small(tmp_path)), "--out", str(out)]) == 1
    line = one_line(capsys)
    assert line.startswith("gearpipe stiffness: error: ") and message in line
    assert kept.read_bytes() == before


def test_results_being_a_file_is_one_line(tmp_path, capsys, monkeypatch):
    monkeypatch.chdir(tmp_path)
    Path("results").write_text("not a folder")
    assert cli(["stiffness", str(small(tmp_path))]) == 1
    assert "results is a file" in one_line(capsys)
    assert Path("results").read_text() == "not a folder"


def test_a_read_only_parent_is_one_line(tmp_path, capsys):
    ro = tmp_path / "ro"
    ro.mkdir()
    ro.chmod(0o555)
    try:
        if os.access(ro, os.W_OK):
            pytest.skip("running as root: chmod does not make a folder read-only")
        assert cli(["stiffness", str(small(tmp_path)), "--out", str(ro / "out")]) == 1
        assert "is not writable" in one_line(capsys)
        assert os.listdir(ro) == []
    finally:
        ro.chmod(0o755)


def test_a_run_refused_after_the_check_leaves_no_folder(tmp_path, capsys):
    """``gearpipe fe`` refuses a model too big for the machine after reading its options;
    before, the empty output folder was already made."""
    out = tmp_path / "results" / "fe"
    rc = cli(["fe", str(small(tmp_path)), "--out", str(out), "--refinement", "20",
              "--teeth", "20"])
    assert rc == 2 and "million unknowns" in one_line(capsys)
    assert sorted(os.listdir(tmp_path)) == ["pair.toml"]


@pytest.mark.parametrize("name", ["../../escape", "/tmp/gearpipe-escape", "a/../../b", ".."])
def test_a_name_in_the_file_never_chooses_the_folder(tmp_path, monkeypatch, name):
    work = tmp_path / "a" / "b"
    work.mkdir(parents=True)
    monkeypatch.chdir(work)
    cfg = small(work)
    lines = cfg.read_text().splitlines()
    cfg.write_text("\n".join(f'name = "{name}"' if line.startswith("name = ") else line
                             for line in lines) + "\n")
    assert cli(["stiffness", str(cfg)]) == 0
    assert sorted(os.listdir(work)) == ["pair.toml", "results"]
    assert (work / "results" / "pair" / "stiffness" / "run.json").is_file()
    assert sorted(os.listdir(tmp_path)) == ["a"] and sorted(os.listdir(tmp_path / "a")) == ["b"]
    assert not Path("/tmp/gearpipe-escape").exists()


@pytest.mark.parametrize(("umask", "file_mode", "dir_mode"), [
    (0o022, 0o644, 0o755), (0o027, 0o640, 0o750), (0o002, 0o664, 0o775), (0o077, 0o600, 0o700),
])
def test_files_and_folders_follow_the_umask(tmp_path, umask, file_mode, dir_mode):
    old = os.umask(umask)
    try:
        out = tmp_path / "out"
        assert cli(["stiffness", str(small(tmp_path)), "--out", str(out)]) == 0
    finally:
        os.umask(old)
    assert out.stat().st_mode & 0o777 == dir_mode
    assert {p.name: p.stat().st_mode & 0o777 for p in out.iterdir()} == \
        dict.fromkeys(os.listdir(out), file_mode)


def test_temp_files_of_dead_processes_are_removed_and_live_ones_kept(tmp_path):
    dead, live = _reaped_pid(), os.getppid()
    stale = tmp_path / f".mesh-ab12.npz.tmp-{dead}-k3j4h5g6.npz"
    busy = tmp_path / f".mesh-cd34.npz.tmp-{live}-a1b2c3d4.npz"
    other = tmp_path / ".mesh-ef56.npz.k3j4h5g6.npz"  # not ours: no process id in the name
    for p in (stale, busy, other):
        p.write_bytes(b"partial")
    atomic_write_text(tmp_path / "x.txt", "new")
    assert sorted(os.listdir(tmp_path)) == sorted([busy.name, other.name, "x.txt"])
    assert remove_stale_temps(tmp_path) == []


def _result(folder: Path, text: str) -> None:
    folder.mkdir()
    (folder / "a.txt").write_text(text)
    (folder / "run.json").write_text(json.dumps({"outputs": ["a.txt"]}))


@pytest.mark.parametrize("leftover", ["staging", "old"])
def test_the_next_run_cleans_up_after_a_killed_one(tmp_path, leftover):
    """A kill while staging leaves ``.out.staging-<pid>-*``; a kill between the two renames
    of the portable swap leaves the previous result as ``.out.old-<pid>-*`` and no ``out``:
    the next run puts that back before it fails, or replaces it when it succeeds."""
    out, pid = tmp_path / "out", _reaped_pid()
    _result(tmp_path / f".out.{leftover}-{pid}-1a2b3c4d", "previous")
    with pytest.raises(RuntimeError), staged_output(out) as staging:
        (staging / "a.txt").write_text("half")
        raise RuntimeError("the computation failed")
    assert hidden(tmp_path) == []
    if leftover == "old":
        assert (out / "a.txt").read_text() == "previous"
    else:
        assert not out.exists()
    with staged_output(out) as staging:
        (staging / "a.txt").write_text("new")
    assert (out / "a.txt").read_text() == "new" and os.listdir(tmp_path) == ["out"]


def test_a_live_run_s_staging_folder_is_left_alone(tmp_path):
    busy = tmp_path / f".out.staging-{os.getppid()}-1a2b3c4d"
    busy.mkdir()
    with staged_output(tmp_path / "out") as staging:
        (staging / "a.txt").write_text("new")
    assert busy.is_dir()


def test_the_portable_swap_gives_the_same_result(tmp_path, monkeypatch):
    import pipeline.output_folder as of

    monkeypatch.setattr(of, "exchange", lambda a, b: False)
    out = tmp_path / "out"
    _result(out, "previous")
    with staged_output(out) as staging:
        (staging / "a.txt").write_text("new")
    assert (out / "a.txt").read_text() == "new" and os.listdir(tmp_path) == ["out"]


def test_an_error_in_the_computation_is_not_an_output_error(tmp_path):
    out = tmp_path / "out"
    _result(out, "previous")
    with pytest.raises(FileNotFoundError), staged_output(out):
        open(tmp_path / "missing-input.csv")  # noqa: SIM115 - the error is the point
    assert (out / "a.txt").read_text() == "previous" and hidden(tmp_path) == []
    with pytest.raises(OutputError, match="No space left"), staged_output(out):
        raise OSError(errno.ENOSPC, os.strerror(errno.ENOSPC))


def _writer(target: str, writer: int, rounds: int, barrier, portable: bool) -> None:
    """Write ``rounds`` complete results (three files naming ``writer``) into ``target``."""
    import pipeline.output_folder as of

    if portable:
        of.exchange = lambda a, b: False  # the two-rename swap of other systems
    for r in range(rounds):
        barrier.wait()
        with staged_output(target) as out:
            for name in ("a.txt", "b.txt"):
                atomic_write_text(out / name, f"{writer} {r} {name}\n" * 200)
            atomic_write_text(out / "run.json",
                              json.dumps({"writer": writer, "round": r,
                                          "outputs": ["a.txt", "b.txt", "run.json"]}))


@pytest.mark.parametrize("portable", [False, True], ids=["exchange", "two_renames"])
def test_concurrent_runs_on_one_target_leave_one_whole_result(tmp_path, portable):
    """Three processes write results into the same folder at the same moments, 15 rounds
    each: after every one has finished, the folder holds one writer's whole result of one
    round (the last writer wins), and no staging, old or temporary entry is left."""
    import multiprocessing

    ctx = multiprocessing.get_context("fork")
    target = tmp_path / "out"
    writers, rounds = 4, 40
    barrier = ctx.Barrier(writers, timeout=20)  # a writer that fails breaks it: no hang
    procs = [ctx.Process(target=_writer, args=(str(target), w, rounds, barrier, portable),
                         daemon=True) for w in range(writers)]
    try:
        for p in procs:
            p.start()
        for p in procs:
            p.join(timeout=120)
    finally:
        for p in procs:
            if p.is_alive():
                p.kill()
    assert [p.exitcode for p in procs] == [0] * writers
    record = json.loads((target / "run.json").read_text())
    w, r = record["writer"], record["round"]
    assert r == rounds - 1
    assert sorted(os.listdir(target)) == ["a.txt", "b.txt", "run.json"]
    for name in ("a.txt", "b.txt"):
        assert (target / name).read_text() == f"{w} {r} {name}\n" * 200
    assert sorted(os.listdir(tmp_path)) == ["out"]


def test_a_target_moved_away_during_the_swap_is_no_error(tmp_path, monkeypatch):
    """The portable swap: another run moves the previous result away between our check and
    our rename (the race the test above runs into); ours still goes in whole."""
    import pipeline.output_folder as of

    target = tmp_path / "out"
    with staged_output(target) as out:
        atomic_write_text(out / "run.json", json.dumps({"outputs": ["run.json"], "n": 1}))
    monkeypatch.setattr(of, "exchange", lambda a, b: False)
    rename = os.rename

    def racing_rename(src, dst):
        if Path(src) == target and ".old-" in str(dst) and target.exists():
            rename(target, tmp_path / "elsewhere")  # the other run's move
        return rename(src, dst)

    monkeypatch.setattr(of.os, "rename", racing_rename)
    with staged_output(target) as out:
        atomic_write_text(out / "run.json", json.dumps({"outputs": ["run.json"], "n": 2}))
    assert json.loads((target / "run.json").read_text())["n"] == 2
