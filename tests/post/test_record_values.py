"""The pure pieces of the records (issue 42, item 3): JSON values, peaks, largest values."""
from __future__ import annotations

import math

import numpy as np

from mechreport.post.records import jnum, largest, peak_record
from mechreport.post.torque import Peak


def test_jnum_makes_undefined_none_and_round_off_zero():
    assert jnum(None) is None and jnum(math.nan) is None and jnum(math.inf) is None
    assert jnum(1e-12, 100.0) == 0.0 and jnum(-0.0) == 0.0
    assert jnum(3.5, 100.0) == 3.5


def test_a_peak_record_carries_its_unit_and_angle():
    assert peak_record(None, "N") is None
    assert peak_record(Peak(-12.0, 45.0), "N", 1.0) == {"value": -12.0, "unit": "N",
                                                        "angle_deg": 45.0}


def test_largest_is_the_largest_magnitude_and_its_angle():
    angles = np.array([0.0, 10.0, 20.0])
    assert largest(np.array([1.0, -5.0, 3.0]), angles) == (5.0, 10.0)
    assert largest(np.array([math.nan, math.nan, math.nan]), angles) is None
    assert largest(None, angles) is None
