"""The motor of machine dynamics: its torque against the crank's speed."""
from __future__ import annotations

import bisect

import numpy as np

from ..spec.types import MotorCurve
from ..units import RPM



def motor_torque(motor: MotorCurve, omega: np.ndarray) -> np.ndarray:
    """The motor's torque [N m] at crank speeds ``omega`` [rad/s]: linear between the
    characteristic's points and along its end segments beyond them."""
    pts = np.asarray(motor.points(), float)
    rpm = np.asarray(omega, float) / RPM
    x, y = pts[:, 0], pts[:, 1]
    k = np.clip(np.searchsorted(x, rpm) - 1, 0, len(x) - 2)
    slope = (y[k + 1] - y[k]) / (x[k + 1] - x[k])
    return y[k] + slope * (rpm - x[k])


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



__all__ = ["RPM", "motor_function", "motor_torque"]
