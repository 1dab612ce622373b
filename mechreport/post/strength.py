"""Strength of the links: internal forces along each member, stresses and safety factors.

A link with a ``section`` is made of straight members (beams) between two of its points. Its
mass is spread uniformly along its members, in proportion to their lengths (line density
mu = m / sum of the members' lengths). Along a member P -> Q, at a cut at distance s from P
[m], in the member's own frame (x = e along P -> Q, y = n = e turned +90 degrees):

- ``N`` [N] the axial force, positive in tension; ``V`` [N] the shear; ``M`` [N m] the
  bending moment, counter-clockwise positive on the face whose outward normal is +e (so that
  a beam loaded against +n between two pins has M > 0, sagging).
- They are the resultant of everything acting on the part of the link beyond the cut (the
  rest of the member up to Q and the members hanging from Q): N e + V n = F_beyond,
  M = moment of those actions about the cut. From the other side they are minus the
  resultant of the part before the cut; the two agree when the link's own ``com`` and
  ``inertia`` are those of its uniform members (else :attr:`MemberStrength.note` says so).
- What acts on the link: the joints' reactions (and couples, friction), the loads and the
  driver's effort at their points, and the distributed weight mu g and d'Alembert inertia
  load -mu a(s) with a(s) = a_P + alpha k x (s e) - omega^2 s e (linear in s), plus the
  sections' own rotary inertia, a couple -mu (I / A) alpha per unit length. A point off the
  members acts on the member nearest to it (through a rigid arm). A couple that names no
  point (a moment load) acts at the link's origin; the motor's torque at the driving joint.
- Stress: sigma = |N| / A + |M| c / I, the largest normal stress of the section at s; the
  outer fibres carry N / A -+ M c / I.

Over the analysed angles (for a whole turn, the cycle), per member: the largest stress and
where it occurs, the static safety yield / stress_max, the fatigue safety by the modified
Goodman line at the section and fibre where it is smallest (sigma_a / S_e + sigma_m / S_u =
1 / n for a tensile mean stress; n = S_e / sigma_a for a compressive one), and for a member in
compression the buckling safety P_cr / largest compression, P_cr the smaller of the column's
loads in the plane of motion (effective length k L, second moment I) and out of it (k_out L,
I_out): Euler above the transition slenderness sqrt(2 pi^2 E / S_y), Johnson below (both with
kL), or Rankine's crushing A / (1 + a (kL/r)^2) (format 1.2 ``buckling``; by default a
pinned-pinned column, k = k_out = 1).

Pure functions of the solved kinematics and the reference method's reactions; arrays
(n, K) over the angles and K positions along the member. Nothing here draws or formats.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from ..forces import ForceContext, ForceResult
from ..kinematics.frames import cross, dot, perp
from ..quantities import split as split_quantity
from ..spec import Buckling, Link, Material, Section
from ..units import Display

#: positions along each member where the internal forces are evaluated (ends included)
POSITIONS = 41
#: a link's inertia and its uniform members' differ when they differ by more than this
#: share (a bar shape's plate and a round section's rotary inertia differ by less)
INERTIA_RTOL = 1e-3


@dataclass(frozen=True)
class PointAction:
    """A force ``force`` (n, 2) [N, global] (or None) and a couple ``couple`` (n,) [N m]
    (or None) acting on a link at ``at`` (n, 2) [m, global]; ``symbol`` its textbook name.
    ``member`` (n,) the index of the member it acts on, ``s`` (n,) [m] where along it (the
    foot of the perpendicular from ``at``, snapped to the ends within round-off)."""

    symbol: str
    at: np.ndarray
    force: np.ndarray | None
    couple: np.ndarray | None
    member: np.ndarray
    s: np.ndarray


@dataclass(frozen=True)
class Diagram:
    """The internal forces along a member at every analysed angle: positions ``s`` (K,) [m]
    from P; ``N``, ``V`` [N] and ``M`` [N m], (n, K)."""

    s: np.ndarray
    N: np.ndarray
    V: np.ndarray
    M: np.ndarray


@dataclass(frozen=True)
class MemberStrength:
    """One member's results. ``name``: ``L`` (a link of one member) or ``L.P_Q``;
    ``quantity(attr)`` its quantity name. ``diagram`` the internal forces, ``stress`` (n, K)
    [Pa] |N|/A + |M|c/I. Extremes over the analysed angles: ``stress_max`` [Pa] at
    ``stress_angle`` [deg], ``stress_s`` [m]; safety factors (None where undefined:
    ``static_safety`` with no stress, ``fatigue_safety`` with no alternating nor tensile
    stress, ``buckling_safety`` never in compression) with where the fatigue safety is smallest
    (``fatigue_s`` [m], ``sigma_a``, ``sigma_m`` [Pa]) and the column's data
    (``compression`` [N] at ``compression_angle``, ``critical_load`` [N], ``slenderness``,
    ``buckling_rule`` Euler | Johnson). ``note``: where the link's com or inertia differ
    from its uniform members' ("" when they do not)."""

    name: str
    link: str
    P: str
    Q: str
    length: float
    section: Section
    material: Material
    diagram: Diagram | None = field(repr=False)     # None for a sweep checked in chunks
    stress: np.ndarray | None = field(repr=False)
    stress_max: float
    stress_angle: float
    stress_s: float
    static_safety: float | None
    fatigue_safety: float | None
    fatigue_s: float
    sigma_a: float
    sigma_m: float
    compression: float
    compression_angle: float | None
    critical_load: float
    slenderness: float
    buckling_rule: str
    buckling_safety: float | None
    note: str = ""
    buckling_plane: int = 1
    column: Column | None = field(default=None, repr=False)   # both planes' loads

    @property
    def plane_text(self) -> str:
        """Where the member buckles, in words: "in the plane" or "out of the plane"."""
        return "in the plane" if self.buckling_plane == 1 else "out of the plane"

    def quantity(self, attr: str) -> str:
        return f"member.{self.name}.{attr}"

    def values(self) -> dict[str, float]:
        """Its quantities by name [SI], the undefined ones left out."""
        out = {self.quantity("stress_max"): self.stress_max}
        for attr in ("static_safety", "fatigue_safety", "buckling_safety"):
            v = getattr(self, attr)
            if v is not None:
                out[self.quantity(attr)] = v
        if self.buckling_safety is not None:      # the plane that governs it
            out[self.quantity("buckling_plane")] = float(self.buckling_plane)
        return out


