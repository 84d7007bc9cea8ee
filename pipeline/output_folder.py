"""A run's output folder, written as a unit: it holds the previous complete result or the
new one, never a mix.

:func:`staged_output` hands the caller a fresh hidden staging folder beside the target
(``.<target>.staging-<pid>-<random>``, on the same filesystem). When the caller's block
succeeds, the staging folder is flushed to disk (its files were flushed as they were
written, :func:`pipeline.io.atomic_write`) and swapped in: on Linux in one atomic step
(``renameat2`` with ``RENAME_EXCHANGE``), elsewhere by renaming the previous folder away
(``.<target>.old-<pid>-<random>``) and the new one in; then the parent is flushed and the
previous result deleted. When the block fails, the staging folder and any parent folder
made for it are removed, so a failed run changes nothing. A process killed while writing
leaves its staging folder hidden; the next run for the same target removes it, and when
the kill came between the two renames it first puts the previous result back.

A target must be new, empty, or a previous result (a folder whose ``run.json`` lists
every file in it): a folder holding anything else (``--out .`` in a project folder) is
refused rather than replaced. A command whose results folder has its own layout passes
its own :class:`FolderRule` (``gearpipe study`` accepts only an earlier result of the same
study, :func:`pipeline.study.store.study_folder`); the check, the message and the swap are
the same. So is a target whose name or path the file system cannot hold together with
what the writer adds: the staging folder's name (the target's plus 26 bytes) must fit
NAME_MAX, and the longest temporary file inside it (a name of up to
:data:`LONGEST_FILE_NAME` bytes plus its decoration) PATH_MAX; on Linux a result folder's
name has at most 229 bytes. Problems with the target are :class:`OutputError`, one line
naming the folder; the command line prints it without a traceback.

Checks: ``tests/test_kill_during_write.py`` (slow) kills a run with SIGKILL inside a cache
write, after 3 or 15 result files and inside the swap; the rerun is complete and
bit-identical, figures drawn afresh included. Runs writing into one folder at the same time
each swap in a whole result and the last one stays (three processes, 15 rounds each, both
swaps: ``tests/test_output_folder.py``). The next run for a folder also deletes the
temporary files whose process is gone (in the cache too). Files and folders get the
permissions of the umask (0644 / 0755 with the usual 022).

Cost, measured side by side on 2 cores shared with other jobs (load average 4-5): 25 small
CSV files staged and flushed 124-265 ms against 108-135 ms written plainly.
"""

from __future__ import annotations

import ctypes
import errno
import json
import os
import re
import secrets
import shutil
import stat
import tempfile
from collections.abc import Callable, Iterable, Iterator
from contextlib import contextmanager
from dataclasses import dataclass
from pathlib import Path

from pipeline.io import fsync_path, pid_alive, process_umask

# errors of the disk rather than of the computation
_DISK_ERRNOS = {errno.ENOSPC, errno.EDQUOT, errno.EROFS, errno.EFBIG}

LONGEST_FILE_NAME = 64
"""Longest name (bytes) of a file a command writes into its folder; the longest today is
``planet_ring_report_transmission_error.png`` (41). The length check of a target counts
on it, so the tests hold every command's outputs to it."""
_PID_DIGITS = 7  # PID_MAX_LIMIT of Linux is 4194304; other systems stay below it
_RANDOM = 8  # random characters of tempfile's names
_STAGING_EXTRA = len("..staging--") + _PID_DIGITS + _RANDOM
"""What ``.<target>.staging-<pid>-<random>`` adds to the target's name."""
_LONGEST_TEMP = len("..tmp--") + LONGEST_FILE_NAME + _PID_DIGITS + _RANDOM + len(".parquet")
"""Longest temporary file name :func:`pipeline.io.atomic_write` makes in a result folder:
``.<name>.tmp-<pid>-<random><suffix>``."""


def mesh_prefix(mesh: str) -> str:
    """File-name prefix of a mesh's outputs in a run folder: none for a pair's one mesh
    ("mesh"), ``"<mesh>_"`` for each mesh of a planetary set."""
    return "" if mesh == "mesh" else f"{mesh}_"


