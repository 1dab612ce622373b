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
