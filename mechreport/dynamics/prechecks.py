"""What can be said of a motion before integrating it: the checks that refuse, at once and with
the reason, an equation of motion the integrator could only grind on (a vanishing inertia, a
stiff motor) or a ``until`` that asks for more turns than the simulation integrates.

All of them read the equation's values on its grid of crank angles (J, B, C, D, see
:mod:`.equation`) and the motor's characteristic, piecewise linear in the speed.
"""
from __future__ import annotations

import math

import numpy as np

from ..errors import AnalysisError
from .equation import flywheel_estimate
from .motor import RPM, motor_torque
from .pieces import GRID_STEP_DEG

#: the reduced inertia on the crank (with the flywheel) at its smallest, relative to its
#: largest, at or below which the motion is refused: the kinetic energy the crank carries
#: would need a speed sqrt(1 / ratio) times the mean there (1000 times at 1e-6), and where
#: it reaches zero (light links at a dead centre) the equation of motion is singular
INERTIA_FLOOR = 1e-6
#: samples per grid interval of the spline of J where its smallest value is looked for (a
#: dead centre between two grid angles)
INERTIA_SAMPLES = 16
#: the stability limit of DOP853 along the negative real axis, |h lambda| (h the step [s],
#: lambda = d alpha / d omega [1/s]): an explicit method needs steps no longer than this
#: over the rate at which the speed settles onto the motor's curve
STABILITY = 6.0


def require_inertia(eom, file: str) -> None:
    """Raise ``AnalysisError`` where the reduced inertia on the crank J(phi) + flywheel
    [kg m^2] nearly vanishes (at most ``INERTIA_FLOOR`` of its largest value, on its spline
    sampled ``INERTIA_SAMPLES`` times per grid interval): the motor's torque would give the
    crank an unbounded acceleration there (light links at a dead centre, nothing with mass
    moving with the crank)."""
    deg = np.arange(0.0, math.degrees(eom.period), GRID_STEP_DEG / INERTIA_SAMPLES)
    total = eom.at(np.radians(deg))[:, 0] + eom.flywheel
    top = float(np.max(total))
    k = int(np.argmin(total))
    if top > 0 and total[k] > INERTIA_FLOOR * top:
        return
    where = f"at crank angle {float(deg[k]):.4g}°" if top > 0 else "at every crank angle"
    advice = (f"add a flywheel (dynamics.flywheel: {_round_up(1e-2 * top):g} kg·m², a "
              "hundredth of the largest, keeps the speed within about 10 times its mean)"
              if top > 0 else
              "give the links their masses, or add a flywheel (dynamics.flywheel, kg·m²)")
    raise AnalysisError(
        f"{file}: dynamics: the reduced inertia on the crank, J(φ) + flywheel, vanishes "
        f"{where} ({max(float(total[k]), 0.0):.3g} kg·m², against {top:.3g} kg·m² at most): "
        "there nothing with mass moves with the crank, so the motor's torque would give it an "
        f"unbounded acceleration and the equation of motion is singular; {advice}")


def steady_speed(eom, omega0: float) -> float | None:
    """The speed [rad/s] the crank settles near, from the energy balance at constant speed:
    over a turn the motor's torque Mm(omega) equals the mean load C_mean omega + D_mean (the
    inertia terms return over a turn; friction left out). The first speed, up from
    ``omega0`` where the motor gives more than that and down from it where it gives less,
    at which the balance turns from speeding up to slowing down. None where there is none
    (the crank runs down, or speeds up without end)."""
    c, d = float(np.mean(eom.C)), float(np.mean(eom.D))
    pts = [(float(x), float(y)) for x, y in eom.motor.points()]
    n0 = omega0 / RPM
    # g(n) = Mm(n) - c n RPM - d, linear in n [rpm] between the motor's points, and along
    # the end segments beyond them
    pieces = []
    for k in range(len(pts) - 1):
        (x0, y0), (x1, y1) = pts[k], pts[k + 1]
        lo = -math.inf if k == 0 else x0
        hi = math.inf if k == len(pts) - 2 else x1
        slope = (y1 - y0) / (x1 - x0) - c * RPM
        pieces.append((lo, hi, x0, y0 - c * RPM * x0 - d, slope))

    def g(piece, n):
        _, _, x0, g0, slope = piece
        return g0 + slope * (n - x0)

    def root(piece):
        _, _, x0, g0, slope = piece
        return x0 - g0 / slope

    up = g(next(p for p in pieces if p[0] <= n0 <= p[1]), n0) >= 0
    order = pieces if up else pieces[::-1]
    for p in order:
        lo, hi = max(p[0], 0.0), p[1]
        lo, hi = (max(lo, n0), hi) if up else (lo, min(hi, n0))
        if not lo <= hi or p[4] >= 0:
            continue
        if g(p, lo) >= 0 > (g(p, hi) if math.isfinite(hi) else -1.0):
            n = root(p)
            return n * RPM if n > 0 and math.isfinite(n) else None
    return None


