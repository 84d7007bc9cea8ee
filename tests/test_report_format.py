"""The report's one number formatter: plain grouped digits for reading, scientific only
outside 1e-3 .. 1e9 (SI Brochure, 9th ed. 2019, 5.4.4 for the thin-space groups)."""

from __future__ import annotations

import math

import pytest

from pipeline.report.model import format_value

S = "\u202f"  # narrow no-break space between digit groups

CASES = [
    (18500.0, f"18{S}500"),             # a torque in N m, was "1.85e+04"
    (-18500.0, f"-18{S}500"),
    (123456.7, f"123{S}500"),           # 4 significant digits, grouped
    (12345678.0, f"12{S}350{S}000"),
    (99995.0, f"100{S}000"),             # rounding carries into a new group
    (9999.0, "9999"),                   # four digits are not grouped
    (3.14159, "3.142"),
    (1.729, "1.729"),
    (1.0, "1"),                         # trailing zeros dropped
    (0.1, "0.1"),
    (0.00123, "0.00123"),
    (0.0, "0"),
    (1.5e-9, "1.500e-09"),              # below 1e-3: scientific
    (0.0009996, "9.996e-04"),
    (2.5e9, "2.500e+09"),               # from 1e9 on: scientific
    (56, "56"),                         # integers exact
    (18500, f"18{S}500"),
    (-1234567, f"-1{S}234{S}567"),
    (True, "yes"),
    (None, "\u2013"),
    (math.nan, "\u2013"),
    ("linear", "linear"),
]


@pytest.mark.parametrize(("value", "text"), CASES)
def test_format_value_rule(value, text):
    assert format_value(value) == text