@dataclass(frozen=True)
class StrengthReview:
    """Every member's results by name, in spec order; ``values`` every member quantity by
    name [SI]; ``method`` the force method whose reactions were used."""

    method: str
    members: dict[str, MemberStrength]

    @property
    def values(self) -> dict[str, float]:
        out: dict[str, float] = {}
        for m in self.members.values():
            out.update(m.values())
        return out

    def worst(self) -> MemberStrength | None:
        """The most loaded member: the one with the smallest static safety (the largest
        stress relative to its yield strength)."""
        return max(self.members.values(),
                   key=lambda m: m.stress_max / m.material.yield_, default=None)


# ------------------------------------------------------------------------------ geometry

def member_names(link: Link) -> list[str]:
    """The quantity names of ``link``'s members: ``L`` for one member, ``L.P_Q`` each for
    several."""
    members = link.strength.members
    if len(members) == 1:
        return [link.name]
    return [f"{link.name}.{p}_{q}" for p, q in members]


def sides(members: tuple[tuple[str, str], ...]) -> list[tuple[set[int], set[int]]]:
    """For each member (P, Q) of a tree of members, the other members on P's side and on
    Q's side (those reached from P, from Q, without crossing it)."""
    out = []
    for m, (p, q) in enumerate(members):
        def reach(start: str) -> set[int]:
            seen, todo, nodes = set(), [start], {start}
            while todo:
                node = todo.pop()
                for k, (a, b) in enumerate(members):
                    if k == m or k in seen or node not in (a, b):
                        continue
                    seen.add(k)
                    other = b if node == a else a
                    if other not in nodes:
                        nodes.add(other)
                        todo.append(other)
            return seen
        out.append((reach(p), reach(q)))
    return out


