"""Transmission angles: how well a dyad passes motion on, over the analysed angles."""
from __future__ import annotations

import numpy as np

from ..kinematics import Kinematics
from ..kinematics.frames import dot, perp


def _fold(angle_rad: np.ndarray) -> np.ndarray:
    """An angle between two lines, folded into [0, 90] degrees."""
    deg = np.degrees(np.abs(angle_rad)) % 180.0
    return np.minimum(deg, 180.0 - deg)


def _line_angle(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """Angle (n,) [rad] between direction vectors a, b (n, 2)."""
    return np.arctan2(np.abs(a[:, 0] * b[:, 1] - a[:, 1] * b[:, 0]), dot(a, b))


def transmission_angles(kin: Kinematics) -> dict[str, np.ndarray]:
    """Per dyad label, the transmission angle (n,) [deg] in [0, 90]:

    - RRR: the angle between the two links at the interior pin, each taken along the line
      from its outer pin to the interior pin;
    - RRT / TRR (a slider fed by a rod): the angle between the rod (outer pin to interior pin)
      and the guide's normal.
    Other groups have none."""
    out: dict[str, np.ndarray] = {}
    for dyad in kin.mechanism.dyads:
        kind = dyad.kind
        i, j = dyad.links
        if kind == "RRR":
            inner = kin.named_point(dyad.inner.point, i).r
            a = inner - kin.named_point(dyad.outer[0].point, i).r
            b = inner - kin.named_point(dyad.outer[1].point, j).r
            out[dyad.label] = _fold(_line_angle(a, b))
        elif kind in ("RRT", "TRR") and dyad.inner.type == "R":
            rod, slide = (0, 1) if kind == "RRT" else (1, 0)
            rod_link = dyad.links[rod]
            guide_joint = dyad.outer[slide]
            inner = kin.named_point(dyad.inner.point, rod_link).r
            a = inner - kin.named_point(dyad.outer[rod].point, rod_link).r
            u = kin.frames.rotate(guide_joint.guide, guide_joint.line.direction)
            out[dyad.label] = _fold(_line_angle(a, perp(u)))
    return out


def smallest_transmission_angle(kin: Kinematics) -> np.ndarray:
    """The smallest transmission angle over the groups that have one (n,) [deg], as
    ``cycle.transmission_angle.min`` takes it over the cycle; NaN where none has one."""
    angles = list(transmission_angles(kin).values())
    if not angles:
        return np.full(kin.n, np.nan)
    return np.min(np.stack(angles), axis=0)


def instant_quantities(kin: Kinematics) -> dict[str, np.ndarray]:
    """The mechanism's own quantities at each angle (``quantities.MECHANISM_UNITS``)."""
    return {"transmission_angle": smallest_transmission_angle(kin)}
