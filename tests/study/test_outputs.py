"""The one cell writer of the study's CSV files (study.csv, tolerance.csv, the optimiser's
history.csv): numbers in their shortest exact form, undefined values as empty cells."""
from __future__ import annotations

import math

import numpy as np

from mechreport.study.outputs import TRI, csv_cell


def test_numbers_are_written_exactly_and_undefined_values_empty():
    assert [csv_cell(x) for x in (-10.0, np.float64(0.125), 1e20, 0.1)] == \
        ["-10", "0.125", "1e+20", "0.1"]
    assert [csv_cell(x) for x in (None, math.nan, np.inf, -math.inf)] == ["", "", "", ""]
    assert csv_cell("no assembly") == "no assembly"


def test_a_pass_fail_cell_is_true_false_or_empty():
    assert [TRI[k] for k in (1, 0, -1)] == ["true", "false", ""]
