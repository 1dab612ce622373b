"""Coulomb friction in the joints (format 1.1 `friction:`), against closed forms: a journal
(M_f = mu r |F|), a block on a guide (F = mu N), the drawer effect (a slider with a length
jams where the friction's loop gain mu k tan(beta) reaches 1), and the energy balance over a
cycle (the extra input work is the energy the joints dissipate)."""
from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

import mechreport
from mechreport.errors import SpecError
from mechreport.spec import parse_spec

ROOT = Path(__file__).resolve().parents[2]
G = 9.80665

FLYWHEEL = """\
mechreport: 1.1
name: flywheel on a journal
ground: {A: [0, 0]}
links:
  wheel: {points: {A: [0, 0]}, mass: 20, com: [0, 0], inertia: 0.5}
joints:
  A: {type: R, links: [ground, wheel]}
driver: {joint: A, rpm: RPM}
sweep: {start: 0, stop: 360, step: 30}
friction:
  A: {mu: 0.05, radius: 0.02}
"""

BLOCK = """\
mechreport: 1.1
name: block pushed along a guide
ground: {O: [0, 0]}
links:
  block: {points: {P: [0, 0]}, mass: 10, com: [0, 0], inertia: 0}
joints:
  T: {type: T, links: [ground, block], point: P, line: {through: O, direction: 0}}
driver: {joint: T, SPEED}
sweep: {start: 0, stop: 1, step: 0.1}
friction:
  T: {mu: 0.3FRICTION}
"""

# a slider-crank (crank 0.1 m, massless rod 0.2 m) whose rod pushes the slider at C, 0.1 m
# ahead of the slider's point P on a guide 0.1 m long, against 100 N opposing its motion
DRAWER = """\
mechreport: 1.1
name: drawer effect
gravity: [0, 0]
ground: {A: [0, 0], O: [0, 0]}
links:
  crank:  {points: {A: [0, 0], B: [0.1, 0]}, mass: 0}
  rod:    {points: {B: [0, 0], C: [0.2, 0]}, mass: 0}
  slider: {points: {P: [0, 0], C: [0.1, 0]}, mass: 1, com: [0, 0], inertia: 0}
joints:
  A: {type: R, links: [ground, crank]}
  B: {type: R, links: [crank, rod]}
  C: {type: R, links: [rod, slider]}
  S: {type: T, links: [ground, slider], point: P, line: {through: O, direction: 0}}
driver: {joint: A, rpm: 60}
sweep: {start: 0, stop: 360, step: 1}
assembly: {C: [0.3, 0]}
loads:
  - {type: force, link: slider, point: P, value: [100, 0], oppose: velocity}
friction:
  S: {mu: MU, length: 0.1}
"""


@pytest.mark.parametrize("rpm, sign", [(300, 1.0), (-300, -1.0)])
def test_a_journal_takes_mu_r_times_its_load(rpm, sign):
    """A balanced wheel on a journal: the pin carries the weight, so the motor supplies
    M = mu r m g against the rotation, by every method."""
    a = mechreport.analyse(FLYWHEEL.replace("RPM", str(rpm)))
    assert a.passed
    for name, res in a.forces.items():
        np.testing.assert_allclose(res.driver_torque, sign * 0.05 * 0.02 * 20 * G,
                                   rtol=1e-12, err_msg=name)
        if res.reactions:
            np.testing.assert_allclose(res.reactions["A"].friction,
                                       -sign * 0.05 * 0.02 * 20 * G, rtol=1e-12)


def test_a_block_on_a_guide_is_pushed_with_mu_times_its_weight():
    a = mechreport.analyse(BLOCK.replace("SPEED", "speed: 0.5").replace("FRICTION", ""))
    assert a.passed
    for name, res in a.forces.items():
        np.testing.assert_allclose(res.driver_torque, 0.3 * 10 * G, rtol=1e-12, err_msg=name)


@pytest.mark.parametrize("sense, push", [("", 0.0), (", friction_sense: 1", 0.3 * 10 * G),
                                         (", friction_sense: -1", -0.3 * 10 * G)])
