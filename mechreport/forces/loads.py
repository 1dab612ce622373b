"""Applied loads evaluated over the sweep: constant or profile values, and the oppose rules.

- force ``oppose: velocity``: F = -sign(v_P . F0) F0, zero where |v_P . F0/|F0|| < 1e-9 m/s;
- moment ``oppose: rotation``: M = -sign(omega) |M0|, zero where |omega| < 1e-9 rad/s;
- spring: tension k (L - L0) pulls its two ends together; damper: c dL/dt along the line,
  resisting extension; torsion spring: k (theta_rel - a0), wrapped to [-180, 180) deg, resists
  the second link's rotation relative to the first, equal and opposite on the two links.
Profiles interpolate linearly in the crank angle mod the spec's ``cycle`` (360 unless longer),
phased by the load's ``shift``, wrapping from the last point to the first point plus ``cycle``
(a pressure load is a force whose profile is (p - ambient) A; textbook: F_ext = -sign(v_C) 100 i, M_5ext = -sign(omega_5) 100 k).
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..kinematics import EPS, TRUST_RTOL, Kinematics
from ..kinematics.constraints import wrap_angle
from ..spec import Load, profile_at

SPEED_EPS = 1e-9   # [m/s] and [rad/s]


@dataclass(frozen=True)
class AppliedLoad:
    """A load over the sweep as it acts on one link: ``force`` (n, 2) [N] at ``point`` of
    ``link``, or ``moment`` (n,) [N m]. ``symbol`` is its textbook-style name (F3ext, M5ext;
    Fk3 for a spring on link 3, Fc for a damper, Mk for a torsion spring). A spring, damper or
    torsion spring gives one AppliedLoad per end; an end on ``ground`` acts on the frame (only
    the shaking force reads it)."""

    load: Load
    symbol: str
    link: str
    point: str | None = None
    force: np.ndarray | None = None
    moment: np.ndarray | None = None

    @property
    def name(self) -> str:
        return self.load.label


def _profile(load: Load, angles_deg: np.ndarray, cycle: float) -> np.ndarray:
    """``load``'s profile at the crank angles, phased by its ``shift``, repeating every
    ``cycle`` degrees (:func:`mechreport.spec.profiles.profile_at`)."""
    return profile_at(load.profile, angles_deg, cycle, load.shift)


BASES = {"force": "F{}ext", "moment": "M{}ext", "spring": "Fk{}", "damper": "Fc{}",
         "torsion_spring": "Mk{}"}


def evaluate_loads(kin: Kinematics) -> list[AppliedLoad]:
    """Every load over the analysed angles, one AppliedLoad per link it acts on."""
    spec = kin.mechanism.spec
    parts: list[tuple[Load, str, str | None, np.ndarray | None, np.ndarray | None]] = []
    for load in spec.loads:
        parts.extend(_evaluate(kin, load))
    counts: dict[str, int] = {}
    for load, link, *_ in parts:
        base = BASES[load.kind].format(spec.number(link))
        counts[base] = counts.get(base, 0) + 1
    seen: dict[str, int] = {}
    out = []
    for load, link, point, force, moment in parts:
        base = BASES[load.kind].format(spec.number(link))
        seen[base] = seen.get(base, 0) + 1
        symbol = base if counts[base] == 1 else f"{base},{seen[base]}"
        out.append(AppliedLoad(load, symbol, link, point, force, moment))
    return out


def undefined_directions(kin: Kinematics) -> list[tuple[Load, np.ndarray]]:
    """Each spring (with a free length) or damper whose two ends coincide at some analysed
    angle, with those angles (n,) bool: its force pulls along the line between its ends,
    which has no direction there. "Coincide" is within what the positions are trustworthy
    to: the ends' distance L is at most their round-off (the kinematics' relative error
    bound times their distance from the origin) over ``TRUST_RTOL``, so that a direction
    taken from them could be wrong by more than that. A spring of free length 0 pulls with
    k (B - A), defined everywhere."""
    out = []
    for load in kin.mechanism.spec.loads:
        if load.kind not in ("spring", "damper"):
            continue
        # a stacked batch's free length is an array over its rows (each variant's own)
        length0 = 0.0 if load.free_length is None else load.free_length
        free = np.broadcast_to(np.asarray(length0, float), (kin.n,)) \
            if load.kind == "spring" else np.ones(kin.n)
        if not free.any():
            continue
        (la, pa), (lb, pb) = load.between
        A, B = kin.named_point(pa, la).r, kin.named_point(pb, lb).r
        length = np.hypot(*(B - A).T)
        size = np.maximum(np.hypot(*A.T), np.hypot(*B.T))
        error = kin.error if kin.error is not None else np.zeros(kin.n)
        bad = (length * TRUST_RTOL <= (error + EPS) * size) & (free != 0)
        if bad.any():
            out.append((load, bad))
    return out


def _evaluate(kin: Kinematics, load: Load):
    """(load, link, point, force, moment) for each link the load acts on."""
    spec = kin.mechanism.spec
    if load.kind in ("spring", "damper"):
        (la, pa), (lb, pb) = load.between
        A, B = kin.named_point(pa, la), kin.named_point(pb, lb)
        d = B.r - A.r
        length = np.hypot(d[:, 0], d[:, 1])
        u = d / np.where(length > 0, length, 1.0)[:, None]
        if load.kind == "spring":     # tension k (L - L0) pulls the two ends together
            pull = load.stiffness * (length - load.free_length)
        else:                         # c dL/dt resists extension
            pull = load.damping * np.einsum("ni,ni->n", B.v - A.v, u)
        f = pull[:, None] * u         # on end A, toward B; -f on end B
        return [(load, la, pa, f, None), (load, lb, pb, -f, None)]
    if load.kind == "torsion_spring":  # k (theta_rel - a0) resists the second link's turn
        joint = spec.joint(load.joint)
        a, b = joint.links
        rel = kin.theta[:, spec.number(b)] - kin.theta[:, spec.number(a)]
        delta = wrap_angle(rel - np.radians(load.free_angle))
        m = load.stiffness * delta
        return [(load, b, None, None, -m), (load, a, None, None, m)]
    num = spec.number(load.link)
    if load.kind == "force":
        if load.value is not None:
            f0 = np.broadcast_to(np.asarray(load.value, float), (kin.n, 2)).copy()
        else:
            f0 = (_profile(load, kin.angles, spec.cycle)[:, None]
                  * np.asarray(load.direction))
        if load.oppose == "velocity":
            v = kin.named_point(load.point, load.link).v
            mag = np.hypot(f0[:, 0], f0[:, 1])
            along = np.einsum("ni,ni->n", v, f0) / np.where(mag > 0, mag, 1.0)
            sign = np.where(np.abs(along) < SPEED_EPS, 0.0, -np.sign(along))
            f0 = sign[:, None] * f0
        return [(load, load.link, load.point, f0, None)]
    m0 = (np.broadcast_to(np.asarray(load.value, float), (kin.n,)).copy()
          if load.value is not None
          else _profile(load, kin.angles, spec.cycle))
    if load.oppose == "rotation":
        w = kin.omega[:, num]
        m0 = np.where(np.abs(w) < SPEED_EPS, 0.0, -np.sign(w)) * np.abs(m0)
    return [(load, load.link, None, None, m0)]
