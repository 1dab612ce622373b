"""Direct dynamics: the crank's motion from its equation of motion, in time.

The state (crank angle phi [rad], speed omega [rad/s]) is integrated with scipy's
``solve_ivp`` (DOP853, relative tolerance ``RTOL``) one turn at a time: an event ends each
turn exactly at the start angle plus a whole number of turns, another stops at a stall (the
speed falling to ``STALL_SPEED``: the motor cannot carry the load on, or the crank would
turn back). ``until: steady`` stops when two successive turns agree (the speed at the turn's
start and the turn's period within ``STEADY_RTOL``); ``until: TIME`` at that time.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..errors import AnalysisError
from ..spec.types import Dynamics
from .equation import EquationOfMotion
from .motor import RPM, motor_torque

RTOL = 1e-10              # the integrator's relative tolerance (speed and angle)
ATOL_ANGLE = 1e-10        # [rad]
STEADY_RTOL = 1e-6        # two turns agree: speed and period within this, relative
STALL_SPEED = 1e-6        # [rad/s]: below it the crank has stopped
MAX_TURNS = 5_000         # turns integrated at most before giving up on a steady state
SETTLE_TURNS = 20         # turns after which the approach to a steady state is extrapolated
STARTUP_FRACTION = 0.95   # the start-up ends at this fraction of the steady mean speed
DEFAULT_SAMPLES = 200     # time-history samples per steady turn, without output_step
MAX_ROWS = 2_000_000      # time-history rows at most (about 80 MB of CSV)
FINE = 2000               # samples of a steady turn in time for its extremes and means


@dataclass(frozen=True)
class SteadyCycle:
    """The periodic motion reached: at the sweep's ``angles`` (n,) [deg] the speed ``omega``
    and acceleration ``alpha`` (n,) [rad/s, rad/s^2]; the turn's ``period`` [s], its time-mean
    speed ``mean_omega`` = 2 pi / period [rad/s], its ``omega_min`` and ``omega_max``, the
    motor's RMS torque over time ``motor_rms``, its largest magnitude ``motor_peak`` [N m]
    and largest power ``motor_power`` [W], and when the turn began, ``t0`` [s]."""

    angles: np.ndarray
    omega: np.ndarray
    alpha: np.ndarray
    period: float
    mean_omega: float
    omega_min: float
    omega_max: float
    motor_rms: float
    motor_peak: float
    motor_power: float
    t0: float

    @property
    def fluctuation(self) -> float:
        """(max - min) / mean of the speed over the turn."""
        return (self.omega_max - self.omega_min) / self.mean_omega


@dataclass(frozen=True)
class Simulation:
    """The time histories from the start to the end, one row per output step: ``time``
    [s], ``angle`` [rad] (unwrapped), ``omega`` [rad/s], ``alpha`` [rad/s^2], ``motor``
    [N m]; ``turns`` integrated; ``steady`` the periodic motion (None with ``until`` a
    time); ``startup_time`` [s] to ``STARTUP_FRACTION`` of its mean speed (None without)."""

    time: np.ndarray
    angle: np.ndarray
    omega: np.ndarray
    alpha: np.ndarray
    motor: np.ndarray
    turns: int
    steady: SteadyCycle | None
    startup_time: float | None


class _Segments:
    """The integrator's dense outputs, one per turn, and the time each begins."""

    def __init__(self) -> None:
        self.starts: list[float] = []
        self.sols: list = []

    def add(self, t0: float, sol) -> None:
        self.starts.append(t0)
        self.sols.append(sol)

    def __call__(self, t: np.ndarray) -> np.ndarray:
        """The state (2, m) at times ``t`` (m,), each from the turn it falls in."""
        t = np.asarray(t, float)
        k = np.clip(np.searchsorted(self.starts, t, side="right") - 1, 0, len(self.sols) - 1)
        out = np.empty((2, len(t)))
        for i in np.unique(k):
            hit = k == i
            out[:, hit] = self.sols[i](t[hit])
        return out


