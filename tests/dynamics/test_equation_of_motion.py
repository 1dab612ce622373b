"""The equation of motion (format 1.1 ``dynamics:``) against independent computations: the
generalized inertia from the velocity coefficients, its derivative by finite differences,
energy conservation, a constant-inertia crank's closed form, the energy balance of a steady
turn, and the steady turn's forces against kinetostatic analyses at the same speed."""
from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

import mechreport
from mechreport.dynamics import equation_of_motion, generalized_inertia, simulate
from mechreport.dynamics.motor import RPM, motor_torque
from mechreport.errors import AnalysisError, SpecError
from mechreport.kinematics import at_unit_rate, solve_kinematics
from mechreport.model import build_mechanism
from mechreport.spec import parse_spec

FOUR_BAR = """\
mechreport: 1.1
name: four-bar on a motor
units: {{length: mm, mass: kg}}
gravity: {gravity}
ground: {{A: [0, 0], D: [200, 0]}}
links:
  crank:   {{points: {{A: [0, 0], B: [50, 0]}}, mass: 0.4, com: [20, 5], inertia: 1.0e-4}}
  coupler: {{points: {{B: [0, 0], C: [180, 0]}}, mass: 1.2, com: [90, 10], inertia: 3.0e-3}}
  rocker:  {{points: {{D: [0, 0], C: [120, 0]}}, mass: 0.8, com: [60, 0], inertia: 1.0e-3}}
joints:
  A: {{type: R, links: [ground, crank]}}
  B: {{type: R, links: [crank, coupler]}}
  C: {{type: R, links: [coupler, rocker]}}
  D: {{type: R, links: [ground, rocker]}}
driver: {{joint: A, rpm: 300}}
sweep: {{start: 0, stop: 360, step: {step}}}
at: [30, 210]
assembly: {{C: [196, 120]}}
loads: {loads}
dynamics: {dynamics}
"""
DAMPER = "[{type: damper, between: [[coupler, C], [ground, A]], damping: 40, name: damper}]"


def four_bar(dynamics: str, loads: str = "[]", gravity: str = "[0, -9.80665]",
             step: float = 1) -> str:
    return FOUR_BAR.format(dynamics=dynamics, loads=loads, gravity=gravity, step=step)


def equation(text: str):
    spec = parse_spec(text, "dyn.yaml")
    mech = build_mechanism(spec)
    return spec, mech, equation_of_motion(mech)


def test_the_generalized_inertia_is_the_kinetic_energy_of_the_velocity_coefficients():
    """J(phi) found from the reference method's driver torque (its part proportional to
    alpha) equals sum m |v_G/omega|^2 + I (omega_i/omega)^2, computed from the kinematics
    alone; B = J'/2 against a central difference of that J."""
    spec, mech, eom = equation(four_bar("{motor: {torque: 1}}", DAMPER))
    kin = solve_kinematics(mech, eom.grid)
    j = generalized_inertia(kin)
    assert np.max(np.abs(eom.J - j)) <= 1e-9 * np.max(j)
    h = 1e-4                                     # [deg]
    phi = np.array([10.0, 95.0, 200.0, 333.0])
    plus = generalized_inertia(solve_kinematics(mech, phi + h))
    minus = generalized_inertia(solve_kinematics(mech, phi - h))
    slope = (plus - minus) / (2 * math.radians(h))
    j_b = eom.at(np.radians(phi))[:, 1]          # B at those angles, from the spline
    assert np.allclose(j_b, slope / 2, rtol=1e-6, atol=1e-9 * np.max(j))