# ---------------------------------------------------------------------------- the loads

def _unknown(res: ForceResult, name: str) -> np.ndarray:
    if name == res.driver_quantity:
        return res.driver_torque
    _, joint, attr = split_quantity(name)
    return res.reactions[joint].component(attr)


def _action_value(act, res: ForceResult) -> np.ndarray:
    """An Action's value over the angles: (n, 2) [N] for a force, (n,) [N m] for a couple."""
    if act.value is not None:
        return np.asarray(act.value, float)
    if act.kind == "force":
        if act.direction is not None:
            return act.sign * _unknown(res, act.unknowns[0])[:, None] * act.direction
        return act.sign * np.stack([_unknown(res, u) for u in act.unknowns], axis=1)
    return act.sign * _unknown(res, act.unknowns[0])


def point_actions(ctx: ForceContext, res: ForceResult, link: str,
                  geometry: list[tuple]) -> list[PointAction]:
    """Every action on ``link`` but its weight (the members carry it spread out): the
    reactions of its joints (couples at the joint's point), friction, loads (a moment load
    at the link's origin) and the driver's effort (at the driving joint), each placed on the
    member nearest to where it acts (``geometry``: (rP, e, L) per member)."""
    spec = ctx.spec
    k = spec.number(link)
    placed: list[tuple] = []
    for j in spec.joints:
        if link in j.links:
            for act in ctx.reaction(j, link):
                placed.append((act, act.at if act.kind == "force" else ctx.joint_points[j.name]))
    origin = ctx.kin.r[:, k]
    for act in ctx.load_actions(link):
        placed.append((act, act.at if act.kind == "force" else origin))
    for act in ctx.driver_actions(link):
        placed.append((act, act.at if act.kind == "force"
                       else ctx.joint_points[spec.driver.joint]))
    out = []
    for act, at in placed:
        value = _action_value(act, res)
        member, s = _nearest(np.asarray(at, float), geometry)
        out.append(PointAction(act.symbol, np.asarray(at, float),
                               value if act.kind == "force" else None,
                               value if act.kind == "couple" else None, member, s))
    return out


def _nearest(at: np.ndarray, geometry) -> tuple[np.ndarray, np.ndarray]:
    """The member nearest to the points ``at`` (n, 2) and the distance along it (n,) [m]."""
    dist, along = [], []
    for rP, e, L in geometry:
        d = at - rP
        t = np.clip(dot(d, e), 0.0, L)
        tol = 1e-9 * L
        t = np.where(t <= tol, 0.0, np.where(t >= L - tol, L, t))
        dist.append(np.hypot(*(d - t[:, None] * e).T))
        along.append(t)
    m = np.argmin(np.stack(dist), axis=0)
    return m, np.choose(m, np.stack(along))


# ------------------------------------------------------------------- internal forces

@dataclass(frozen=True)
class Member:
    """A member's state over the angles: P's position ``rP`` and acceleration ``aP``
    (n, 2), its unit vectors ``e`` and ``n`` (n, 2), its length ``L`` [m]."""

    rP: np.ndarray
    aP: np.ndarray
    e: np.ndarray
    n: np.ndarray
    L: float


