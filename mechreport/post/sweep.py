"""What a sweep's results come to, computed once: the driver effort's statistics, each
joint's peak and RMS load (and its peak away from left-out angles), the frame load and its
peaks, each pin's load traced in its bearing's frame, and the power balance against the
reference method. Every output (report, summary.json, index, diff) reads these records.

Over the analysed angles (n,) [deg, or a stroke's length unit], from the reference method
(:func:`~mechreport.post.frame.reference_method`); SI throughout.
"""
from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np

from .bearings import bearing_trace
from .frame import FrameLoad, frame_load, reference_method
from .torque import Peak, TorqueStats, peak, torque_stats

#: how far either side of a left-out angle values are near-singular: reported, but they do
#: not set a plot's scale nor a joint's peak "away from left-out angles" (in sweep steps, at
#: least 2 degrees)
NEAR_STEPS = 5


def near_mask(angles: np.ndarray, flagged, step: float) -> tuple[np.ndarray, float]:
    """Angles (n,) within ``NEAR_STEPS`` sweep steps (at least 2 degrees) of a left-out
    angle, and that width [deg]."""
    angles = np.asarray(angles, float)
    width = max(NEAR_STEPS * float(step), 2.0)
    if not len(flagged) or not len(angles):
        return np.zeros(len(angles), bool), width
    f = np.asarray(sorted(flagged), float)
    d = np.abs(angles[:, None] - f[None, :]) % 360.0
    d = np.minimum(d, 360.0 - d)                      # circular: 359 is next to 0
    return (d.min(axis=1) <= width + 1e-9), width


@dataclass(frozen=True)
class JointLoad:
    """One joint's reaction over the analysed angles [N]: the magnitude's ``peak`` (largest,
    first angle on a tie), ``peak_far`` its largest away from left-out angles (None when
    every angle is near one), ``rms``; the components' peaks ``fx_peak``, ``fy_peak``."""

    joint: str
    peak: Peak | None
    peak_far: Peak | None
    rms: float | None
    fx_peak: Peak | None
    fy_peak: Peak | None


@dataclass(frozen=True)
class PowerCheck:
    """The driver effort by the power balance against the reference method's: the largest
    difference ``max_abs`` [N m, or N], ``relative`` to the reference's peak effort, at
    ``angle``."""

    max_abs: float
    relative: float
    angle: float


@dataclass(frozen=True)
class SweepSummary:
    """The records above for one analysis. ``near`` (n,) marks the angles within
    ``near_deg`` of a left-out angle; ``torque`` the effort's statistics (None for an empty
    sweep); ``frame`` the load on the frame with its ``shaking_force`` and
    ``shaking_moment`` peaks; ``joints`` by joint name (joints the reference method solves);
    ``largest`` the joint with the largest peak load and that peak; ``traces`` each pin's
    reaction (n, 2) [N] in its carrier's frame (:func:`~.bearings.bearing_trace`);
    ``power_check`` None when the power balance was not solved separately."""

    method: str
    near: np.ndarray
    near_deg: float
    torque: TorqueStats | None
    frame: FrameLoad
    shaking_force: Peak | None
    shaking_moment: Peak | None
    joints: dict[str, JointLoad]
    largest: tuple[str, Peak] | None
    traces: dict[str, np.ndarray]
    power_check: PowerCheck | None


def far_peak(angles: np.ndarray, values: np.ndarray, near: np.ndarray) -> Peak | None:
    """Peak of ``values`` away from the ``near`` angles (None when every angle is near)."""
    far = ~near if len(near) == len(values) else np.ones(len(values), bool)
    if not far.any():
        return None
    return peak(angles[far], np.asarray(values)[far])


def joint_load(name: str, angles: np.ndarray, fx: np.ndarray, fy: np.ndarray,
               near: np.ndarray) -> JointLoad:
    f = np.hypot(fx, fy)
    return JointLoad(name, peak(angles, f), far_peak(angles, f, near),
                     float(np.sqrt(np.mean(f ** 2))) if len(f) else None,
                     peak(angles, fx), peak(angles, fy))


def power_check(torque: np.ndarray, check: np.ndarray, angles: np.ndarray
                ) -> PowerCheck | None:
    """The largest difference between the power balance's effort ``check`` and the
    reference ``torque`` (n,) each; None for an empty sweep."""
    if len(torque) == 0:
        return None
    diff = np.abs(check - torque)
    k = int(np.argmax(diff))
    scale = max(float(np.max(np.abs(torque))), 1e-300)
    return PowerCheck(float(diff[k]), float(diff[k] / scale), float(angles[k]))


def over_cycle(stats: TorqueStats | None, cycle: dict[str, float] | None
               ) -> TorqueStats | None:
    """The effort's statistics with one definition of its mean, RMS and mean power: over a
    whole turn (``cycle``, the review's cycle quantities) those of the cycle, where a
    left-out angle counts with the value interpolated between its neighbours (the cycle
    grid: :mod:`mechreport.post.cycle`); otherwise over the analysed angles. The peaks are
    the analysed angles' (an interpolated value never exceeds its neighbours)."""
    if stats is None or not cycle or "cycle.torque.rms" not in cycle:
        return stats
    return replace(stats, mean=cycle["cycle.torque.mean"], rms=cycle["cycle.torque.rms"],
                   power=cycle["cycle.power.mean"])


def sweep_summary(kin, forces: dict, loads, flags, cycle: dict[str, float] | None = None
                  ) -> SweepSummary:
    """The :class:`SweepSummary` of kinematics ``kin``, the methods' ``forces``, the applied
    ``loads`` and the left-out angles ``flags``; ``cycle`` the review's cycle quantities,
    when defined (see :func:`over_cycle`)."""
    spec = kin.mechanism.spec
    ref = reference_method(forces)
    res = forces[ref]
    angles = kin.angles
    near, width = near_mask(angles, [f.angle for f in flags if not f.isolated], spec.sweep.step)
    joints = {name: joint_load(name, angles, r.fx, r.fy, near)
              for name in spec.reported_reactions() if (r := res.reactions.get(name))}
    largest = None
    for name, jl in joints.items():
        if jl.peak is not None and (largest is None or jl.peak.value > largest[1].value):
            largest = (name, jl.peak)
    traces = {}
    for j in spec.joints:
        if j.type == "R" and j.name in res.reactions:
            try:
                traces[j.name] = bearing_trace(kin, res, j)
            except Exception:  # noqa: BLE001 - a joint that cannot be traced is not drawn
                continue
    frame = frame_load(kin, res, loads)
    check = forces.get("power")
    return SweepSummary(
        ref, near, width, over_cycle(torque_stats(res, kin.driver_rate), cycle), frame,
        peak(angles, frame.f), peak(angles, frame.m), joints, largest, traces,
        None if check is None or check is res else power_check(res.driver_torque,
                                                               check.driver_torque, angles))


__all__ = ["NEAR_STEPS", "JointLoad", "PowerCheck", "SweepSummary",
           "far_peak", "near_mask", "sweep_summary"]
