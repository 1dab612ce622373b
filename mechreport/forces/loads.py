"""Applied loads evaluated over the sweep: constant or profile values, and the oppose rules.

- force ``oppose: velocity``: F = -sign(v_P . F0) F0, zero where |v_P . F0/|F0|| < 1e-9 m/s;
- moment ``oppose: rotation``: M = -sign(omega) |M0|, zero where |omega| < 1e-9 rad/s.
Profiles interpolate linearly in the crank angle mod 360, wrapping from the last point to the
first point plus 360 (textbook: F_ext = -sign(v_C) 100 i, M_5ext = -sign(omega_5) 100 k).
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..kinematics import Kinematics
from ..spec import Load

SPEED_EPS = 1e-9   # [m/s] and [rad/s]


@dataclass(frozen=True)
class AppliedLoad:
    """A load over the sweep: ``force`` (n, 2) [N] at ``point`` of ``link``, or ``moment`` (n,)
    [N m]. ``symbol`` is its textbook-style name (F3ext, M5ext)."""

    load: Load
    symbol: str
    force: np.ndarray | None = None
    moment: np.ndarray | None = None

    @property
    def name(self) -> str:
        return self.load.label


def _profile(profile, angles_deg: np.ndarray) -> np.ndarray:
    xp = np.array([p[0] for p in profile])
    fp = np.array([p[1] for p in profile])
    if len(xp) == 1:
        return np.full(angles_deg.shape, fp[0])
    return np.interp(np.mod(angles_deg, 360.0), xp, fp, period=360.0)


def evaluate_loads(kin: Kinematics) -> list[AppliedLoad]:
    spec = kin.mechanism.spec
    counts: dict[tuple[str, str], int] = {}
    for load in spec.loads:
        key = (load.kind, load.link)
        counts[key] = counts.get(key, 0) + 1
    seen: dict[tuple[str, str], int] = {}
    out = []
    for load in spec.loads:
        num = spec.number(load.link)
        key = (load.kind, load.link)
        seen[key] = seen.get(key, 0) + 1
        base = f"F{num}ext" if load.kind == "force" else f"M{num}ext"
        symbol = base if counts[key] == 1 else f"{base},{seen[key]}"
        if load.kind == "force":
            if load.value is not None:
                f0 = np.broadcast_to(np.asarray(load.value, float), (kin.n, 2)).copy()
            else:
                f0 = _profile(load.profile, kin.angles)[:, None] * np.asarray(load.direction)
            if load.oppose == "velocity":
                v = kin.named_point(load.point, load.link).v
                mag = np.hypot(f0[:, 0], f0[:, 1])
                along = np.einsum("ni,ni->n", v, f0) / np.where(mag > 0, mag, 1.0)
                sign = np.where(np.abs(along) < SPEED_EPS, 0.0, -np.sign(along))
                f0 = sign[:, None] * f0
            out.append(AppliedLoad(load, symbol, force=f0))
        else:
            m0 = (np.full(kin.n, float(load.value)) if load.value is not None
                  else _profile(load.profile, kin.angles))
            if load.oppose == "rotation":
                w = kin.omega[:, num]
                m0 = np.where(np.abs(w) < SPEED_EPS, 0.0, -np.sign(w)) * np.abs(m0)
            out.append(AppliedLoad(load, symbol, moment=m0))
    return out
