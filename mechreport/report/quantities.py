"""Derived sweep quantities the reports show: frame (shaking) loads, bearing polar traces,
driver-torque statistics. Pure numpy over an :class:`~mechreport.analysis.Analysis`; arrays
are ``(n,)`` over ``analysis.angles`` (the angle axis first)."""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..forces import ForceResult
from ..kinematics.frames import cross, rotate
from ..spec import GROUND, Joint


def reference_method(forces: dict[str, ForceResult]) -> str:
    """The method whose reactions the plots and drawings show: the first that has reactions
    (all methods agree to rounding; the agreement table says how well)."""
    for name, res in forces.items():
        if res.reactions:
            return name
    return next(iter(forces))


@dataclass(frozen=True)
class FrameLoad:
    """Resultant of the reactions acting on the ground link (the shaking force) ``fx``,
    ``fy`` (n,) [N], and its moment ``m`` (n,) [N m] about the driver pivot, including the
    driver's reaction torque -M on the frame."""

    fx: np.ndarray
    fy: np.ndarray
    m: np.ndarray

    @property
    def f(self) -> np.ndarray:
        return np.hypot(self.fx, self.fy)


def frame_load(analysis, res: ForceResult) -> FrameLoad:
    """Shaking force and moment on the frame from method ``res``'s reactions.

    For a joint [ground, X] the ground receives -F (F is ground on X); for [X, ground] +F.
    T joints add their couple with the same sign. Moments about the driver pivot."""
    spec, ctx = analysis.spec, analysis.context
    n = len(res.angles)
    pivot = np.asarray(ctx.joint_points[spec.driver.joint])
    fx, fy, m = np.zeros(n), np.zeros(n), -np.asarray(res.driver_torque, float)
    for joint in spec.joints:
        if GROUND not in joint.links or joint.name not in res.reactions:
            continue
        sign = -1.0 if joint.links[0] == GROUND else 1.0
        r = res.reactions[joint.name]
        f = sign * np.stack([r.fx, r.fy], axis=1)
        fx, fy = fx + f[:, 0], fy + f[:, 1]
        m = m + cross(ctx.joint_points[joint.name] - pivot, f)
        if r.moment is not None:
            m = m + sign * r.moment
    return FrameLoad(fx, fy, m)


def bearing_carrier(joint: Joint) -> str:
    """The link whose frame a pin's polar diagram is drawn in: ground for a frame pin,
    otherwise the joint's second link (the one the reaction F acts on)."""
    return GROUND if GROUND in joint.links else joint.links[1]


def bearing_trace(analysis, res: ForceResult, joint: Joint) -> np.ndarray:
    """Reaction F of ``joint`` (first link on second) in the carrier's frame, (n, 2) [N]:
    the global vector rotated by -theta of the carrier (unchanged for ground)."""
    r = res.reactions[joint.name]
    f = np.stack([r.fx, r.fy], axis=1)
    carrier = bearing_carrier(joint)
    if carrier == GROUND:
        return f
    return rotate(f, -analysis.kinematics.theta[:, analysis.spec.number(carrier)])


@dataclass(frozen=True)
class Peak:
    """Largest |value| [unit of the quantity] and the crank angle [deg] where it occurs."""

    value: float
    angle: float


def peak(angles: np.ndarray, values: np.ndarray) -> Peak | None:
    """Signed value of largest magnitude and its angle; None for an empty sweep."""
    if len(values) == 0:
        return None
    k = int(np.argmax(np.abs(values)))
    return Peak(float(values[k]), float(angles[k]))


@dataclass(frozen=True)
class TorqueStats:
    """Driver torque over the sweep [N m]: mean, RMS, peak (signed, largest |T|), min, max;
    ``power`` the mean input power T omega [W]."""

    mean: float
    rms: float
    peak: Peak
    low: Peak
    high: Peak
    power: float


def torque_stats(analysis, res: ForceResult) -> TorqueStats | None:
    t = np.asarray(res.driver_torque, float)
    if len(t) == 0:
        return None
    ang = res.angles
    omega = analysis.kinematics.omega[:, analysis.spec.number(analysis.spec.driver.link)]
    kmin, kmax = int(np.argmin(t)), int(np.argmax(t))
    return TorqueStats(float(np.mean(t)), float(np.sqrt(np.mean(t**2))), peak(ang, t),
                       Peak(float(t[kmin]), float(ang[kmin])),
                       Peak(float(t[kmax]), float(ang[kmax])), float(np.mean(t * omega)))


def with_gaps(angles: np.ndarray, *arrays: np.ndarray):
    """Angles and arrays with NaN inserted where the sweep skips angles (left-out angles), so
    plotted lines break there instead of bridging the gap. For plotting only."""
    angles = np.asarray(angles, float)
    if len(angles) < 3:
        return (angles, *arrays)
    step = np.median(np.diff(angles))
    cut = np.flatnonzero(np.diff(angles) > 1.5 * step) + 1
    out_a = np.insert(angles, cut, np.nan)
    return (out_a, *(np.insert(np.asarray(a, float), cut, np.nan, axis=0) for a in arrays))
