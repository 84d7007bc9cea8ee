"""The study's sensitivity figure: one row of panels per KPI asked for, however many."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from pipeline.study.kpis import KPIS, kpi_label
from pipeline.study.plots import plot_sensitivity
from pipeline.study.points import design_points
from pipeline.study.spec import study_from_file

ROOT = Path(__file__).resolve().parents[1]
BASE = ROOT / "workflows" / "configs" / "spur_pair_assembly_errors.toml"


def test_sensitivity_has_one_panel_row_per_kpi_asked_for(tmp_path):
    """Twelve KPIs over two axes: 12 x 2 panels, row i labelled with KPI i, each panel's
    line the KPI's values through the reference point (a study used to keep the first
    four)."""
    f = tmp_path / "s.toml"
    f.write_text(f'base = "{BASE}"\n[[axes]]\nkey = "contact.tip_relief_pinion_um"\n'
                 'range = [0.0, 20.0]\npoints = 3\n[[axes]]\nkey = "operation.torque_Nm"\n'
                 'values = [200.0, 340.0]\n')
    spec = study_from_file(f)
    points = design_points(spec)
    kpis = [k.name for k in KPIS if k.needs in ("contact", "root_stress")]
    assert len(kpis) == 12
    table: dict[str, list] = {"point": [p.index for p in points]}
    for a in spec.axes:
        table[a.label] = [p.values[a.label] for p in points]
    for j, k in enumerate(kpis):
        table[k] = [float(j * 100 + p.index) for p in points]
    fig = plot_sensitivity(spec, table, kpis)
    axs = np.array(fig.axes).reshape(len(kpis), 2)
    for i, k in enumerate(kpis):
        assert [ax.get_ylabel() for ax in axs[i]] == [kpi_label(k)] * 2
        # through the reference point: the base torque (340 N m) and, the base file giving
        # no relief, the middle relief (10 um); point = 2 x relief index + torque index
        y_relief = axs[i, 0].lines[0].get_ydata()
        y_torque = axs[i, 1].lines[0].get_ydata()
        assert list(y_relief) == [i * 100 + 1.0, i * 100 + 3.0, i * 100 + 5.0]
        assert list(y_torque) == [i * 100 + 2.0, i * 100 + 3.0]