def simulate(eom: EquationOfMotion, dyn: Dynamics, angles: np.ndarray, file: str
             ) -> Simulation:
    """The motion ``dyn`` (motor, flywheel, start, until) gives the mechanism of ``eom``;
    ``angles`` [deg] the sweep's, where the steady turn is sampled. Raises
    ``AnalysisError`` at a stall, or without a steady state after ``MAX_TURNS`` turns."""
    from scipy.integrate import solve_ivp
    alpha = eom.scalar()

    def rhs(t, y):
        return (y[1], alpha(y[0], y[1]))

    phi = math.radians(dyn.start_angle)
    omega = dyn.start_rpm * RPM
    if omega <= STALL_SPEED and alpha(phi, 0.0) <= 0:
        raise AnalysisError(_stall(file, eom, 0.0, phi, 0.0, start=True))
    if dyn.until is None:
        _require_balance(eom, file)

    def stall(t, y):
        return y[1] - STALL_SPEED
    stall.terminal, stall.direction = True, -1

    def reverse(t, y):            # started from rest, turned back before reaching STALL_SPEED
        return y[1] + STALL_SPEED
    reverse.terminal, reverse.direction = True, -1

    segments = _Segments()
    t, start_turns = 0.0, []      # (time, speed) at the start of each turn
    end = math.inf if dyn.until is None else dyn.until
    turn_start = phi
    steady = False
    for _ in range(MAX_TURNS):
        target = turn_start + 2 * math.pi

        def turn(t, y, target=target):
            return y[0] - target
        turn.terminal, turn.direction = True, 1
        scale = max(abs(omega), 1.0)
        sol = solve_ivp(rhs, (t, end), (phi, omega), method="DOP853", rtol=RTOL,
                        atol=(ATOL_ANGLE, RTOL * scale), events=(turn, stall, reverse),
                        dense_output=True)
        if sol.status < 0:
            raise AnalysisError(f"{file}: the integration of the equation of motion failed "
                                f"at t = {sol.t[-1]:.6g} s: {sol.message}")
        segments.add(t, sol.sol)
        t, (phi, omega) = float(sol.t[-1]), sol.y[:, -1]
        if sol.t_events[1].size or sol.t_events[2].size:
            raise AnalysisError(_stall(file, eom, t, phi, sol.sol(t)[1]))
        if not sol.t_events[0].size:          # the end time reached within the turn
            break
        phi = target                           # exactly: the event located it
        start_turns.append((t, float(omega)))
        turn_start = target
        if dyn.until is None and len(start_turns) >= 3:
            (t0, w0), (t1, w1), (t2, w2) = start_turns[-3:]
            # what is left to the limit of a geometric approach, d1 r / (1 - r): two turns
            # that agree are not enough where each turn changes the speed only a little less
            # than the one before (a large flywheel)
            d0, d1 = w1 - w0, w2 - w1
            r = abs(d1 / d0) if d0 else 0.0
            left = abs(d1) * r / (1 - r) if r < 1 else math.inf
            if abs(d1) <= STEADY_RTOL * abs(w2) and left <= STEADY_RTOL * abs(w2) and \
                    abs((t2 - t1) - (t1 - t0)) <= STEADY_RTOL * (t2 - t1):
                steady = True
                break
            if len(start_turns) >= SETTLE_TURNS:
                _require_settling(file, start_turns, t)
        if t >= end:
            break
    else:
        if dyn.until is not None:
            raise AnalysisError(
                f"{file}: dynamics.until = {dyn.until:g} s is more than {MAX_TURNS} turns "
                f"(reached at {t:.6g} s): simulate a shorter time")
        w = [s[1] for s in start_turns[-2:]]
        raise AnalysisError(
            f"{file}: no steady state after {MAX_TURNS} turns ({t:.6g} s): the speed at the "
            f"start of a turn still changes by {abs(w[-1] - w[0]) / abs(w[-1]):.2g} relative "
            "per turn; write dynamics.until as a time to see the transient")
    cycle = _steady(segments, eom, start_turns, angles) if steady else None
    startup = _startup(segments, t, cycle.mean_omega) if cycle else None
    time = _output_times(t, dyn, cycle, file)
    (ang, w) = segments(time)
    acc = eom.alpha(ang, w)
    return Simulation(time, ang, w, acc, motor_torque(eom.motor, w), len(start_turns), cycle,
                      startup)


def _require_balance(eom: EquationOfMotion, file: str) -> None:
    """Raise ``AnalysisError`` when nothing in the equation depends on the speed (a constant
    motor torque, no viscous load): the motor's work per turn and the loads' are then fixed
    numbers that balance only by accident, and the crank speeds up or runs down for ever."""
    if eom.motor.kind != "torque" or eom.viscous:
        return
    h = math.radians(eom.grid[1] - eom.grid[0])
    motor = 2 * math.pi * eom.motor.constant
    loads = float(np.sum(eom.D)) * h
    if abs(motor - loads) <= 1e-9 * max(abs(motor), abs(loads)):
        return
    raise AnalysisError(
        f"{file}: no steady state: the motor's torque is constant and no load depends on the "
        f"speed, so every turn the motor does {motor:.6g} J of work against the loads' "
        f"{loads:.6g} J and the crank {'speeds up without end' if motor > loads else 'runs down'}"
        "; give the motor a torque curve that falls with speed (curve or linear), or write "
        "dynamics.until as a time to see the transient")


def _require_settling(file: str, start_turns, t: float) -> None:
    """Raise ``AnalysisError`` when the speed at the turns' start does not approach a limit
    fast enough to reach ``STEADY_RTOL`` within ``MAX_TURNS``: the change per turn shrinks by
    a ratio r per turn (a steady state approaches geometrically), so what is left takes
    log(tol / change) / log(r) more turns."""
    (_, w0), (_, w1), (_, w2) = start_turns[-3:]
    d0, d1 = w1 - w0, w2 - w1
    if d0 == 0 or abs(d1) <= STEADY_RTOL * abs(w2):
        return
    ratio = abs(d1 / d0)
    more = (math.log(STEADY_RTOL * abs(w2) / abs(d1)) / math.log(ratio)
            if ratio < 1 else math.inf)
    if len(start_turns) + more <= MAX_TURNS:
        return
    trend = "rises" if d1 > 0 else "falls"
    raise AnalysisError(
        f"{file}: no steady state: after {len(start_turns)} turns ({t:.6g} s) the speed "
        f"{trend} by {abs(d1) / abs(w2):.2g} of itself per turn and does not settle within "
        f"{MAX_TURNS} turns (does anything take the motor's energy? a motor whose torque "
        "falls with speed, a damper or friction does); write dynamics.until as a time to see "
        "the transient")