def test_at_rest_friction_acts_only_where_the_spec_says_which_way_it_is_about_to_move(
        sense, push):
    a = mechreport.analyse(BLOCK.replace("SPEED", "speed: 0").replace("FRICTION", sense))
    assert a.passed and not a.flags
    for name, res in a.forces.items():
        np.testing.assert_allclose(res.driver_torque, push, atol=1e-12, err_msg=name)


def test_the_drawer_effect_jams_the_slider_where_the_loop_gain_reaches_one():
    """The rod's force F at angle beta to the guide, applied 0.1 m ahead of the slider's
    point: N = F sin(beta), M = 0.1 N, so the ends carry N/2 -/+ M/L and the friction is
    mu k |N| with k = 2 x 0.1 / 0.1 = 2; F cos(beta) = Q + mu k F |sin(beta)| has a
    determined solution only while mu k |tan(beta)| < 1, with sin(beta) = (0.1/0.2) sin(phi)."""
    mu = 0.9
    a = mechreport.analyse(DRAWER.replace("MU", str(mu)))
    phi = np.radians(np.arange(360.0))
    sb = 0.5 * np.sin(phi)
    gain = mu * 2 * np.abs(sb / np.sqrt(1 - sb**2))
    jammed = sorted(f.angle for f in a.flags if f.reason.startswith("self-locking"))
    assert jammed == list(np.arange(360.0)[gain >= 1])
    assert jammed and all(a.kinematics.index_of(x) is None for x in jammed)
    stopped = sorted(f.angle for f in a.flags if "undetermined" in f.reason)
    assert stopped == [0.0, 180.0]            # the slider reverses there
    assert a.passed


def test_without_length_a_slider_jams_only_beyond_the_friction_angle():
    """With no length, the friction is mu |N|: the loop gain is mu |tan(beta)|, below 1 for
    beta up to 30 degrees and mu = 0.9: nothing jams."""
    a = mechreport.analyse(DRAWER.replace("MU", "0.9").replace(", length: 0.1", ""))
    assert not [f for f in a.flags if f.reason.startswith("self-locking")]
    assert a.passed


def test_mu_zero_reproduces_the_frictionless_results_bit_for_bit():
    plain = (ROOT / "specs" / "four_bar.yaml").read_text(encoding="utf-8")
    rubbed = plain.replace("\ndesign:", "\nfriction:\n  A: {mu: 0, radius: 10}\n"
                           "  B: {mu: 0, radius: 8}\n\ndesign:", 1)
    assert "friction:" in rubbed
    a, b = mechreport.analyse(plain), mechreport.analyse(rubbed)
    np.testing.assert_array_equal(a.angles, b.angles)
    for name in a.forces:
        np.testing.assert_array_equal(a.forces[name].driver_torque,
                                      b.forces[name].driver_torque)
        for j, r in a.forces[name].reactions.items():
            np.testing.assert_array_equal(r.fx, b.forces[name].reactions[j].fx)
    assert a.review.values == b.review.values


