"""Progress on stderr only for work that lasts: :func:`pipeline.progress.progress` shows no
bar for a loop that ends within its ``after`` seconds and a bar for one that runs longer."""

from __future__ import annotations

import time

from pipeline.progress import REPORT_AFTER, progress


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
