"""The turning-moment diagram's areas between the crossings with the mean, against closed
forms: M = M0 + a sin(phi) crosses its mean at 0 and 180 deg, with areas +2a and -2a (the
integral of a sin over half a turn), a largest fluctuation of 2a; M0 + a sin(2 phi) has
four areas of +-a; the largest fluctuation equals max - min of the running integral."""
from __future__ import annotations

import numpy as np
import pytest

from mechreport.post.flywheel import energy_areas, largest_fluctuation


def test_a_sine_has_two_areas_of_two_a():
    angles = np.arange(0.0, 360.0, 0.25) + 0.1          # crossings between grid angles
    torque = 50 + 7 * np.sin(np.radians(angles))
    areas = energy_areas(angles, torque, 50.0, 360.0)
    assert [round(a.start, 6) % 360 for a in areas] == [180.0, 0.0]
    assert [a.energy for a in areas] == pytest.approx([-14, 14], rel=1e-5)
    swing, top, low = largest_fluctuation(areas)
    assert swing == pytest.approx(14, rel=1e-5)
    assert abs(areas[-1].level) < 1e-9


def test_a_double_sine_has_four_areas_and_the_running_integral_s_swing():
    angles = np.arange(0.0, 360.0, 0.5)
    torque = 3 + 2 * np.sin(2 * np.radians(angles + 10))
    areas = energy_areas(angles, torque, 3.0, 360.0)
    assert len(areas) == 4
    assert [abs(a.energy) for a in areas] == pytest.approx([2] * 4, rel=1e-4)   # trapezoids
    swing, _, _ = largest_fluctuation(areas)
    fine = np.linspace(0, 2 * np.pi, 200001)
    running = np.cumsum(2 * np.sin(2 * (fine + np.radians(10)))) * (fine[1] - fine[0])
    assert swing == pytest.approx(np.ptp(running), rel=1e-4)


def test_without_a_crossing_one_area_holds_the_cycle():
    areas = energy_areas(np.arange(0.0, 360.0, 10.0), np.full(36, 5.0), 4.0, 360.0)
    assert len(areas) == 1 and areas[0].energy == pytest.approx(2 * np.pi)
