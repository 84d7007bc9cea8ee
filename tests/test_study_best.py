"""A study's best design over a load range (``[best] mean_over``) instead of its best point."""

from __future__ import annotations

import math
from pathlib import Path

import pytest

from pipeline.cli.study import best_row, best_row_mean_over
from pipeline.study.execute import check_study
from pipeline.study.spec import study_from_file
from pipeline.validation import InputError

ROOT = Path(__file__).resolve().parents[1]


def test_the_best_relief_over_the_torques_is_not_the_lightest_torque_s_point():
    """Relief 0 / 10 / 20 um x torque 100 / 300 N m. TE p-p (um): relief 0: 1, 9 (mean 5);
    10: 4, 2 (mean 3); 20: 8, 3 (mean 5.5). The best point is relief 0 at 100 N m (1 um),
    the best relief over the load range is 10 um (mean 3 um), reported at 300 N m."""
    relief = [0.0, 0.0, 10.0, 10.0, 20.0, 20.0]
    torque = [100.0, 300.0] * 3
    te = [1.0, 9.0, 4.0, 2.0, 8.0, 3.0]
    t = {"point": list(range(6)), "r": relief, "T": torque, "te": te}
    assert best_row(t, "te", "min") == 0
    row, mean = best_row_mean_over(t, "te", "min", "T", ["r", "T"], 300.0)
    assert (row, mean) == (3, pytest.approx(3.0, abs=1e-15))
    assert best_row_mean_over(t, "te", "max", "T", ["r", "T"], 100.0) == (4, 5.5)
    t["te"][3] = math.nan  # a failed point leaves its design out
    assert best_row_mean_over(t, "te", "min", "T", ["r", "T"], 300.0)[0] == 1


def test_the_example_study_picks_over_its_load_range_and_a_bad_axis_is_one_line(tmp_path):
    spec = study_from_file(ROOT / "workflows" / "configs" / "tip_relief_study.toml")
    assert spec.best_mean_over == "operation.torque_Nm"
    check_study(spec)
    text = (ROOT / "workflows" / "configs" / "tip_relief_study.toml").read_text().replace(
        'mean_over = "operation.torque_Nm"', 'mean_over = "operation.torque"').replace(
        'base = "', f'base = "{ROOT}/workflows/configs/')
    f = tmp_path / "s.toml"
    f.write_text(text)
    with pytest.raises(InputError, match=r"best\.mean_over = 'operation\.torque' is not an "
                                         r"axis of this study; its axes: "
                                         r"contact\.tip_relief_pinion_um, operation\.torque_Nm"):
        check_study(study_from_file(f))
