"""The solution sheet's flywheel problem (specs/punching_press.yaml): the turning-moment
diagram's areas between the crossings with the mean sum to zero, the largest energy
fluctuation from them is the design review's (whose extremes are at the analysed angles,
not at the crossings: within the trapezoids' resolution), and I = dE / (Cs omega^2)."""
from __future__ import annotations

import math
from pathlib import Path

import pytest

import mechreport
from mechreport.post.flywheel import energy_areas, largest_fluctuation
from mechreport.report.sheet import build_sheet, render_markdown

ROOT = Path(__file__).resolve().parents[2]


@pytest.fixture(scope="module")
def press():
    return mechreport.analyse(ROOT / "specs" / "punching_press.yaml")


def test_the_flywheel_problem_is_worked_from_the_turning_moment_diagram(press):
    sheet = build_sheet(press)
    assert sheet.flywheel is not None
    text = render_markdown(sheet)
    assert "## Flywheel" in text and "| A1 |" in text
    # the method by its title, as everywhere else in the sheet and the report
    assert "(the Newton-Euler solution at every analysed angle)" in text
    review = press.review.values
    torque = press.forces["newton_euler"].driver_torque
    areas = energy_areas(press.angles, torque, review["cycle.torque.mean"], 360.0)
    swing, _, _ = largest_fluctuation(areas)
    assert abs(areas[-1].level) < 1e-9 * swing
    assert swing == pytest.approx(review["cycle.energy_fluctuation"], rel=2e-3)
    omega = 2 * math.pi                                   # 60 rpm
    inertia = swing / (0.1 * omega ** 2)
    from mechreport.units import fmt
    assert f"= {fmt(inertia)} kg·m²" in text
    simulated = fmt(press.dynamics.values["dynamics.speed_fluctuation"])
    assert f"dynamics.speed\\_fluctuation = {simulated}" in text


def test_no_flywheel_problem_without_a_coefficient_of_speed_fluctuation():
    a = mechreport.analyse(ROOT / "specs" / "slider_crank.yaml")
    assert a.spec.design.speed_fluctuation is None
    assert build_sheet(a).flywheel is None
