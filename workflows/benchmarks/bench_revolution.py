"""Benchmark: the loaded contact through a revolution on the demo pair (not a test).

The demo pair (z 50/50: the hunting cycle is one revolution, 50 mesh cycles) with the
errors of ``workflows/configs/errors_runout_demo.toml`` (pinion runout 10 um, one proud gear
tooth, tip reliefs), 60 positions per mesh cycle = 3000 contact solves, on the analytical
slice compliance and on the 2D FE compliance of the demo (``compliance = "fe2d"``; its
tables are built once into a temporary cache first and not timed). For each: the source's
build, the revolution (wall time, two runs, the faster kept) and its breakdown from a
profiled run (the per-position setups: candidate points, ``G``, Weber's model, gaps, at
all ``N m`` positions because the runout moves the centre distance each mesh cycle, and
the ``N`` pairs at those centre distances with their tip-contact zones; the ``N m``
solves; recording the loads and pressures), against one mesh cycle of 60 positions.
Prints the figures and writes ``results/benchmarks/revolution.json``.
"""

from __future__ import annotations

import cProfile
import dataclasses
import os
import pstats
import sys
import tempfile
import time
import warnings
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT))

from pipeline.cache.folder import Cache  # noqa: E402
from pipeline.config import load_gearbox  # noqa: E402
from pipeline.contact.analysis import analyse_contact, line_of_action_load  # noqa: E402
from pipeline.contact.compliance import compliance_source  # noqa: E402
from pipeline.contact.revolution import loaded_revolution  # noqa: E402
from pipeline.io import write_json  # noqa: E402
from pipeline.provenance import library_versions  # noqa: E402

PARTS = {  # profile entries (file tail, function) -> part of the breakdown
    "setup per position (points, G, local model, gaps)": (("revolution.py", "_phase"),),
    "pairs at the runout's centre distances": (("revolution.py", "_runout_source"),),
    "contact solves": (("complementarity.py", "solve_contact"),),
    "recording loads and pressures": (("recording.py", "add"), ("recording.py", "cycle")),
}


def _breakdown(run) -> dict[str, float]:
    """Shares of the profiled run's time per part (cumulative times; the rest: the loop)."""
    prof = cProfile.Profile()
    prof.enable()
    run()
    prof.disable()
    stats = pstats.Stats(prof).stats
    total = max(v[3] for v in stats.values())
    out = {}
    for part, keys in PARTS.items():
        out[part] = sum(v[3] for (f, _, name), v in stats.items()
                        if any(f.endswith(t) and name == n for t, n in keys)) / total
    out["the rest (errors' gaps, warm starts, loop)"] = 1.0 - sum(out.values())
    return out


def _case(box, compliance: str, cache: Cache) -> dict:
    contact = dataclasses.replace(box.contact, compliance=compliance)
    pair, op = box.actual_pair, box.operation
    fe = None if compliance == "analytical" else box.fe
    compliance_source(pair, op, contact, box.stiffness, fe, cache=cache)  # FE tables: untimed
    t = time.perf_counter()
    src = compliance_source(pair, op, contact, box.stiffness, fe, cache=cache)
    t_source = time.perf_counter() - t
    load = line_of_action_load(pair, op)

    def run():
        return loaded_revolution(src, load, box.errors, contact.modifications,
                                 contact.local_contact, contact.positions)

    walls = []
    for _ in range(2):
        t = time.perf_counter()
        rev = run()
        walls.append(time.perf_counter() - t)
    t = time.perf_counter()
    analyse_contact(src, op, contact)
    t_cycle = time.perf_counter() - t
    wall = min(walls)
    return {"compliance": compliance, "positions": len(rev), "mesh_cycles": rev.mesh_cycles,
            "source_build_s": t_source, "revolution_s": wall,
            "per_position_ms": wall / len(rev) * 1e3, "mesh_cycle_s": t_cycle,
            "breakdown_share": _breakdown(run),
            "te_peak_to_peak_um": rev.summary()["transmission_error_peak_to_peak_m"] * 1e6}


def main() -> int:
    warnings.simplefilter("ignore")
    box = load_gearbox(ROOT / "workflows/configs/errors_runout_demo.toml")
    cache = Cache(Path(tempfile.mkdtemp()))
    cases = [_case(box, c, cache) for c in ("analytical", "fe2d")]
    for c in cases:
        print(f"{c['compliance']}: {c['positions']} positions ({c['mesh_cycles']} mesh cycles) "
              f"in {c['revolution_s']:.2f} s ({c['per_position_ms']:.2f} ms each; one mesh "
              f"cycle {c['mesh_cycle_s']:.3f} s, source {c['source_build_s']:.3f} s), TE "
              f"{c['te_peak_to_peak_um']:.3g} um p-p")
        for part, share in c["breakdown_share"].items():
            print(f"    {part:48s} {share:6.1%}")
    out = ROOT / "results" / "benchmarks" / "revolution.json"
    out.parent.mkdir(parents=True, exist_ok=True)
    write_json(out, {"cases": cases, "load_average": os.getloadavg(),
                     "cpus": os.cpu_count(), "versions": library_versions()})
    print(f"written to {out}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
