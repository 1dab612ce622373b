"""Joint (bearing) loads: polar traces in the carrying link's frame, cycle statistics and the
basic rating life. Pure functions; arrays (n,) over the analysed angles."""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..forces import ForceResult
from ..kinematics import Kinematics
from ..kinematics.frames import rotate
from ..spec import GROUND, Joint


def bearing_carrier(joint: Joint) -> str:
    """The link whose frame a pin's polar diagram is drawn in: ground for a frame pin,
    otherwise the joint's second link (the one the reaction F acts on)."""
    return GROUND if GROUND in joint.links else joint.links[1]


def bearing_trace(kin: Kinematics, res: ForceResult, joint: Joint) -> np.ndarray:
    """Reaction F of ``joint`` (first link on second) in the carrier's frame, (n, 2) [N]:
    the global vector rotated by -theta of the carrier (unchanged for ground)."""
    r = res.reactions[joint.name]
    f = np.stack([r.fx, r.fy], axis=1)
    carrier = bearing_carrier(joint)
    if carrier == GROUND:
        return f
    return rotate(f, -kin.theta[:, kin.index(carrier)])


@dataclass(frozen=True)
class BearingLoad:
    """A joint's reaction magnitude over one turn: largest ``f_max``, mean ``f_mean`` and
    cube-mean ``f_equivalent`` = (mean |F|^3)^(1/3) [N]; ``life_h`` the basic rating life
    [h] for a dynamic rating (None without one)."""

    f_max: float
    f_mean: float
    f_equivalent: float
    life_h: float | None = None


def rating_life_h(rating: float, f_equivalent: float, rpm: float) -> float:
    """Basic rating life L10 = 10^6 (C / P)^3 / (60 n) [h] for a dynamic load rating C [N],
    an equivalent load P [N] and a speed n [rpm] (ball bearings: exponent 3). Infinite for
    an unloaded bearing."""
    if f_equivalent <= 0:
        return float("inf")
    return 1e6 * (rating / f_equivalent) ** 3 / (60.0 * abs(rpm))


def bearing_load(f_cycle: np.ndarray, rating: float | None = None,
                 rpm: float | None = None) -> BearingLoad:
    """Statistics of |F| sampled over one turn on a uniform grid ``f_cycle`` (N,) [N]."""
    f = np.abs(np.asarray(f_cycle, float))
    feq = float(np.mean(f ** 3)) ** (1.0 / 3.0)
    life = rating_life_h(rating, feq, rpm) if rating is not None and rpm else None
    return BearingLoad(float(np.max(f)), float(np.mean(f)), feq, life)
