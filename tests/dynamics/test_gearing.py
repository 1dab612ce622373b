"""Geared flywheels and motors (format 1.2 ``dynamics.flywheel: {inertia, ratio}``, motor
``ratio`` and ``efficiency``): a flywheel geared at ratio n behaves exactly as n^2 I on the
crank (its kinetic energy I (n omega)^2 / 2 = (n^2 I) omega^2 / 2); a motor geared at n with
efficiency eta gives the crank n eta T while it drives and n T / eta when driven back."""
from __future__ import annotations

import numpy as np
import pytest

from mechreport.dynamics.motor import RPM, motor_torque, on_crank, own_power, own_torque
from mechreport.errors import SpecError
from mechreport.model import build_mechanism
from mechreport.pipeline.dynamics import simulated
from mechreport.spec import parse_spec
from mechreport.spec.types import MotorCurve

from test_equation_of_motion import DAMPER, four_bar  # noqa: E402 - the four-bar, written once

MOTOR = "{linear: {stall_torque: 40, no_load_rpm: 330}}"


def _steady(dynamics: str):
    spec = parse_spec(four_bar(dynamics, DAMPER, step=2), "dyn.yaml")
    return spec, simulated(build_mechanism(spec))


def test_a_flywheel_geared_at_n_behaves_exactly_as_n_squared_times_its_inertia():
    n, inertia = 3.0, 0.004
    geared, (_, sim_g, values_g) = _steady(
        f"{{motor: {MOTOR}, flywheel: {{inertia: {inertia!r}, ratio: {n!r}}}}}")
    plain, (_, sim_p, values_p) = _steady(f"{{motor: {MOTOR}, flywheel: {n * n * inertia!r}}}")
    assert geared.dynamics.flywheel == plain.dynamics.flywheel == n * n * inertia
    assert geared.dynamics.flywheel_geared == (inertia, n)
    assert values_g == values_p
    assert np.array_equal(sim_g.omega, sim_p.omega)


def test_a_motor_geared_without_loss_is_its_torque_times_n_at_its_speed_over_n():
    """A linear motor (stall T0, no-load N) at ratio n is, on the crank, a linear motor of
    stall n T0 and no-load N / n: the two give the same steady state."""
    _, (_, sim_g, values_g) = _steady(
        "{motor: {linear: {stall_torque: 10, no_load_rpm: 1320}, ratio: 4}, flywheel: 0.01}")
    _, (_, sim_p, values_p) = _steady(
        "{motor: {linear: {stall_torque: 40, no_load_rpm: 330}}, flywheel: 0.01}")
    assert values_g["dynamics.mean_rpm"] == pytest.approx(values_p["dynamics.mean_rpm"],
                                                          rel=1e-12)
    # the time history's motor torque is the motor's own, a quarter of the crank's
    cycle_g, cycle_p = sim_g.steady, sim_p.steady
    assert cycle_g.motor_rms == pytest.approx(cycle_p.motor_rms / 4, rel=1e-9)
    assert cycle_g.motor_power == pytest.approx(cycle_p.motor_power, rel=1e-9)


@pytest.mark.parametrize("motor", [
    MotorCurve(stall_torque=2.0, no_load_rpm=1500.0, ratio=10.0, efficiency=0.9),
    MotorCurve(curve=((100.0, 5.0), (200.0, 3.0), (300.0, 1.0)), ratio=3.0, efficiency=0.8),
    MotorCurve(curve=((0.0, -1.0), (50.0, 4.0), (400.0, -2.0)), ratio=0.5, efficiency=0.7),
    MotorCurve(constant=-3.0, ratio=2.0, efficiency=0.5),
])
def test_the_crank_receives_n_eta_t_while_the_motor_drives_and_n_t_over_eta_back(motor):
    crank = np.linspace(0.0, 2000.0 / motor.ratio, 4001) * RPM
    own = motor_torque(MotorCurve(constant=motor.constant, curve=motor.curve,
                                  stall_torque=motor.stall_torque,
                                  no_load_rpm=motor.no_load_rpm), motor.ratio * crank)
    expected = motor.ratio * np.where(own > 0, motor.efficiency * own, own / motor.efficiency)
    got = motor_torque(on_crank(motor), crank)
    assert np.max(np.abs(got - expected)) <= 1e-12 * np.max(np.abs(expected))
    assert np.array_equal(own_torque(motor, crank), own)
    assert np.allclose(own_power(motor, crank), own * motor.ratio * crank, rtol=1e-15)


@pytest.mark.parametrize("dynamics, words", [
    ("{mean_rpm: 100, motor: {torque: 1}}", "exactly one of motor"),
    ("{flywheel: 1}", "exactly one of motor"),
    ("{motor: {torque: 1, efficiency: 1.5}}", "at most 1"),
    ("{motor: {torque: 1, ratio: 0}}", ""),
    ("{motor: {torque: 1}, flywheel: {inertia: 1}}", "ratio"),
    ("{mean_rpm: 100, until: 2}", "not used"),
    ("{mean_rpm: -100}", ""),
])
def test_gearing_and_mean_speed_mistakes_are_reported(dynamics, words):
    with pytest.raises(SpecError) as info:
        parse_spec(four_bar(dynamics), "dyn.yaml")
    found = [p for p in info.value.problems if p.path.startswith("dynamics")]
    assert found and any(words in p.message for p in found), info.value.problems
