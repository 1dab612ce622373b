"""What the mechanism exerts on its frame: the shaking force and moment, and the inertial
shaking force that balancing acts on. Pure functions; arrays (n,) over the analysed angles."""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..forces import ForceResult
from ..forces.context import joint_point
from ..kinematics import Kinematics
from ..kinematics.frames import cross
from ..spec import GROUND


def reference_method(forces: dict[str, ForceResult]) -> str:
    """The method whose reactions plots, drawings and cycle quantities use: the first that has
    reactions (all methods agree to rounding; the agreement table says how well)."""
    for name, res in forces.items():
        if res.reactions:
            return name
    return next(iter(forces))


@dataclass(frozen=True)
class FrameLoad:
    """Resultant force ``fx``, ``fy`` (n,) [N] the mechanism exerts on the frame, and its
    moment ``m`` (n,) [N m] about the crank's ground pivot (CCW positive; about the frame's
    origin for other drivers)."""

    fx: np.ndarray
    fy: np.ndarray
    m: np.ndarray

    @property
    def f(self) -> np.ndarray:
        """Magnitude [N]."""
        return np.hypot(self.fx, self.fy)


def frame_load(kin: Kinematics, res: ForceResult, loads=()) -> FrameLoad:
    """Shaking force and moment from method ``res``'s reactions: every joint with ground (for
    [ground, X] the frame receives -F, for [X, ground] +F; T couples likewise), a crank motor's
    reaction torque -M (a T driver on a frame guide: its push back on the frame; a driver
    between moving links reacts on them, not on the frame), the reaction -F (or -M) of each
    load that ``reacts_on: ground``, the frame end of every spring, damper and torsion
    spring anchored on ground (``loads``: the analysis' AppliedLoads), and the friction of every
    joint with ground. Weights reach the frame through the joints."""
    spec = kin.mechanism.spec
    d = spec.driver
    n = kin.n
    pivot = joint_point(kin, spec.joint(d.joint)) if d.crank else np.zeros((n, 2))
    fx, fy, m = np.zeros(n), np.zeros(n), np.zeros(n)
    if d.crank:                       # the motor's stator takes -M
        m = m - np.asarray(res.driver_torque, float)
    elif d.kind == "T" and GROUND in d.links:   # the actuator pushes the frame back
        joint = spec.joint(d.joint)
        u = kin.frames.rotate(joint.guide, joint.line.direction)
        sign = 1.0 if d.links[1] == GROUND else -1.0
        f = sign * np.asarray(res.driver_torque, float)[:, None] * u
        fx, fy = fx + f[:, 0], fy + f[:, 1]
        m = m + cross(joint_point(kin, joint) - pivot, f)
    for joint in spec.joints:
        if GROUND not in joint.links or joint.name not in res.reactions:
            continue
        sign = -1.0 if joint.links[0] == GROUND else 1.0
        r = res.reactions[joint.name]
        f = sign * np.stack([r.fx, r.fy], axis=1)
        fx, fy = fx + f[:, 0], fy + f[:, 1]
        m = m + cross(joint_point(kin, joint) - pivot, f)
        if r.moment is not None:
            m = m + sign * r.moment
        if r.friction is not None:       # the joint's friction on the frame, likewise
            if joint.type == "R":
                m = m + sign * r.friction
            else:
                u = kin.frames.rotate(joint.guide, joint.line.direction)
                f = (sign * r.friction)[:, None] * u
                fx, fy = fx + f[:, 0], fy + f[:, 1]
                m = m + cross(joint_point(kin, joint) - pivot, f)
    for ld in loads:
        if ld.link == GROUND:            # a spring, damper or torsion spring's frame end
            sign = 1.0
        elif ld.load.reacts_on == GROUND:  # the frame takes the load's reaction
            sign = -1.0
        else:
            continue
        if ld.force is not None:
            at = kin.named_point(ld.point, ld.link).r
            fx, fy = fx + sign * ld.force[:, 0], fy + sign * ld.force[:, 1]
            m = m + sign * cross(at - pivot, ld.force)
        else:
            m = m + sign * ld.moment
    return FrameLoad(fx, fy, m)


def inertia_force(kin: Kinematics) -> np.ndarray:
    """Sum of m a_C over the moving links (n, 2) [N]: the inertial shaking force's negative
    (gravity and loads left out)."""
    total = np.zeros((kin.n, 2))
    for link in kin.mechanism.spec.links:
        total += link.mass * kin.com(link.name).a
    return total