def fluctuation_bound(eom, omega: float) -> float:
    """The speed fluctuation (max - min) / mean [-] to expect near a steady ``omega``
    [rad/s], the smaller of two estimates: the design review's (the kinetic energy taking up
    the loads' energy swing, :func:`~.equation.flywheel_estimate`) and the motor's (a steep
    motor curve holds the speed where its torque meets the loads': within the loads' range
    of torque over the motor's slope there)."""
    kinetic = flywheel_estimate(eom, omega)[2]
    loads = np.asarray(eom.B) * omega ** 2 + np.asarray(eom.C) * omega + np.asarray(eom.D)
    h = omega * 1e-9
    slope = abs(float(np.diff(motor_torque(eom.motor, np.array([omega - h, omega + h])))[0])
                / (2 * h))
    held = float(np.ptp(loads)) / (slope * omega) if slope > 0 else math.inf
    return min(kinetic, held)


def require_not_stiff(eom, omega: float | None, fluctuation: float, max_steps: int,
                      file: str) -> None:
    """Raise ``AnalysisError`` where the equation is stiff near the speed ``omega`` [rad/s]
    the crank settles at (:func:`steady_speed`): a change of speed dies out at the rate
    lambda = |dMm/domega - 2 B omega - C| / (J + If) [1/s] (a steep motor curve, or strong
    dampers on a small inertia), and an explicit integrator needs at least T mean(lambda) /
    STABILITY steps in a turn of period T = 2 pi / omega, however smooth the motion.
    Refused when that is more than ``max_steps``, the integrator's budget for a turn. The
    speeds within ``fluctuation`` / 2 of ``omega`` (:func:`fluctuation_bound`) are looked
    at, each motor segment there by its slope; not at all where that estimate is 1 or more
    (the kinetic energy does not cover the loads' swing: the crank may well stall, which the
    integration tells)."""
    if omega is None or not omega > 0 or not fluctuation < 1:
        return
    pts = [(float(x), float(y)) for x, y in eom.motor.points()]
    lo, hi = omega / RPM * (1 - fluctuation / 2), omega / RPM * (1 + fluctuation / 2)
    j, b, c = np.asarray(eom.J, float) + eom.flywheel, np.asarray(eom.B), np.asarray(eom.C)
    loads = 2 * b * omega + c
    period = 2 * math.pi / omega
    worst = None
    for k in range(len(pts) - 1):
        (x0, y0), (x1, y1) = pts[k], pts[k + 1]
        if (k > 0 and x0 > hi) or (k < len(pts) - 2 and x1 < lo):
            continue                               # the segment's speeds are not visited
        slope = (y1 - y0) / ((x1 - x0) * RPM)      # N m per rad/s
        rate = float(np.mean(np.abs(slope - loads) / j))
        steps = period * rate / STABILITY
        if worst is None or steps > worst[0]:
            worst = (steps, rate, k, slope)
    if worst is None or not worst[0] > max_steps:
        return
    steps, rate, k, slope = worst
    (x0, y0), (x1, y1) = pts[k], pts[k + 1]
    rpm = omega / RPM
    why = (f"there a change of speed dies out within {1 / rate:.3g} s, {period * rate:.3g} "
           f"times faster than a turn takes ({period:.3g} s), so the equation of motion is "
           f"stiff and its integration would need at least {steps:.3g} steps a turn (the "
           f"limit is {max_steps})")
    if abs(slope) < float(np.mean(np.abs(loads))):
        raise AnalysisError(
            f"{file}: dynamics: the loads that grow with the speed (dampers, C up to "
            f"{float(np.max(c)):.3g} N·m·s on the crank) against an inertia of "
            f"{float(np.mean(j)):.3g} kg·m² on it, near the speed the crank settles at "
            f"(about {rpm:.6g} rpm, from the energy balance): {why}. The crank then turns at "
            "the speed where the motor and the loads balance, turn by turn: analyse the sweep "
            f"at driver.rpm {rpm:.6g} without dynamics, or add a flywheel (dynamics.flywheel)")
    if eom.motor.kind == "linear":
        curve = f"the motor's torque falls from {y0:.4g} N·m at rest to 0 at {x1:.4g} rpm"
    else:
        curve = (f"the motor's torque {'falls' if y1 < y0 else 'rises'} from {y0:.4g} N·m at "
                 f"{x0:.10g} rpm to {y1:.4g} N·m at {x1:.10g} rpm")
    gentle = max_steps * STABILITY / period * float(np.mean(j)) * RPM   # N m per rpm
    raise AnalysisError(
        f"{file}: dynamics.motor: {curve}, {abs((y1 - y0) / (x1 - x0)):.3g} N·m per rpm, "
        f"near the speed the crank settles at (about {rpm:.6g} rpm, from the energy balance): "
        f"{why}. A motor that holds its speed this tightly turns the crank at that speed: "
        f"analyse the sweep at driver.rpm {rpm:.6g} without dynamics, or give the motor a "
        f"gentler slope (under about {gentle:.3g} N·m per rpm here)")