def _steady(segments: _Segments, eom: EquationOfMotion, start_turns, angles) -> SteadyCycle:
    """The last turn integrated, sampled at the sweep's ``angles`` [deg]."""
    (t0, _), (t1, _) = start_turns[-2:]
    period = t1 - t0
    times = np.linspace(t0, t1, FINE + 1)
    phi, w = segments(times)
    phi0 = float(phi[0])
    # the time of each sweep angle within the turn: interpolated, then Newton's method
    want = phi0 + np.mod(np.radians(np.asarray(angles, float)) - phi0, 2 * math.pi)
    ts = np.interp(want, phi, times)
    for _ in range(4):
        p, v = segments(ts)
        ts = np.clip(ts - (p - want) / v, t0, t1)
    p, v = segments(ts)
    motor = motor_torque(eom.motor, w[:-1])
    mean = 2 * math.pi / period
    return SteadyCycle(np.asarray(angles, float), v, eom.alpha(p, v), period, mean,
                       float(min(np.min(w), np.min(v))), float(max(np.max(w), np.max(v))),
                       float(np.sqrt(np.mean(motor ** 2))), float(np.max(np.abs(motor))),
                       float(np.max(motor * w[:-1])), t0)


def _startup(segments: _Segments, t_end: float, mean: float) -> float:
    """The first time the speed reaches ``STARTUP_FRACTION`` of the steady ``mean`` [s]
    (0 when it starts faster)."""
    level = STARTUP_FRACTION * mean
    times = np.linspace(0.0, t_end, 20 * FINE + 1)
    w = segments(times)[1]
    above = np.flatnonzero(w >= level)
    if not len(above) or above[0] == 0:
        return 0.0
    lo, hi = times[above[0] - 1], times[above[0]]
    for _ in range(60):                     # bisection to the integrator's resolution
        mid = 0.5 * (lo + hi)
        if segments(np.array([mid]))[1][0] >= level:
            hi = mid
        else:
            lo = mid
    return float(hi)


def _output_times(t_end: float, dyn: Dynamics, cycle: SteadyCycle | None, file: str
                  ) -> np.ndarray:
    """One time per output step from 0 to ``t_end`` [s], and ``t_end`` itself last when
    ``until`` is a time. Raises ``AnalysisError`` beyond ``MAX_ROWS`` rows."""
    step = dyn.output_step
    if step is None:
        period = cycle.period if cycle else None
        step = period / DEFAULT_SAMPLES if period else t_end / (DEFAULT_SAMPLES * 10)
    rows = t_end / step
    if not rows < MAX_ROWS:
        raise AnalysisError(f"{file}: dynamics.output_step = {step:g} s gives {rows:.3g} rows "
                            f"of time history up to {t_end:.6g} s, more than {MAX_ROWS}: "
                            "write a larger output_step")
    n = int(math.floor(rows + 1e-9)) + 1
    times = np.arange(n) * step
    if dyn.until is not None:               # the last row exactly at `until`
        if times[-1] >= t_end - 1e-9 * step:
            times[-1] = t_end
        else:
            times = np.append(times, t_end)
    return times


def _stall(file: str, eom: EquationOfMotion, t: float, phi: float, omega: float,
           start: bool = False) -> str:
    """Why the crank stops: the motor's torque against the load's there."""
    deg = math.degrees(phi)
    load = float(eom.load_torque(np.array([phi]), np.array([max(omega, 0.0)]),
                                 np.array([0.0]))[0])
    motor = float(motor_torque(eom.motor, np.array([max(omega, 0.0)]))[0])
    where = f"at crank angle {deg % 360:.4g}° (turn {int(deg // 360) + 1})"
    # with friction the load's own number would leave the friction out: not printed
    needs = ("the mechanism's loads and friction" if eom.friction is not None
             else f"the {load:.6g} N·m the mechanism needs")
    if start:
        return (f"{file}: the crank cannot start {where}: the motor's starting torque "
                f"{motor:.6g} N·m does not overcome {needs} to move there (dynamics.motor, "
                "or dynamics.start)")
    return (f"{file}: the crank stalls {where}, t = {t:.6g} s: its speed falls to zero, the "
            f"motor's {motor:.6g} N·m there cannot carry {needs.replace('needs', 'takes')} "
            "on (a stronger motor, a larger flywheel, or a faster start)")


__all__ = ["MAX_TURNS", "RTOL", "STEADY_RTOL", "Simulation", "SteadyCycle", "simulate"]
