"""Turn actions on a free body into labelled equations (shared by every method), and read
the terms back (:func:`read_term`, the one decoder of what the encoders here build)."""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..kinematics.frames import cross, perp, project, scaled
from ..spec import Joint
from .context import AXES, ForceContext
from .equations import Action, Equation, Term, no_coefficients, no_constant


def body_tag(ctx: ForceContext, bodies) -> str:
    """``(2&3)`` for links 2 and 3."""
    return ctx.once(("tag", *bodies), _tag, ctx, bodies)


def _tag(ctx: ForceContext, bodies) -> str:
    return "(" + "&".join([str(ctx.num(b)) for b in bodies]) + ")"


def force_term(act: Action, d: np.ndarray, side: str = "rhs") -> Term | None:
    """Projection of a force action on direction ``d`` (n, 2); None for couples."""
    if act.kind != "force":
        return None
    if act.direction is not None:      # one unknown magnitude along a known direction
        return Term(act, act.sign * project(act.direction, d)[:, None],
                    no_constant(d.shape[0]), side, direction=d, kind="projection")
    if act.unknowns:
        return Term(act, act.sign * d, no_constant(d.shape[0]), side, direction=d,
                    kind="projection")
    return Term(act, no_coefficients(d.shape[0]), project(act.value, d), side,
                direction=d, kind="projection")


def moment_term(act: Action, about: np.ndarray, n: int, side: str = "rhs",
                about_name: str | None = None) -> Term:
    """Moment of an action about point ``about`` (n, 2) named ``about_name``, z-component
    (CCW positive)."""
    if act.kind == "couple":
        if act.unknowns:
            return Term(act, np.full((n, 1), act.sign), no_constant(n), side, kind="couple")
        return Term(act, no_coefficients(n), np.asarray(act.value, float), side, kind="couple")
    lever = act.at - about
    named = (("about", about_name),)
    if act.direction is not None:
        return Term(act, act.sign * cross(lever, act.direction)[:, None], no_constant(n), side,
                    lever=lever, kind="moment", factors=named)
    if act.unknowns:
        coeffs = perp(lever)
        if act.sign != 1.0:
            coeffs *= act.sign
        return Term(act, coeffs, no_constant(n), side, lever=lever, kind="moment", factors=named)
    return Term(act, no_coefficients(n), cross(lever, act.value), side, lever=lever,
                kind="moment", factors=named)


def with_moment(ctx: ForceContext, acts: list[Action], p: np.ndarray) -> list[Action]:
    """The actions that enter a moment equation about point ``p`` (n, 2): all but the forces
    applied at ``p`` itself (:func:`applied_at`), which have no moment (the text leaves them
    out)."""
    memo = ctx.once(("at centre",), dict)
    out = []
    for act in acts:
        at = act.at
        if act.kind != "force":
            out.append(act)
        elif at is not p:
            hit = memo.get((id(at), id(p)))
            if hit is None:
                hit = _coincide(ctx, memo, at, p)
            if not hit[0]:
                out.append(act)
    return out


def applied_at(ctx: ForceContext, at: np.ndarray, p: np.ndarray) -> bool:
    """Whether a force applied at ``at`` (n, 2) is applied at point ``p`` (n, 2) at every
    angle, as :func:`with_moment` judges it."""
    if at is p:
        return True
    memo = ctx.once(("at centre",), dict)
    hit = memo.get((id(at), id(p)))
    return (hit if hit is not None else _coincide(ctx, memo, at, p))[0]


def _coincide(ctx: ForceContext, memo: dict, at: np.ndarray, p: np.ndarray) -> tuple:
    """(whether ``at`` is ``p`` at every angle, within :func:`_coincidence_tol`; ``at``,
    ``p``), kept in ``memo``: the same arrays are asked about again and again, and the
    arrays are kept with the answer, so their ids stay theirs."""
    tol = _coincidence_tol(ctx, p)
    # apart at the first angle (most pairs) needs no look at the others
    apart = at.size > 0 and not (abs(at.item(0) - p.item(0)) <= tol
                                 and abs(at.item(1) - p.item(1)) <= tol)
    same = not apart and bool((np.abs(at - p) <= tol).all())
    hit = memo[(id(at), id(p))] = (same, at, p)
    return hit


def _coincidence_tol(ctx: ForceContext, p: np.ndarray) -> float:
    """How close (m) a force's point must be to ``p`` (n, 2) at every angle to be taken as
    applied there: 1e-12 of (1 m + the largest coordinate of ``p``), once per point."""
    return ctx.once(("coincidence tol", id(p)), _tol_about, p, keep=p)


def _tol_about(p: np.ndarray) -> float:
    return 1e-12 * (1.0 + float(np.abs(p).max(initial=0.0)))


