"""Joint constraint equations differentiated once and twice, for the velocity and acceleration
analysis. Over link-frame coordinates q = (x, y, theta) of each link:

- R joint a-b, points p_a, p_b:  r_a + R_a p_a - r_b - R_b p_b = 0;
- T joint, guide g, slider s:   theta_s - theta_g = 0  and  e . n = 0, with
  e = (r_s + R_s p_S) - (r_g + R_g L) and n the guide line's normal.

Velocity: J qdot = 0.  Acceleration: J qddot = gamma, gamma holding the centripetal and
Coriolis terms (for a T joint on a moving guide: 2 omega_g (edot . u) + ...).

Each joint's global vectors at the poses (:func:`geometry`) are computed once and give both its
Jacobian blocks and its gamma. Blocks and gamma are angle-last, ``(rows, 3, n)`` and
``(rows, n)``, the layout of the batched rate systems (see ``linalg``); blocks are written
straight into the system that holds them.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..spec import GROUND, Joint, Spec
from .frames import LinkFrames, dot, perp


@dataclass(frozen=True)
class RGeometry:
    """An R joint between links ``a`` and ``b`` at every angle: the joint's point from each
    link's origin, ``sa`` and ``sb`` (n, 2) [m, global frame]."""

    a: str
    b: str
    sa: np.ndarray
    sb: np.ndarray

    def write_blocks(self, out: dict) -> None:
        """Jacobian blocks of r_a + R_a p_a - r_b - R_b p_b (velocity rows [m/s] per unit of
        (vx, vy, omega)), written into ``out`` {link: zero-filled (2, 3, n)} for its links."""
        for link, s, sign in ((self.a, self.sa, 1.0), (self.b, self.sb, -1.0)):
            blk = out.get(link)
            if blk is not None:
                blk[0, 0] = blk[1, 1] = sign
                blk[:, 2] = sign * perp(s).T

    def gamma(self, v: dict, w: dict) -> np.ndarray:
        """The rows' acceleration terms not in J qddot (2, n) [m/s^2]: w_a^2 s_a - w_b^2 s_b."""
        return ((w[self.a] ** 2)[:, None] * self.sa - (w[self.b] ** 2)[:, None] * self.sb).T


@dataclass(frozen=True)
class TGeometry:
    """A T joint at every angle, each (n, 2) in the global frame: the guide line's unit
    direction ``u`` and normal ``n``, the slider's point from the slider's origin ``s_p`` [m],
    the line's through point from the guide's origin ``s_l`` [m], and ``e`` [m] the slider's
    point minus the through point."""

    guide: str
    slider: str
    u: np.ndarray
    n: np.ndarray
    s_p: np.ndarray
    s_l: np.ndarray
    e: np.ndarray

    def write_blocks(self, out: dict) -> None:
        """Jacobian blocks of theta_s - theta_g and e . n, written into ``out`` {link:
        zero-filled (2, 3, n)} for its links."""
        bs, bg = out.get(self.slider), out.get(self.guide)
        if bs is not None:
            bs[0, 2] = 1.0
            bs[1, :2] = self.n.T
            bs[1, 2] = dot(perp(self.s_p), self.n)
        if bg is not None:
            bg[0, 2] = -1.0
            bg[1, :2] = -self.n.T
            bg[1, 2] = -dot(perp(self.s_l), self.n) - dot(self.e, self.u)

    def edot(self, v: dict, w: dict) -> np.ndarray:
        """The rate of ``e`` (n, 2) [m/s]."""
        s, g = self.slider, self.guide
        return v[s] + w[s][:, None] * perp(self.s_p) - v[g] - w[g][:, None] * perp(self.s_l)

    def gamma(self, v: dict, w: dict) -> np.ndarray:
        """The rows' acceleration terms not in J qddot (2, n): 0 [rad/s^2] and
        (w_s^2 s_p - w_g^2 s_l) . n + 2 w_g edot . u + w_g^2 e . n [m/s^2]."""
        s, g = self.slider, self.guide
        out = np.zeros((2, len(self.u)))
        out[1] = (dot((w[s] ** 2)[:, None] * self.s_p - (w[g] ** 2)[:, None] * self.s_l, self.n)
                  + 2 * w[g] * dot(self.edot(v, w), self.u) + w[g] ** 2 * dot(self.e, self.n))
        return out


