"""The Hertz pressure map covers the whole face width 0..b, not only the slice centres."""

import numpy as np
import pytest
from gearsets import spur
from helpers import UniformSlices
from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.collections import QuadMesh

from pipeline.contact.distribution import load_distribution
from pipeline.contact.ltca import loaded_mesh_cycle
from pipeline.contact.pressure_envelope import to_face_ends
from pipeline.contact.separations import FlankModifications
from pipeline.geometry import GearPair
from pipeline.operation import OperatingPoint
from pipeline.viz.distribution import plot_contact_pressure


def test_to_face_ends_holds_the_end_slices():
    """Slices of width 10 mm on b = 40 mm have centres 5, 15, 25, 35 mm: the map gains z = 0
    with the first slice's values and z = 40 mm with the last one's; the inside is unchanged."""
    z = np.array([5.0, 15.0, 25.0, 35.0]) * 1e-3
    values = np.array([[9.0, 4.0, 3.0, 7.0], [8.0, 2.0, 1.0, 6.0]])
    z_out, v_out = to_face_ends(z, values, 40e-3)
    np.testing.assert_array_equal(z_out, np.array([0.0, 5.0, 15.0, 25.0, 35.0, 40.0]) * 1e-3)
    np.testing.assert_array_equal(v_out, [[9.0, 9.0, 4.0, 3.0, 7.0, 7.0],
                                          [8.0, 8.0, 2.0, 1.0, 6.0, 6.0]])
    one_z, one_v = to_face_ends(np.array([20e-3]), np.array([[5.0]]), 40e-3)
    np.testing.assert_array_equal(one_z, [0.0, 20e-3, 40e-3])
    np.testing.assert_array_equal(one_v, [[5.0, 5.0, 5.0]])


def test_pressure_map_spans_the_face():
    """z 50/50 spur pair, b = 20 mm (tests/gearsets.py), 8 slices of 2.5 mm: both flank
    panels' maps run from z = 0 to 20 mm, and their largest value is the reported maximum."""
    pair = GearPair(spur(50, "pinion"), spur(50, "gear"))
    b_mm = pair.face_width * 1e3
    torque = 150.0
    cyc = loaded_mesh_cycle(UniformSlices(pair, 8, 1.4e10), torque / pair.pinion.base_radius,
                            FlankModifications(), "none", 24)
    dist = load_distribution(cyc, pair, OperatingPoint(torque=torque, speed=100.0))
    assert np.unique(np.round(cyc.point_z, 12)).min() == pytest.approx(b_mm / 16 * 1e-3)
    fig = plot_contact_pressure(cyc, dist, pair, "t")
    FigureCanvasAgg(fig).draw()
    for ax in fig.axes[:2]:
        (mesh,) = [c for c in ax.collections if isinstance(c, QuadMesh)]
        zs = mesh.get_coordinates()[..., 1]
        assert zs.min() == 0.0 and zs.max() == pytest.approx(b_mm, rel=1e-12)
        assert mesh.get_array().max() == pytest.approx(dist.hertz_max.value * 1e-6, rel=1e-9)
