"""Progress on stderr only for work that lasts: :func:`pipeline.progress.progress` shows no
bar for a loop that ends within its ``after`` seconds and a bar for one that runs longer."""

from __future__ import annotations

import time

import pytest

from pipeline.progress import REPORT_AFTER, Steps, progress


def _slow(n: int, pause: float):
    for i in range(n):
        time.sleep(pause)
        yield i


def test_fast_loop_shows_no_bar(capsys):
    # 10000 items take about 5 ms, far below the default 1 s
    assert REPORT_AFTER == 1.0
    assert sum(progress(range(10_000), "fast")) == 49_995_000
    assert capsys.readouterr().err == ""


def test_loop_longer_than_after_shows_its_bar(capsys, monkeypatch):
    import sys

    monkeypatch.setattr(sys.stderr, "isatty", lambda: True)  # the bar is for a terminal
    # 8 x 0.05 s = 0.4 s, at least 4 times the 0.1 s after which the bar appears
    assert list(progress(_slow(8, 0.05), "slow loop", total=8, after=0.1)) == list(range(8))
    err = capsys.readouterr().err
    assert "slow loop:" in err and "/8 [" in err, repr(err)
    assert capsys.readouterr().out == ""


def test_disabled_loop_shows_no_bar_however_long(capsys):
    assert list(progress(_slow(4, 0.05), "off", total=4, enabled=False, after=0.01)) == [0, 1,
                                                                                          2, 3]
    assert capsys.readouterr().err == ""


def test_captured_stderr_has_whole_lines_only():
    """stderr to a pipe: no carriage returns, every line ends with a newline; a slow loop
    gives one line at its end, before the next message."""
    import subprocess
    import sys

    code = ("import sys, time\n"
            "from pipeline.progress import progress\n"
            "for _ in progress(range(4), 'slow', after=0.1):\n"
            "    time.sleep(0.05)\n"
            "print('next message', file=sys.stderr)\n")
    p = subprocess.run([sys.executable, "-c", code], capture_output=True, text=False)
    err = p.stderr.decode()
    assert p.returncode == 0 and "\r" not in err and err.endswith("\n")
    first, second = err.splitlines()
    assert first.startswith("slow: 4 done in ") and second == "next message"


def test_figure_drawing_reports_the_figures_written(tmp_path, capsys):
    """Four drawings of 0.3 s each, drawn in turn (1.2 s, over the 1 s REPORT_AFTER): the
    queue reports the four files as they appear, in one line when stderr is captured;
    a queue without show_progress says nothing."""
    from pipeline.viz.figure_queue import FigureQueue

    def job(path):
        def draw():
            time.sleep(0.3)
            path.write_bytes(b"png")
            return path
        return draw

    for show, folder in ((True, tmp_path / "a"), (False, tmp_path / "b")):
        folder.mkdir()
        queue = FigureQueue()
        for i in range(4):
            queue.add(folder / f"f{i}.png", job(folder / f"f{i}.png"))
        queue.draw_all(workers=1, show_progress=show)
        assert sorted(p.name for p in folder.iterdir()) == [f"f{i}.png" for i in range(4)]
        err = capsys.readouterr().err
        if show:
            assert err.startswith("figures drawn: 4 done in ") and err.count("\n") == 1
        else:
            assert err == ""


def test_steps_keep_timings_and_report_slow_steps(capsys):
    """Every step's wall time is kept (summed over repeats); a step that reaches the
    reporting threshold is announced and its end printed on stderr, a quicker one is
    not; a disabled reporter prints nothing; stdout stays empty."""
    steps = Steps("fe3d test", after=0.0)
    with steps.step("mesh"):
        pass
    with steps.step("mesh"):
        pass
    quiet = Steps("fe3d quiet", after=3600.0)
    with quiet.step("solve"):
        quiet.advance("solve", 1, 2)
    silent = Steps("fe3d silent", enabled=False, after=0.0)
    with silent.step("factorise"):
        pass
    out = capsys.readouterr()
    assert out.out == ""
    assert set(steps.timings) == {"mesh"} and steps.timings["mesh"] >= 0.0
    assert set(quiet.timings) == {"solve"} and set(silent.timings) == {"factorise"}
    assert out.err.count("[fe3d test] mesh: ") == 2
    assert "quiet" not in out.err and "silent" not in out.err


def test_a_run_step_list_names_every_step_with_its_cache_hit_and_result(capsys):
    """every_step: each step's line when it ends, however short, with "(from the cache)"
    and its note's text; an announced step says so at once; the summary adds the times."""
    log = Steps("gearpipe run", after=3600.0, every_step=True)
    with log.step("geometry"):
        pass
    with log.step("loaded contact (fe2d)", announce=True) as note:
        note["cached"] = True
        note["text"] = "60 positions"
    lines = capsys.readouterr().err.splitlines()
    assert lines[0].startswith("[gearpipe run] geometry: ") and lines[0].endswith(" s")
    assert lines[1] == "[gearpipe run] loaded contact (fe2d) ..."
    assert lines[2].startswith("[gearpipe run] loaded contact (fe2d): ")
    assert lines[2].endswith(" s (from the cache), 60 positions") and len(lines) == 3
    s = log.summary()
    assert s["from_cache"] == ["loaded contact (fe2d)"]
    assert s["total_s"] == pytest.approx(sum(s["steps_s"].values()))
