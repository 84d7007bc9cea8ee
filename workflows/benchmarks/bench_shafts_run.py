"""Benchmark: what the shafts add to a warm run (not a test).

``workflows/configs/shaft_straddle_pinion.toml`` (the demo pair, its pinion cut on a
straddle-mounted shaft, the gear on an output shaft, with the dynamics: the shafts' supports
and torsion to a motor and a driven machine, and the comparison on rigid supports) and the
same file without the shafts, each run twice in this
process on one cache (the second, warm run timed): the run's stages without the writing,
the shafts' step (the fixed point of the contact with the beam shaft), and the ratio.
Then the 3D superelement of the pinion's shaft, cold (a new cache) and warm. Prints the
figures with the breakdown and writes them to ``results/bench_shafts_run.json``.
"""

from __future__ import annotations

import json
import sys
import tempfile
import time
import warnings
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT))

from pipeline.cache.folder import Cache  # noqa: E402
from pipeline.config import load_gearbox  # noqa: E402
from pipeline.config.gearbox import gearbox_from_text  # noqa: E402
from pipeline.run.chain import RunOptions  # noqa: E402
from pipeline.run.runner import run_pipeline  # noqa: E402


def _warm(box, cache: Cache) -> tuple[float, dict]:
    opts = RunOptions(show_progress=False, cache=cache)
    run_pipeline(box, opts)
    t = time.perf_counter()
    r = run_pipeline(box, opts)
    return time.perf_counter() - t, r.log.summary()["steps_s"]


def _without_shafts(text: str) -> str:
    """The example without its shafts (and the motor and machine behind them)."""
    for table, after in (("[pinion.shaft]", "[gear]"), ("[gear.shaft]", "[operation]")):
        text = text[:text.index(table)] + text[text.index(after):]
    return "\n".join(line for line in text.splitlines()
                     if not line.startswith(("drive_inertia", "load_inertia"))) + "\n"


def main() -> int:
    warnings.simplefilter("ignore")
    path = ROOT / "workflows/configs/shaft_straddle_pinion.toml"
    with_shaft = load_gearbox(path)
    text = path.read_text()
    without = gearbox_from_text(_without_shafts(text), "no_shaft")
    cache = Cache(Path(tempfile.mkdtemp()))
    t_without, _ = _warm(without, cache)
    t_with, steps = _warm(with_shaft, cache)
    shaft_step = steps.get("shaft deflection and loaded contact", float("nan"))
    # the pinion's shaft as the 3D superelement (the gear's stays a beam)
    fe3d = gearbox_from_text(text.replace('model = "beam"', 'model = "fe3d"', 1), "fe3d")
    cold_cache = Cache(Path(tempfile.mkdtemp()))
    t = time.perf_counter()
    run_pipeline(fe3d, RunOptions(show_progress=False, cache=cold_cache))
    t_fe3d_cold = time.perf_counter() - t
    t_fe3d_warm, steps3 = _warm(fe3d, cold_cache)
    out = {
        "warm_run_without_shaft_s": t_without, "warm_run_with_beam_shaft_s": t_with,
        "added_by_the_beam_shaft_s": t_with - t_without, "ratio": t_with / t_without,
        "beam_shaft_step_s": shaft_step,
        "run_with_fe3d_shaft_cold_s": t_fe3d_cold, "run_with_fe3d_shaft_warm_s": t_fe3d_warm,
        "fe3d_shaft_step_warm_s": steps3.get("shaft deflection and loaded contact"),
    }
    for k, v in out.items():
        print(f"{k:36s} {v:.3f}")
    target = ROOT / "results" / "bench_shafts_run.json"
    target.parent.mkdir(exist_ok=True)
    target.write_text(json.dumps(out, indent=2) + "\n")
    print(f"written to {target}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
