"""The Coulomb friction law of a joint (format 1.1 ``friction:``): the relative motion it
opposes, its direction, and its magnitude from the joint's reaction. What a method's result
reports as ``joint.J.friction`` (from its own reactions) and what
:mod:`mechreport.forces.friction` solves for."""
from __future__ import annotations

import numpy as np

from ..kinematics import Kinematics
from ..kinematics.frames import perp
from ..spec import Friction, Joint
from .context import ForceContext

RATE_ZERO = 1e-9     # |relative rate| below this [rad/s or m/s]: the motion stops there


def relative_rate(kin: Kinematics, joint: Joint) -> np.ndarray:
    """The rate the friction of ``joint`` opposes, (n,): an R joint's second link's angular
    velocity relative to its first [rad/s]; a T joint's slider's velocity relative to the
    guide's material point under it, along the line [m/s]."""
    a, b = joint.links
    ia, ib = kin.index(a), kin.index(b)
    if joint.type == "R":
        return kin.omega[:, ib] - kin.omega[:, ia]
    spec = kin.mechanism.spec
    p = kin.point(b, spec.points_of(b)[joint.point])
    guide = kin.v[:, ia] + kin.omega[:, ia][:, None] * perp(p.r - kin.r[:, ia])
    u = kin.frames.rotate(a, joint.line.direction)
    return np.einsum("ij,ij->i", p.v - guide, u)


def senses(kin: Kinematics, frictions: tuple[Friction, ...]) -> tuple[np.ndarray, np.ndarray]:
    """(s (n, J) the sign of each joint's relative motion, undetermined (n, J) where it
    moves but its relative motion stops). A driver at rest takes each entry's ``sense``
    (none: no friction there, 0)."""
    spec = kin.mechanism.spec
    s = np.zeros((kin.n, len(frictions)))
    stopped = np.zeros((kin.n, len(frictions)), bool)
    for k, fr in enumerate(frictions):
        if spec.driver.at_rest:
            s[:, k] = fr.sense or 0
            continue
        rate = relative_rate(kin, spec.joint(fr.joint))
        s[:, k] = np.sign(rate)
        stopped[:, k] = np.abs(rate) < RATE_ZERO
        s[stopped[:, k], k] = 0.0
    return s, stopped


def magnitude(fr: Friction, joint: Joint, ctx: ForceContext, fx: np.ndarray, fy: np.ndarray,
              moment: np.ndarray | None) -> tuple[np.ndarray, np.ndarray, np.ndarray,
                                                  np.ndarray]:
    """The friction's magnitude (n,) from the joint's reaction (fx, fy [N], a T joint's
    couple [N m]), and its derivatives with respect to fx, fy and the couple (n,) each."""
    zero = np.zeros_like(fx)
    if joint.type == "T" and fr.length is not None:
        n = perp(ctx.line_direction(joint))                      # the line's normal
        normal = fx * n[:, 0] + fy * n[:, 1]
        lo, hi = normal / 2 - moment / fr.length, normal / 2 + moment / fr.length
        slo, shi = np.sign(lo), np.sign(hi)
        mag = fr.mu * (np.abs(lo) + np.abs(hi))
        d_normal = fr.mu * (slo + shi) / 2
        return mag, d_normal * n[:, 0], d_normal * n[:, 1], fr.mu * (shi - slo) / fr.length
    arm = fr.radius if joint.type == "R" else 1.0
    f = np.hypot(fx, fy)
    with np.errstate(invalid="ignore", divide="ignore"):
        ux, uy = np.where(f > 0, fx / f, 0.0), np.where(f > 0, fy / f, 0.0)
    mu = fr.journal_mu if joint.type == "R" else fr.mu       # the friction circle's, or mu
    return mu * arm * f, mu * arm * ux, mu * arm * uy, zero


def friction_from(ctx: ForceContext, fr: Friction, sense: np.ndarray, fx: np.ndarray,
                  fy: np.ndarray, moment: np.ndarray | None) -> np.ndarray:
    """The friction (n,) on the joint's second link that its reaction (fx, fy [N], a T
    joint's couple [N m]) gives by the law, opposing the relative motion of sign ``sense``
    (n,): -sense x magnitude."""
    return -sense * magnitude(fr, ctx.spec.joint(fr.joint), ctx, fx, fy, moment)[0] + 0.0


def joint_senses(ctx: ForceContext) -> dict[str, np.ndarray]:
    """:func:`senses` of the context's kinematics by joint name (computed once)."""
    def build():
        s, _ = senses(ctx.kin, ctx.spec.friction)
        return {fr.joint: s[:, k] for k, fr in enumerate(ctx.spec.friction)}
    return ctx.once(("friction senses",), build)
