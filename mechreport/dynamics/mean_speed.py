"""The steady state at a mean speed (format 1.2 ``dynamics.mean_rpm``), found directly.

The crank is driven by a constant torque T (the textbooks' uniform driving or resisting
torque) and the motion wanted is periodic over one cycle with time-mean speed
omega_m = 2 pi n / 60 (n = ``mean_rpm``): its period is cycle / omega_m. Over a periodic
cycle the kinetic energy returns, so the work of T equals the work the mechanism takes,
T = (1 / cycle) * integral of M(phi, omega, alpha) dphi: T is the exact cycle mean of the
torque the mechanism takes at that motion (not a grid average), and is found with it.

Method (shooting): from the start angle at speed omega_0 one cycle is integrated in time
(the integrator of :mod:`.simulate`, DOP853, here at relative tolerance 1e-12) under T; the two
conditions are the speed's return (omega_end = omega_0, scaled by omega_m) and the cycle's
duration (t_cycle = cycle / omega_m, scaled by it). The unknowns (T, omega_0) are found by
Newton's method, its Jacobian by finite differences at the start and Broyden's updates
after, from the estimate of constant speed (T the mean of C omega_m + D over the grid,
omega_0 = omega_m). Why not settle from a start, as a motor's steady state is found: under
a constant torque nothing but dampers and friction takes energy out of a speed error, so
without them a start-up never settles (the speed error stays), and with a large flywheel
they take thousands of cycles; the shooting needs some six integrations of one cycle
whatever the flywheel. Where no periodic motion exists at that speed (the kinetic energy
does not carry the crank over the loads' swing: it stalls) that is said.
"""
from __future__ import annotations

import math
from dataclasses import replace

import numpy as np

from ..errors import AnalysisError
from ..spec.types import Dynamics
from .equation import EquationOfMotion
from .motor import RPM, constant_drive
from .prechecks import require_inertia
from .simulate import (DEFAULT_SAMPLES, MAX_ROWS, STALL_SPEED, Simulation, _start_angle,
                       _too_many_rows, _Turns, simulate, steady_cycle)

#: the integrator's relative tolerance here (a motor's start-up uses 1e-10): the shooting's
#: conditions are then smooth in the unknowns down to about 1e-12
RTOL = 1e-12
#: the conditions met to within these, relative: the speed's return (periodic as a motor's
#: steady state is, 1e-6, and much closer) and the cycle's period (the time-mean speed is
#: mean_rpm within 1e-9); Newton's steps go on while they improve, to ``TOL`` of these
RETURN_TOL, PERIOD_TOL = 1e-8, 5e-10
TOL = 1e-3
MAX_ITERATIONS = 30
#: the relative step of the finite differences of the first Jacobian
STEP = 1e-6


def motion(eom: EquationOfMotion, dyn: Dynamics, angles: np.ndarray, file: str
           ) -> Simulation:
    """The motion ``dyn`` asks for: the steady state at ``mean_rpm``
    (:func:`steady_at_mean_speed`), or what its motor gives (:func:`.simulate.simulate`)."""
    if dyn.mean_rpm is not None:
        return steady_at_mean_speed(eom, dyn, angles, file)
    return simulate(eom, dyn, angles, file)


