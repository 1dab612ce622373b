"""The motor of machine dynamics: its torque against the crank's speed, through its gearing.

A motor geared at ``ratio`` (its speed ratio times the crank's) with efficiency ``eta`` gives
the crank ratio eta T while it drives (T > 0 at a positive speed: its power flows to the
crank) and ratio T / eta when the crank drives it back (T < 0), T its own torque at its own
speed. :func:`on_crank` writes that as one characteristic in crank rpm and crank N m (linear
pieces, a corner where T changes sign), so that the equation of motion, its prechecks and
its integrator read a geared motor as any other.
"""
from __future__ import annotations

import bisect
import numpy as np

from ..spec.types import MotorCurve
from ..units import RPM


def motor_torque(motor: MotorCurve, omega: np.ndarray) -> np.ndarray:
    """The torque [N m] of the characteristic ``motor`` at speeds ``omega`` [rad/s] (its
    own speed: the gearing is not applied, see :func:`on_crank`): linear between the
    characteristic's points and along its end segments beyond them."""
    pts = np.asarray(motor.points(), float)
    rpm = np.asarray(omega, float) / RPM
    x, y = pts[:, 0], pts[:, 1]
    k = np.clip(np.searchsorted(x, rpm) - 1, 0, len(x) - 2)
    slope = (y[k + 1] - y[k]) / (x[k + 1] - x[k])
    return y[k] + slope * (rpm - x[k])


def own_torque(motor: MotorCurve, omega: np.ndarray) -> np.ndarray:
    """The motor's own torque [N m] while the crank turns at ``omega`` [rad/s] (the motor
    at ``motor.ratio`` times that)."""
    return motor_torque(motor, motor.ratio * np.asarray(omega, float))


def own_power(motor: MotorCurve, omega: np.ndarray) -> np.ndarray:
    """The motor's own power [W] (its torque times its speed) at crank speeds ``omega``."""
    omega = np.asarray(omega, float)
    return own_torque(motor, omega) * motor.ratio * omega


def on_crank(motor: MotorCurve) -> MotorCurve:
    """The characteristic the crank shaft receives from ``motor`` through its gearing:
    ``motor`` itself without one (ratio and efficiency 1), else a curve in crank rpm and
    crank N m (a constant torque stays constant), equal to the geared motor at every speed:
    its points, a corner where the motor's torque changes sign (within the points and on
    the end segments' extensions), and one point beyond each such corner outside them."""
    n, eta = motor.ratio, motor.efficiency
    if n == 1.0 and eta == 1.0:
        return motor
    if motor.kind == "torque":
        c = motor.constant
        return MotorCurve(constant=n * (eta * c if c > 0 else c / eta))
    if eta == 1.0 and motor.kind == "linear":
        return MotorCurve(stall_torque=n * motor.stall_torque,
                          no_load_rpm=motor.no_load_rpm / n)
    pts = [tuple(map(float, p)) for p in motor.points()]
    (xa, ya), (xb, yb) = pts[0], pts[1]
    (xc, yc), (xd, yd) = pts[-2], pts[-1]
    out = list(pts)
    # a corner on an end segment's extension (its zero at or beyond the end point): the
    # corner, and the segment's reflection about it (the torque's sign beyond it)
    if ya != yb and (x0 := xa - ya * (xb - xa) / (yb - ya)) <= xa:
        out = [(2 * x0 - xb, -yb)] + ([(x0, 0.0)] if x0 < xa else []) + out
    if yc != yd and (x0 := xd - yd * (xd - xc) / (yd - yc)) >= xd:
        out = out + ([(x0, 0.0)] if x0 > xd else []) + [(2 * x0 - xc, -yc)]
    full = [out[0]]
    for (x1, y1), (x2, y2) in zip(out, out[1:]):
        if y1 * y2 < 0:                               # a corner within the points
            full.append((x1 - y1 * (x2 - x1) / (y2 - y1), 0.0))
        full.append((x2, y2))
    return MotorCurve(curve=tuple((x / n, n * (eta * y if y > 0 else y / eta))
                                  for x, y in full))


def motor_function(motor: MotorCurve):
    """:func:`motor_torque` for one speed, in plain floats."""
    pts = [tuple(map(float, p)) for p in motor.points()]
    xs = [p[0] for p in pts]
    last = len(pts) - 2

    def torque(omega: float) -> float:
        rpm = omega / RPM
        k = min(max(bisect.bisect_left(xs, rpm) - 1, 0), last)
        (x0, y0), (x1, y1) = pts[k], pts[k + 1]
        return y0 + (y1 - y0) / (x1 - x0) * (rpm - x0)
    return torque


def constant_drive(torque: float) -> MotorCurve:
    """A constant driving torque [N m] on the crank (``dynamics.mean_rpm``'s)."""
    return MotorCurve(constant=float(torque))


__all__ = ["RPM", "constant_drive", "motor_function", "motor_torque", "on_crank", "own_power",
           "own_torque"]