def force_equation(ctx: ForceContext, bodies, acts: list[Action], axis: str,
                   direction: np.ndarray | None = None, kind: str = "force") -> Equation:
    """sum F^(bodies) . axis = 0; ``axis`` x or y, or a named sliding ``direction`` (n, 2)."""
    d = ctx.axis(axis) if direction is None else direction
    # (the methods write many of the same equations, and share them as they share actions)
    key = ("equation", "force", tuple(bodies), axis, kind, id(d), *map(id, acts))
    eq = ctx.cache.get(key)
    return eq if eq is not None else ctx.once(key, _force_equation, ctx, bodies, acts, axis,
                                              d, kind, keep=(d, tuple(acts)))


def _force_equation(ctx: ForceContext, bodies, acts, axis: str, d, kind: str) -> Equation:
    return Equation(f"sum F^{body_tag(ctx, bodies)} . {axis}", kind, tuple(bodies),
                    _force_terms(ctx, acts, d), axis=axis)


def moment_equation(ctx: ForceContext, bodies, acts: list[Action], about: str,
                    at: np.ndarray | None = None) -> Equation:
    """sum M_about^(bodies) = 0 (moments about the named point ``about``)."""
    p = ctx.point_of(about) if at is None else at
    acts = with_moment(ctx, acts, p)     # (the same equation from more actions: shared)
    key = ("equation", "moment", tuple(bodies), about, id(p), *map(id, acts))
    eq = ctx.cache.get(key)
    return eq if eq is not None else ctx.once(key, _moment_equation, ctx, bodies, acts, about,
                                              p, keep=(p, acts))


def _moment_equation(ctx: ForceContext, bodies, acts, about: str, p) -> Equation:
    return Equation(f"sum M_{about}^{body_tag(ctx, bodies)}", "moment", tuple(bodies),
                    _moment_terms(ctx, acts, p, about), about=about)


def _force_terms(ctx: ForceContext, acts: list[Action], d: np.ndarray) -> list[Term]:
    """The force actions' :func:`force_term` on ``d``, each built once per context: an
    action enters the force equations of every free body that holds it (terms are
    immutable; several equations share one). Read from the cache first: half the calls
    are hits, and these loops are the hottest users of ``ForceContext.once``."""
    cache = ctx.cache
    out = []
    for a in acts:
        if a.kind == "force":
            key = ("force term", id(a), id(d))
            term = cache.get(key)
            out.append(term if term is not None
                       else ctx.once(key, force_term, a, d, keep=(a, d)))
    return out


def _moment_terms(ctx: ForceContext, acts: list[Action], p: np.ndarray,
                  about: str) -> list[Term]:
    """The actions' :func:`moment_term` about point ``p`` named ``about``, each built once
    per context (see :func:`_force_terms`)."""
    cache = ctx.cache
    out = []
    for a in acts:
        key = ("moment term", id(a), id(p), about)
        term = cache.get(key)
        out.append(term if term is not None
                   else ctx.once(key, moment_term, a, p, ctx.n, "rhs", about, keep=(a, p)))
    return out


def normal_constraint(ctx: ForceContext, joint: Joint) -> Equation:
    """A T joint's reaction has no component along its line: F . Delta = 0."""
    return ctx.once(("equation", "normal", joint.name), _normal_constraint, ctx, joint)


def _normal_constraint(ctx: ForceContext, joint: Joint) -> Equation:
    act = ctx.reaction(joint, joint.slider)[0]
    d = ctx.line_direction(joint)
    term = Term(act, d.copy(), no_constant(ctx.n), direction=d, kind="projection")
    return Equation(f"{act.symbol} . Delta_{joint.name} = 0", "constraint",
                    (joint.slider,), [term], axis=f"Delta_{joint.name}")


def newton_euler_equations(ctx: ForceContext, link: str) -> list[Equation]:
    """m a_C = sum F (x and y) and I_C alpha = sum M_C for one link (textbook 4.26-4.27);
    built once per context (the Newton-Euler method and the residual check share them)."""
    return list(ctx.once(("newton-euler", link), _newton_euler, ctx, link))


def _newton_euler(ctx: ForceContext, link: str) -> tuple[Equation, ...]:
    s = ctx.links[link]
    acts = ctx.actions_on([link], inertia=False)
    tag = body_tag(ctx, [link])
    out = []
    lhs = Action(f"m{s.number} aC{s.number}", "force", "inertia", link, s.r, f"C{s.number}",
                 value=scaled(s.mass, s.a))
    for axis, k in (("x", 0), ("y", 1)):
        d = ctx.axis(axis)
        terms = [Term(lhs, no_coefficients(ctx.n), s.mass * s.a[:, k], "lhs", direction=d,
                      kind="inertia", factors=(("mass", s.mass), ("accel", s.a)))]
        terms += _force_terms(ctx, acts, d)
        out.append(Equation(f"m{s.number} aC{s.number}{axis} = sum F^{tag} . {axis}", "force",
                            (link,), terms, axis=axis))
    lhs = Action(f"IC{s.number} alpha{s.number}", "couple", "inertia", link,
                 value=s.inertia * s.alpha)
    terms = [Term(lhs, no_coefficients(ctx.n), lhs.value, "lhs", kind="inertia",
                  factors=(("inertia", s.inertia), ("alpha", s.alpha)))]
    terms += _moment_terms(ctx, acts, s.r, f"C{s.number}")
    out.append(Equation(f"IC{s.number} alpha{s.number} = sum M_C{s.number}^{tag}", "moment",
                        (link,), terms, about=f"C{s.number}"))
    return tuple(out)