def mesh_label(gearbox: str, mesh: str) -> str:
    """How titles name a mesh: the gearbox's name, with ``sun-planet`` / ``planet-ring``
    for the meshes of a planetary set."""
    return gearbox if mesh == "mesh" else f"{gearbox} {mesh.replace('_', '-')}"


class OutputError(Exception):
    """The results cannot be written where asked (full or read-only disk, a file in the
    way, a folder holding other files); the message is one line naming the folder."""


def folder_entries(folder: Path) -> list[str]:
    """The entries of ``folder`` (sorted); none if it is gone (another run is swapping its
    result in)."""
    try:
        return sorted(os.listdir(folder))
    except FileNotFoundError:
        return []


def read_json_object(path: Path) -> dict | None:
    """The JSON object in ``path`` as a dictionary, or None (missing, unreadable, not JSON or
    not an object): a record or manifest that is not there or not ours."""
    try:
        value = json.loads(path.read_text(encoding="utf-8"))
    except (OSError, ValueError):
        return None
    return value if isinstance(value, dict) else None


def read_record(folder: Path) -> dict | None:
    """The ``run.json`` of ``folder`` as a dictionary, or None (missing or not a record)."""
    return read_json_object(folder / "run.json")


def record_outputs(record: dict) -> set[str]:
    """The names a run record lists as its outputs, ``run.json`` included."""
    outputs = record.get("outputs", [])
    return {str(o) for o in outputs} | {"run.json"} if isinstance(outputs, list) else set()


def unlisted(entries: Iterable[str], listed: set[str]) -> list[str]:
    """The ``entries`` that are neither ``listed`` nor a temporary file of a listed one
    (``.<name>.*``, :func:`pipeline.io.atomic_write`)."""
    return [e for e in entries if e not in listed
            and not any(e.startswith(f".{name}.") for name in listed)]


def _foreign_entries(folder: Path) -> list[str]:
    """Entries of ``folder`` that no ``run.json`` in it lists (sorted)."""
    entries = folder_entries(folder)
    if not entries:
        return []
    record = read_record(folder)
    return unlisted(entries, set() if record is None else record_outputs(record))


@dataclass(frozen=True)
class FolderRule:
    """Which existing folder a run may write its result over.

    Attributes
    ----------
    result : what such a folder holds, completing "holds files that are not ..."
        (``"one gearpipe result"``).
    foreign : the entries of an existing folder that are not part of such a result
        (sorted; names relative to the folder; none for an empty folder).
    """

    result: str
    foreign: Callable[[Path], list[str]]


ANY_RESULT = FolderRule("one gearpipe result", _foreign_entries)


def check_target(target: str | os.PathLike, rule: FolderRule = ANY_RESULT) -> Path:
    """The folder ``target`` as it will be written, or :class:`OutputError` if it cannot be.

    Checked before any work: every name and the path fit the file system with what the
    writer adds (module docstring), ``target`` is not a file, holds nothing but an earlier
    result (``rule``: by default any folder whose ``run.json`` lists every file in it), and
    its nearest existing parent is a writable folder.
    """
    shown = Path(target)
    path = shown.resolve()
    _check_lengths(shown, path)
    try:
        mode = path.stat().st_mode  # one look: another run may be swapping the folder
    except (FileNotFoundError, NotADirectoryError):  # new, or under a file (checked below)
        mode = None
    if mode is not None:
        if not stat.S_ISDIR(mode):
            raise OutputError(f"{shown} is a file, not a folder; give --out a folder "
                              "(new, empty, or an earlier result)")
        foreign = rule.foreign(path)
        if foreign:
            more = f" and {len(foreign) - 5} more" if len(foreign) > 5 else ""
            raise OutputError(f"{shown} holds files that are not {rule.result} "
                              f"({', '.join(foreign[:5])}{more}); choose a new or empty folder "
                              "or move them away")
    for parent in path.parents:
        if parent.exists():
            if not parent.is_dir():
                raise OutputError(f"{parent} is a file, so the folder {shown} cannot "
                                  "be made; move the file or give --out another folder")
            if not os.access(parent, os.W_OK | os.X_OK):
                raise OutputError(f"{parent} is not writable, so the results cannot be "
                                  f"written to {shown}; give --out another folder")
            break
    return path


