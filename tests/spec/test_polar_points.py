"""Polar data (format 1.1): anywhere a point [x, y] is written, {r: R, angle: A} may be
written instead, R in the length unit and A in degrees from the frame's x-axis."""
from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

import mechreport
from mechreport.errors import SpecError
from mechreport.spec import parse_spec

ROOT = Path(__file__).resolve().parents[2]
SLIDER = (ROOT / "specs" / "slider_crank.yaml").read_text(encoding="utf-8")
FOUR_BAR = (ROOT / "specs" / "four_bar.yaml").read_text(encoding="utf-8")


def test_points_on_the_axes_in_polar_form_are_exactly_the_cartesian_ones():
    polar = (SLIDER.replace("points: {A: [0, 0], B: [1, 0]}",
                            "points: {A: [0, 0], B: {r: 1, angle: 0}}")
             .replace("assembly: {C: [1.4, 0]}", "assembly: {C: {r: 1.4, angle: 0}}")
             .replace("  O: [0, 0]\n", "  O: {r: 0, angle: 90}\n"))
    assert polar.count("angle: ") >= 3
    a, b = mechreport.analyse(SLIDER), mechreport.analyse(polar)
    assert a.spec.links == b.spec.links and a.spec.assembly == b.spec.assembly
    for m in a.forces:
        np.testing.assert_array_equal(a.forces[m].driver_torque, b.forces[m].driver_torque)
    assert b.passed


def test_a_ground_point_at_an_angle_gives_the_same_results_to_rounding():
    spec = parse_spec(FOUR_BAR, "f.yaml")
    name, (x, y) = next((n, p) for n, p in spec.ground.items() if p != (0.0, 0.0))
    r, angle = math.hypot(x, y), math.degrees(math.atan2(y, x))
    unit_scale = {"m": 1.0, "mm": 1e-3, "cm": 1e-2}[spec.units["length"]]
    old = next(line for line in FOUR_BAR.splitlines() if line.strip().startswith(f"{name}:"))
    new = old.split(":")[0] + f": {{r: {r / unit_scale!r}, angle: {angle!r}}}"
    polar = FOUR_BAR.replace(old, new)
    assert polar != FOUR_BAR
    a, b = mechreport.analyse(FOUR_BAR), mechreport.analyse(polar)
    np.testing.assert_allclose(b.forces["dyad"].driver_torque,
                               a.forces["dyad"].driver_torque, rtol=1e-12, atol=1e-12)
    assert b.passed == a.passed


@pytest.mark.parametrize("value, message", [
    ("{r: -1, angle: 0}", "not negative"),
    ("{r: 1}", "missing required key 'angle'"),
    ("{r: 1, angle: 0, z: 2}", "unknown key"),
])
def test_a_bad_polar_point_is_an_error_at_its_key(value, message):
    text = SLIDER.replace("points: {A: [0, 0], B: [1, 0]}", f"points: {{A: [0, 0], B: {value}}}")
    with pytest.raises(SpecError) as info:
        parse_spec(text, "x.yaml")
    assert any(p.path.startswith("links.crank.points.B") and message in p.message
               for p in info.value.problems), info.value.problems