def test_the_viscous_part_is_the_damper_along_its_velocity_coefficient():
    """C(phi) = c (dL/dphi)^2 for a damper of coefficient c whose length L changes by
    dL/dphi per radian of crank (the power it takes, c (dL/dt)^2, over omega^2)."""
    spec, mech, eom = equation(four_bar("{motor: {torque: 1}}", DAMPER))
    kin = at_unit_rate(solve_kinematics(mech, eom.grid))
    c_pt, a_pt = kin.named_point("C", "coupler"), kin.named_point("A", "crank")
    d = c_pt.r - a_pt.r
    rate = np.einsum("ij,ij->i", c_pt.v - a_pt.v, d) / np.hypot(d[:, 0], d[:, 1])
    assert np.allclose(eom.C, 40 * rate ** 2, rtol=1e-9, atol=1e-12)


def test_without_motor_or_losses_the_kinetic_energy_is_conserved():
    """No motor torque, no load, no gravity: 1/2 (J(phi) + If) omega^2 stays what it was
    at the start, to the integrator's tolerance, over many turns."""
    text = four_bar("{motor: {torque: 0}, flywheel: 0.002, start: {angle: 0, rpm: 300}, "
                    "until: 1.5, output_step: 0.001}", gravity="[0, 0]")
    spec, mech, eom = equation(text)
    sim = simulate(eom, spec.dynamics, spec.analysed_angles(), spec.file)
    assert sim.time[-1] == pytest.approx(1.5, abs=1e-12) and sim.steady is None
    j = generalized_inertia(solve_kinematics(mech, np.degrees(sim.angle) % 360.0))
    energy = 0.5 * (j + 0.002) * sim.omega ** 2
    assert np.ptp(energy) <= 1e-8 * energy[0]
    assert np.max(sim.angle) > 6 * 2 * math.pi       # it turned on, several turns


SPINNER = """\
mechreport: 1.1
name: a balanced disc on a motor
gravity: [0, 0]
ground: {A: [0, 0]}
links:
  disc: {points: {A: [0, 0], B: [0.1, 0]}, mass: 2, com: [0, 0], inertia: 0.01}
joints:
  A: {type: R, links: [ground, disc]}
driver: {joint: A, rpm: 100}
sweep: {start: 0, stop: 360, step: 1}
dynamics:
  motor: {torque: 0.3}
  flywheel: 0.04
  start: {angle: 10, rpm: 60}
  until: 2
  output_step: 0.01
"""


def test_a_constant_inertia_under_a_constant_torque_accelerates_uniformly():
    """A balanced disc (J = 0.01 kg m^2) with a 0.04 kg m^2 flywheel and 0.3 N m: alpha =
    0.3 / 0.05 = 6 rad/s^2, omega = omega0 + 6 t, phi = phi0 + omega0 t + 3 t^2."""
    spec, mech, eom = equation(SPINNER)
    sim = simulate(eom, spec.dynamics, spec.analysed_angles(), spec.file)
    t = sim.time
    w0, phi0 = 60 * math.pi / 30, math.radians(10)
    assert len(t) == 201 and t[-1] == pytest.approx(2.0, abs=1e-12)
    assert np.allclose(sim.omega, w0 + 6 * t, rtol=1e-9)
    assert np.allclose(sim.angle, phi0 + w0 * t + 3 * t ** 2, rtol=1e-9)
    assert np.allclose(sim.alpha, 6.0, rtol=1e-9)
    assert np.allclose(sim.motor, 0.3)


def test_the_motor_characteristic_is_linear_between_its_points_and_beyond_them():
    from mechreport.spec.types import MotorCurve
    curve = MotorCurve(curve=((0, 180), (1400, 60), (1500, 0)))
    rpm = np.array([0, 700, 1400, 1450, 1600, -100])
    assert np.allclose(motor_torque(curve, rpm * RPM), [180, 120, 60, 30, -60, 180 + 100 * 120
                                                        / 1400])
    linear = MotorCurve(stall_torque=10, no_load_rpm=1000)
    assert np.allclose(motor_torque(linear, np.array([0, 500, 1000]) * RPM), [10, 5, 0])


STEADY = "{motor: {linear: {stall_torque: 40, no_load_rpm: 330}}, flywheel: 0.01}"


@pytest.fixture(scope="module")
def steady():
    return mechreport.analyse(four_bar(STEADY, DAMPER, step=0.5))