def segment(m: Member, mu: float, k2: float, g: np.ndarray, w: np.ndarray,
             al: np.ndarray, a, b, X: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Resultant force (n, K, 2) and moment about ``X`` (n, K, 2) -> (n, K) of the weight
    and d'Alembert load of the stretch a <= t <= b of member ``m`` (a, b scalars or (K,)
    [m]): q(t) = mu (g - a_P - alpha t n + omega^2 t e) per unit length, plus the rotary
    couple -mu k2 alpha per unit length."""
    a = np.broadcast_to(np.asarray(a, float), X.shape[1:2])
    b = np.broadcast_to(np.asarray(b, float), X.shape[1:2])
    trans = (g - m.aP)[:, None, :]                                     # (n, 1, 2)
    lin = (-al[:, None] * m.n + (w ** 2)[:, None] * m.e)[:, None, :]   # per unit t
    d1, d2, d3 = b - a, (b ** 2 - a ** 2) / 2, (b ** 3 - a ** 3) / 3
    F = mu * (trans * d1[None, :, None] + lin * d2[None, :, None])
    e = m.e[:, None, :]
    moment = (cross(m.rP[:, None, :] - X, F)
              + mu * (cross(e, trans) * d2[None, :] - al[:, None] * d3[None, :])
              - mu * k2 * al[:, None] * d1[None, :])
    return F, moment


def internal_forces(members: list[Member], actions: list[PointAction], mu: float, k2: float,
                    g: np.ndarray, w: np.ndarray, al: np.ndarray, which: int,
                    s: np.ndarray, side_sets, from_end: bool = True) -> Diagram:
    """N, V, M (n, K) along member ``which`` at positions ``s`` (K,) [m], from the part of
    the link beyond each cut (``from_end``: toward Q) or before it (toward P; then minus that
    part's resultant). ``side_sets``: (P side, Q side) member sets of each member."""
    m = members[which]
    X = m.rP[:, None, :] + s[None, :, None] * m.e[:, None, :]           # (n, K, 2)
    behind, beyond = side_sets[which]
    others = beyond if from_end else behind
    F, Mo = segment(m, mu, k2, g, w, al, s if from_end else 0.0, m.L if from_end else s, X)
    for k in others:
        f, mo = segment(members[k], mu, k2, g, w, al, 0.0, members[k].L, X)
        F, Mo = F + f, Mo + mo
    for act in actions:
        on = act.member == which                                         # (n,)
        if from_end:
            part = on[:, None] & ((act.s[:, None] > s[None, :]) | (act.s == m.L)[:, None])
        else:
            part = on[:, None] & ((act.s[:, None] < s[None, :]) | (act.s == 0.0)[:, None])
        part |= np.isin(act.member, list(others))[:, None]
        if act.force is not None:
            f = np.where(part[..., None], act.force[:, None, :], 0.0)
            F = F + f
            Mo = Mo + cross(act.at[:, None, :] - X, f)
        if act.couple is not None:
            Mo = Mo + np.where(part, act.couple[:, None], 0.0)
    sign = 1.0 if from_end else -1.0
    e, n = m.e[:, None, :], m.n[:, None, :]
    return Diagram(s, sign * dot(F, e), sign * dot(F, n), sign * Mo)


@dataclass(frozen=True)
class CutAction:
    """One action on the free part beyond a cut, at one angle: the :class:`PointAction`
    ``action`` (None for the part's distributed loads), its ``force`` (2,) [N, global] and
    its ``moment`` about the cut [N m] (its couple included); ``load`` names a distributed
    load: ``weight`` or ``inertia`` ("" for a point action)."""

    action: PointAction | None
    force: np.ndarray
    moment: float
    load: str = ""


@dataclass(frozen=True)
class MemberCut:
    """Member ``which`` of a link cut at ``s`` [m] from its first point, at angle index
    ``k``: where the cut is, ``at`` (2,) [m], the member's unit vectors ``e`` and ``n`` (2,),
    the members beyond it ``beyond`` (indices), the ``actions`` on the free part beyond the
    cut (point actions first, then its weight and its d'Alembert load), and the section's
    resultant: ``F`` (2,) [N], ``N``, ``V`` [N], ``M`` [N m] and the stress [Pa]."""

    which: int
    s: float
    at: np.ndarray
    e: np.ndarray
    n: np.ndarray
    beyond: set
    actions: list[CutAction]
    F: np.ndarray
    N: float
    V: float
    M: float
    stress: float


def member_cut(members: list[Member], actions: list[PointAction], mu: float, k2: float,
               g: np.ndarray, w: np.ndarray, al: np.ndarray, which: int, s: float,
               side_sets, k: int, section: Section) -> MemberCut:
    """The equilibrium of the free part beyond a cut of member ``which`` at ``s`` [m], at
    angle index ``k``, action by action (what :func:`internal_forces` sums over every angle
    and position at once): every point action on the member beyond the cut or on the
    members beyond it, then the part's weight (mu g per unit length) and its d'Alembert load
    (-mu a per unit length and the sections' rotary couple -mu k2 alpha)."""
    m = members[which]
    ss = np.array([s])
    X = m.rP[:, None, :] + ss[None, :, None] * m.e[:, None, :]
    beyond = side_sets[which][1]
    xk = X[k, 0]
    out = []
    F, Mo = np.zeros(2), 0.0
    for act in actions:
        inside = (act.member[k] == which and (act.s[k] > ss[0] or act.s[k] == m.L)) \
            or int(act.member[k]) in beyond
        if not inside:
            continue
        f = act.force[k] if act.force is not None else np.zeros(2)
        c = float(act.couple[k]) if act.couple is not None else 0.0
        moment = float(cross(act.at[k] - xk, f)) + c
        F, Mo = F + f, Mo + moment
        out.append(CutAction(act, f, moment))
    zero = np.zeros_like(w)
    still = [Member(mm.rP, np.zeros_like(mm.aP), mm.e, mm.n, mm.L) for mm in members]
    for load, parts in (
            ("weight", [(still[which], ss, m.L, g, zero, zero, 0.0)]
             + [(still[j], 0.0, members[j].L, g, zero, zero, 0.0) for j in beyond]),
            ("inertia", [(members[which], ss, m.L, np.zeros(2), w, al, k2)]
             + [(members[j], 0.0, members[j].L, np.zeros(2), w, al, k2) for j in beyond])):
        f_sum, m_sum = np.zeros(2), 0.0
        for mem, a, b, gg, ww, aa, kk in parts:
            f, mo = segment(mem, mu, kk, gg, ww, aa, a, b, X)
            f_sum, m_sum = f_sum + f[k, 0], m_sum + float(mo[k, 0])
        F, Mo = F + f_sum, Mo + m_sum
        out.append(CutAction(None, f_sum, m_sum, load))
    e, n = m.e[k], m.n[k]
    N, V = float(F @ e), float(F @ n)
    return MemberCut(which, float(ss[0]), xk, e, n, set(beyond), out, F, N, V, Mo,
                     float(stress(N, Mo, section)))


# ------------------------------------------------------------------------- safety

def goodman(sigma_a, sigma_m, endurance: float, ultimate: float):
    """Fatigue safety factor by the modified Goodman line: 1 / (sigma_a / S_e + sigma_m /
    S_u) for a tensile mean stress, S_e / sigma_a for a compressive one (the mean stress
    then does not shorten the life); inf where the stress does not alternate and is not
    tensile. Arrays or numbers [Pa]."""
    sa, sm = np.asarray(sigma_a, float), np.asarray(sigma_m, float)
    with np.errstate(divide="ignore"):
        tensile = 1.0 / (sa / endurance + np.maximum(sm, 0.0) / ultimate)
        compressive = np.where(sa > 0, endurance / np.where(sa > 0, sa, 1.0), np.inf)
    return np.where(sm > 0, tensile, compressive)


def column_load(area: float, inertia: float, material: Material, length: float,
                k: float = 1.0, rankine: tuple[float, float] | None = None
                ) -> tuple[float, float, str]:
    """The buckling load [N] of a column of ``length`` [m], effective-length factor ``k``,
    bending about an axis of second moment ``inertia`` [m^4] (r = sqrt(I / A)); its
    slenderness kL / r and the rule used. By Rankine's formula with ``rankine`` = (crushing
    stress [Pa], a): crushing A / (1 + a (kL / r)^2). Else Euler (pi^2 E I / (kL)^2) at or
    above the transition slenderness pi sqrt(2 E / S_y), Johnson (A (S_y - (S_y kL / (2 pi
    r))^2 / E)) below it."""
    E, Sy = material.E, material.yield_
    r = math.sqrt(inertia / area)
    kl = k * length
    slender = kl / r
    if rankine is not None:
        crushing, a = rankine
        return crushing * area / (1.0 + a * slender ** 2), slender, "Rankine"
    transition = math.pi * math.sqrt(2.0 * E / Sy)
    if slender >= transition:
        return math.pi ** 2 * E * inertia / kl ** 2, slender, "Euler"
    return area * (Sy - (Sy * slender / (2 * math.pi)) ** 2 / E), slender, "Johnson"


@dataclass(frozen=True)
class Column:
    """A member as a column: the buckling load [N] of the plane that governs (the smaller),
    its slenderness kL / r and rule (Euler | Johnson | Rankine), and ``plane`` 1 (the plane
    of motion: bending about the axis normal to it, I) or 2 (out of the plane: about the
    axis in it, I_out)."""

    load: float
    slenderness: float
    rule: str
    plane: int
    planes: tuple = ()      # ((load, kL/r, rule) in the plane, the same out of it)


def column(section: Section, material: Material, length: float,
           buckling: Buckling | None = None) -> Column:
    """How a member of ``length`` [m] buckles: in the plane of motion (k, I) and out of it
    (k_out, I_out), the smaller load governing (the plane of motion on a tie)."""
    b = buckling or Buckling()
    rankine = (b.crushing, b.a) if b.formula == "rankine" else None
    planes = ((b.k, section.inertia), (b.k_out, section.inertia_out))
    loads = tuple(column_load(section.area, inertia, material, length, k, rankine)
                  for k, inertia in planes)
    plane = 1 if loads[0][0] <= loads[1][0] else 2
    return Column(*loads[plane - 1], plane, loads)


def critical_load(section: Section, material: Material, length: float,
                  buckling: Buckling | None = None) -> tuple[float, float, str]:
    """The buckling load [N] of a member of ``length`` [m] in the plane that governs, its
    slenderness kL / r and the rule used (:func:`column`; by default a pinned-pinned
    column about the section's weakest axis, Euler or Johnson)."""
    c = column(section, material, length, buckling)
    return c.load, c.slenderness, c.rule


def link_mass_note(link: Link, d: Display | None = None) -> str:
    """:func:`mass_note` of ``link`` from its own points and members, its numbers in the
    units of ``d`` (default SI; a report passes its Display, to print the note in its
    units)."""
    pts = link.points
    pairs = link.strength.members
    lengths = [float(np.hypot(*np.subtract(pts[b], pts[a]))) for a, b in pairs]
    mids = [(np.asarray(pts[a]) + np.asarray(pts[b])) / 2 for a, b in pairs]
    return mass_note(link, lengths, mids, d)


def mass_note(link: Link, lengths: list[float], mids: list[np.ndarray],
              d: Display | None = None) -> str:
    """What differs between ``link``'s own centre of mass and inertia and those of its
    members with its mass spread uniformly ("" when nothing does: the centres within 1e-6
    of the members' length, the inertias within ``INERTIA_RTOL``); its numbers by the one
    formatter in the units of ``d`` (default SI)."""
    d = d or Display()
    total = sum(lengths)
    com = sum(L * c for L, c in zip(lengths, mids)) / total
    k2 = link.strength.section.inertia / link.strength.section.area
    spread = link.mass / total * (sum(L ** 3 / 12 + L * float(np.dot(c - com, c - com))
                                      for L, c in zip(lengths, mids)) + k2 * total)
    parts = []
    off = float(np.hypot(*(np.asarray(link.com) - com)))
    if off > 1e-6 * total:
        parts.append(f"its centre of mass is {d.q(off, 'length')} from its members' middle "
                     f"({d.num(com[0], 'length')}, {d.num(com[1], 'length')}) "
                     f"{d.unit('length')}")
    if abs(link.inertia - spread) > INERTIA_RTOL * max(link.inertia, spread, 1e-300):
        parts.append(f"its inertia is {d.q(link.inertia, 'inertia')}, its uniform members' "
                     f"{d.q(spread, 'inertia')}")
    if not parts or link.mass == 0:
        return ""
    return (f"link {link.name}: {' and '.join(parts)}; the members carry the link's mass "
            "spread uniformly, so the internal forces from the two sides of a cut differ")


# ------------------------------------------------------------------------- the review

@dataclass(frozen=True)
class Extremes:
    """What a member's safety factors need from some angles, mergeable chunk by chunk: the
    largest stress ``stress_max`` [Pa] at ``stress_angle`` [deg] and position index
    ``stress_k``; each outer fibre's largest and smallest stress at each position ``hi``,
    ``lo`` (2, K) [Pa]; the largest compression ``compression`` [N] at
    ``compression_angle``; ``scale`` the largest |N| or |V| [N]."""

    stress_max: float
    stress_angle: float
    stress_k: int
    hi: np.ndarray
    lo: np.ndarray
    compression: float
    compression_angle: float
    scale: float

    def merge(self, other: "Extremes") -> "Extremes":
        """These extremes and ``other``'s (later angles) together."""
        a = self if self.stress_max >= other.stress_max else other
        c = self if self.compression >= other.compression else other
        return Extremes(a.stress_max, a.stress_angle, a.stress_k,
                        np.maximum(self.hi, other.hi), np.minimum(self.lo, other.lo),
                        c.compression, c.compression_angle, max(self.scale, other.scale))


def stress(N, M, sec: Section):
    """The largest normal stress [Pa] in a section ``sec`` that carries the axial force ``N``
    [N] and the bending moment ``M`` [N m] (numbers or arrays): |N| / A + |M| c / I, at the
    fibre where the two add."""
    return np.abs(N) / sec.area + np.abs(M) * sec.c / sec.inertia


def extremes(angles: np.ndarray, dia: Diagram, sec: Section) -> Extremes:
    """The :class:`Extremes` of the diagrams ``dia`` over ``angles`` (n,) [deg]."""
    axial, bending = dia.N / sec.area, dia.M * sec.c / sec.inertia
    sigma = stress(dia.N, dia.M, sec)
    a, j = np.unravel_index(int(np.argmax(sigma)), sigma.shape)
    fibres = np.stack([axial - bending, axial + bending])               # (2, n, K)
    comp = -dia.N.min(axis=1)                                           # (n,)
    ac = int(np.argmax(comp))
    scale = float(max(np.max(np.abs(dia.N)), np.max(np.abs(dia.V))))
    return Extremes(float(sigma[a, j]), float(angles[a]), int(j), fibres.max(axis=1),
                    fibres.min(axis=1), float(comp[ac]), float(angles[ac]), scale)


@dataclass(frozen=True)
class MemberPart:
    """One member's results over some angles, before the safety factors: its identity
    (``name``, ``link``, ``P``, ``Q``, ``length`` [m], positions ``s`` (K,) [m], ``note``)
    and its :class:`Extremes`; ``diagram`` and ``stress`` (n, K) only for one whole
    in-memory sweep (None once merged)."""

    name: str
    link: Link
    P: str
    Q: str
    length: float
    s: np.ndarray
    note: str
    extremes: Extremes
    diagram: Diagram | None = None
    stress: np.ndarray | None = None

    def merge(self, other: "MemberPart") -> "MemberPart":
        return MemberPart(self.name, self.link, self.P, self.Q, self.length, self.s,
                          self.note, self.extremes.merge(other.extremes))


def strength_parts(ctx: ForceContext, res: ForceResult, positions: int = POSITIONS,
                   keep: bool = True) -> dict[str, MemberPart]:
    """Every member of every link with a ``section`` over ``ctx``'s angles, from the
    reactions ``res``; ``keep``: keep the diagrams (else only the extremes)."""
    out: dict[str, MemberPart] = {}
    g = np.asarray(ctx.spec.gravity, float)
    for link in ctx.spec.links:
        if link.strength is not None and ctx.n:
            out.update(_link_parts(ctx, res, link, g, positions, keep))
    return out


def merge_parts(a: dict[str, MemberPart] | None,
                b: dict[str, MemberPart]) -> dict[str, MemberPart]:
    """Parts of consecutive chunks of a sweep merged (``a`` None: the first chunk's)."""
    if a is None:
        return {k: MemberPart(p.name, p.link, p.P, p.Q, p.length, p.s, p.note, p.extremes)
                for k, p in b.items()}
    return {k: a[k].merge(b[k]) if k in a else b[k] for k in b}


def strength_review(ctx: ForceContext, res: ForceResult,
                    positions: int = POSITIONS) -> StrengthReview | None:
    """Every member of every link with a ``section``: internal forces, stresses and safety
    factors over the analysed angles (``res``: the reference method's reactions). None when
    no link has a section."""
    parts = strength_parts(ctx, res, positions)
    return review_of_parts(parts, res.method) if parts else None


def review_of_parts(parts: dict[str, MemberPart], method: str) -> StrengthReview:
    """The safety factors of each member from its extremes (see the module docstring)."""
    return StrengthReview(method, {k: member_strength(p) for k, p in parts.items()})


def member_strength(part: MemberPart) -> MemberStrength:
    link, ext = part.link, part.extremes
    sec, mat = link.strength.section, link.strength.material
    sa, sm = (ext.hi - ext.lo) / 2, (ext.hi + ext.lo) / 2
    nf = goodman(sa, sm, mat.endurance, mat.ultimate)
    f, jf = np.unravel_index(int(np.argmin(nf)), nf.shape)
    fatigue = float(nf[f, jf])
    index = link.strength.members.index((part.P, part.Q))
    col = column(sec, mat, part.length, link.strength.buckling_of(index))
    pcr, slender, rule = col.load, col.slenderness, col.rule
    compressed = ext.compression > 1e-9 * ext.scale and ext.compression > 0
    smax = ext.stress_max
    return MemberStrength(
        part.name, link.name, part.P, part.Q, part.length, sec, mat, part.diagram,
        part.stress, smax, ext.stress_angle, float(part.s[ext.stress_k]),
        mat.yield_ / smax if smax > 0 else None,
        fatigue if math.isfinite(fatigue) else None, float(part.s[jf]), float(sa[f, jf]),
        float(sm[f, jf]), max(ext.compression, 0.0),
        ext.compression_angle if compressed else None, pcr, slender, rule,
        pcr / ext.compression if compressed else None, part.note, col.plane, col)


def link_members(ctx: ForceContext, link: Link) -> list[Member]:
    """The state of each member of ``link`` over the angles."""
    kin = ctx.kin
    pts = link.points
    out = []
    for p, q in link.strength.members:
        d = np.subtract(pts[q], pts[p])
        L = float(np.hypot(*d))
        e = kin.frames.rotate(link.name, d / L)
        P = kin.named_point(p, link.name)
        out.append(Member(P.r, P.a, e, perp(e), L))
    return out


def _link_parts(ctx: ForceContext, res: ForceResult, link: Link, g: np.ndarray,
                positions: int, keep: bool) -> dict[str, MemberPart]:
    kin = ctx.kin
    st = link.strength
    sec = st.section
    k = link.number
    w, al = kin.omega[:, k], kin.alpha[:, k]
    members = link_members(ctx, link)
    lengths = [m.L for m in members]
    mu = link.mass / sum(lengths)
    k2 = sec.inertia / sec.area
    acts = point_actions(ctx, res, link.name, [(m.rP, m.e, m.L) for m in members])
    side_sets = sides(st.members)
    mids = [(np.asarray(link.points[p]) + np.asarray(link.points[q])) / 2
            for p, q in st.members]
    note = mass_note(link, lengths, mids)
    out = {}
    for i, name in enumerate(member_names(link)):
        m = members[i]
        s = np.linspace(0.0, m.L, positions)
        dia = internal_forces(members, acts, mu, k2, g, w, al, i, s, side_sets)
        sigma = stress(dia.N, dia.M, sec) if keep else None
        p, q = st.members[i]
        out[name] = MemberPart(name, link, p, q, m.L, s, note,
                               extremes(kin.angles, dia, sec), dia if keep else None, sigma)
    return out


__all__ = ["POSITIONS", "Column", "Diagram", "Extremes", "MemberPart", "MemberStrength",
           "PointAction", "StrengthReview", "column", "column_load", "critical_load", "extremes", "goodman", "internal_forces",
           "link_members", "member_names", "merge_parts", "point_actions", "review_of_parts",
           "sides", "strength_parts", "strength_review"]