def test_the_extra_input_work_over_a_cycle_is_the_energy_the_joints_dissipate():
    """Over a turn at constant speed the kinetic and potential energies come back: the
    driver's extra work with friction, integral of (M - M0) dphi, equals the energy lost,
    which is also integrated here independently from each joint's friction and its relative
    rate (trapezoids over the cycle grid)."""
    plain = (ROOT / "specs" / "four_bar.yaml").read_text(encoding="utf-8")
    # (not in C: the coupler and the rocker turn together where the crank lies along the
    # frame, at 0 and 180 deg, which would be left out: friction's direction flips there)
    rubbed = plain.replace("\ndesign:", "\nfriction:\n  A: {mu: 0.08, radius: 10}\n"
                           "  B: {mu: 0.08, radius: 8}\n  D: {mu: 0.08, radius: 10}\n"
                           "\ndesign:", 1)
    a, b = mechreport.analyse(plain), mechreport.analyse(rubbed)
    assert not b.flags and b.worst.relative < 1e-9     # (its design verdicts may change)
    step = np.radians(1.0)
    extra = np.sum(b.forces["newton_euler"].driver_torque
                   - a.forces["newton_euler"].driver_torque) * step
    kin = b.kinematics
    omega = b.spec.driver.omega
    lost = 0.0
    for joint, m in kin.friction.items():
        first, second = b.spec.joint(joint).links
        rel = kin.omega[:, kin.index(second)] - kin.omega[:, kin.index(first)]
        lost += np.sum(np.abs(m * rel)) / omega * step        # J: power / omega dphi
    energy = b.review.values["cycle.friction.energy"]
    assert energy == pytest.approx(lost, rel=1e-10)
    assert extra == pytest.approx(lost, rel=1e-9)
    work_in = np.sum(np.maximum(b.forces["newton_euler"].driver_torque, 0)) * step
    assert b.review.values["cycle.efficiency"] == pytest.approx(1 - lost / work_in, rel=1e-10)
    assert 0 < b.review.values["cycle.efficiency"] < 1


def test_every_method_includes_friction_and_the_power_balance_checks_it():
    plain = (ROOT / "specs" / "offset_slider_crank.yaml").read_text(encoding="utf-8")
    rubbed = plain.replace("\nloads:", "\nfriction:\n  A: {mu: 0.05, radius: 12}\n"
                           "  B: {mu: 0.05, radius: 10}\nloads:", 1)
    assert "friction:" in rubbed
    a = mechreport.analyse(rubbed)
    ref = a.forces["newton_euler"].driver_torque
    scale = np.max(np.abs(ref))
    for name, res in a.forces.items():
        np.testing.assert_allclose(res.driver_torque, ref, rtol=0, atol=1e-9 * scale,
                                   err_msg=name)
    assert a.worst.relative < 1e-9


@pytest.mark.parametrize("entry, path, words", [
    ("  A: {mu: 0.1}\n", "friction.A", "radius"),
    ("  A: {mu: -0.1, radius: 0.01}\n", "friction.A.mu", "0 or more"),
    ("  A: {mu: 0.1, radius: 0.01, length: 0.1}\n", "friction.A.length", "unknown key"),
    ("  Z: {mu: 0.1, radius: 0.01}\n", "friction.Z", "no joint named 'Z'"),
    ("  A: {mu: 0.1, radius: 0.01, friction_sense: 2}\n", "friction.A.friction_sense",
     "+1 or -1"),
])
def test_friction_mistakes_are_reported_where_they_are(entry, path, words):
    text = FLYWHEEL.replace("RPM", "300")
    text = text[:text.index("friction:")] + "friction:\n" + entry
    with pytest.raises(SpecError) as info:
        parse_spec(text, "f.yaml")
    found = [p for p in info.value.problems if p.path == path]
    assert found and words in found[0].message, info.value.problems


def test_friction_at_a_pin_joining_several_links_rubs_in_each_links_bearing():
    """`friction: {C: ...}` for a pin joining three links puts a journal in each of its
    two-link joints (the bearing of each link on the pin); every method agrees."""
    text = (ROOT / "tests" / "data" / "compound_pin_six_bar.yaml").read_text(encoding="utf-8")
    a = mechreport.analyse(text + "friction:\n  C: {mu: 0.1, radius: 8}\n")
    assert [fr.joint for fr in a.spec.friction] == ["C.on.rocker", "C.on.rod"]
    assert a.worst.relative < 1e-9
    frictionless = mechreport.analyse(text)
    common = np.isin(frictionless.angles, a.angles)
    extra = (a.forces["newton_euler"].driver_torque
             - frictionless.forces["newton_euler"].driver_torque[common])
    assert np.any(np.abs(extra) > 1e-6)
    for name, res in a.forces.items():
        if res.reactions:
            law = 0.1 * 0.008 * res.reactions["C.on.rod"].f
            np.testing.assert_allclose(np.abs(res.reactions["C.on.rod"].friction), law,
                                       rtol=1e-12, err_msg=name)