# ------------------------------------------------------------------------ reading terms back

@dataclass(frozen=True)
class Piece:
    """One product of a term, as a worked solution prints it, over the angles (n,):
    ``factor`` times the ``comp`` component (``x``, ``y``; ``""`` for a couple or a
    magnitude) of the term's action. The action's component is the unknown ``unknown`` times
    ``sign`` (F21x = -F12x: the unknown is joint.B.fx, the sign -1), or the known ``value``.
    ``factor`` is a lever component (+r_x for F_y, -r_y for F_x), a direction cosine, a mass,
    an inertia or a rate."""

    factor: np.ndarray
    comp: str = ""
    unknown: str | None = None
    sign: float = 1.0
    value: np.ndarray | None = None

    def coeff(self) -> np.ndarray:
        """What the piece adds to its unknown's coefficient (n,)."""
        return self.factor * self.sign

    def const(self) -> np.ndarray:
        """What a known piece adds to the constant part (n,)."""
        return self.factor * self.value


def _force_parts(act: Action, n: int):
    """A force's (comp, unknown, sign, value) for x and y, or its magnitude along
    ``direction`` (one part, comp "")."""
    if act.direction is not None:
        return [("", act.unknowns[0], act.sign, None)]
    if act.unknowns:
        return [("x", act.unknowns[0], act.sign, None), ("y", act.unknowns[1], act.sign, None)]
    value = np.broadcast_to(act.value, (n, 2))
    return [("x", None, 1.0, value[:, 0]), ("y", None, 1.0, value[:, 1])]


def read_term(t: Term) -> tuple[Piece, ...]:
    """The products ``t`` is made of, from its ``kind`` and named factors: the decoder of
    what :func:`force_term`, :func:`moment_term`, :func:`normal_constraint`,
    :func:`newton_euler_equations` and the power balance build. Summed, the pieces give the
    term's ``coeffs`` and ``const`` back (tests/test_sheet_terms.py checks it on every term
    of every method and spec)."""
    act, n = t.action, len(t.const)
    ones = np.ones(n)
    if t.kind == "inertia":
        if act.kind == "force":                       # m (a . d)
            a = t.factor("accel")
            return (Piece(_per_row(t.factor("mass"), n), _axis_comp(t.direction),
                          value=project(a, np.broadcast_to(t.direction, a.shape))),)
        return (Piece(_per_row(t.factor("inertia"), n), value=t.factor("alpha")),)
    if t.kind == "couple":
        if act.unknowns:
            return (Piece(ones, "", act.unknowns[0], act.sign),)
        return (Piece(ones, value=np.broadcast_to(np.asarray(act.value, float), (n,))),)
    if t.kind == "power" and act.unknowns:            # the driver: M omega or F v
        return (Piece(np.broadcast_to(t.rate, (n,)), "", act.unknowns[0], act.sign),)
    parts = None if act.kind == "couple" else _force_parts(act, n)
    if t.kind == "projection":
        d = np.broadcast_to(t.direction, (n, 2))
        if act.direction is not None:
            return (Piece(project(act.direction, d), "", act.unknowns[0],
                          act.sign),)
        return tuple(Piece(d[:, i], c, u, s, v) for i, (c, u, s, v) in enumerate(parts))
    if t.kind == "moment":
        lever = t.lever
        if act.direction is not None:
            return (Piece(cross(lever, act.direction), "", act.unknowns[0], act.sign),)
        (cx, ux, sx, vx), (cy, uy, sy, vy) = parts     # r x F = r_x F_y - r_y F_x
        return (Piece(lever[:, 0], cy, uy, sy, vy), Piece(-lever[:, 1], cx, ux, sx, vx))
    if t.kind == "power":
        rate = t.rate
        if act.kind == "couple":
            return (Piece(rate, value=np.broadcast_to(np.asarray(act.value, float), (n,))),)
        return tuple(Piece(rate[:, i], c, u, s, v) for i, (c, u, s, v) in enumerate(parts))
    raise ValueError(f"term of {act.symbol}: unknown kind {t.kind!r}")


def _per_row(x, n: int) -> np.ndarray:
    """A number, or one per row (a stacked variant's mass), as (n,)."""
    return np.broadcast_to(np.asarray(x, float), (n,))


def _axis_comp(d) -> str:
    """``x`` or ``y`` for a projection on i or j (every angle), else ``""``."""
    d = np.asarray(d)
    for name, axis in AXES.items():
        if np.all(np.abs(d - axis) <= 0):
            return name
    return ""
