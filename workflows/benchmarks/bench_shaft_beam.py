"""Benchmark: the Timoshenko beam shaft model at the demo pair's size (not a test).

A straddle-mounted pinion shaft of the demo pair's size (face width 20 mm, seat of
diameter 60 mm, journals of 40 mm, bearings 120 mm apart, coupling at the end) with a rigid
hub and elastic bearings. Timed, best of several repeats:

* building the model (nodes, vectorised assembly, constraints, the sparse LU factor);
* one static solve under the mesh's line load as 20 point loads across the face (the
  solve builds the model again with nodes at the loads);
* the same with the model built once with those nodes (what the contact coupling does);
* the 120 x 120 flexibility of the 20 face points and the 6 x 6 seat stiffness.

Prints the figures (milliseconds).
"""

from __future__ import annotations

import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT))

import numpy as np  # noqa: E402

from pipeline.shaft.beam import BeamShaft  # noqa: E402
from pipeline.shaft.layout import Bearing, ShaftLayout, ShaftSegment  # noqa: E402
from pipeline.shaft.model import PointLoad  # noqa: E402


def demo_layout() -> ShaftLayout:
    """The demo pinion's shaft (dimensions in the module docstring), m."""
    segs = (ShaftSegment(0.0, 0.05, 0.04), ShaftSegment(0.05, 0.13, 0.06),
            ShaftSegment(0.13, 0.22, 0.04))
    return ShaftLayout(segments=segs, gear_position=0.09, seat_width=0.02,
                       bearings=(Bearing(0.03, 5e8, axial=True), Bearing(0.15, 5e8)),
                       torque_position=0.22, hub="rigid", name="pinion.shaft")


def best_ms(fn, repeats: int = 20) -> float:
    """The best wall time of ``repeats`` calls, ms."""
    best = np.inf
    for _ in range(repeats):
        t0 = time.perf_counter()
        fn()
        best = min(best, time.perf_counter() - t0)
    return best * 1e3


def main() -> None:
    layout = demo_layout()
    face = np.linspace(0.08, 0.10, 20)
    loads = [PointLoad(float(z), (0.0, 226.7, 82.5)) for z in face]  # 4.53 kN over 20 points
    model = BeamShaft(layout)
    with_face = BeamShaft(layout, extra_nodes=tuple(face))
    print(f"nodes: {model.z.size} (with the face points {with_face.z.size})")
    print(f"build:                        {best_ms(lambda: BeamShaft(layout)):7.2f} ms")
    print(f"solve, 20 off-node loads:     {best_ms(lambda: model.solve(loads)):7.2f} ms")
    print(f"solve, loads at nodes:        {best_ms(lambda: with_face.solve(loads)):7.2f} ms")
    print(f"flexibility 120 x 120:        {best_ms(lambda: with_face.flexibility(face)):7.2f} ms")
    print(f"seat stiffness 6 x 6:         {best_ms(model.seat_stiffness):7.2f} ms")
    print("seat stiffness diagonal (N/m, N m/rad):",
          np.array2string(np.diag(model.seat_stiffness()), precision=3))


if __name__ == "__main__":
    main()