def _short(text: str) -> str:
    """A long name cut in the middle, for one-line messages."""
    return text if len(text) <= 70 else f"{text[:40]}...{text[-25:]}"


def _limits(path: Path) -> tuple[int, int]:
    """(NAME_MAX, PATH_MAX) in bytes of the file system that will hold ``path``: that of
    its nearest existing parent (POSIX defaults 255 and 4096 where it does not say)."""
    existing = Path(path.anchor)
    for p in (path, *path.parents):
        try:
            os.stat(p)
        except OSError:  # missing, or itself a name too long: look further up
            continue
        existing = p
        break
    limits = []
    for name, default in (("PC_NAME_MAX", 255), ("PC_PATH_MAX", 4096)):
        try:
            limits.append(int(os.pathconf(existing, name)))
        except (OSError, ValueError, AttributeError):
            limits.append(default)
    return limits[0], limits[1]


def _check_lengths(shown: Path, path: Path) -> None:
    """:class:`OutputError` unless every name and path the writer will make for the folder
    ``path`` fits the file system: each folder name, the staging folder's name beside it
    (the target's name plus :data:`_STAGING_EXTRA`) and the longest temporary file inside
    that (:data:`_LONGEST_TEMP`) under PATH_MAX. Checked before any work, so a name that
    cannot be written never costs a computation."""
    name_max, path_max = _limits(path)
    for part in path.parts[1:-1]:
        if len(os.fsencode(part)) > name_max:
            raise OutputError(f"the folder name {_short(part)} in {_short(str(shown))} is "
                              f"{len(os.fsencode(part))} bytes long; the file system allows "
                              f"at most {name_max}; give --out a shorter path")
    name = len(os.fsencode(path.name))
    if name + _STAGING_EXTRA > name_max:
        raise OutputError(f"the results folder name {_short(path.name)} is {name} bytes long; "
                          f"it can have at most {name_max - _STAGING_EXTRA} (the file system "
                          f"allows {name_max} and the writer adds {_STAGING_EXTRA} for its "
                          "staging folder); give --out a shorter name")
    longest = len(os.fsencode(str(path))) + _STAGING_EXTRA + 1 + _LONGEST_TEMP
    if longest > path_max - 1:
        allowed = path_max - 1 - _STAGING_EXTRA - 1 - _LONGEST_TEMP
        raise OutputError(f"the results folder {_short(str(path))} is "
                          f"{len(os.fsencode(str(path)))} bytes long as an absolute path; it "
                          f"can have at most {allowed} (the file system allows {path_max} for "
                          "a path, and the files written into it need the rest); give --out a "
                          "shorter path")


def _stale(target: Path) -> list[tuple[str, Path]]:
    """Staging and old folders of ``target`` whose process is gone: (kind, path)."""
    pattern = re.compile(rf"^\.{re.escape(target.name)}\.(staging|old)-(\d+)-")
    out = []
    for entry in os.scandir(target.parent):
        m = pattern.match(entry.name)
        if m and not pid_alive(int(m.group(2))):
            out.append((m.group(1), Path(entry.path)))
    return out


def recover(target: str | os.PathLike) -> None:
    """Clean up after a killed run: put back the previous result if it was renamed away
    and the new one never arrived, and delete stale staging and old folders."""
    target = Path(target)
    stale = _stale(target)
    olds = sorted((p for kind, p in stale if kind == "old"), key=lambda p: p.stat().st_mtime)
    if olds and not target.exists():
        os.rename(olds[-1], target)
        stale = [(k, p) for k, p in stale if p != olds[-1]]
    for _, p in stale:
        shutil.rmtree(p, ignore_errors=True)


def _aside(target: Path) -> Path:
    return target.parent / f".{target.name}.old-{os.getpid()}-{secrets.token_hex(4)}"