def test_over_the_steady_turn_the_motor_does_the_work_the_damper_dissipates(steady):
    """Motor work per turn, the integral of Mm(omega(phi)) dphi, equals the damper's
    dissipation, the integral of c (dL/dphi)^2 omega(phi) dphi (gravity and the kinetic
    energy return over a turn), both from the steady speed and the kinematics alone
    (periodic trapezoids: the integrands are smooth)."""
    cycle = steady.dynamics.simulation.steady
    mech = steady.mechanism
    assert len(cycle.angles) == 720 and cycle.angles[-1] == 359.5   # one turn, each once
    kin = at_unit_rate(solve_kinematics(mech, cycle.angles))
    c_pt, a_pt = kin.named_point("C", "coupler"), kin.named_point("A", "crank")
    d = c_pt.r - a_pt.r
    rate = np.einsum("ij,ij->i", c_pt.v - a_pt.v, d) / np.hypot(d[:, 0], d[:, 1])
    w = cycle.omega
    h = math.radians(0.5)
    motor = np.sum(motor_torque(steady.spec.dynamics.motor, w)) * h
    damper = np.sum(40 * rate ** 2 * w) * h
    assert motor == pytest.approx(damper, rel=1e-6)


def test_the_steady_turn_forces_equal_a_kinetostatic_analysis_at_the_same_motion(steady):
    """At a few angles, a constant-speed analysis with the driver's omega and alpha set to
    the steady turn's there gives every method's reactions and driver torque."""
    cycle = steady.dynamics.simulation.steady
    turn = steady.dynamics.steady
    text = four_bar(STEADY, DAMPER).replace("dynamics: {motor", "#").replace(
        "mechreport: 1.1", "mechreport: 1.1")
    text = "\n".join(line for line in text.splitlines() if not line.startswith("#"))
    for angle in (30.0, 123.5, 300.0):
        k = int(np.flatnonzero(np.isclose(cycle.angles, angle))[0])
        w, a = float(cycle.omega[k]), float(cycle.alpha[k])
        fixed = text.replace("driver: {joint: A, rpm: 300}",
                             f"driver: {{joint: A, omega: {w!r}, alpha: {a!r}}}")
        fixed = fixed.replace("at: [30, 210]", f"at: [{angle!r}]").replace(
            "sweep: {start: 0, stop: 360, step: 1}", f"sweep: {{start: {angle!r}, stop: "
                                                      f"{angle + 1!r}, step: 1}}")
        one = mechreport.analyse(fixed)
        i = int(np.flatnonzero(np.isclose(turn.angles, angle))[0])
        for name, res in turn.forces.items():
            ref = one.forces[name]
            assert res.driver_torque[i] == pytest.approx(ref.driver_torque[0], rel=1e-9)
            for joint, r in res.reactions.items():
                scale = max(abs(ref.reactions[joint].f[0]), 1.0)
                assert abs(r.fx[i] - ref.reactions[joint].fx[0]) <= 1e-9 * scale
                assert abs(r.fy[i] - ref.reactions[joint].fy[0]) <= 1e-9 * scale


def test_the_steady_turn_is_checked_like_a_sweep(steady):
    """Every method agrees, the power balance (with the true speed at each angle) holds."""
    turn = steady.dynamics.steady
    assert turn.worst.relative <= 1e-9
    assert all(r.force <= 1e-9 and r.moment <= 1e-9 for r in turn.residuals)


