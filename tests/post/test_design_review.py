"""The design review: `design:`, load names and `reacts_on`, angle-less `expect` entries for
cycle quantities, verdicts and `mechreport check` failing on a missed one."""
from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from mechreport.pipeline.analysis import analyse
from mechreport.errors import SpecError
from mechreport.post import Verdict, frame_load
from mechreport.spec import parse_spec

ROOT = Path(__file__).resolve().parents[2]
SLIDER_CRANK = (ROOT / "specs" / "slider_crank.yaml").read_text().split("expect:")[0]
FOUR_BAR = ROOT / "specs" / "four_bar.yaml"
OVER = ROOT / "tests" / "data" / "edge" / "four_bar_over_limits.yaml"


def messages(text: str) -> list[str]:
    with pytest.raises(SpecError) as info:
        parse_spec(text, "x.yaml")
    return [f"{p.path}: {p.message}" for p in info.value.problems]


def with_design(design: str, extra: str = "") -> str:
    return SLIDER_CRANK + "design:\n" + design + extra


def test_design_section_is_validated_with_key_paths():
    got = messages(with_design("  motor: {rated_torque: -3, peak: 5}\n"
                               "  bearings: {Z: {rating: 100}, B: {life_h: 10}}\n"
                               "  limits: {transmission_angle: 120}\n  flywheel: 1\n"))
    assert "design.flywheel: unknown key; allowed: speed_fluctuation, motor, bearings, " \
           "limits" in got
    assert "design.motor.rated_torque: must be a positive number, got -3" in got
    assert "design.motor.peak: unknown key; allowed: rated_torque, peak_torque, " \
           "rated_power" in got
    assert any(m.startswith("design.bearings.Z: no joint named 'Z'") for m in got)
    assert "design.bearings.B: missing required key 'rating'" in got
    assert any(m.startswith("design.limits.transmission_angle: must be at most 90") for m in got)


def test_cycle_quantities_have_no_angle_and_others_need_one():
    text = SLIDER_CRANK + ("expect:\n  - {angle: 45, quantity: cycle.torque.rms, value: 1}\n"
                           "  - {quantity: driver.torque, value: 1}\n"
                           "  - {quantity: cycle.torque.rsm, value: 1}\n")
    got = messages(text)
    assert got[0].startswith("expect[0].angle: 'cycle.torque.rms' is a cycle quantity")
    assert got[1].startswith("expect[1]: missing required key 'angle'")
    assert got[2] == ("expect[2].quantity: 'cycle.torque.rsm' is not a cycle quantity; did you "
                      "mean 'cycle.torque.rms'?")


def test_cycle_quantity_without_a_whole_turn_is_an_error():
    text = SLIDER_CRANK.replace("sweep: {start: 0, stop: 360, step: 1}",
                                "sweep: {start: 0, stop: 180, step: 1}")
    got = messages(text + "expect:\n  - {quantity: cycle.torque.rms, value: 1}\n"
                          "design:\n  limits: {shaking_force: 10}\n")
    assert got == ["expect[0]: 'cycle.torque.rms' is undefined: cycle quantities need a sweep "
                   "over one whole turn of the crank; this one runs from 0 to 180 deg",
                   "design: the design review is undefined: cycle quantities need a sweep over "
                   "one whole turn of the crank; this one runs from 0 to 180 deg"]


def test_flywheel_and_life_need_their_design_inputs():
    got = messages(SLIDER_CRANK + "expect:\n  - {quantity: cycle.flywheel_inertia, value: 1}\n"
                                  "  - {quantity: joint.A.life_h, value: 1}\n")
    assert got[0].startswith("expect[0]: 'cycle.flywheel_inertia' needs "
                             "design.speed_fluctuation")
    assert got[1].startswith("expect[1]: 'joint.A.life_h' needs design.bearings.A.rating")


def test_load_names_differ_and_reacts_on_is_ground():
    text = SLIDER_CRANK.replace(
        "  - {type: force, link: slider, point: C, value: [100, 0], oppose: velocity}",
        "  - {type: force, link: slider, point: C, value: [100, 0], name: gas}\n"
        "  - {type: moment, link: crank, value: 1, name: gas, reacts_on: frame}")
    got = messages(text)
    assert got[0].startswith("loads[1].name: 'gas' is the name of loads[0] too")
    assert got[1] == "loads[1].reacts_on: must be one of ground, got 'frame'"


def test_a_load_that_reacts_on_ground_leaves_the_shaking_force():
    """The frame receives the load's reaction -F: the shaking force differs by exactly -F."""
    base = analyse(parse_spec(SLIDER_CRANK, "a.yaml"))
    grounded = analyse(parse_spec(SLIDER_CRANK.replace("oppose: velocity}",
                                                       "oppose: velocity, reacts_on: ground}"),
                                  "b.yaml"))
    f0 = frame_load(base.kinematics, base.forces["newton_euler"], base.loads)
    f1 = frame_load(grounded.kinematics, grounded.forces["newton_euler"], grounded.loads)
    (load,) = base.loads
    np.testing.assert_allclose(f1.fx - f0.fx, -load.force[:, 0], atol=1e-9)
    np.testing.assert_allclose(f1.fy - f0.fy, -load.force[:, 1], atol=1e-9)
    # the gas force's moment about the pivot is zero (on the line y = 0 through A)
    np.testing.assert_allclose(f1.m, f0.m, atol=1e-9)


def test_verdict_passes_on_equality_and_gives_its_margin():
    upper = Verdict("limits.shaking_force", "cycle.shaking.force_max", 200.0, 200.0, "N")
    lower = Verdict("limits.transmission_angle", "cycle.transmission_angle.min", 36.0, 40.0,
                    "deg", at_least=True)
    assert upper.passed and upper.margin == 0
    assert not lower.passed and lower.margin == pytest.approx(-0.1)
    assert lower.describe() == ("limits.transmission_angle: cycle.transmission_angle.min = 36 "
                                "deg < limit 40 deg")


def test_every_design_item_of_the_four_bar_is_a_verdict_and_passes():
    a = analyse(FOUR_BAR)
    items = [v.item for v in a.verdicts]
    assert items == ["motor.rated_torque", "motor.peak_torque", "motor.rated_power",
                     "bearings.A.life_h", "bearings.D.life_h", "limits.joint_force",
                     "limits.transmission_angle", "limits.shaking_force"]
    assert all(v.passed for v in a.verdicts) and a.passed
    # the joint that sets the largest joint force is named
    force = next(v for v in a.verdicts if v.item == "limits.joint_force")
    assert force.where in {j.name for j in a.spec.joints}
    assert force.value == max(a.review.bearings[j].f_max for j in a.review.bearings)


def test_check_fails_naming_every_missed_verdict():
    out = subprocess.run([sys.executable, "-m", "mechreport", "check", str(OVER)],
                         capture_output=True, text=True, cwd=ROOT)
    assert out.returncode == 1
    missed = [l.strip() for l in out.stdout.splitlines() if "design verdict missed" in l]
    assert [m.split(": ")[1] for m in missed] == ["motor.rated_torque", "motor.rated_power",
                                                  "bearings.D.life_h", "limits.shaking_force"]
    assert "cycle.torque.rms = 2.278 N·m > limit 2 N·m" in missed[0]
    assert "8 design verdict(s) (4 missed)" in out.stdout
