"""Turn actions on a free body into labelled equations (shared by every method)."""
from __future__ import annotations

import numpy as np

from ..kinematics.frames import cross, rotate
from ..spec import Joint
from .context import ForceContext
from .equations import Action, Equation, Term

AXES = {"x": np.array([1.0, 0.0]), "y": np.array([0.0, 1.0])}


def body_tag(ctx: ForceContext, bodies) -> str:
    """``(2&3)`` for links 2 and 3."""
    return "(" + "&".join(str(ctx.num(b)) for b in bodies) + ")"


def force_term(act: Action, d: np.ndarray, side: str = "rhs") -> Term | None:
    """Projection of a force action on direction ``d`` (n, 2); None for couples."""
    if act.kind != "force":
        return None
    if act.direction is not None:      # one unknown magnitude along a known direction
        return Term(act, act.sign * np.einsum("ni,ni->n", act.direction, d)[:, None],
                    np.zeros(d.shape[0]), side, direction=d)
    if act.unknowns:
        return Term(act, act.sign * d, np.zeros(d.shape[0]), side, direction=d)
    return Term(act, np.zeros((d.shape[0], 0)), np.einsum("ni,ni->n", act.value, d), side,
                direction=d)


def moment_term(act: Action, about: np.ndarray, n: int, side: str = "rhs") -> Term:
    """Moment of an action about point ``about`` (n, 2), z-component (CCW positive)."""
    if act.kind == "couple":
        if act.unknowns:
            return Term(act, np.full((n, 1), act.sign), np.zeros(n), side)
        return Term(act, np.zeros((n, 0)), np.asarray(act.value, float), side)
    lever = act.at - about
    if act.direction is not None:
        return Term(act, act.sign * cross(lever, act.direction)[:, None], np.zeros(n), side,
                    lever=lever)
    if act.unknowns:
        coeffs = act.sign * np.stack([-lever[:, 1], lever[:, 0]], axis=1)
        return Term(act, coeffs, np.zeros(n), side, lever=lever)
    return Term(act, np.zeros((n, 0)), cross(lever, act.value), side, lever=lever)


def _at_centre(act: Action, p: np.ndarray) -> bool:
    if act.kind != "force":
        return False
    scale = 1.0 + float(np.max(np.abs(p)))
    return bool(np.all(np.abs(act.at - p) <= 1e-12 * scale))


def force_equation(ctx: ForceContext, bodies, acts: list[Action], axis: str,
                   direction: np.ndarray | None = None, kind: str = "force") -> Equation:
    """sum F^(bodies) . axis = 0; ``axis`` x or y, or a named sliding ``direction`` (n, 2)."""
    d = np.broadcast_to(AXES[axis], (ctx.n, 2)) if direction is None else direction
    terms = [t for t in (force_term(a, d) for a in acts) if t is not None]
    label = f"sum F^{body_tag(ctx, bodies)} . {axis}"
    return Equation(label, kind, tuple(bodies), terms, axis=axis)


def moment_equation(ctx: ForceContext, bodies, acts: list[Action], about: str,
                    at: np.ndarray | None = None) -> Equation:
    """sum M_about^(bodies) = 0 (moments about the named point ``about``)."""
    p = ctx.point_of(about) if at is None else at
    # a force applied at the moment centre itself has no moment: leave it out, as the text does
    terms = [moment_term(a, p, ctx.n) for a in acts if not _at_centre(a, p)]
    return Equation(f"sum M_{about}^{body_tag(ctx, bodies)}", "moment", tuple(bodies), terms,
                    about=about)


def sliding_direction(ctx: ForceContext, joint: Joint) -> np.ndarray:
    """Unit direction (n, 2) of a T joint's line in the global frame."""
    return rotate(joint.line.direction, ctx.kin.theta[:, ctx.num(joint.guide)])


def normal_constraint(ctx: ForceContext, joint: Joint) -> Equation:
    """A T joint's reaction has no component along its line: F . Delta = 0."""
    act = ctx.reaction(joint, joint.slider)[0]
    d = sliding_direction(ctx, joint)
    term = Term(act, d.copy(), np.zeros(ctx.n), direction=d)
    return Equation(f"{act.symbol} . Delta_{joint.name} = 0", "constraint", (joint.slider,),
                    [term], axis=f"Delta_{joint.name}")


def newton_euler_equations(ctx: ForceContext, link: str) -> list[Equation]:
    """m a_C = sum F (x and y) and I_C alpha = sum M_C for one link (textbook 4.26-4.27)."""
    s = ctx.links[link]
    acts = ctx.actions_on([link], inertia=False)
    tag = body_tag(ctx, [link])
    out = []
    for axis, k in (("x", 0), ("y", 1)):
        d = np.broadcast_to(AXES[axis], (ctx.n, 2))
        lhs = Action(f"m{s.number} aC{s.number}", "force", "inertia", link, s.r, f"C{s.number}",
                     value=s.mass * s.a)
        terms = [force_term(lhs, d, side="lhs")]
        terms += [t for t in (force_term(a, d) for a in acts) if t is not None]
        out.append(Equation(f"m{s.number} aC{s.number}{axis} = sum F^{tag} . {axis}", "force",
                            (link,), terms, axis=axis))
    lhs = Action(f"IC{s.number} alpha{s.number}", "couple", "inertia", link,
                 value=s.inertia * s.alpha)
    terms = [moment_term(lhs, s.r, ctx.n, side="lhs")]
    terms += [moment_term(a, s.r, ctx.n) for a in acts]
    out.append(Equation(f"IC{s.number} alpha{s.number} = sum M_C{s.number}^{tag}", "moment",
                        (link,), terms, about=f"C{s.number}"))
    return out