def test_a_large_flywheel_approaches_the_design_estimate():
    """With a flywheel much larger than the mechanism, the simulated fluctuation approaches
    the estimate Cs = dE / (If omega^2) of the kinetostatic review at the mean speed; the
    larger the flywheel, the closer."""
    errors = []
    for flywheel in (0.05, 0.5):
        dyn = (f"{{motor: {{linear: {{stall_torque: 400, no_load_rpm: 310}}}}, "
               f"flywheel: {flywheel}}}")
        a = mechreport.analyse(four_bar(dyn, DAMPER))
        cycle = a.dynamics.simulation.steady
        energy = a.dynamics.steady.review.values["cycle.energy_fluctuation"]
        estimate = energy / (flywheel * cycle.mean_omega ** 2)
        errors.append(abs(cycle.fluctuation - estimate) / estimate)
        # the report's estimate: the same formula from the equation's constant-speed torque
        swing, inertia, predicted = a.dynamics.estimate
        assert inertia > flywheel and predicted == pytest.approx(
            swing / (inertia * cycle.mean_omega ** 2))
        assert abs(cycle.fluctuation - predicted) / predicted < 2 * errors[-1] + 0.02
    assert errors[1] < 0.05 and errors[1] < errors[0]


def test_a_motor_too_weak_to_start_the_crank_is_a_clear_error():
    """Started from rest where the weights need the most torque to move on, a motor giving
    less than that cannot start the crank."""
    _, _, eom = equation(four_bar("{motor: {torque: 1}}"))
    k = int(np.argmax(eom.D))
    text = four_bar(f"{{motor: {{torque: {float(0.9 * eom.D[k])!r}}}, start: {{angle: "
                    f"{float(eom.grid[k])!r}}}}}")
    with pytest.raises(AnalysisError, match="cannot start at crank angle"):
        mechreport.analyse(text)


def test_a_constant_torque_against_speed_independent_loads_has_no_steady_state():
    """Nothing depends on the speed: the motor's work per turn exceeds the loads' for ever.
    Said before integrating."""
    with pytest.raises(AnalysisError, match="speeds up without end"):
        mechreport.analyse(four_bar("{motor: {torque: 2}}", gravity="[0, 0]"))


def test_a_motor_whose_torque_rises_with_speed_runs_away_and_is_stopped():
    """A torque that grows with the speed faster than the damper's: the change per turn
    grows; from the 20th turn on the extrapolation says it will not settle."""
    with pytest.raises(AnalysisError, match="does not settle"):
        mechreport.analyse(four_bar("{motor: {curve: [[0, 1], [100, 30]]}}", DAMPER,
                                    gravity="[0, 0]"))


def test_a_crank_that_runs_down_stalls_with_a_clear_error():
    with pytest.raises(AnalysisError, match="stalls at crank angle"):
        mechreport.analyse(four_bar("{motor: {torque: 0}, start: {rpm: 100}}", DAMPER))


@pytest.mark.parametrize("dynamics, path, words", [
    ("{motor: {torque: 1, linear: {stall_torque: 1, no_load_rpm: 10}}}", "dynamics.motor",
     "exactly one of torque"),
    ("{motor: {curve: [[0, 5], [100, 2], [50, 0]]}}", "dynamics.motor.curve[2][0]",
     "the speeds must increase"),
    ("{motor: {torque: 1}, flywheel: -1}", "dynamics.flywheel", ""),
    ("{motor: {torque: 1}, until: soon}", "dynamics.until", "steady or a time"),
    ("{motor: {torque: 1}, start: {rpm: -5}}", "dynamics.start.rpm", ""),
])
def test_mistakes_in_dynamics_are_reported_where_they_are(dynamics, path, words):
    with pytest.raises(SpecError) as info:
        parse_spec(four_bar(dynamics), "dyn.yaml")
    found = [p for p in info.value.problems if p.path == path]
    assert found and words in found[0].message, info.value.problems


def test_steady_quantities_need_a_steady_state():
    text = four_bar("{motor: {torque: 1}, until: 0.5}") + (
        "expect:\n  - {quantity: dynamics.mean_rpm, value: 300, tol: 1}\n"
        "design: {limits: {speed_fluctuation: 0.1}}\n")
    with pytest.raises(SpecError) as info:
        parse_spec(text, "dyn.yaml")
    paths = {p.path: p.message for p in info.value.problems}
    assert "transient only" in paths["expect[0]"]
    assert "transient only" in paths["design.limits.speed_fluctuation"]


