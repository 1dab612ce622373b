"""Direct dynamics: the crank's motion from its equation of motion, in time.

The state (crank angle phi [rad], speed omega [rad/s]) is integrated with scipy's
``solve_ivp`` (DOP853, relative tolerance ``RTOL``) one turn at a time, each turn from the
start angle (taken within a turn) on its own clock, so that neither the angle nor the time
grows and loosens the relative tolerance; the turns are counted apart. An event ends each
turn exactly one turn on, another stops at a stall (the speed falling to ``STALL_SPEED``:
the motor cannot carry the load on, or the crank would turn back). ``until: steady`` stops
when successive turns agree (the speed at the turn's start and the turn's period within
``STEADY_RTOL``, and both within it of the limits the turns approach, their ratio fitted
over several turns); ``until: TIME`` at that time.

Errors, never an endless run: what can be told before integrating is
(:mod:`.prechecks`: a vanishing inertia, a stiff motor, an ``until`` beyond ``MAX_TURNS``),
and the integration's work is bounded however it goes: ``MAX_EVALUATIONS_PER_TURN``
evaluations of the equation in a turn, ``MAX_EVALUATIONS`` in all, ``MAX_TURNS`` turns, and
the integrator's dense output kept for ``KEEP_STEPS`` steps at most (older turns are
integrated again, from their recorded start, when they are sampled).
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..errors import AnalysisError
from ..spec.types import Dynamics
from .equation import EquationOfMotion
from .motor import RPM, motor_torque
from .prechecks import (STABILITY, fluctuation_bound, require_inertia, require_not_stiff,
                        steady_speed, turns_at_least)

RTOL = 1e-10              # the integrator's relative tolerance (speed and angle)
ATOL_ANGLE = 1e-10        # [rad]
STEADY_RTOL = 1e-6        # two turns agree: speed and period within this, relative
STALL_SPEED = 1e-6        # [rad/s]: below it the crank has stopped
MAX_TURNS = 5_000         # turns integrated at most before giving up on a steady state
SETTLE_TURNS = 20         # turns after which the approach to a steady state is extrapolated
FIT_TURNS = 8             # turn-to-turn changes of the speed the approach's ratio is fitted to
NOISE = 1e-8              # a change per turn below this, relative, is the integrator's round-off
HOPELESS_TURNS = 5        # successive turns predicting no steady state before giving up
PREDICT_TURNS = 3         # turns after which an ``until`` time's count of turns is predicted
STARTUP_FRACTION = 0.95   # the start-up ends at this fraction of the steady mean speed
DEFAULT_SAMPLES = 200     # time-history samples per turn (the last one's), without output_step
MAX_ROWS = 2_000_000      # time-history rows at most (dynamics.csv about 180 MB)
FINE = 2000               # samples of a steady turn in time for its extremes and means
EVALUATIONS_PER_STEP = 15     # DOP853's right-hand sides per step: 12 stages, 3 for dense output
MAX_EVALUATIONS_PER_TURN = 300_000   # a turn normally takes about 2000
MAX_EVALUATIONS = 15_000_000         # in all: MAX_TURNS ordinary turns and some
KEEP_STEPS = 100_000      # the integrator's steps whose dense output is kept (some 60 MB)
START_SPACING = 1e-3      # [deg] the coarsest float spacing of a start angle reduced to a turn
CHUNK = 100_000           # time-history rows evaluated at once


@dataclass(frozen=True)
class SteadyCycle:
    """The periodic motion reached: at the sweep's ``angles`` (n,) [deg] the speed ``omega``
    and acceleration ``alpha`` (n,) [rad/s, rad/s^2]; the turn's ``period`` [s], its time-mean
    speed ``mean_omega`` = cycle / period [rad/s], its ``omega_min`` and ``omega_max`` (the
    integrated motion's, located between samples) and where they occur,
    ``omega_min_angle``, ``omega_max_angle`` [deg within the cycle], the motor's own RMS
    torque over time ``motor_rms``, its largest magnitude ``motor_peak`` [N m] and largest
    power ``motor_power`` [W] (the constant driving torque's with ``mean_rpm``), and when
    the turn began, ``t0`` [s]."""

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
    omega_max_angle: float = math.nan
    omega_min_angle: float = math.nan

    @property
    def fluctuation(self) -> float:
        """(max - min) / mean of the speed over the turn."""
        return (self.omega_max - self.omega_min) / self.mean_omega


@dataclass(frozen=True)
class Simulation:
    """The time histories from the start to the end, one row per output step: ``time``
    [s], ``angle`` [rad] (unwrapped, from the start angle taken within a turn), ``omega``
    [rad/s], ``alpha`` [rad/s^2], ``motor`` [N m]; ``turns`` integrated; ``steady`` the
    periodic motion (None with ``until`` a time); ``startup_time`` [s] to
    ``STARTUP_FRACTION`` of its mean speed (None without)."""

    time: np.ndarray
    angle: np.ndarray
    omega: np.ndarray
    alpha: np.ndarray
    motor: np.ndarray
    turns: int
    steady: SteadyCycle | None
    startup_time: float | None
    drive_torque: float | None = None     # mean_rpm: the constant driving torque [N m]


class _OverBudget(Exception):
    """The integration of a turn took more evaluations than allowed (private)."""


class _Turns:
    """The integration one turn at a time, and what it keeps of each turn: its start time
    ``starts`` [s] and speed ``omegas`` [rad/s] (every turn starts at the angle ``theta0``
    [rad]), the time it was given ``bounds`` [s, on its own clock], the integrator's dense
    output while within ``KEEP_STEPS`` steps in all (the oldest turns' are let go and
    integrated again, identically, when sampled), and the speed's largest value at its steps
    ``peaks``. Counts the equation's evaluations: ``evaluations`` in all."""

    def __init__(self, eom: EquationOfMotion, theta0: float, file: str, rtol: float = RTOL):
        self.eom, self.file, self.theta0, self.rtol = eom, file, theta0, rtol
        self.alpha = eom.scalar()
        self.evaluations = 0
        self._count, self._limit, self._y, self._nan = 0, 0, None, False
        self.starts: list[float] = []
        self.omegas: list[float] = []
        self.bounds: list[float] = []
        self.peaks: list[float] = []
        self._dense: list = []
        self._steps: list[int] = []
        self._kept, self._oldest = 0, 0
        self._again: dict = {}
        target = theta0 + eom.period          # a "turn" here is one cycle of the loads

        def turn(t, y):
            return y[0] - target
        turn.terminal, turn.direction = True, 1

        def stall(t, y):
            return y[1] - STALL_SPEED
        stall.terminal, stall.direction = True, -1

        def reverse(t, y):        # started from rest, turned back before reaching STALL_SPEED
            return y[1] + STALL_SPEED
        reverse.terminal, reverse.direction = True, -1
        self._events = (turn, stall, reverse)

    def _rhs(self, t, y):
        self._count += 1
        if self._count > self._limit:
            self._y = y
            raise _OverBudget
        phi, omega = float(y[0]), float(y[1])
        try:
            a = self.alpha(phi, omega)
        except (ValueError, OverflowError, ZeroDivisionError):     # from a state not finite
            a = math.nan
        if not math.isfinite(a):
            # a trial stage of a step too long for a stiff stretch: NaN makes the integrator
            # reject the step and try a shorter one; where none helps it fails (reported)
            if math.isfinite(phi) and math.isfinite(omega) or not self._nan:
                self._y = y                 # where, for the message: a finite state if any
            self._nan = True
            return (math.nan, math.nan)
        return (omega, a)

    def _integrate(self, omega: float, bound: float, limit: int):
        from scipy.integrate import solve_ivp
        self._count, self._limit, self._nan = 0, limit, False
        scale = max(abs(omega), 1.0)
        return solve_ivp(self._rhs, (0.0, bound), (self.theta0, omega), method="DOP853",
                         rtol=self.rtol, atol=(ATOL_ANGLE * self.rtol / RTOL,
                                               self.rtol * scale), events=self._events,
                         dense_output=True)

    def run(self, t0: float, omega: float, bound: float):
        """Integrate the next turn from time ``t0`` [s] at speed ``omega`` [rad/s] for at
        most ``bound`` [s]: the solver's result, on the turn's own clock. Raises
        ``AnalysisError`` beyond the evaluations allowed, or where the equation is not
        finite."""
        turn = len(self.starts)
        limit = min(MAX_EVALUATIONS_PER_TURN, MAX_EVALUATIONS - self.evaluations)
        try:
            sol = self._integrate(omega, bound, limit)
        except _OverBudget:
            raise AnalysisError(_too_costly(self.eom, self.file, turn, t0, self._y,
                                            limit < MAX_EVALUATIONS_PER_TURN)) from None
        finally:
            self.evaluations += self._count
        if sol.status < 0 and self._nan:
            raise AnalysisError(_not_finite(self.eom, self.file, turn, self._y))
        if sol.status < 0:
            raise AnalysisError(f"{self.file}: the integration of the equation of motion "
                                f"failed in turn {turn + 1} at t = {t0 + sol.t[-1]:.6g} s: "
                                f"{sol.message}")
        self.starts.append(t0)
        self.omegas.append(omega)
        self.bounds.append(bound)
        self.peaks.append(float(np.max(sol.y[1])))
        self._dense.append(sol.sol)
        self._steps.append(len(sol.sol.ts) - 1)
        self._kept += self._steps[-1]
        while self._kept > KEEP_STEPS and self._oldest < len(self._dense) - 2:
            self._kept -= self._steps[self._oldest]
            self._dense[self._oldest] = None
            self._oldest += 1
        return sol

    def dense(self, i: int):
        """Turn ``i``'s dense output (on its own clock), integrated again if let go."""
        if self._dense[i] is not None:
            return self._dense[i]
        if i not in self._again:
            if len(self._again) >= 2:
                self._again.pop(next(iter(self._again)))
            try:
                self._again[i] = self._integrate(self.omegas[i], self.bounds[i],
                                                 MAX_EVALUATIONS_PER_TURN).sol
            except _OverBudget:     # it did not the first time; with friction, barely
                raise AnalysisError(_too_costly(self.eom, self.file, i, self.starts[i],
                                                self._y, False)) from None
        return self._again[i]

    def __call__(self, t: np.ndarray) -> np.ndarray:
        """The state (2, m) at times ``t`` (m,) [s], the angle unwrapped (whole turns
        added), each from the turn it falls in."""
        t = np.asarray(t, float)
        starts = np.asarray(self.starts)
        k = np.clip(np.searchsorted(starts, t, side="right") - 1, 0, len(starts) - 1)
        out = np.empty((2, len(t)))
        for i in np.unique(k):
            hit = k == i
            out[:, hit] = self.dense(i)(t[hit] - starts[i])
            out[0, hit] += self.eom.period * i
        return out


def simulate(eom: EquationOfMotion, dyn: Dynamics, angles: np.ndarray, file: str
             ) -> Simulation:
    """The motion ``dyn`` (motor, flywheel, start, until) gives the mechanism of ``eom``;
    ``angles`` [deg] the sweep's, where the steady turn is sampled. Raises
    ``AnalysisError`` at a stall, without a steady state (``MAX_TURNS``), where the
    equation is singular or stiff, or beyond the integration's bounds."""
    theta0 = math.radians(_start_angle(dyn.start_angle, file))
    omega = dyn.start_rpm * RPM
    require_inertia(eom, file)
    turns = _Turns(eom, theta0, file)
    start_alpha = _finite_alpha(turns.alpha, theta0, 0.0)
    if omega <= STALL_SPEED and not start_alpha > 0:
        if math.isnan(start_alpha):
            raise AnalysisError(_not_finite(eom, file, 0, (theta0, omega)))
        raise AnalysisError(_stall(file, eom, 0.0, theta0, 0.0, 0, start=True))
    if dyn.until is None:
        _require_balance(eom, file)
    settle = steady_speed(eom, omega)
    require_not_stiff(eom, settle, fluctuation_bound(eom, settle) if settle else 0.0,
                      MAX_EVALUATIONS_PER_TURN // EVALUATIONS_PER_STEP, file)
    if dyn.until is not None:
        _require_reachable(eom, dyn, omega, file)

    t, start_turns = 0.0, []      # (time, speed) at the end of each turn
    end = math.inf if dyn.until is None else dyn.until
    steady, hopeless = False, 0
    for n in range(MAX_TURNS):
        sol = turns.run(t, omega, end - t)
        tau, (phi_end, omega_end) = float(sol.t[-1]), sol.y[:, -1]
        if sol.t_events[1].size or sol.t_events[2].size:
            raise AnalysisError(_stall(file, eom, t + tau, float(phi_end),
                                       float(sol.sol(tau)[1]), n))
        if not sol.t_events[0].size:          # the end time reached within the turn
            t = end
            break
        t, omega = t + tau, float(omega_end)
        start_turns.append((t, omega))
        if dyn.until is None and len(start_turns) >= 3:
            if _settled(start_turns):
                steady = True
                break
            hopeless = hopeless + 1 if len(start_turns) >= SETTLE_TURNS and \
                _hopeless(start_turns) else 0
            if hopeless >= HOPELESS_TURNS:
                raise AnalysisError(_no_settling(file, start_turns))
        if t >= end:
            break
        if dyn.until is not None and len(start_turns) >= PREDICT_TURNS:
            _require_turns_left(eom, start_turns, dyn.until, turns.evaluations, file)
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
    cycle = _steady(turns, eom, start_turns, angles) if steady else None
    startup = _startup(turns, t, cycle.mean_omega) if cycle else None
    time = _output_times(t, dyn, start_turns, file)
    ang, w, acc = (np.empty(len(time)) for _ in range(3))
    for k in range(0, len(time), CHUNK):
        part = slice(k, k + CHUNK)
        ang[part], w[part] = turns(time[part])
        acc[part] = eom.alpha(ang[part], w[part])
    return Simulation(time, ang, w, acc, eom.motor_own(w), len(start_turns), cycle,
                      startup)


def _finite_alpha(alpha, phi: float, omega: float) -> float:
    """``alpha(phi, omega)`` [rad/s^2], NaN where it is not finite."""
    try:
        a = alpha(phi, omega)
    except (ValueError, OverflowError, ZeroDivisionError):
        return math.nan
    return a if math.isfinite(a) else math.nan


def _start_angle(deg: float, file: str) -> float:
    """``dynamics.start.angle`` [deg] taken within a turn: its remainder after whole turns,
    the sign kept (math.fmod, exact: an angle within a turn stays as written). Raises
    ``AnalysisError`` where floats near the angle are more than ``START_SPACING`` apart:
    its place within a turn is then not known."""
    spacing = math.ulp(deg)
    if spacing > START_SPACING:
        raise AnalysisError(
            f"{file}: dynamics.start.angle: {deg:g}° names no place in a turn: numbers that "
            f"large are {spacing:.3g}° apart as floats, so what remains after whole turns is "
            "lost (a meaningful start angle is within a turn, e.g. between 0 and 360°); "
            "write the start angle within a turn")
    return math.fmod(deg, 360.0)


def _require_reachable(eom: EquationOfMotion, dyn: Dynamics, omega: float, file: str
                       ) -> None:
    """Raise ``AnalysisError``, before integrating, where ``until`` is a time the crank
    surely needs more than ``MAX_TURNS`` turns for (:func:`.prechecks.turns_at_least`,
    halved as a margin for the grid's sampling), or the time histories more than
    ``MAX_ROWS`` rows at the given ``output_step``."""
    if dyn.output_step is not None:
        rows = dyn.until / dyn.output_step
        if not rows < MAX_ROWS:
            raise AnalysisError(_too_many_rows(dyn.output_step, rows, dyn.until, file))
    bound = turns_at_least(eom, omega, dyn.until)
    if bound is None or not 0.5 * bound[0] > MAX_TURNS:
        return
    turns, speed, after = bound
    raise AnalysisError(
        f"{file}: dynamics.until = {dyn.until:g} s is more than {MAX_TURNS} turns, the most "
        f"integrated: from the energy balance the crank turns at {speed / RPM:.4g} rpm or "
        f"faster {f'after {after:.3g} s' if after > 0 else 'throughout'}, at least "
        f"{0.5 * turns:.3g} turns by then; simulate a shorter time ({MAX_TURNS} turns are "
        f"done within {after + MAX_TURNS * eom.period / speed:.3g} s here), or write until: "
        "steady")


def _require_turns_left(eom: EquationOfMotion, start_turns, until: float, evaluations: int,
                        file: str) -> None:
    """Raise ``AnalysisError`` where the turns to ``until`` [s], predicted from the last
    ones, would be more than ``MAX_TURNS``, or their evaluations of the equation (at the
    mean so far, ``evaluations`` in all) more than ``MAX_EVALUATIONS``. While the crank is
    not slowing down, at the rate it now turns: it makes no fewer. While it slows down, its
    kinetic energy (as its mean speed squared) falling by the last turn's loss each turn,
    and only as far as it keeps twice the loads' energy swing (it cannot stall against
    them before): no fewer either where that loss does not grow as the crank slows
    (dampers, a braking motor and friction take less at a lower speed)."""
    (t0, _), (t1, _), (t2, _) = start_turns[-3:]
    period, before = t2 - t1, t1 - t0
    done, left = len(start_turns), until - t2
    steady = period <= before * (1 + STEADY_RTOL)
    if steady:
        more = left / period
    else:
        stop = 1 / (1 - (before / period) ** 2)           # turns until the energy is gone
        omega = eom.period / period
        energy = (float(np.mean(eom.J)) + eom.flywheel) * omega ** 2 / 2
        safe = stop * (1 - 2 * _load_swing(eom, omega) / energy)
        if not safe > 0:
            return
        keep = 1 - left / (2 * stop * period)             # the speed kept by then, relative
        more = min(safe, stop * (1 - keep ** 2) if keep > 0 else math.inf)
    turns = done + more
    work = evaluations * turns / done
    if turns <= MAX_TURNS and work <= MAX_EVALUATIONS:
        return
    limit = (f"{MAX_TURNS} turns, the most integrated" if turns > MAX_TURNS else
             f"{MAX_EVALUATIONS:.3g} evaluations of the equation of motion, the most made "
             f"(here {evaluations / done:.3g} a turn)")
    pace = "does not slow down" if steady else "loses its energy slowly"
    most = min(MAX_TURNS, MAX_EVALUATIONS * done / evaluations)
    raise AnalysisError(
        f"{file}: dynamics.until = {until:g} s is more than {limit}: after {done} turns "
        f"({t2:.4g} s) the crank turns once in {period:.4g} s and {pace}, so it would make "
        f"at least some {turns:.3g} turns by then; simulate a shorter time (about "
        f"{most:.4g} turns take {period * most:.3g} s at the present rate), or write until: "
        "steady")


def _load_swing(eom: EquationOfMotion, omega: float) -> float:
    """The largest swing [J] over a turn of the work of the loads (C omega + D, at the
    constant speed ``omega`` [rad/s], against their mean): what the kinetic energy must
    carry the crank over."""
    torque = np.asarray(eom.C) * omega + np.asarray(eom.D)
    work = np.cumsum(torque - np.mean(torque)) * math.radians(eom.grid[1] - eom.grid[0])
    return float(np.max(work) - np.min(np.concatenate([[0.0], work])))


def _contraction(values) -> float:
    """The ratio by which the change of ``values`` from turn to turn (the speed at the
    turns' ends, or their periods) shrinks per turn, fitted to the last ``FIT_TURNS``
    changes above the integrator's resolution (``NOISE`` of the value; looked for among the
    last 4 ``FIT_TURNS``): the median of the slopes of log |change| against the turn between
    every two of them (Theil and Sen), which a change or two disturbed by round-off does not
    move. 0 where fewer than two changes are above it: nothing left to see."""
    v = np.asarray(values[-4 * FIT_TURNS - 1:], float)
    d = np.abs(np.diff(v))
    turn = np.flatnonzero(d > NOISE * abs(v[-1]))[-FIT_TURNS:]
    if len(turn) < 2:
        return 0.0
    x = np.log(d[turn])
    i, j = np.triu_indices(len(x), 1)
    return float(np.exp(np.median((x[j] - x[i]) / (turn[j] - turn[i]))))


def _left(values) -> float:
    """What is left, relative, between the last of ``values`` and the limit of their
    geometric approach: d r / (1 - r) of the last change d, r by :func:`_contraction`."""
    r = _contraction(values)
    d = abs(values[-1] - values[-2])
    return (d * r / (1 - r) if r < 1 else math.inf if d else 0.0) / abs(values[-1])


def _settled(start_turns) -> bool:
    """Whether the last two turns agree (the speed at their ends and their periods within
    ``STEADY_RTOL``) and what is left of both to the limit of their geometric approach is
    within it too: two turns that agree are not enough where each turn changes the speed
    only a little less than the one before (a large flywheel)."""
    if len(start_turns) < 3:
        return False
    speeds = [s[1] for s in start_turns[-4 * FIT_TURNS - 1:]]
    ends = [0.0] + [s[0] for s in start_turns]
    periods = list(np.diff(ends[-4 * FIT_TURNS - 2:]))
    tol = STEADY_RTOL
    return abs(speeds[-1] - speeds[-2]) <= tol * abs(speeds[-1]) and \
        abs(periods[-1] - periods[-2]) <= tol * periods[-1] and \
        _left(speeds) <= tol and _left(periods) <= tol


def _turns_to_settle(start_turns) -> float:
    """The turns after which the approach, extrapolated, is settled: the change per turn d
    shrinks by the fitted ratio r each turn, so what is left, d r^m r / (1 - r) after m
    more turns, reaches ``STEADY_RTOL`` after m = log(tol (1 - r) / (r d)) / log r (inf
    where the change does not shrink)."""
    w = [s[1] for s in start_turns]
    d, tol = abs(w[-1] - w[-2]), STEADY_RTOL * abs(w[-1])
    r = _contraction(w)
    if r >= 1:
        return math.inf if d > 0 else len(w)
    if r == 0 or d * r / (1 - r) <= tol:
        return len(w)
    return len(w) + math.log(tol * (1 - r) / (r * d)) / math.log(r)


def _hopeless(start_turns) -> bool:
    """Whether the turns' approach, extrapolated, would not settle within ``MAX_TURNS``."""
    return _turns_to_settle(start_turns) > MAX_TURNS


def _no_settling(file: str, start_turns) -> str:
    """Why there is no steady state: the change of speed per turn does not shrink, or too
    slowly to settle within ``MAX_TURNS``."""
    (_, w1), (t, w2) = start_turns[-2:]
    d1 = w2 - w1
    r = _contraction([s[1] for s in start_turns])
    trend = "rises" if d1 > 0 else "falls"
    if r < 1:
        how = (f", the change shrinking by only {1 - r:.2g} of itself a turn: it would settle "
               f"after some {_turns_to_settle(start_turns):.3g} turns, and does not settle "
               f"within the {MAX_TURNS} integrated (a start nearer the speed it settles at, "
               "or a smaller flywheel, settles sooner)")
    else:
        how = (f" and the change does not shrink: it does not settle within {MAX_TURNS} "
               "turns (does anything take the motor's energy? a motor whose torque falls "
               "with speed, a damper or friction does)")
    return (f"{file}: no steady state: after {len(start_turns)} turns ({t:.6g} s) the speed "
            f"{trend} by {abs(d1) / abs(w2):.2g} of itself per turn{how}; write "
            "dynamics.until as a time to see the transient")


def _too_costly(eom: EquationOfMotion, file: str, turn: int, t0: float, y, total: bool
                ) -> str:
    """Why the integration took more evaluations of the equation than allowed, from the
    state ``y`` (phi [rad], omega [rad/s]) it had reached: the inertia nearly vanishing
    there, or the speed's rate of settling (the equation stiff), or else the count."""
    phi, omega = float(y[0]), float(y[1])
    if total:
        return (f"{file}: the integration of the equation of motion took more than "
                f"{MAX_EVALUATIONS:.3g} evaluations in all (in turn {turn + 1}, t = {t0:.6g} "
                "s; some 5000 ordinary turns take that many): write dynamics.until as a time, "
                "or a shorter one")
    if not (math.isfinite(phi) and math.isfinite(omega)):
        return (f"{file}: the integration of the equation of motion took more than "
                f"{MAX_EVALUATIONS_PER_TURN:.3g} evaluations in turn {turn + 1} (an ordinary "
                "turn takes about 2000) and its state overflowed: the motor's torque "
                "(dynamics.motor) or the loads are too large for the inertia on the crank")
    deg = math.degrees(phi) % 360
    j, b, c, _ = (float(x) for x in eom.at(np.array([phi]))[0])
    inertia = j + eom.flywheel
    top = float(np.max(eom.J)) + eom.flywheel
    head = (f"{file}: the integration of the equation of motion took more than "
            f"{MAX_EVALUATIONS_PER_TURN:.3g} evaluations in turn {turn + 1} (an ordinary turn "
            f"takes about 2000), stuck near crank angle {deg:.4g}° at {omega / RPM:.6g} rpm")
    if inertia <= 1e-4 * top:
        return (f"{head}: there the reduced inertia on the crank is {inertia:.3g} kg·m², "
                f"against {top:.3g} kg·m² at most, and the speed swings violently; add a "
                "flywheel (dynamics.flywheel)")
    h = max(abs(omega), 1e-9) * 1e-9
    slope = float(np.diff(motor_torque(eom.motor, np.array([omega - h, omega + h])))[0]
                  / (2 * h))
    rate = abs(slope - 2 * b * omega - c) / inertia
    period = 2 * math.pi / abs(omega) if omega else math.inf
    if rate * period / STABILITY > 0.1 * MAX_EVALUATIONS_PER_TURN / EVALUATIONS_PER_STEP:
        return (f"{head}: there a change of speed dies out within {1 / rate:.3g} s, "
                f"{rate * period:.3g} times faster than a turn takes, so the equation is stiff "
                f"(the motor's torque changes by {abs(slope) * RPM:.3g} N·m per rpm there, "
                f"dynamics.motor, over {inertia:.3g} kg·m² on the crank); "
                "give the motor's curve a gentler slope near that speed, or the crank more "
                "inertia (dynamics.flywheel)")
    return (f"{head}: the motion changes there faster than the integrator can follow at its "
            "tolerance; check the loads and the motor near that angle and speed")


def _not_finite(eom: EquationOfMotion, file: str, turn: int, y) -> str:
    """Where the equation of motion gave no finite acceleration."""
    phi, omega = float(y[0]), float(y[1])
    where = (f"at crank angle {math.degrees(phi) % 360:.4g}° and {omega / RPM:.6g} rpm"
             if math.isfinite(phi) and math.isfinite(omega) else "(the state overflowed)")
    return (f"{file}: the equation of motion has no finite acceleration {where}, in turn "
            f"{turn + 1}: the motor's torque (dynamics.motor) or the loads are too large for the "
            "inertia on the crank; check their magnitudes and units")


def _require_balance(eom: EquationOfMotion, file: str) -> None:
    """Raise ``AnalysisError`` when nothing in the equation depends on the speed (a constant
    motor torque, no viscous load): the motor's work per turn and the loads' are then fixed
    numbers that balance only by accident, and the crank speeds up or runs down for ever."""
    if eom.motor.kind != "torque" or eom.viscous:
        return
    h = math.radians(eom.grid[1] - eom.grid[0])
    motor = eom.period * eom.motor.constant
    loads = float(np.sum(eom.D)) * h
    if abs(motor - loads) <= 1e-9 * max(abs(motor), abs(loads)):
        return
    raise AnalysisError(
        f"{file}: no steady state: the motor's torque is constant and no load depends on the "
        f"speed, so every turn the motor does {motor:.6g} J of work against the loads' "
        f"{loads:.6g} J and the crank {'speeds up without end' if motor > loads else 'runs down'}"
        "; give the motor a torque curve that falls with speed (curve or linear), or write "
        "dynamics.until as a time to see the transient")


def _steady(turns: _Turns, eom: EquationOfMotion, start_turns, angles) -> SteadyCycle:
    """The last turn (cycle) integrated, sampled at the sweep's ``angles`` [deg], on its own
    clock."""
    (t0, _), (t1, _) = start_turns[-2:]
    return steady_cycle(turns.dense(len(start_turns) - 1), turns.alpha, eom, t1 - t0, t0,
                        angles)


def steady_cycle(sol, alpha, eom: EquationOfMotion, period: float, t0: float, angles
                 ) -> SteadyCycle:
    """The periodic motion given by the dense output ``sol`` of one cycle (time [s] on its
    own clock, from 0 to ``period``, to (phi [rad], omega [rad/s])): sampled at the sweep's
    ``angles`` [deg], its extremes of speed located between samples (:func:`_extreme`),
    the motor's torque and power over it. ``alpha``: the equation's scalar acceleration."""
    times = np.linspace(0.0, period, FINE + 1)
    phi, w = sol(times)
    phi0 = float(phi[0])
    # the time of each sweep angle within the turn: interpolated, then Newton's method
    want = phi0 + np.mod(np.radians(np.asarray(angles, float)) - phi0, eom.period)
    ts = np.interp(want, phi, times)
    for _ in range(4):
        p, v = sol(ts)
        ts = np.clip(ts - (p - want) / v, 0.0, period)
    p, v = sol(ts)
    motor = eom.motor_own(w[:-1])
    cycle_deg = math.degrees(eom.period)
    (w_max, a_max), (w_min, a_min) = (_extreme(sol, alpha, times, w, sign, period, cycle_deg)
                                      for sign in (1.0, -1.0))
    return SteadyCycle(np.asarray(angles, float), v, eom.alpha(p, v), period,
                       eom.period / period, w_min, w_max,
                       float(np.sqrt(np.mean(motor ** 2))), float(np.max(np.abs(motor))),
                       float(np.max(eom.motor_power(w[:-1]))), t0, a_max, a_min)


def _extreme(sol, alpha, times: np.ndarray, w: np.ndarray, sign: float, period: float,
             cycle_deg: float) -> tuple[float, float]:
    """The largest (``sign`` +1) or smallest (-1) speed of the periodic motion ``sol`` and
    the crank angle where it occurs [rad/s, deg within the cycle]: near the extreme sample
    of ``w`` (at ``times``), where the acceleration ``alpha(phi, omega)`` changes sign
    (Brent's method on the dense output, the times taken modulo the period), or, where it
    does not change sign there (a friction's corner), the dense output's extreme between
    the neighbouring samples."""
    from scipy.optimize import brentq, minimize_scalar
    k = int(np.argmax(sign * w[:-1]))
    dt = times[1] - times[0]
    lo, hi = times[k] - dt, times[k] + dt

    def state(t: float) -> tuple[float, float]:
        t = t % period
        p, v = sol(t)
        return float(p), float(v)

    def acc(t: float) -> float:
        return sign * alpha(*state(t))
    try:
        a_lo, a_hi = acc(lo), acc(hi)
        if a_lo > 0 > a_hi:
            t = brentq(acc, lo, hi, xtol=1e-15 * max(period, 1.0))
        else:
            t = minimize_scalar(lambda t: -sign * state(t)[1], bounds=(lo, hi),
                                method="bounded", options={"xatol": 1e-12 * period}).x
    except (ValueError, ArithmeticError):
        t = times[k]
    p, v = state(t)
    if sign * v < sign * w[k]:               # never less extreme than a sample
        p, v = state(times[k])
    return v, math.degrees(p) % cycle_deg


def _startup(turns: _Turns, t_end: float, mean: float) -> float:
    """The first time the speed reaches ``STARTUP_FRACTION`` of the steady ``mean`` [s]
    (0 when it starts faster), from samples over the run, only as far as the first turn
    whose integrator steps reach it (the turns after it are not sampled again)."""
    level = STARTUP_FRACTION * mean
    times = np.linspace(0.0, t_end, 20 * FINE + 1)
    first = next((i for i, p in enumerate(turns.peaks) if p >= level), None)
    w = None
    if first is not None and first + 1 < len(turns.starts):
        early = times[times <= turns.starts[first + 1]]
        w = turns(early)[1]
        if np.any(w >= level):
            times = early
        else:
            w = None                        # reached between two samples only: all of them
    if w is None:
        w = turns(times)[1]
    above = np.flatnonzero(w >= level)
    if not len(above) or above[0] == 0:
        return 0.0
    lo, hi = times[above[0] - 1], times[above[0]]
    for _ in range(60):                     # bisection to the integrator's resolution
        mid = 0.5 * (lo + hi)
        if turns(np.array([mid]))[1][0] >= level:
            hi = mid
        else:
            lo = mid
    return float(hi)


def _output_times(t_end: float, dyn: Dynamics, start_turns, file: str) -> np.ndarray:
    """One time per output step from 0 to ``t_end`` [s], and ``t_end`` itself last when
    ``until`` is a time. Without ``output_step``: ``DEFAULT_SAMPLES`` per turn at the last
    whole turn's period (the steady one with ``until: steady``; with no whole turn, over the
    time simulated). Raises ``AnalysisError`` beyond ``MAX_ROWS`` rows."""
    step = dyn.output_step
    if step is None:
        times = [0.0] + [s[0] for s in start_turns[-2:]]
        period = times[-1] - times[-2] if len(times) > 1 else t_end
        step = period / DEFAULT_SAMPLES
    rows = t_end / step
    if not rows < MAX_ROWS:
        raise AnalysisError(_too_many_rows(step, rows, t_end, file))
    n = int(math.floor(rows + 1e-9)) + 1
    times = np.arange(n) * step
    if dyn.until is not None:               # the last row exactly at `until`
        if times[-1] >= t_end - 1e-9 * step:
            times[-1] = t_end
        else:
            times = np.append(times, t_end)
    return times


def _too_many_rows(step: float, rows: float, t_end: float, file: str) -> str:
    return (f"{file}: dynamics.output_step = {step:g} s gives {rows:.3g} rows of time history "
            f"up to {t_end:.6g} s, more than {MAX_ROWS}: write a larger output_step")


def _stall(file: str, eom: EquationOfMotion, t: float, phi: float, omega: float, turn: int,
           start: bool = False) -> str:
    """Why the crank stops at angle ``phi`` [rad] in turn ``turn`` (from 0): the motor's
    torque against the load's there."""
    deg = math.degrees(phi)
    load = float(eom.load_torque(np.array([phi]), np.array([max(omega, 0.0)]),
                                 np.array([0.0]))[0])
    motor = float(motor_torque(eom.motor, np.array([max(omega, 0.0)]))[0])
    where = f"at crank angle {deg % 360:.4g}° (turn {turn + 1})"
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
