"""The solution sheet's cuts: for each member of a link with a ``section``, at a reference
angle, the member cut at its middle and the equilibrium of the free part beyond the cut (the
rest of the member up to its second point, and the members hanging from it), written out as
the chapter writes free bodies: every action on the part with its point and its moment
about the cut, the part's own weight and d'Alembert load, then N, V, M and the stress.

The numbers are :func:`mechreport.post.strength.member_cut`'s: the cut's equilibrium is
computed there, once, and only written out here; SI units."""
from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from ...post.strength import link_members, member_cut, member_names, point_actions, sides
from .expr import fmt
from .statement import sci
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


#: how the sheet writes a cut's distributed loads: (symbol in TeX, in Typst, meaning)
DISTRIBUTED = {
    "weight": (r"\mathbf{G}'", "bold(G)'", "weight of the free part, μ g per unit length"),
    "inertia": (r"\mathbf{F}_{in}'", "bold(F)_(i n)'",
                "d'Alembert load of the free part, −μ a(s) per unit length and the sections' "
                "rotary couple −μ (I/A) α"),
}


def _cut(analysis, k, link, name, i, members, acts, mu, k2, g, w, al, side_sets) -> Cut:
    p, q = link.strength.members[i]
    m = members[i]
    sec = link.strength.section
    cut = member_cut(members, acts, mu, k2, g, w, al, i, m.L / 2, side_sets, k, sec)
    rows = []
    for ca in cut.actions:
        if ca.action is None:
            tex, typ, label = DISTRIBUTED[ca.load]
            rows.append([[R(tex, typ), f" ({label})"], "distributed", _v(ca.force[0]),
                         _v(ca.force[1]), _v(ca.moment)])
            continue
        act = ca.action
        sym = scalar_sym(act.symbol) if act.force is None else vec_sym(act.symbol)
        rows.append([[sym], _where(analysis, act, k), _v(ca.force[0]) if act.force is not None
                     else "", _v(ca.force[1]) if act.force is not None else "",
                     _v(ca.moment)])
    s, xk, e, n, beyond = [cut.s], cut.at, cut.e, cut.n, cut.beyond
    F, N, V, M, sigma = cut.F, cut.N, cut.V, cut.M, cut.stress
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
              f" = {_v(sigma / 1e6)} MPa (A = {sci(sec.area)} m², I = {sci(sec.inertia)} m⁴, "
              f"c = {sci(sec.c)} m)."]
    result += column_check(analysis.strength.members[name], link.strength.buckling_of(i),
                           bool(link.strength.buckling))
    return Cut(f"Cut of member {name}", intro, rows, result)


#: each rule's formula for the buckling load, as the sheet writes it (TeX, Typst)
RULES = {
    "Euler": (r"P = \pi^2 E I / (kL)^2", "P = pi^2 E I / (k L)^2"),
    "Johnson": (r"P = A\,(S_y - (S_y\,kL/(2\pi r))^2/E)",
                "P = A (S_y - (S_y k L / (2 pi r))^2 / E)"),
    "Rankine": (r"P = \sigma_c A / (1 + a\,(kL/r)^2)",
                "P = sigma_c A / (1 + a (k L / r)^2)"),
}


def column_check(m, b, given: bool = True) -> list:
    """The member as a column, worked as a machine-design book works a connecting rod: the
    slenderness in the plane of motion and out of it, each plane's buckling load by its rule,
    the smaller governing, and the safety against the largest compression over the sweep
    (the numbers are :func:`mechreport.post.strength.column`'s). Nothing for a member never
    in compression, nor (``given`` False) for a link without ``buckling`` data (its report
    gives the pinned-pinned column's load)."""
    if m.buckling_safety is None or m.column is None or not given:
        return []
    sec = m.section
    formula = (f"Rankine, σc = {_v(b.crushing / 1e6)} MPa, a = {sci(b.a)}"
               if b.formula == "rankine" else "Euler, or Johnson below the transition "
               "slenderness π √(2E/S_y)")
    out = [f" Column check over the sweep ({formula}): L = {sci(m.length)} m, "
           f"A = {sci(sec.area)} m², r = √(I/A) = "
           f"{sci((sec.inertia / sec.area) ** 0.5)} m in the plane and "
           f"{sci((sec.inertia_out / sec.area) ** 0.5)} m out of it (I_out = "
           f"{sci(sec.inertia_out)} m⁴)."]
    for (load, slender, rule), k, where in zip(m.column.planes, (b.k, b.k_out),
                                               ("In the plane", "Out of the plane")):
        out += [f" {where}, k = {_v(k)}: kL/r = {_v(slender)}, ", R(*RULES[rule]),
                f" = {_v(load)} N ({rule})."]
    out.append(f" The smaller governs: P_cr = {_v(m.critical_load)} N, {m.plane_text}; the "
               f"largest compression is {_v(m.compression)} N at {_v(m.compression_angle)}°, "
               f"so the buckling safety is P_cr / P = {_v(m.buckling_safety)}.")
    return out


def _where(analysis, act, k: int) -> str:
    """Where an action acts: its point's name where one is named, else its position."""
    at = act.at[k]
    for name, link in analysis.spec.named_points():
        r = analysis.kinematics.named_point(name, link).r[k]
        if np.hypot(*(r - at)) <= 1e-9 * max(1.0, float(np.hypot(*at))):
            return name
    return f"({_v(at[0])}, {_v(at[1])}) m"


__all__ = ["Cut", "cuts"]
