"""Driver effort statistics over the analysed angles (not a whole-turn cycle: see review)."""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..forces import ForceResult


@dataclass(frozen=True)
class Peak:
    """Largest |value| [unit of the quantity] and the crank angle [deg] where it occurs."""

    value: float
    angle: float


TIE_RTOL = 1e-12   # values this close to the largest tie with it: the first angle is reported


def first_largest(v: np.ndarray) -> int:
    """Index of the first value within ``TIE_RTOL`` of the largest of ``v`` (a NaN: the first
    NaN). Equal peaks, such as a symmetric mechanism's, are reported at the first of them,
    not at whichever the last bit of rounding favours, so that a report does not change
    between runs whose numbers differ by rounding only."""
    k = int(np.argmax(v))
    top = v[k]
    if np.isfinite(top):
        k = int(np.argmax(v >= top - TIE_RTOL * abs(top)))
    return k


def peak(angles: np.ndarray, values: np.ndarray) -> Peak | None:
    """Signed value of largest magnitude and its angle (the first, on a tie); None for an
    empty sweep."""
    if len(values) == 0:
        return None
    k = first_largest(np.abs(values))
    return Peak(float(values[k]), float(angles[k]))


@dataclass(frozen=True)
class TorqueStats:
    """Driver torque over the analysed angles [N m]: mean, RMS, peak (signed, largest |T|),
    min, max; ``power`` the mean input power T omega [W]."""

    mean: float
    rms: float
    peak: Peak
    low: Peak
    high: Peak
    power: float


def torque_stats(res: ForceResult, omega: np.ndarray) -> TorqueStats | None:
    """Statistics of ``res.driver_torque`` (the driver's effort); ``omega`` (n,) the driven
    coordinate's rate [rad/s, or m/s for a T driver], so that ``power`` is effort x rate [W]."""
    t = np.asarray(res.driver_torque, float)
    if len(t) == 0:
        return None
    ang = res.angles
    kmin, kmax = first_largest(-t), first_largest(t)
    return TorqueStats(float(np.mean(t)), float(np.sqrt(np.mean(t**2))), peak(ang, t),
                       Peak(float(t[kmin]), float(ang[kmin])),
                       Peak(float(t[kmax]), float(ang[kmax])), float(np.mean(t * omega)))
