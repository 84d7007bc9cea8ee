"""Figures say what they show: units in the labels match the plotted numbers, nothing is cut.

Checked from the data the figures hold (lines, bars, labels, limits), not from pixels.
"""

from __future__ import annotations

from types import SimpleNamespace

import numpy as np
import pytest
from helpers import load_workflow
from matplotlib.backends.backend_agg import FigureCanvasAgg

from pipeline.viz.stiffness import plot_friction_coefficients, plot_stiffness_curves
from pipeline.viz.units import STIFFNESS_UNIT, stiffness_in_plot_unit, stiffness_label


def test_stiffness_unit_is_N_per_um():
    assert STIFFNESS_UNIT == "N/um"
    assert stiffness_in_plot_unit(3.2e8) == pytest.approx(320.0)
    assert stiffness_label() == "mesh stiffness [N/um]"


def test_stiffness_curves_are_drawn_in_N_per_um():
    x = np.linspace(0.0, 7.2, 5)
    k = np.array([3.1e8, 3.2e8, 4.4e8, 4.5e8, 3.1e8])
    ax = plot_stiffness_curves([("a", x, k)])
    assert ax.get_ylabel() == "mesh stiffness [N/um]"
    assert ax.lines[0].get_ydata() == pytest.approx(k / 1e6)
    fig = plot_friction_coefficients(x, 2e6 * np.ones(5), np.ones(5), np.ones(5))
    assert fig.axes[0].get_ylabel() == "friction stiffness K_f [N/um]"
    assert fig.axes[0].lines[0].get_ydata() == pytest.approx(2.0 * np.ones(5))


NO_TIP = dict(point_corner=np.zeros(0, int), point_position=np.zeros(0, int),
              point_pair=np.zeros(0, int), point_load=np.zeros(0), load=1.0)
"""Point arrays of a cycle without tip contact (the contact-cycle figure reads them)."""


def test_contact_cycle_stiffness_in_N_per_um():
    from pipeline.viz.contact import plot_contact_cycle

    n = 4
    cyc = SimpleNamespace(pinion_angle=np.linspace(0, 0.1, n), mesh_stiffness=np.full(n, 3e8),
                          mesh_stiffness_secant=np.full(n, 2.9e8),
                          transmission_error=np.full(n, 1e-6), pair_index=(0,),
                          pair_loads=np.ones((n, 1)), load_share=np.ones((n, 1)), **NO_TIP)
    fig = plot_contact_cycle(cyc, np.full(n, 3.1e8), "t")
    ax = fig.axes[0]
    assert ax.get_ylabel() == "mesh stiffness [N/um]"
    assert [line.get_ydata()[0] for line in ax.lines] == pytest.approx([300.0, 290.0, 310.0])


def test_fe3d_workflow_plot_labels_match_its_numbers():
    """The workflow's stiffness axis said N/um but showed kN/um (1e-9 scaling)."""
    wf = load_workflow("fe3d_helical_stiffness")
    cyc = SimpleNamespace(mesh_stiffness=np.array([1.1e9, 1.2e9]),
                          transmission_error=np.array([1e-6, 2e-6]))
    fig = wf.plot(np.array([0.0, 1.0]), {"slice": cyc}, "t")
    assert fig.axes[0].get_ylabel() == "mesh stiffness dP/dx [N/um]"
    assert fig.axes[0].lines[0].get_ydata() == pytest.approx([1100.0, 1200.0])


def test_contact_lines_equal_axes_and_legend_beside_them(helical_traction_pair):
    """The plane of action at equal scale, the legend outside it (it covered the lines)."""
    from pipeline.viz.geometry import plot_contact_lines

    ax = plot_contact_lines(helical_traction_pair)
    fig = ax.figure
    FigureCanvasAgg(fig).draw()
    assert ax.get_aspect() == 1.0
    legend = ax.get_legend().get_window_extent()
    frame = ax.get_window_extent()
    assert legend.x0 > frame.x1  # entirely to the right of the axes
    lo, hi = ax.get_xlim()
    assert lo < helical_traction_pair.s_start * 1e3 and hi > helical_traction_pair.s_end * 1e3


def test_contact_cycle_legend_names_pairs_and_methods_for_a_reader():
    """Tooth pairs counted from 1 in the order they take load (not the internal indices
    -1, 0, 1), an unloaded pair left out, no Python module in the legend."""
    from pipeline.viz.contact import plot_contact_cycle

    n = 4
    loads = np.array([[0.0, 1.0, 0.0, 0.0],   # index -1 loaded from position 1
                      [1.0, 1.0, 0.0, 0.0],   # index 0 loaded from position 0
                      [0.0, 0.0, 0.0, 1.0],   # index 1 loaded from position 3
                      [0.0, 0.0, 0.0, 0.0]]).T  # index 2 never loaded
    cyc = SimpleNamespace(pinion_angle=np.linspace(0, 0.1, n), mesh_stiffness=np.full(n, 3e8),
                          mesh_stiffness_secant=np.full(n, 2.9e8),
                          transmission_error=np.full(n, 1e-6), pair_index=(-1, 0, 1, 2),
                          pair_loads=loads, load_share=loads * np.array([1.0, 2.0, 3.0, 4.0]),
                          **NO_TIP)
    fig = plot_contact_cycle(cyc, np.full(n, 3.1e8), "t")
    labels = [t.get_text() for t in fig.axes[0].get_legend().get_texts()]
    assert labels == ["LTCA tangent dP/dx", "LTCA secant P/x",
                      "analytical (potential energy, slices)"]
    share = fig.axes[2]
    assert [t.get_text() for t in share.get_legend().get_texts()] == [
        "tooth pair 1", "tooth pair 2", "tooth pair 3"]
    # pair 1 is the internal index 0 (column 1), pair 2 index -1, pair 3 index 1
    assert [line.get_ydata().max() for line in share.lines] == [2.0, 1.0, 3.0]


def test_line_of_action_and_contact_line_titles_name_the_case(helical_traction_pair):
    from pipeline.viz.geometry import plot_contact_lines, plot_line_of_action

    ax = plot_contact_lines(helical_traction_pair, name="traction_helical_pair")
    assert ax.get_title() == "traction_helical_pair: contact lines on the plane of action"
    # z is the number of teeth; the face position has its own symbol in every label
    assert ax.get_ylabel() == "face position b_z [mm]"
    fig = plot_line_of_action(helical_traction_pair, name="traction_helical_pair")
    assert fig.get_suptitle().startswith("traction_helical_pair: external pair: eps_alpha = ")
    fig = plot_line_of_action(helical_traction_pair, title="with assembly errors", name="sun")
    assert fig.get_suptitle() == "sun: with assembly errors"