def turns_at_least(eom, omega0: float, until: float) -> tuple[float, float, float] | None:
    """A lower bound on the turns the crank makes by ``until`` [s], started at the speed
    ``omega0`` [rad/s], from the energy balance: with E = (J + If) omega^2 / 2 the kinetic
    energy, dE/dphi = Mm(omega) - C(phi) omega - D(phi) (the inertia terms B cancel). Where
    that is at least p >= 0 at every angle and every speed up to some omega_c, E cannot
    fall below E_c = (J_min + If) omega_c^2 / 2 once it has reached it (nor below its start
    while under it), and it reaches it within t_c = sqrt(2 (J_max + If)) (sqrt(E_c) -
    sqrt(E_0)) / p; after that the speed is at least sqrt(2 E_c / (J_max + If)).
    (turns, that speed [rad/s], t_c [s]) of the best omega_c, None without a bound. Without
    friction only (the friction's loss has no such bound)."""
    if eom.friction is not None:
        return None
    j = np.asarray(eom.J, float) + eom.flywheel
    jmin, jmax = float(np.min(j)), float(np.max(j))
    c, d = np.asarray(eom.C, float), np.asarray(eom.D, float)
    pts = [float(x) * RPM for x, _ in eom.motor.points()]
    top = max([omega0] + pts + [1.0])
    # the net torque is linear in omega between the motor's points at every angle: its
    # smallest value over [0, omega_c] is at one of them or at the ends; speeds far beyond
    # the motor's points (a constant torque has no speed of its own) on a geometric scale
    speeds = np.unique(np.concatenate([np.linspace(0.0, 4 * top, 801),
                                       np.geomspace(4 * top, 4e12 * top, 121),
                                       [w for w in pts if w > 0]]))
    with np.errstate(all="ignore"):
        net = motor_torque(eom.motor, speeds) - np.max(np.outer(speeds, c) + d, axis=1)
        floor = np.minimum.accumulate(net)                 # p over [0, speeds[k]]
        e0 = 0.5 * jmin * omega0 ** 2
        ec = 0.5 * jmin * speeds ** 2
        held = np.minimum(ec, e0)                          # from the start, with p >= 0
        reach = np.where(floor > 0, np.sqrt(2 * jmax) * np.maximum(
            np.sqrt(ec) - math.sqrt(e0), 0.0) / floor, np.inf)
        w_held = np.sqrt(2 * held / jmax)
        w_reach = np.sqrt(2 * ec / jmax)
        a = np.where(floor >= 0, until * w_held, 0.0)
        b = np.where((floor > 0) & (reach < until), (until - reach) * w_reach, 0.0)
    turns = np.maximum(a, b) / (2 * math.pi)
    turns[~np.isfinite(turns)] = 0.0
    k = int(np.argmax(turns))
    if not turns[k] > 0:
        return None
    if b[k] >= a[k]:
        return float(turns[k]), float(w_reach[k]), float(reach[k])
    return float(turns[k]), float(w_held[k]), 0.0


def _round_up(x: float) -> float:
    """``x`` > 0 rounded up to one significant digit."""
    e = math.floor(math.log10(x))
    return math.ceil(x / 10 ** e) * 10 ** e


__all__ = ["INERTIA_FLOOR", "STABILITY", "fluctuation_bound", "require_inertia",
           "require_not_stiff", "steady_speed", "turns_at_least"]