FRICTION = "friction: {A: {mu: 0.08, radius: 12}, B: {mu: 0.1, radius: 8}, C: {mu: 0.1, " \
           "radius: 8}}\n"


@pytest.fixture(scope="module")
def rubbed():
    """The damped four-bar with friction in its pins A, B, C, swept from 0.25° so that no
    angle falls where a joint's relative motion stops (0° and 180°: left out)."""
    text = four_bar(STEADY, DAMPER, step=0.5).replace(
        "sweep: {start: 0, stop: 360, step: 0.5}", "sweep: {start: 0.25, stop: 360.25, "
                                                   "step: 0.5}").replace("at: [30, 210]",
                                                                         "at: [30.25, 210.25]")
    return mechreport.analyse(text + FRICTION)


def test_with_friction_the_motor_does_the_work_the_damper_and_the_joints_dissipate(rubbed):
    """Over the steady turn the motor's work equals the damper's dissipation plus each
    joint's, |friction x relative rate| integrated over the turn: the frictions as the
    steady turn's kinetostatic analysis finds them at the true motion (its own Newton
    iteration over the sweep), the equation of motion's solved per state in time."""
    cycle = rubbed.dynamics.simulation.steady
    turn = rubbed.dynamics.steady
    assert np.array_equal(turn.angles, cycle.angles)     # no angle left out
    kin = at_unit_rate(turn.kinematics)
    c_pt, a_pt = kin.named_point("C", "coupler"), kin.named_point("A", "crank")
    d = c_pt.r - a_pt.r
    rate = np.einsum("ij,ij->i", c_pt.v - a_pt.v, d) / np.hypot(d[:, 0], d[:, 1])
    w = cycle.omega
    h = math.radians(0.5)
    from mechreport.forces.friction_law import relative_rate
    rubbing = sum(np.abs(turn.kinematics.friction[j] * relative_rate(kin, turn.spec.joint(j)))
                  for j in ("A", "B", "C"))
    motor = np.sum(motor_torque(rubbed.spec.dynamics.motor, w)) * h
    lost = np.sum(40 * rate ** 2 * w + rubbing) * h
    assert np.sum(rubbing) * h > 0.05 * lost                   # the friction matters here
    assert motor == pytest.approx(lost, rel=1e-6)


def test_with_friction_the_steady_turn_is_slower_and_checked_like_a_sweep(rubbed, steady):
    turn = rubbed.dynamics.steady
    assert turn.worst.relative <= 1e-9
    assert rubbed.dynamics.values["dynamics.mean_rpm"] < steady.dynamics.values[
        "dynamics.mean_rpm"]
    assert "cycle.friction.energy" in turn.review.values


def test_the_speed_fluctuation_limit_is_a_verdict_on_the_simulated_value(steady):
    text = four_bar(STEADY, DAMPER, step=0.5) + "design: {limits: {speed_fluctuation: 0.01}}\n"
    a = mechreport.analyse(text)
    verdict = next(v for v in a.verdicts if v.item == "limits.speed_fluctuation")
    assert verdict.value == steady.dynamics.values["dynamics.speed_fluctuation"]
    assert verdict.passed == (verdict.value <= 0.01)


def test_a_study_varies_the_flywheel_and_keeps_the_simulated_fluctuation():
    """Sizing a flywheel is a study: `vary: dynamics.flywheel`, `keep:
    dynamics.speed_fluctuation`; each row is what analysing that variant alone gives, and a
    larger flywheel smooths the speed."""
    from mechreport.study.run import run_variants
    from mechreport.spec.loader import parse_source, spec_from_data
    from mechreport.study import plan_of
    from mechreport.study.variants import base_of
    keep = ["dynamics.speed_fluctuation", "dynamics.mean_rpm"]
    text = four_bar(STEADY, DAMPER, step=10) + (
        "study:\n  vary:\n    - {key: dynamics.flywheel, values: [0.005, 0.02]}\n"
        f"  keep: [{', '.join(keep)}]\n")
    src = parse_source(text, "flywheel_study.yaml")
    base = base_of(spec_from_data(src.data, src), src)
    table = run_variants(base, plan_of(base.spec.study), "newton_euler", keep, jobs=1)
    assert table.ok.all()
    for i, flywheel in enumerate((0.005, 0.02)):
        alone = mechreport.analyse(text.replace("flywheel: 0.01", f"flywheel: {flywheel}"),
                                   methods=["newton_euler"])
        np.testing.assert_allclose(table.values[i], [alone.dynamics.values[q] for q in keep],
                                   rtol=1e-12)
    assert table.values[1][0] < table.values[0][0]


