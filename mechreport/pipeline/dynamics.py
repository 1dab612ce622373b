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

from ..dynamics import (EquationOfMotion, Simulation, equation_of_motion, simulate,
                        spec_at_speed)
from ..dynamics.equation import RPM
from ..kinematics import solve_kinematics, with_rates
from ..model import Mechanism


@dataclass(frozen=True)
class DynamicsResult:
    """The machine dynamics of one spec: its ``equation`` of motion, the ``simulation`` (time
    histories, the steady turn), the ``steady`` turn's own :class:`Analysis` (every method,
    check, cycle quantity and verdict at the true motion; None with ``until`` a time), and
    ``values``: the ``dynamics.*`` quantities (SI; empty without a steady state)."""

    equation: EquationOfMotion
    simulation: Simulation
    steady: object | None
    values: dict[str, float]


def run_dynamics(mech: Mechanism, methods=None, tol: float = 1e-6, plans=None
                 ) -> DynamicsResult:
    """The machine dynamics of ``mech``'s spec (its ``dynamics:``). Raises
    ``AnalysisError`` at a stall, where the crank cannot turn, or without a steady state."""
    from .analysis import analysis_of
    spec = mech.spec
    eom = equation_of_motion(mech)
    angles = spec.analysed_angles()
    sim = simulate(eom, spec.dynamics, angles, spec.file)
    cycle = sim.steady
    if cycle is None:
        return DynamicsResult(eom, sim, None, {})
    # the steady turn's own analysis: the spec's expectations are the sweep's (at its speed)
    steady_spec = replace(spec_at_speed(spec, cycle.mean_omega), expect=())
    smech = mech.with_spec(steady_spec)
    kin = solve_kinematics(smech)
    pick = np.searchsorted(np.round(angles, 9), np.round(kin.angles, 9))
    kin = with_rates(kin, cycle.omega[pick], cycle.alpha[pick])
    values = {"dynamics.speed_fluctuation": cycle.fluctuation,
              "dynamics.mean_rpm": cycle.mean_omega / RPM,
              "dynamics.startup_time": sim.startup_time,
              "dynamics.motor_rms_torque": cycle.motor_rms}
    steady = analysis_of(smech, kin, methods, tol, plans, extra=values)
    return DynamicsResult(eom, sim, steady, values)


__all__ = ["DynamicsResult", "run_dynamics"]
