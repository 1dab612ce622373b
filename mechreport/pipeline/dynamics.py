"""Machine dynamics in the pipeline: the equation of motion, the motion it gives, and the
steady turn analysed like a sweep, by every method, at the crank's true speed and
acceleration at each angle.

    from mechreport import analyse
    a = analyse("specs/four_bar_motor.yaml")
    a.dynamics.values["dynamics.speed_fluctuation"]
    a.dynamics.steady.forces["dyad"].driver_torque      # over the steady turn
"""
from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np

from ..checks.agreement import DEFAULT_TOL
from ..dynamics import (EquationOfMotion, Simulation, equation_of_motion, flywheel_estimate,
                        motion, spec_at_speed)
from ..dynamics.motor import constant_drive
from ..kinematics import Kinematics, solve_kinematics, with_rates
from ..model import Mechanism
from ..units import RPM


@dataclass(frozen=True)
class DynamicsResult:
    """The machine dynamics of one spec: its ``equation`` of motion, the ``simulation`` (time
    histories, the steady turn), the ``steady`` turn's own :class:`Analysis` (every method,
    check, cycle quantity and verdict at the true motion; None with ``until`` a time), and
    ``values``: the ``dynamics.*`` quantities (SI; empty without a steady state);
    ``estimate`` what the design review's constant-speed flywheel formula predicts at the
    steady mean speed: (energy fluctuation [J], mean inertia on the crank with the flywheel
    [kg m^2], speed fluctuation), None without a steady state; ``verdicts`` the steady turn's
    design verdicts."""

    equation: EquationOfMotion
    simulation: Simulation
    steady: object | None
    values: dict[str, float]
    estimate: tuple[float, float, float] | None = None
    verdicts: tuple = ()      # the steady turn's design verdicts (steady_verdicts)


def motion_of(mech: Mechanism) -> tuple[EquationOfMotion, Simulation]:
    """The equation of motion of ``mech``'s spec (with ``mean_rpm``, its constant driving
    torque as found) and the motion it gives. Raises ``AnalysisError`` at a stall, where the
    crank cannot turn, or without a steady state."""
    spec = mech.spec
    eom = equation_of_motion(mech)
    sim = motion(eom, spec.dynamics, spec.analysed_angles(), spec.file)
    if sim.drive_torque is not None:
        eom = replace(eom, motor=constant_drive(sim.drive_torque))
    return eom, sim


def simulated(mech: Mechanism) -> tuple[EquationOfMotion, Simulation, dict[str, float]]:
    """:func:`motion_of` and the ``dynamics.*`` quantities of its steady cycle (empty
    without one): what a check needs of machine dynamics."""
    eom, sim = motion_of(mech)
    if sim.steady is None:
        return eom, sim, {}
    return eom, sim, steady_values(sim, flywheel_estimate(eom, sim.steady.mean_omega))


def steady_values(sim: Simulation, estimate: tuple[float, float, float]
                  ) -> dict[str, float]:
    """The ``dynamics.*`` quantities of the steady cycle of ``sim`` (SI; the speeds'
    angles in degrees within the cycle), ``estimate`` the flywheel estimate at its mean
    speed (:func:`~mechreport.dynamics.flywheel_estimate`); ``dynamics.startup_time`` only
    after a start-up (not with ``mean_rpm``)."""
    cycle = sim.steady
    values = {"dynamics.speed_fluctuation": cycle.fluctuation,
              "dynamics.mean_rpm": cycle.mean_omega / RPM,
              "dynamics.startup_time": sim.startup_time,
              "dynamics.motor_rms_torque": cycle.motor_rms,
              "dynamics.omega_max": cycle.omega_max, "dynamics.omega_min": cycle.omega_min,
              "dynamics.omega_max_angle": cycle.omega_max_angle,
              "dynamics.omega_min_angle": cycle.omega_min_angle,
              "dynamics.speed_fluctuation_estimate": estimate[2]}
    return {k: v for k, v in values.items() if v is not None}


def run_dynamics(mech: Mechanism, analyse_turn, methods=None, tol: float = DEFAULT_TOL,
                 plans=None, kin: Kinematics | None = None) -> DynamicsResult:
    """The machine dynamics of ``mech``'s spec (its ``dynamics:``), its steady turn analysed
    by ``analyse_turn(mech, kin, methods, tol, plans, extra=values)`` (the pipeline's
    :func:`~mechreport.pipeline.analysis.analysis_of`). ``kin``: the sweep's kinematics,
    whose positions the steady turn takes (solved here when not given). Raises
    ``AnalysisError`` at a stall, where the crank cannot turn, or without a steady state."""
    spec = mech.spec
    eom, sim = motion_of(mech)
    cycle = sim.steady
    angles = spec.analysed_angles()
    if cycle is None:
        return DynamicsResult(eom, sim, None, {})
    estimate = flywheel_estimate(eom, cycle.mean_omega)
    values = steady_values(sim, estimate)
    # the steady turn's own analysis: the spec's expectations are the sweep's (at its speed)
    steady_spec = replace(spec_at_speed(spec, cycle.mean_omega), expect=())
    smech = mech.with_spec(steady_spec)
    # the sweep's poses: the steady turn differs in its speed only (with_rates sets it)
    kin = solve_kinematics(smech) if kin is None else replace(kin, mechanism=smech)
    pick = np.searchsorted(np.round(angles, 9), np.round(kin.angles, 9))
    kin = with_rates(kin, cycle.omega[pick], cycle.alpha[pick])
    steady = analyse_turn(smech, kin, methods, tol, plans, extra=values)
    return DynamicsResult(eom, sim, steady, values, estimate,
                          steady_verdicts(steady.verdicts, cycle))


def steady_rates(sim: Simulation, angles: np.ndarray) -> dict[str, np.ndarray]:
    """``dynamics.omega`` [rad/s] and ``dynamics.alpha`` [rad/s^2] of the steady cycle at
    the sweep's ``angles`` [deg] (NaN at an angle it was not sampled at; empty without a
    steady state): what ``expect`` reads at an angle."""
    cycle = sim.steady
    if cycle is None:
        return {}
    where = np.searchsorted(np.round(cycle.angles, 9), np.round(angles, 9))
    where = np.minimum(where, len(cycle.angles) - 1)
    found = np.isclose(cycle.angles[where], angles, rtol=0, atol=1e-9)
    return {"dynamics.omega": np.where(found, cycle.omega[where], np.nan),
            "dynamics.alpha": np.where(found, cycle.alpha[where], np.nan)}


#: the motor's own quantities a steady turn's motor verdicts read (the crank shaft's torque,
#: cycle.torque.*, is the motor's and the flywheel's together)
MOTOR_QUANTITIES = {"motor.rated_torque": ("dynamics.motor_rms_torque", "motor_rms", "N·m"),
                    "motor.peak_torque": ("max |motor torque|", "motor_peak", "N·m"),
                    "motor.rated_power": ("max motor power", "motor_power", "W")}


def steady_verdicts(verdicts, cycle) -> tuple:
    """The steady turn's design verdicts, the motor's against the motor's own torque and
    power over the turn (with a flywheel the crank shaft's torque is not the motor's)."""
    out = []
    for v in verdicts:
        if v.item in MOTOR_QUANTITIES:
            quantity, attr, unit = MOTOR_QUANTITIES[v.item]
            v = replace(v, quantity=quantity, value=getattr(cycle, attr), unit=unit, why="")
        out.append(v)
    return tuple(out)


__all__ = ["DynamicsResult", "MOTOR_QUANTITIES", "motion_of", "run_dynamics", "simulated",
           "steady_rates", "steady_values", "steady_verdicts"]
