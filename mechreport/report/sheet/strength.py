"""The solution sheet's cuts: for each member of a link with a ``section``, at a reference
angle, the member cut at its middle and the equilibrium of the free part beyond the cut (the
rest of the member up to its second point, and the members hanging from it), written out as
the chapter writes free bodies: every action on the part with its point and its moment
about the cut, the part's own weight and d'Alembert load, then N, V, M and the stress.

The numbers are those of :mod:`mechreport.post.strength` (the same functions); SI units."""
from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from ...kinematics.frames import cross
from ...post.strength import (_Member, _segment, link_members, member_names, point_actions,
                              sides, stress)
from .expr import fmt
from .symbols import R, scalar_sym, vec_sym


@dataclass
class Cut:
    """One member's cut at one angle: ``title``; ``intro`` and ``result`` rich text (strings
    and math); ``rows`` the free part's actions: (symbol math, where, Fx [N], Fy [N], moment
    about the cut [N m])."""

    title: str
    intro: list = field(default_factory=list)
    rows: list = field(default_factory=list)
    result: list = field(default_factory=list)


def _v(x: float) -> str:
    return fmt(float(x) + 0.0)


def cuts(analysis, k: int) -> list[Cut]:
    """The cuts of every member of every link with a section at angle index ``k`` (none
    without a section)."""
    st = analysis.strength
    if st is None:
        return []
    ctx = analysis.strength_context()
    res = analysis.forces[st.method]
    spec, kin = analysis.spec, analysis.kinematics
    g = np.asarray(spec.gravity, float)
    out = []
    for link in spec.links:
        if link.strength is None:
            continue
        members = link_members(ctx, link)
        acts = point_actions(ctx, res, link.name, [(m.rP, m.e, m.L) for m in members])
        mu = link.mass / sum(m.L for m in members)
        sec = link.strength.section
        k2 = sec.inertia / sec.area
        num = link.number
        w, al = kin.omega[:, num], kin.alpha[:, num]
        side_sets = sides(link.strength.members)
        for i, name in enumerate(member_names(link)):
            out.append(_cut(analysis, k, link, name, i, members, acts, mu, k2, g, w, al,
                            side_sets))
    return out


def _cut(analysis, k, link, name, i, members, acts, mu, k2, g, w, al, side_sets) -> Cut:
    p, q = link.strength.members[i]
    m = members[i]
    s = np.array([m.L / 2])
    X = m.rP[:, None, :] + s[None, :, None] * m.e[:, None, :]
    beyond = side_sets[i][1]
    rows = []
    F = np.zeros(2)
    Mo = 0.0
    xk = X[k, 0]
    for act in acts:
        inside = (act.member[k] == i and (act.s[k] > s[0] or act.s[k] == m.L)) \
            or int(act.member[k]) in beyond
        if not inside:
            continue
        f = act.force[k] if act.force is not None else np.zeros(2)
        c = float(act.couple[k]) if act.couple is not None else 0.0
        moment = float(cross(act.at[k] - xk, f)) + c
        F, Mo = F + f, Mo + moment
        sym = scalar_sym(act.symbol) if act.force is None else vec_sym(act.symbol)
        rows.append([[sym], _where(analysis, act, k), _v(f[0]) if act.force is not None
                     else "", _v(f[1]) if act.force is not None else "", _v(moment)])
    zero = np.zeros_like(w)
    still = [_Member(mm.rP, np.zeros_like(mm.aP), mm.e, mm.n, mm.L) for mm in members]
    for label, tex, typ, parts in (
            ("weight of the free part, μ g per unit length", r"\mathbf{G}'", "bold(G)'",
             [(still[i], s, m.L, g, zero, zero, 0.0)]
             + [(still[j], 0.0, members[j].L, g, zero, zero, 0.0) for j in beyond]),
            ("d'Alembert load of the free part, −μ a(s) per unit length and the sections' "
             "rotary couple −μ (I/A) α", r"\mathbf{F}_{in}'", "bold(F)_(i n)'",
             [(members[i], s, m.L, np.zeros(2), w, al, k2)]
             + [(members[j], 0.0, members[j].L, np.zeros(2), w, al, k2) for j in beyond])):
        f_sum, m_sum = np.zeros(2), 0.0
        for mem, a, b, gg, ww, aa, kk in parts:
            f, mo = _segment(mem, mu, kk, gg, ww, aa, a, b, X)
            f_sum, m_sum = f_sum + f[k, 0], m_sum + float(mo[k, 0])
        F, Mo = F + f_sum, Mo + m_sum
        rows.append([[R(tex, typ), f" ({label})"], "distributed", _v(f_sum[0]), _v(f_sum[1]),
                     _v(m_sum)])
    e, n = m.e[k], m.n[k]
    N, V, M = float(F @ e), float(F @ n), Mo
    sec = link.strength.section
    sigma = float(stress(N, M, sec))
    beyond_names = [f"{a}–{b}" for j, (a, b) in enumerate(link.strength.members)
                    if j in beyond]
    intro = [f"Member {name} ({p}–{q}, L = {_v(m.L)} m) cut at its middle, s = {_v(s[0])} m "
             f"from {p}, at ({_v(xk[0])}, {_v(xk[1])}) m. The free part runs from the cut to "
             f"{q}" + (f", with the members beyond it ({', '.join(beyond_names)})"
                       if beyond_names else "")
             + ". Along the member ", R(r"\mathbf{e}", "bold(e)"),
             f" = [{_v(e[0])}, {_v(e[1])}] and ", R(r"\mathbf{n}", "bold(n)"),
             f" = [{_v(n[0])}, {_v(n[1])}] (e turned +90°). The actions on the free part, "
             "their forces [N] and moments about the cut [N·m]:"]
    result = ["Equilibrium of the free part: the section at the cut carries what it "
              "exerts, ", R(r"\mathbf{F}", "bold(F)"), f" = [{_v(F[0])}, {_v(F[1])}] N, the "
              "sum of its forces, and ", R(r"M = \sum (\mathbf{r} - \mathbf{r}_s) \times "
                                         r"\mathbf{F} + \sum M",
                                         "M = sum (bold(r) - bold(r)_s) times bold(F) + sum M"),
              ", so ", R(r"N = \mathbf{F}\cdot\mathbf{e}", "N = bold(F) dot bold(e)"),
              f" = {_v(N)} N, ", R(r"V = \mathbf{F}\cdot\mathbf{n}", "V = bold(F) dot bold(n)"),
              f" = {_v(V)} N, M = {_v(M)} N·m. Stress: ",
              R(r"\sigma = |N|/A + |M|\,c/I", "sigma = abs(N)/A + abs(M) c / I"),
              f" = {_v(sigma / 1e6)} MPa (A = {_v(sec.area)} m², I = {_v(sec.inertia)} m⁴, "
              f"c = {_v(sec.c)} m)."]
    return Cut(f"Cut of member {name}", intro, rows, result)


def _where(analysis, act, k: int) -> str:
    """Where an action acts: its point's name where one is named, else its position."""
    at = act.at[k]
    for name, link in analysis.spec.named_points():
        r = analysis.kinematics.named_point(name, link).r[k]
        if np.hypot(*(r - at)) <= 1e-9 * max(1.0, float(np.hypot(*at))):
            return name
    return f"({_v(at[0])}, {_v(at[1])}) m"


__all__ = ["Cut", "cuts"]
