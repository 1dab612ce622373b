"""Joint constraint equations differentiated once and twice, for the velocity and acceleration
analysis. Over link-frame coordinates q = (x, y, theta) of each link:

- R joint a-b, points p_a, p_b:  r_a + R_a p_a - r_b - R_b p_b = 0;
- T joint, guide g, slider s:   theta_s - theta_g = 0  and  e . n = 0, with
  e = (r_s + R_s p_S) - (r_g + R_g L) and n the guide line's normal.

Velocity: J qdot = 0.  Acceleration: J qddot = gamma, gamma holding the centripetal and
Coriolis terms (for a T joint on a moving guide: 2 omega_g (edot . u) + ...).
"""
from __future__ import annotations

import numpy as np

from ..spec import GROUND, Joint, Spec
from .frames import dot, perp, rotate


def _pts(spec: Spec, link: str) -> dict:
    return spec.ground if link == GROUND else spec.link(link).points


def joint_blocks(spec: Spec, joint: Joint, r: dict, th: dict, v=None, w=None):
    """Jacobian blocks {link: (n, 2, 3)} of the joint's two equations, and gamma (n, 2)
    when velocities ``v`` (origins) and ``w`` (omega) are given."""
    n_ang = next(iter(th.values())).shape[0]
    blocks = {}
    gamma = None
    if joint.type == "R":
        a, b = joint.links
        sa = rotate(_pts(spec, a)[joint.name], th[a])
        sb = rotate(_pts(spec, b)[joint.name], th[b])
        for link, s, sign in ((a, sa, 1.0), (b, sb, -1.0)):
            blk = np.zeros((n_ang, 2, 3))
            blk[:, 0, 0] = blk[:, 1, 1] = sign
            blk[:, :, 2] = sign * perp(s)
            blocks[link] = blk
        if w is not None:
            gamma = (w[a] ** 2)[:, None] * sa - (w[b] ** 2)[:, None] * sb
        return blocks, gamma
    g, s = joint.guide, joint.slider
    line = joint.line
    u = rotate(line.direction, th[g])
    n = perp(u)
    s_p = rotate(_pts(spec, s)[joint.point], th[s])
    s_l = rotate(line.through, th[g])
    e = (r[s] + s_p) - (r[g] + s_l)
    bs, bg = np.zeros((n_ang, 2, 3)), np.zeros((n_ang, 2, 3))
    bs[:, 0, 2], bg[:, 0, 2] = 1.0, -1.0
    bs[:, 1, :2], bg[:, 1, :2] = n, -n
    bs[:, 1, 2] = dot(perp(s_p), n)
    bg[:, 1, 2] = -dot(perp(s_l), n) - dot(e, u)
    blocks = {s: bs, g: bg}
    if w is not None:
        edot = v[s] + w[s][:, None] * perp(s_p) - v[g] - w[g][:, None] * perp(s_l)
        gamma = np.zeros((n_ang, 2))
        gamma[:, 1] = (dot((w[s] ** 2)[:, None] * s_p - (w[g] ** 2)[:, None] * s_l, n)
                       + 2 * w[g] * dot(edot, u) + w[g] ** 2 * dot(e, n))
    return blocks, gamma


def joint_residual(spec: Spec, joint: Joint, r: dict, th: dict) -> np.ndarray:
    """How far a joint is from closing (n, 2): an R joint's point gap [m]; a T joint's relative
    angle [rad, wrapped] and the slider point's offset from the line [m]."""
    if joint.type == "R":
        a, b = joint.links
        pa = r[a] + rotate(_pts(spec, a)[joint.name], th[a])
        pb = r[b] + rotate(_pts(spec, b)[joint.name], th[b])
        return pa - pb
    e, u, _, _ = _slide(spec, joint, r, th)
    return np.stack([wrap_angle(th[joint.slider] - th[joint.guide]), dot(e, perp(u))], axis=-1)


def wrap_angle(angle: np.ndarray) -> np.ndarray:
    return (angle + np.pi) % (2 * np.pi) - np.pi


def _slide(spec: Spec, joint: Joint, r: dict, th: dict):
    """T joint geometry: e (slider point minus the line's through point), the line's unit
    direction u, and the rotated slider point and through point (each (n, 2))."""
    g, s = joint.guide, joint.slider
    u = rotate(joint.line.direction, th[g])
    s_p = rotate(_pts(spec, s)[joint.point], th[s])
    s_l = rotate(joint.line.through, th[g])
    return (r[s] + s_p) - (r[g] + s_l), u, s_p, s_l


def driver_row(spec: Spec, r: dict, th: dict, v=None, w=None):
    """The driven coordinate's constraint q_d(q) = value: its current value (n,) [rad or m],
    Jacobian blocks {link: (n, 3)} and, given velocities, gamma (n,) (the part of its second
    time derivative not in J qddot). R with ground: the moving link's angle (the crank angle);
    R between moving links: theta_second - theta_first; T: the stroke e . u."""
    d = spec.driver
    joint = spec.joint(d.joint)
    n = next(iter(th.values())).shape[0]
    if d.kind == "R":
        a, b = joint.links
        if d.crank:
            moving = b if a == GROUND else a
            blk = np.zeros((n, 3))
            blk[:, 2] = 1.0
            return th[moving], {moving: blk}, (np.zeros(n) if w is not None else None)
        ba, bb = np.zeros((n, 3)), np.zeros((n, 3))
        ba[:, 2], bb[:, 2] = -1.0, 1.0
        return th[b] - th[a], {a: ba, b: bb}, (np.zeros(n) if w is not None else None)
    g, s = joint.guide, joint.slider
    e, u, s_p, s_l = _slide(spec, joint, r, th)
    nrm = perp(u)
    bs, bg = np.zeros((n, 3)), np.zeros((n, 3))
    bs[:, :2], bg[:, :2] = u, -u
    bs[:, 2] = dot(perp(s_p), u)
    bg[:, 2] = -dot(perp(s_l), u) + dot(e, nrm)
    gamma = None
    if w is not None:
        edot = v[s] + w[s][:, None] * perp(s_p) - v[g] - w[g][:, None] * perp(s_l)
        gamma = (dot((w[s] ** 2)[:, None] * s_p - (w[g] ** 2)[:, None] * s_l, u)
                 - 2 * w[g] * dot(edot, nrm) + w[g] ** 2 * dot(e, u))
    return dot(e, u), {s: bs, g: bg}, gamma


def mechanism_size(spec) -> float:
    """A length scale of the mechanism [m]: the largest distance between its named points."""
    pts = [np.asarray(p) for p in spec.ground.values()]
    for link in spec.links:
        loc = np.array(list(link.points.values()))
        pts.append(np.ptp(loc, axis=0) if len(loc) > 1 else np.zeros(2))
    return max(float(np.max(np.abs(np.array(pts)))) if pts else 0.0, 1e-9) * 2
