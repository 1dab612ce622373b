"""profile_at: a load's profile over one cycle, repeating every cycle, phased by its shift
(format 1.2), against values worked by hand."""
from __future__ import annotations

import numpy as np

from mechreport.spec import profile_at

DIAGRAM = ((0.0, 1.0), (180.0, 1.0), (360.0, 60.0), (540.0, 3.0))


def test_values_between_points_and_the_wrap_over_a_720_cycle():
    got = profile_at(DIAGRAM, [0, 90, 270, 450, 630, 720, 810, -90], cycle=720)
    # 630: halfway from (540, 3) to (720 = 0 + cycle, 1); 720 and -90 are 0 and 630 again
    np.testing.assert_allclose(got, [1, 1, 30.5, 31.5, 2, 1, 1, 2])


def test_a_closing_point_at_the_cycle_is_the_wrap_written_out():
    closed = DIAGRAM + ((720.0, 1.0),)
    angles = np.linspace(-720, 1440, 2161)
    np.testing.assert_array_equal(profile_at(closed, angles, 720), profile_at(DIAGRAM, angles, 720))


def test_shift_phases_the_profile():
    angles = np.arange(0.0, 720.0, 7.5)
    for shift in (180.0, 540.0, -90.0, 1000.0):
        np.testing.assert_allclose(profile_at(DIAGRAM, angles, 720, shift),
                                   profile_at(DIAGRAM, angles - shift, 720), atol=1e-12)
    # the peak of cylinder 3 (shift 180) comes 180 degrees after cylinder 1's
    assert profile_at(DIAGRAM, [540.0], 720, 180.0)[0] == 60.0


def test_one_turn_profiles_read_as_in_version_1():
    one = ((0.0, 0.0), (90.0, 10.0))
    np.testing.assert_allclose(profile_at(one, [45, 225, 405, -135]), [5, 5, 5, 5])
    assert profile_at(((30.0, 7.0),), [0, 400]).tolist() == [7.0, 7.0]