@pytest.mark.parametrize("dynamics, words", [
    ("{motor: {torque: 0}, start: {rpm: 300}, until: 2.0e3}", "more than 12 turns"),
    ("{motor: {linear: {stall_torque: 40, no_load_rpm: 330}}, until: 1, "
     "output_step: 1.0e-7}", "more than 2000000"),
])
def test_a_run_too_long_to_simulate_or_store_is_a_clear_error(dynamics, words, monkeypatch):
    """The turn limit (lowered here: the real one is minutes of integration) and the row
    limit are errors that say which key to change."""
    import importlib
    monkeypatch.setattr(importlib.import_module("mechreport.dynamics.simulate"), "MAX_TURNS",
                        12)
    with pytest.raises(AnalysisError, match=words):
        mechreport.analyse(four_bar(dynamics, gravity="[0, 0]"))


PRESS = (Path(__file__).resolve().parents[2] / "specs" / "crank_press_friction.yaml")


@pytest.mark.parametrize("which", ["pins", "slider with length", "friction circles"])
def test_the_integrators_friction_path_is_the_batched_one(which):
    """The plain-float right-hand side with friction gives the batched solver's alpha: the
    four-bar's rubbing pins (as couples, and as friction circles, format 1.2), and the crank
    press's pins and ram guide (a slider with a length: the drawer effect)."""
    from mechreport.dynamics.friction import friction_state
    circles = FRICTION.replace("radius: 12}", "radius: 12, model: circle}").replace(
        "radius: 8}", "radius: 8, model: circle}")
    text = (four_bar(STEADY, DAMPER) + FRICTION if which == "pins" else
            four_bar(STEADY, DAMPER) + circles if which == "friction circles" else
            PRESS.read_text(encoding="utf-8")
            + "dynamics: {motor: {linear: {stall_torque: 400, no_load_rpm: 66}}, flywheel: 30}\n")
    spec, mech, eom = equation(text)
    assert (which == "friction circles") == all(f.model == "circle" for f in spec.friction)
    rng = np.random.default_rng(7)
    phi, w = rng.uniform(0, 2 * math.pi, 40), rng.uniform(5, 40, 40)
    one = eom.scalar()
    np.testing.assert_allclose([one(p, x) for p, x in zip(phi, w)],
                               friction_state(eom, phi, w, "dyn.yaml")[0], rtol=1e-12,
                               atol=1e-12 * np.max(np.abs(eom.D)))


def test_a_crank_that_starts_and_swings_back_stalls_instead_of_integrating_on():
    """Started from rest just before an angle where the weights begin to need more than the
    motor gives: the crank moves forward a little, swings back: a stall at once, never a
    simulation of the crank turning backwards (nor an endless pendulum)."""
    _, _, eom = equation(four_bar("{motor: {torque: 1}}"))
    torque = float(0.5 * max(eom.D))
    up = np.flatnonzero((eom.D[:-1] < torque) & (eom.D[1:] >= torque))[0]   # D rises past it
    start = float(eom.grid[up] - 2.0)
    text = four_bar(f"{{motor: {{torque: {torque!r}}}, until: 5, start: {{angle: {start!r}}}}}")
    with pytest.raises(AnalysisError, match="stalls at crank angle"):
        mechreport.analyse(text)
