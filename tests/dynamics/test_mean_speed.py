"""The steady state at a mean speed (format 1.2 ``dynamics.mean_rpm``) and the steady
cycle's new quantities: the time-mean speed is mean_rpm; the constant driving torque is
the exact cycle mean of the torque the mechanism takes at that motion (the energy balance
of a periodic motion); a large flywheel's fluctuation approaches the first-order estimate
dE / ((J_mean + I_f) omega_m^2) (the textbooks' Cs = dE / (I omega^2)); the speed's
extremes lie between the samples, where the acceleration vanishes."""
from __future__ import annotations

import math

import numpy as np
import pytest

import mechreport
from mechreport.errors import SpecError
from mechreport.model import build_mechanism
from mechreport.pipeline.dynamics import simulated
from mechreport.spec import parse_spec
from mechreport.units import RPM

from test_equation_of_motion import DAMPER, four_bar  # noqa: E402 - the four-bar, written once


def _run(dynamics: str, loads: str = DAMPER, step: float = 2):
    spec = parse_spec(four_bar(dynamics, loads, step=step), "dyn.yaml")
    return simulated(build_mechanism(spec))


@pytest.mark.parametrize("flywheel", ["0.01", "{inertia: 0.001, ratio: 4}"])
def test_the_time_mean_speed_is_mean_rpm(flywheel):
    _, sim, values = _run(f"{{mean_rpm: 240, flywheel: {flywheel}}}")
    cycle = sim.steady
    assert abs(2 * math.pi / cycle.period - 240 * RPM) <= 1e-9 * 240 * RPM
    assert values["dynamics.mean_rpm"] == pytest.approx(240, rel=1e-9)
    assert "dynamics.startup_time" not in values            # no start-up to time
    # the time histories are one cycle, periodic: the speed returns
    assert sim.angle[-1] - sim.angle[0] == pytest.approx(2 * math.pi, rel=1e-9)
    assert sim.omega[-1] == pytest.approx(sim.omega[0], rel=1e-8)


def test_the_driving_torque_is_the_cycle_mean_of_what_the_mechanism_takes():
    """T x 2 pi = the integral over the turn of the driver torque of the steady turn's own
    kinetostatic analysis (every method, at the true omega and alpha at each angle; a
    periodic trapezoid on the 0.5 degree sweep)."""
    a = mechreport.analyse(four_bar("{mean_rpm: 240, flywheel: 0.01}", DAMPER, step=0.5))
    torque = a.dynamics.simulation.drive_torque
    assert a.dynamics.values["dynamics.motor_rms_torque"] == pytest.approx(abs(torque))
    for res in a.dynamics.steady.forces.values():
        assert np.mean(res.driver_torque) == pytest.approx(torque, rel=1e-6)


def test_a_large_flywheel_approaches_the_first_order_estimate():
    errors = []
    for flywheel in (0.02, 2.0):
        _, sim, values = _run(f"{{mean_rpm: 240, flywheel: {flywheel}}}")
        estimate = values["dynamics.speed_fluctuation_estimate"]
        errors.append(abs(values["dynamics.speed_fluctuation"] - estimate) / estimate)
    assert errors[1] < 2e-3 and errors[1] < errors[0] / 10


def test_the_speed_extremes_lie_between_samples_where_alpha_vanishes():
    eom, sim, values = _run("{mean_rpm: 240, flywheel: 0.005}", step=7)
    cycle = sim.steady
    w_max, w_min = values["dynamics.omega_max"], values["dynamics.omega_min"]
    assert w_max >= np.max(sim.omega) and w_min <= np.min(sim.omega)
    assert w_max > np.max(cycle.omega) and w_min < np.min(cycle.omega)   # off the 7° grid
    for w, deg in ((w_max, values["dynamics.omega_max_angle"]),
                   (w_min, values["dynamics.omega_min_angle"])):
        assert 0 <= deg < 360
        alpha = float(eom.alpha(np.array([math.radians(deg)]), np.array([w]))[0])
        assert abs(alpha) <= 1e-6 * w ** 2
    assert (w_max - w_min) / (240 * RPM) == pytest.approx(values["dynamics.speed_fluctuation"])