def steady_at_mean_speed(eom: EquationOfMotion, dyn: Dynamics, angles: np.ndarray,
                         file: str) -> Simulation:
    """The periodic motion of ``eom`` under the constant torque that keeps its time-mean
    speed at ``dyn.mean_rpm``, one cycle of it from the start angle as the time histories
    (``drive_torque`` the torque [N m]); its steady cycle sampled at ``angles`` [deg].
    Raises ``AnalysisError`` where the crank stalls at that speed, or the shooting does
    not converge."""
    require_inertia(eom, file)
    target = dyn.mean_rpm * RPM
    _require_resolvable(eom, target, dyn.mean_rpm, file)
    t_target = eom.period / target
    theta0 = math.radians(_start_angle(dyn.start_angle, file))
    inertia = float(np.mean(eom.J)) + eom.flywheel
    torque = float(np.mean(eom.C)) * target + float(np.mean(eom.D))
    scale_t = STEP * inertia * target ** 2 / eom.period       # a torque moving omega by STEP
    x = np.array([torque, target])

    def residual(x):
        turns, sol = _cycle(eom, x, theta0, t_target, file, dyn.mean_rpm)
        tau, w_end = float(sol.t[-1]), float(sol.y[1, -1])
        return np.array([(w_end - x[1]) / target, (tau - t_target) / t_target]), (turns, sol)

    r, run = residual(x)
    steps = np.array([scale_t, STEP * target])
    jac = np.empty((2, 2))
    for k in range(2):
        dx = np.zeros(2)
        dx[k] = steps[k]
        jac[:, k] = (residual(x + dx)[0] - r) / steps[k]
    def size(r) -> float:
        return max(abs(r[0]) / RETURN_TOL, abs(r[1]) / PERIOD_TOL)
    best = (size(r), x, r, run)
    for _ in range(MAX_ITERATIONS):
        if best[0] <= TOL:
            break
        try:
            dx = -np.linalg.solve(jac, r)
        except np.linalg.LinAlgError:
            break
        x_new = x + dx
        r_new, run_new = residual(x_new)
        jac += np.outer(r_new - r - jac @ dx, dx) / (dx @ dx)      # Broyden's update
        x, r, run = x_new, r_new, run_new
        if size(r) < 0.1 * best[0]:
            best = (size(r), x, r, run)
        elif best[0] <= 1:                   # at the integrator's noise: as good as it gets
            break
        elif size(r) < best[0]:
            best = (size(r), x, r, run)
    _, x, r, (turns, sol) = best
    if not best[0] <= 1:
        raise AnalysisError(
            f"{file}: dynamics.mean_rpm = {dyn.mean_rpm:g}: no periodic motion at that mean "
            f"speed was found (the speed's return and the cycle's period still off by "
            f"{abs(r[0]):.2g} and {abs(r[1]):.2g} relative after {MAX_ITERATIONS} steps)")
    solved = replace(eom, motor=constant_drive(float(x[0])))
    tau = float(sol.t[-1])
    cycle = steady_cycle(sol.sol, turns.alpha, solved, tau, 0.0, angles)
    step = dyn.output_step if dyn.output_step is not None else tau / DEFAULT_SAMPLES
    rows = tau / step
    if not rows < MAX_ROWS:
        raise AnalysisError(_too_many_rows(step, rows, tau, file))
    time = np.arange(int(math.floor(rows + 1e-9)) + 1) * step
    if time[-1] < tau * (1 - 1e-12):
        time = np.append(time, tau)
    phi, w = turns(time)
    return Simulation(time, phi, w, solved.alpha(phi, w), solved.motor_own(w), 1, cycle,
                      None, float(x[0]))


#: the inertia forces' torque may be at most this many times the loads' (else the driving
#: torque, their cycle mean, is below the integration's relative resolution RTOL)
RESOLVABLE = 1e9


def _require_resolvable(eom: EquationOfMotion, omega: float, mean_rpm: float, file: str
                        ) -> None:
    """Raise ``AnalysisError`` where, at the speed ``omega`` [rad/s], the torque of the
    changing velocity ratios (B omega^2, which returns over a cycle) is more than
    ``RESOLVABLE`` times that of the loads (C omega + D): the driving torque, the loads'
    cycle mean, would be lost in the integration's round-off (a nonsense speed such as
    1e12 rpm). Loads at the round-off of the equation (a conservative mechanism: its
    driving torque is 0) are none."""
    inertial = float(np.max(np.abs(eom.B))) * omega ** 2
    loads = float(np.max(np.abs(np.asarray(eom.C) * omega + np.asarray(eom.D))))
    floor = 1e-12 * float(np.max(np.abs(eom.J)))      # loads that are round-off: none
    if loads <= floor or inertial <= RESOLVABLE * loads:
        return
    raise AnalysisError(
        f"{file}: dynamics.mean_rpm = {mean_rpm:g}: at that speed the inertia forces' torque "
        f"({inertial:.3g} N·m) is more than {RESOLVABLE:.0e} times the loads' "
        f"({loads:.3g} N·m), so the driving torque, the loads' mean over a cycle, is below "
        "the integration's resolution; check the speed and its unit (rpm)")


def _cycle(eom: EquationOfMotion, x, theta0: float, t_target: float, file: str,
           mean_rpm: float):
    """One cycle from ``theta0`` at speed x[1] [rad/s] under the constant torque x[0]
    [N m]: the integration and its solver's result. Raises ``AnalysisError`` where the
    crank stalls (or the cycle takes more than a hundred times its period)."""
    torque, omega = float(x[0]), float(x[1])
    if not omega > STALL_SPEED:
        raise AnalysisError(_stalls(file, mean_rpm, None))
    turns = _Turns(replace(eom, motor=constant_drive(torque)), theta0, file, RTOL)
    sol = turns.run(0.0, omega, 100 * t_target)
    if sol.t_events[1].size or sol.t_events[2].size or not sol.t_events[0].size:
        raise AnalysisError(_stalls(file, mean_rpm, float(sol.y[0, -1])))
    return turns, sol


def _stalls(file: str, mean_rpm: float, phi: float | None) -> str:
    where = "" if phi is None else f" (near crank angle {math.degrees(phi) % 360:.4g}°)"
    return (f"{file}: dynamics.mean_rpm = {mean_rpm:g}: at that mean speed the crank stalls"
            f"{where}: its kinetic energy does not carry it over the loads' swing in a "
            "cycle under a uniform driving torque; add a flywheel (dynamics.flywheel) or "
            "run it faster")


__all__ = ["motion", "steady_at_mean_speed"]
