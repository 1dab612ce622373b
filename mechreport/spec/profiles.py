"""A load's profile over the crank angle: the one evaluation every output reads.

A profile is a list of (crank angle [deg], value) points given over one cycle of ``cycle``
crank degrees (360 unless the spec's ``cycle`` is longer) that repeats every cycle. Values are
linear between points and wrap from the last point to the first point plus ``cycle``; a point
at exactly ``cycle`` (allowed when it repeats the point at 0: it closes the diagram as books
draw it) is that same wrap written out. ``shift`` phases it: the value at crank angle phi is
profile(phi - shift), so that the cylinders of an engine share one indicator diagram.
"""
from __future__ import annotations

import numpy as np

__all__ = ["profile_at"]


def profile_at(profile, angles_deg, cycle: float = 360.0, shift: float = 0.0) -> np.ndarray:
    """The profile's values at crank angles ``angles_deg`` (n,) [deg]: (n,), vectorised."""
    angles = np.asarray(angles_deg, float)
    xp = np.array([p[0] for p in profile], float)
    fp = np.array([p[1] for p in profile], float)
    if len(xp) > 1 and xp[-1] >= cycle:       # the closing point repeats the first
        xp, fp = xp[:-1], fp[:-1]
    if len(xp) == 1:
        return np.full(angles.shape, fp[0])
    return np.interp(np.mod(angles - shift, cycle), xp, fp, period=cycle)