def test_the_speed_and_acceleration_at_an_angle_are_checked_against_the_steady_cycle():
    text = four_bar("{mean_rpm: 240, flywheel: 0.01}", DAMPER, step=2)
    first = mechreport.analyse(text)
    cycle = first.dynamics.simulation.steady
    k = int(np.flatnonzero(cycle.angles == 30)[0])
    w, a = float(cycle.omega[k]), float(cycle.alpha[k])
    checked = mechreport.analyse(text + (
        f"expect:\n  - {{angle: 30, quantity: dynamics.omega, value: {w!r}, tol: 1e-9}}\n"
        f"  - {{angle: 30, quantity: dynamics.alpha, value: {a!r}, tol: 1e-9}}\n"
        f"  - {{quantity: dynamics.omega_max, value: "
        f"{first.dynamics.values['dynamics.omega_max']!r}, tol: 1e-9}}\n"))
    assert all(e.ok for e in checked.expectations) and len(checked.expectations) == 3
    wrong = mechreport.analyse(text + (
        f"expect:\n  - {{angle: 30, quantity: dynamics.omega, value: {w + 0.01!r}, "
        "tol: 1e-3}\n"))
    assert not wrong.expectations[0].ok


def test_dynamics_quantities_at_an_angle_need_a_steady_cycle():
    text = four_bar("{motor: {torque: 1}, until: 0.5}") + (
        "expect:\n  - {angle: 30, quantity: dynamics.omega, value: 1, tol: 1}\n")
    with pytest.raises(SpecError, match="steady cycle"):
        parse_spec(text, "dyn.yaml")
    text = four_bar("{mean_rpm: 100}") + (
        "expect:\n  - {quantity: dynamics.startup_time, value: 1, tol: 1}\n")
    with pytest.raises(SpecError, match="no start-up"):
        parse_spec(text, "dyn.yaml")


@pytest.mark.parametrize("dynamics", ["{mean_rpm: 240, flywheel: 0.01}",
                                      "{motor: {linear: {stall_torque: 40, no_load_rpm: 330}}, "
                                      "flywheel: 0.01}"])
def test_over_a_two_turn_cycle_the_steady_state_is_the_same_periodic_motion(dynamics):
    """Loads that repeat every turn repeat every two turns too: with ``cycle: 720`` the
    steady state settles on the same motion, its cycle two turns long (200 time-history
    samples per cycle)."""
    one = _run(dynamics)[2]
    text = four_bar(dynamics, DAMPER, step=2).replace(
        "mechreport: 1.1", "mechreport: 1.2\ncycle: 720").replace(
        "stop: 360", "stop: 720")
    spec = parse_spec(text, "dyn.yaml")
    eom, sim, two = simulated(build_mechanism(spec))
    assert eom.period == pytest.approx(4 * math.pi)
    assert sim.steady.period == pytest.approx(2 * 2 * math.pi / sim.steady.mean_omega)
    for name in ("dynamics.mean_rpm", "dynamics.omega_max", "dynamics.omega_min",
                 "dynamics.speed_fluctuation", "dynamics.speed_fluctuation_estimate"):
        assert two[name] == pytest.approx(one[name], rel=1e-6), name
    for name in ("dynamics.omega_max_angle", "dynamics.omega_min_angle"):
        assert two[name] % 360 == pytest.approx(one[name], abs=1e-4), name
    if "mean_rpm" in dynamics:
        assert len(sim.time) == 201
    else:
        step = sim.time[1] - sim.time[0]
        assert step == pytest.approx(sim.steady.period / 200, rel=1e-9)


def test_a_crank_that_cannot_keep_turning_at_the_mean_speed_is_a_clear_error():
    """At 1 rpm with no flywheel the crank's kinetic energy cannot carry it over the
    weights' swing: an error naming mean_rpm and what helps, never a wrong state."""
    from mechreport.errors import AnalysisError
    with pytest.raises(AnalysisError, match="mean_rpm = 1: at that mean speed the crank stalls"):
        _run("{mean_rpm: 1}")


def test_a_mean_speed_too_large_to_resolve_the_driving_torque_is_a_clear_error():
    from mechreport.errors import AnalysisError
    with pytest.raises(AnalysisError, match="below the integration's resolution"):
        _run("{mean_rpm: 1e12, flywheel: 0.01}")