def geometry(spec: Spec, joint: Joint, frames: LinkFrames) -> RGeometry | TGeometry:
    """The joint's global vectors at the poses ``frames`` (its Jacobian blocks and gamma
    follow from them)."""
    if joint.type == "R":
        a, b = joint.links
        return RGeometry(a, b, frames.rotate(a, spec.points_of(a)[joint.point]),
                         frames.rotate(b, spec.points_of(b)[joint.point]))
    g, s = joint.guide, joint.slider
    u = frames.rotate(g, joint.line.direction)
    s_p = frames.rotate(s, spec.points_of(s)[joint.point])
    s_l = frames.rotate(g, joint.line.through)
    e = (frames.r[s] + s_p) - (frames.r[g] + s_l)
    return TGeometry(g, s, u, perp(u), s_p, s_l, e)


def joint_residual(spec: Spec, joint: Joint, frames: LinkFrames,
                   geo: RGeometry | TGeometry | None = None) -> np.ndarray:
    """How far a joint is from closing (n, 2): an R joint's point gap [m]; a T joint's relative
    angle [rad, wrapped] and the slider point's offset from the line [m]. ``geo``: the joint's
    :func:`geometry` at ``frames``, if already computed."""
    if geo is None:
        geo = geometry(spec, joint, frames)
    if isinstance(geo, RGeometry):
        return (frames.r[geo.a] + geo.sa) - (frames.r[geo.b] + geo.sb)
    gap = wrap_angle(frames.th[geo.slider] - frames.th[geo.guide])
    return np.stack([gap, dot(geo.e, geo.n)], axis=-1)


def wrap_angle(angle: np.ndarray) -> np.ndarray:
    """``angle`` [rad] wrapped into [-pi, pi) (the one wrap of an angle difference)."""
    return (angle + np.pi) % (2 * np.pi) - np.pi


def driver_row(spec: Spec, frames: LinkFrames, v=None, w=None,
               geo: RGeometry | TGeometry | None = None):
    """The driven coordinate's constraint q_d(q) = value: its current value (n,) [rad or m],
    Jacobian blocks {link: (3, n)} and, given velocities, gamma (n,) (the part of its second
    time derivative not in J qddot). R with ground: the moving link's angle (the crank angle);
    R between moving links: theta_second - theta_first; T: the stroke e . u. ``geo``: the
    driver joint's :func:`geometry` at ``frames``, if already computed (a T joint's is used)."""
    d = spec.driver
    joint = spec.joint(d.joint)
    th = frames.th
    n = frames.n
    if d.kind == "R":
        a, b = joint.links
        if d.crank:
            moving = b if a == GROUND else a
            blk = np.zeros((3, n))
            blk[2] = 1.0
            return th[moving], {moving: blk}, (np.zeros(n) if w is not None else None)
        ba, bb = np.zeros((3, n)), np.zeros((3, n))
        ba[2], bb[2] = -1.0, 1.0
        return th[b] - th[a], {a: ba, b: bb}, (np.zeros(n) if w is not None else None)
    if geo is None:
        geo = geometry(spec, joint, frames)
    g, s = geo.guide, geo.slider
    u, e = geo.u, geo.e
    bs, bg = np.zeros((3, n)), np.zeros((3, n))
    bs[:2], bg[:2] = u.T, -u.T
    bs[2] = dot(perp(geo.s_p), u)
    bg[2] = -dot(perp(geo.s_l), u) + dot(e, geo.n)
    gamma = None
    if w is not None:
        gamma = (dot((w[s] ** 2)[:, None] * geo.s_p - (w[g] ** 2)[:, None] * geo.s_l, u)
                 - 2 * w[g] * dot(geo.edot(v, w), geo.n) + w[g] ** 2 * dot(e, u))
    return dot(e, u), {s: bs, g: bg}, gamma


def mechanism_size(spec) -> float:
    """A length scale of the mechanism [m]: the largest distance between its named points."""
    pts = [np.asarray(p) for p in spec.ground.values()]
    for link in spec.links:
        loc = np.array(list(link.points.values()))
        pts.append(np.ptp(loc, axis=0) if len(loc) > 1 else np.zeros(2))
    return max(float(np.max(np.abs(np.array(pts)))) if pts else 0.0, 1e-9) * 2