def exchange(a: Path, b: Path) -> bool:
    """Swap two existing paths atomically (Linux ``renameat2(RENAME_EXCHANGE)``); False
    where the system or the filesystem cannot."""
    try:
        renameat2 = ctypes.CDLL(None, use_errno=True).renameat2
    except (AttributeError, OSError):
        return False
    at_fdcwd, rename_exchange = -100, 2
    if renameat2(at_fdcwd, os.fsencode(a), at_fdcwd, os.fsencode(b), rename_exchange) == 0:
        return True
    err = ctypes.get_errno()
    if err in (errno.ENOSYS, errno.EINVAL, errno.ENOTSUP, errno.EOPNOTSUPP):
        return False
    raise OSError(err, os.strerror(err), str(a), None, str(b))


def _commit(staging: Path, target: Path) -> None:
    """Swap the finished staging folder in for ``target`` (see the module docstring)."""
    os.chmod(staging, 0o777 & ~process_umask())
    fsync_path(staging, directory=True)
    try:
        if target.is_dir() and exchange(staging, target):  # staging now holds the old result
            fsync_path(target.parent, directory=True)
            shutil.rmtree(staging, ignore_errors=True)
            return
    except FileNotFoundError:
        pass  # another run moved the target away just now: rename ours in below
    olds: list[Path] = []
    for attempt in range(5):
        old = _aside(target)
        try:
            os.rename(target, old)
            olds.append(old)
        except FileNotFoundError:
            pass  # no previous result, or another run moved it away just now
        try:
            os.rename(staging, target)
            break
        except OSError as exc:  # another run put its result in between: move that too
            if exc.errno in (errno.ENOTEMPTY, errno.EEXIST) and attempt < 4:
                continue
            if olds and not target.exists():
                os.rename(olds.pop(), target)
            raise
    fsync_path(target.parent, directory=True)
    for old in olds:
        shutil.rmtree(old, ignore_errors=True)


def _made_parents(path: Path) -> list[Path]:
    """The parents of ``path`` that do not exist yet, deepest first."""
    return [p for p in path.parents if not p.exists()]


def _is_output_error(exc: BaseException, staging: Path) -> bool:
    if not isinstance(exc, OSError):
        return False
    inside = any(str(f).startswith(str(staging)) for f in (exc.filename, exc.filename2) if f)
    return inside or exc.errno in _DISK_ERRNOS


@contextmanager
def staged_output(target: str | os.PathLike, rule: FolderRule = ANY_RESULT
                  ) -> Iterator[Path]:
    """Yield a staging folder to write a result into; on success it becomes ``target``.

    Parameters
    ----------
    target : the result folder (created with its parents if missing; an earlier result
        there is replaced as a whole).
    rule : which existing folder counts as an earlier result (:func:`check_target`).

    Yields
    ------
    Path : the hidden staging folder beside ``target``; write every file of the result
        into it (names as they should appear in ``target``).

    Raises
    ------
    OutputError : ``target`` cannot be written (see :func:`check_target`), or the disk
        refused a write (full, read-only); nothing was changed.
    """
    shown = Path(target)
    path = check_target(shown, rule)
    made = _made_parents(path)
    unchanged = "the folder holds the previous result" if path.exists() else \
        "nothing was written"
    try:
        path.parent.mkdir(parents=True, exist_ok=True)
        recover(path)
        staging = Path(tempfile.mkdtemp(prefix=f".{path.name}.staging-{os.getpid()}-",
                                        dir=path.parent))
    except OSError as exc:
        _remove_empty(made)
        raise OutputError(f"cannot write the results to {shown}: "
                          f"{exc.strerror or exc} ({unchanged})") from None
    try:
        yield staging
        _commit(staging, path)
    except BaseException as exc:
        shutil.rmtree(staging, ignore_errors=True)
        _remove_empty(made)
        if _is_output_error(exc, staging):
            raise OutputError(f"cannot write the results to {shown}: "
                              f"{exc.strerror or exc} ({unchanged})") from None
        raise


def _remove_empty(folders: list[Path]) -> None:
    for folder in folders:  # deepest first
        try:
            folder.rmdir()
        except OSError:
            return


__all__ = ["ANY_RESULT", "LONGEST_FILE_NAME", "FolderRule", "OutputError", "check_target",
           "folder_entries", "read_record", "record_outputs", "recover", "staged_output",
           "unlisted"]
