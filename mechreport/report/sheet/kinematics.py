"""The kinematics of one reference angle as the textbook derives it (4.6, 4.7), with numbers.

- The crank: each of its points from the pivot, r_B = r_A + AB (cos phi i + sin phi j),
  v_B = v_A + omega_1 k x r_AB, a_B = a_A + alpha_1 k x r_AB - omega_1^2 r_AB.
- A dyad: its positions (the closure conditions and the angles found), then the velocity
  loop at its interior joint, the same point reached through either link,
  v_B + omega_2 k x r_BC (+ v_32 Delta across a slider) = v_D + omega_3 k x r_DC, projected on
  x and y with the two unknown rates as symbols, and the rates found; then accelerations
  likewise (with the Coriolis term 2 omega k x v Delta of a slider on a turning guide).
- Any other group (a triad, a linear actuator's group) is solved numerically; its link angles
  and rates and its joints' positions, velocities and accelerations are listed.
- Each mass centre from a joint of its link, as the crank's points.

Every value is read from the solved kinematics at the angle's index; the printed equations
balance with them (tests evaluate them).
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from ...spec import GROUND
from ..spec_items import numbered_link
from .expr import Equation, Expr, Num, Op, Paren, Point, Raw, RVec, Sym, fmt
from .symbols import (DEG_, K_, M_, MS2_, MS_, RADS2_, RADS_, I_, J_, R, alpha, delta_sym,
                      omega, point_vec, theta)


@dataclass
class KinBlock:
    """One part of the derivation: a title and ``items`` in reading order, each
    ``("text", rich text)``, ``("eq", lead-in text or None, Equation or list of them)`` or
    ``("found", [Equation ...])`` (values found, on one line). ``values`` maps the Python names
    of the symbols its equations leave unknown to their values (tests evaluate the lines)."""

    title: str
    items: list = field(default_factory=list)
    values: dict = field(default_factory=dict)

    def text(self, rich: list) -> None:
        self.items.append(("text", rich, None))

    def eq(self, lead, math) -> None:
        self.items.append(("eq", lead, math))

    def found(self, row: list) -> None:
        self.items.append(("found", row, None))


# ------------------------------------------------------------------------------ helpers

def vec_expr(v, unit=None, exact=None) -> Expr:
    """x i + y j, zero components left out (0 if both vanish); ``exact`` writes closed forms
    where it finds them."""
    e = Expr()
    for x, u in ((float(v[0]), I_), (float(v[1]), J_)):
        if fmt(x) == "0":
            continue
        c = exact(x) if exact is not None else None
        if c is not None:
            atom = exact.atom(-c if x < 0 else c)
            e.add(-1 if x < 0 else 1, Paren(Expr().add(1, atom)) if "+" in atom.p or
                  " - " in atom.p else atom, u)
        elif fmt(abs(x)) == "1":
            e.add(np.sign(x), u)
        else:
            e.add(np.sign(x), Num(abs(x)), u)
    if not e.terms:
        e.add(1, Num(0.0))
    if unit is not None:
        sign, factors = e.terms[-1]
        e.terms[-1] = (sign, factors + [unit])
    return e


def scalar(x: float, unit=None, exact=None) -> Expr:
    x = float(x)
    c = exact(x) if exact is not None and fmt(x) != "0" else None
    if c is not None:
        e = Expr().add(1, exact.atom(c))
    else:
        e = Expr().add(-1 if x < 0 and fmt(x) != "0" else 1, Num(abs(x)))
    if unit is not None:
        sign, factors = e.terms[-1]
        e.terms[-1] = (sign, factors + [unit])
    return e


def _found(atom, value: Expr, exact: Expr | None) -> Equation:
    """``atom = value``, and ``= exact form`` where one was found that is not the same."""
    from .expr import math as render
    sides = [Expr().add(1, atom), value]
    if exact is not None and render(exact, "plain") != render(value, "plain"):
        sides.append(exact)
    return Equation(sides)


def paren_vec(v) -> Paren:
    return Paren(vec_expr(v))


def _zero(v) -> bool:
    return all(fmt(float(c)) == "0" for c in np.atleast_1d(v))


def _sq(w: float) -> Raw:
    n = Num(w, paren=w < 0)
    return Raw(n.tex() + "^2", n.typ() + "^2", n.plain() + "^2", f"({float(w)!r})**2")


class State:
    """Positions, velocities and accelerations at angle index ``k``."""

    def __init__(self, analysis, k: int):
        self.kin, self.spec, self.points, self.k = (analysis.kinematics, analysis.spec,
                                                    analysis.joint_points(), k)

    def num(self, link: str) -> int:
        return self.spec.number(link)

    def w(self, link: str) -> float:
        return float(self.kin.omega[self.k, self.num(link)])

    def al(self, link: str) -> float:
        return float(self.kin.alpha[self.k, self.num(link)])

    def th(self, link: str) -> float:
        return float(self.kin.theta[self.k, self.num(link)])

    def at(self, link: str, r) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """Position, velocity, acceleration of the point of ``link`` now at ``r``."""
        n, k = self.num(link), self.k
        r = np.asarray(r, float)
        d = r - self.kin.r[k, n]
        w, a = self.kin.omega[k, n], self.kin.alpha[k, n]
        v = self.kin.v[k, n] + w * np.array([-d[1], d[0]])
        acc = self.kin.a[k, n] + a * np.array([-d[1], d[0]]) - w * w * d
        return r, v, acc

    def local(self, link: str, name: str):
        return self.kin.point(link, self.spec.link(link).points[name])

    def joint_r(self, joint) -> np.ndarray:
        return np.asarray(self.points[joint.name][self.k], float)


def rigid_lines(st: State, link: str, p: str, rp, q: str, rq, exact=None) -> list[Equation]:
    """r, v, a of point ``q`` of ``link`` from its point ``p`` (positions ``rp``, ``rq``)."""
    n = st.num(link)
    rp, vp, ap = st.at(link, rp)
    rq, vq, aq = st.at(link, rq)
    d = rq - rp
    length = float(np.hypot(*d))
    ang = math.degrees(math.atan2(d[1], d[0]))
    th = math.degrees(st.th(link))
    beta = (ang - th + 180.0) % 360.0 - 180.0
    w, al = st.w(link), st.al(link)
    pq = Raw(Point(p).tex() + Point(q).tex(), Point(p).typ() + " " + Point(q).typ(), p + q)
    # r_Q = r_P + PQ (cos th i + sin th j)
    ang_atom = theta(n) if abs(beta) < 1e-9 else \
        Raw(rf"(\theta_{{{n}}} {'+' if beta > 0 else '-'} {fmt(abs(beta))}^\circ)",
            f"(theta_{n} {'+' if beta > 0 else '-'} {fmt(abs(beta))} degree)",
            f"(theta{n} {'+' if beta > 0 else '-'} {fmt(abs(beta))} deg)")
    trig = Paren(Expr().add(1, Raw(r"\cos", "cos", "cos"), ang_atom, I_)
                 .add(1, Raw(r"\sin", "sin", "sin"), ang_atom, J_))
    deg = Raw(f"{fmt(ang)}^\\circ", f"{fmt(ang)} degree", f"{fmt(ang)}deg")
    if ang < 0:
        deg = Paren(Expr().add(-1, Raw(f"{fmt(-ang)}^\\circ", f"{fmt(-ang)} degree",
                                       f"{fmt(-ang)}deg")))
    trig_num = Paren(Expr().add(1, Raw(r"\cos", "cos", "cos"), deg, I_)
                     .add(1, Raw(r"\sin", "sin", "sin"), deg, J_))
    sym_r = Expr()
    num_r = Expr()
    if not _zero(rp):
        sym_r.add(1, point_vec("r", p))
        num_r.add(1, paren_vec(rp))
    sym_r.add(1, pq, trig)
    num_r.add(1, Num(length), trig_num)
    lines = [Equation([Expr().add(1, point_vec("r", q)), sym_r, num_r, vec_expr(rq, M_)])]
    # v_Q = v_P + omega k x r_PQ
    sym_v, num_v = Expr(), Expr()
    if not _zero(vp):
        num_v.add(1, paren_vec(vp))
    sym_v.add(1, point_vec("v", p)).add(1, omega(n), K_, Op("times"), RVec(p, q))
    if fmt(w) != "0":
        num_v.add(1, Num(w, paren=w < 0), K_, Op("times"), paren_vec(d))
    lines.append(Equation([Expr().add(1, point_vec("v", q)), sym_v, num_v or Expr(),
                           vec_expr(vq, MS_)]))
    # a_Q = a_P + alpha k x r_PQ - omega^2 r_PQ
    sym_a, num_a = Expr(), Expr()
    sym_a.add(1, point_vec("a", p)).add(1, alpha(n), K_, Op("times"), RVec(p, q)) \
        .add(-1, Raw(rf"\omega_{{{n}}}^2", f"omega_{n}^2", f"omega{n}^2"), RVec(p, q))
    if not _zero(ap):
        num_a.add(1, paren_vec(ap))
    if fmt(al) != "0":
        num_a.add(1, Num(al, paren=al < 0), K_, Op("times"), paren_vec(d))
    if fmt(w) != "0":
        num_a.add(-1, _sq(w), paren_vec(d))
    lines.append(Equation([Expr().add(1, point_vec("a", q)), sym_a, num_a or Expr(),
                           vec_expr(aq, MS2_)]))
    return lines


# ------------------------------------------------------------------------------ blocks

def _link_title(spec, links) -> str:
    ls = [spec.link(l) for l in links]
    if len(ls) == 1:
        return numbered_link(ls[0].number, ls[0].name)
    return "links " + ", ".join(str(l.number) for l in ls) + " (" + \
        ", ".join(l.name for l in ls) + ")"


def crank_block(st: State, group, exact=None) -> KinBlock:
    spec = st.spec
    link = group.links[0]
    n = st.num(link)
    joint = spec.joint(spec.driver.joint)
    b = KinBlock(f"Driver: crank {n} ({link}) about {joint.point}")
    b.text([f"The crank turns about {joint.point} with ", R(rf"\varphi = \theta_{{{n}}} = "
              rf"{fmt(math.degrees(st.th(link)))}^\circ", f"phi = theta_{n} = "
              f"{fmt(math.degrees(st.th(link)))} degree"), ", ",
              Equation([Expr().add(1, omega(n)), scalar(st.w(link), RADS_)]), ", ",
              Equation([Expr().add(1, alpha(n)), scalar(st.al(link), RADS2_)]), "."])
    pivot = st.joint_r(joint)
    for j in spec.joints:
        if link in j.links and j.name != joint.name and j.point in spec.link(link).points:
            for e in rigid_lines(st, link, joint.point, pivot, j.point, st.joint_r(j), exact):
                b.eq(None, e)
    return b


def _sigma(joint, frm: str, to: str) -> float:
    """Across T joint ``joint`` from link ``frm`` to ``to``: v(to) = v(frm) + sigma v_rel
    Delta, v_rel the slider's speed relative to the guide along Delta."""
    return 1.0 if to == joint.slider else -1.0


def _delta(st: State, joint) -> np.ndarray:
    g = joint.guide
    th = st.th(g) if g != GROUND else 0.0
    d = np.asarray(joint.line.direction, float)
    c, s = math.cos(th), math.sin(th)
    return np.array([c * d[0] - s * d[1], s * d[0] + c * d[1]])


def _rel(st: State, joint):
    """(v_rel, a_rel, Delta, omega_guide) of a T joint at the angle."""
    r = st.joint_r(joint)
    d = _delta(st, joint)
    _, vs, as_ = st.at(joint.slider, r)
    _, vg, ag = st.at(joint.guide, r)
    wg = st.w(joint.guide) if joint.guide != GROUND else 0.0
    v_rel = float(np.dot(vs - vg, d))
    cor = 2 * wg * v_rel * np.array([-d[1], d[0]])
    a_rel = float(np.dot(as_ - ag - cor, d))
    return v_rel, a_rel, d, wg


def _rel_syms(st: State, joint):
    s, g = st.num(joint.slider), st.num(joint.guide)
    return (Sym("v", f"{s}{g}", py_name=f"v{s}{g}"), Sym("a", f"{s}{g}", py_name=f"a{s}{g}"))


class _Side:
    """One side of a loop equation: known vectors and unknown scalars times vectors."""

    def __init__(self):
        self.sym = Expr()
        self.terms: list[tuple] = []     # (vector, unknown py name | None, atom | None)

    def known(self, atoms, v, always_zero: bool = False):
        if always_zero:
            return
        self.sym.add(1, *atoms)
        self.terms.append((np.asarray(v, float), None, None))

    def known_neg(self, atoms, v):
        self.sym.add(-1, *atoms)
        self.terms.append((-np.asarray(v, float), None, None))

    def unknown(self, atoms, coef, atom, signed: float = 1.0):
        self.sym.add(signed, *atoms)
        self.terms.append((signed * np.asarray(coef, float), atom.py(), atom))

    def component(self, i: int) -> Expr:
        e = Expr()
        for v, name, atom in self.terms:
            c = float(v[i])
            if fmt(c) == "0":
                continue
            if name is None:
                e.add(np.sign(c), Num(abs(c)))
            elif fmt(abs(c)) == "1":
                e.add(np.sign(c), atom)
            else:
                e.add(np.sign(c), Num(abs(c)), atom)
        return e


def dyad_block(st: State, group, exact=None, known: set | None = None) -> KinBlock | None:
    """The loop equations of a dyad (None if its rates are not two: then the generic list)."""
    spec, dy = st.spec, group.dyad
    i, j = dy.links
    j0, j1, j2 = dy.outer[0], dy.inner, dy.outer[1]
    k0, k2 = dy.known_link(0), dy.known_link(1)
    r0, r1, r2 = st.joint_r(j0), st.joint_r(j1), st.joint_r(j2)
    # whose rotation each link has: a link sliding on another turns with it
    owns = {i: k0 if j0.type == "T" else i, j: k2 if j2.type == "T" else j}
    if j1.type == "T":
        if owns[i] not in (i, j):
            owns[j] = owns[i]
        elif owns[j] not in (i, j):
            owns[i] = owns[j]
        else:                    # the slider turns with its guide (4.7: omega_2 = omega_3)
            owns[j1.slider] = j1.guide
    unknown_w = list(dict.fromkeys(o for o in (owns[i], owns[j]) if o in (i, j)))
    rates = unknown_w + [jt.name for jt in (j0, j1, j2) if jt.type == "T"]
    if len(rates) != 2:
        return None
    ni, nj = st.num(i), st.num(j)
    title = f"Dyad {dy.label}: {_link_title(spec, dy.links)}"
    b = KinBlock(title)

    def rot_owner(l: str) -> str:
        return owns[l]

    # ---- positions
    conds: list = []
    for link, (pa, ra, ja), (pb, rb, jb) in ((i, (j0.point, r0, j0), (j1.point, r1, j1)),
                                             (j, (j2.point, r2, j2), (j1.point, r1, j1))):
        if ja.type == "R" and jb.type == "R":
            conds.append(R(rf"|\mathbf{{r}}_{{{Point(pa).tex()} {Point(pb).tex()}}}| = "
                           rf"{fmt(float(np.hypot(*(rb - ra))))}\ \mathrm{{m}}",
                           f"|bold(r)_({Point(pa).typ()} {Point(pb).typ()})| = "
                           f"{fmt(float(np.hypot(*(rb - ra))))} \"m\""))
    for jt in (j0, j1, j2):
        if jt.type == "T":
            d = _delta(st, jt)
            conds.append(R(Point(jt.point).tex() + r"\ \text{on the line of}\ " +
                           Point(jt.name).tex() + r"\ \text{along}\ " + delta_sym(jt.name).tex()
                           + " = " + _vec_tex(d),
                           Point(jt.point).typ() + ' "on the line of" ' + Point(jt.name).typ()
                           + ' "along" ' + delta_sym(jt.name).typ() + " = " + _vec_typ(d)))
    text = ["Positions: the dyad closes with "]
    for c in conds:
        text += [c, ", "]
    text[-1] = " (on the branch followed from the assembly):"
    b.text(text)
    pos = [Equation([Expr().add(1, theta(st.num(l))),
                     Expr().add(1 if st.th(l) >= -1e-15 else -1,
                                Num(abs(math.degrees((st.th(l) + math.pi) % (2 * math.pi)
                                                     - math.pi))), DEG_)])
           for l in (i, j)]
    seen = known if known is not None else set()
    for jt, r in ((j0, r0), (j1, r1), (j2, r2)):
        if jt.point in seen:
            continue
        seen.add(jt.point)
        pos.append(_found(point_vec("r", jt.point), vec_expr(r, M_),
                          vec_expr(r, M_, exact) if exact is not None else None))
    b.found(pos)

    # ---- velocities and accelerations: the interior point through link i and through j
    for what in ("v", "a"):
        left, right = _Side(), _Side()
        for side, link, jt, kl, r_from in ((left, i, j0, k0, r0), (right, j, j2, k2, r2)):
            _, vk, ak = st.at(kl, r_from) if kl != GROUND else (r_from, np.zeros(2), np.zeros(2))
            pnt = jt.point if jt.type == "R" else f"{jt.point}{st.num(kl)}"
            side.known([point_vec(what, pnt)], vk if what == "v" else ak,
                       always_zero=kl == GROUND)
            if jt.type == "T":
                _slider_terms(st, side, jt, kl, link, what)
            d = r1 - r_from
            if _zero(d):
                continue
            owner = rot_owner(link)
            n_own = st.num(owner) if owner != GROUND else 0
            kxd = np.array([-d[1], d[0]])
            # omega k x r (velocities) or alpha k x r - omega^2 r (accelerations)
            atom, rate = (omega(n_own), st.w) if what == "v" else (alpha(n_own), st.al)
            cross_term = [atom, K_, Op("times"), RVec(jt.point, j1.point)]
            if owner in (i, j):
                side.unknown(cross_term, kxd, atom)
                b.values[atom.py()] = rate(owner)
            elif owner != GROUND:
                side.known(cross_term, rate(owner) * kxd)
            if what != "v" and owner != GROUND:
                w = st.w(owner)
                side.known_neg([Raw(rf"\omega_{{{n_own}}}^2", f"omega_{n_own}^2",
                                    f"omega{n_own}^2"), RVec(jt.point, j1.point)], w * w * d)
        if j1.type == "T":
            _slider_terms(st, left, j1, i, j, what)
        for jt in (j0, j1, j2):
            if jt.type == "T":
                v_rel, a_rel, _, _ = _rel(st, jt)
                vs, as_ = _rel_syms(st, jt)
                b.values[vs.py()] = v_rel
                b.values[as_.py()] = a_rel
        head = "Velocities" if what == "v" else "Accelerations"
        lead = [f"{head}: the point {j1.point} reached through link {ni} and through link "
                f"{nj}"]
        for jt in (j0, j1, j2):
            if jt.type == "T":
                vs, as_ = _rel_syms(st, jt)
                lead += ["; ", vs if what == "v" else as_,
                         f" is link {st.num(jt.slider)}'s "
                         f"{'speed' if what == 'v' else 'acceleration'} relative to link "
                         f"{st.num(jt.guide)} along ", delta_sym(jt.name)]
        b.eq(lead + [","], Equation([left.sym, right.sym]))
        b.eq(["projected on x and y,"], [Equation([left.component(0), right.component(0)]),
                                         Equation([left.component(1), right.component(1)])])
        found = []
        for name in rates:
            if name in (i, j):
                atom = omega(st.num(name)) if what == "v" else alpha(st.num(name))
                val = st.w(name) if what == "v" else st.al(name)
                unit = RADS_ if what == "v" else RADS2_
            else:
                jt = spec.joint(name)
                vs, as_ = _rel_syms(st, jt)
                v_rel, a_rel, _, _ = _rel(st, jt)
                atom, val = (vs, v_rel) if what == "v" else (as_, a_rel)
                unit = MS_ if what == "v" else MS2_
            found.append(_found(atom, scalar(val, unit),
                                scalar(val, unit, exact) if exact is not None else None))
        extra = [l for l in (i, j) if l not in rates and rot_owner(l) != l and
                 rot_owner(l) != GROUND]
        for l in extra:
            own = rot_owner(l)
            atom = omega(st.num(l)) if what == "v" else alpha(st.num(l))
            found.append(Equation([Expr().add(1, atom), Expr().add(
                1, omega(st.num(own)) if what == "v" else alpha(st.num(own)))]))
        b.found(found)
    # the dyad's links' other joints (where the next groups attach), from a joint of the link
    for link in (i, j):
        pts = spec.link(link).points
        base = next((jt for jt in (j0, j1, j2) if link in jt.links and jt.type == "R"
                     and jt.point in pts), None)
        if base is None:
            continue
        for jt in spec.joints:
            if link in jt.links and jt not in (j0, j1, j2) and jt.point in pts and \
                    jt.point != base.point:
                for e in rigid_lines(st, link, base.point, st.joint_r(base), jt.point,
                                     st.joint_r(jt), exact):
                    b.eq(None, e)
    return b


def _slider_terms(st: State, side: _Side, jt, frm: str, to: str, what: str) -> None:
    """Across slider ``jt`` from link ``frm`` to ``to``: + sigma v_rel Delta (velocities),
    + sigma (a_rel Delta + 2 omega_g k x v_rel Delta) (accelerations)."""
    sigma = _sigma(jt, frm, to)
    v_rel, a_rel, d, wg = _rel(st, jt)
    vs, as_ = _rel_syms(st, jt)
    delta = delta_sym(jt.name)
    if what == "v":
        side.unknown([vs, delta], d, vs, sigma)
        return
    side.unknown([as_, delta], d, as_, sigma)
    if jt.guide != GROUND:
        ng = st.num(jt.guide)
        cor = 2 * wg * v_rel * np.array([-d[1], d[0]])
        atoms = [Num(2), omega(ng), K_, Op("times"), vs, delta]
        if sigma > 0:
            side.known(atoms, cor)
        else:
            side.known_neg(atoms, cor)


def _vec_tex(d) -> str:
    return _render(vec_expr(d), "tex")


def _vec_typ(d) -> str:
    return _render(vec_expr(d), "typ")


def _render(e, how):
    from .expr import math as render
    return render(e, how)


def group_block(st: State, group) -> KinBlock:
    """A group with no closed form: what was found, listed."""
    spec = st.spec
    b = KinBlock(f"{group.class_name[0].upper()}{group.class_name[1:]} {group.label}: "
                 f"{_link_title(spec, group.links)}")
    b.text(["These links are solved together, numerically: positions by Newton-Raphson on "
              "the joint constraints, then velocities and accelerations from the "
              "differentiated constraints (one linear system each). They give:"])
    rows = []
    for l in group.links:
        n = st.num(l)
        rows.append([Equation([Expr().add(1, theta(n)),
                               Expr().add(1, Num(math.degrees(st.th(l))), DEG_)]),
                     Equation([Expr().add(1, omega(n)), scalar(st.w(l), RADS_)]),
                     Equation([Expr().add(1, alpha(n)), scalar(st.al(l), RADS2_)])])
    for row in rows:
        b.found(row)
    seen = set()
    for jt in group.joints:
        if jt.point in seen:
            continue
        seen.add(jt.point)
        owner = jt.links[1] if jt.links[1] != GROUND else jt.links[0]
        r, v, a = st.at(owner, st.joint_r(jt))
        b.found([Equation([Expr().add(1, point_vec("r", jt.point)), vec_expr(r, M_)]),
                         Equation([Expr().add(1, point_vec("v", jt.point)), vec_expr(v, MS_)]),
                         Equation([Expr().add(1, point_vec("a", jt.point)),
                                   vec_expr(a, MS2_)])])
    return b


def mass_centres(st: State, exact=None) -> KinBlock:
    spec = st.spec
    b = KinBlock("Mass centres")
    b.text(["Each centre of mass from a joint of its link:"])
    for link in spec.links:
        base = None
        for j in spec.joints:
            if link.name in j.links and j.point in link.points:
                base = j
                break
        n = link.number
        cname = f"C{n}"
        rc = st.kin.com(link.name).r[st.k]
        if base is None:
            continue
        rp = st.joint_r(base)
        if np.allclose(np.asarray(link.com, float), np.asarray(link.points[base.point], float),
                       atol=1e-12):
            b.text([Point(cname), " is at ", Point(base.point), "."])
            continue
        for e in rigid_lines(st, link.name, base.point, rp, cname, rc, exact):
            b.eq(None, e)
    return b


def derive(analysis, k: int, exact=None) -> list[KinBlock]:
    """The derivation at angle index ``k``: groups from the driver outward, then the mass
    centres."""
    st = State(analysis, k)
    spec = st.spec
    blocks = []
    known = set(spec.ground)              # points whose position is given or already found
    for group in analysis.mechanism.groups:
        if group.driver is not None and len(group.links) == 1 and spec.driver.crank:
            blocks.append(crank_block(st, group, exact))
        else:
            block = dyad_block(st, group, exact, known) if group.dyad is not None else None
            blocks.append(block if block is not None else group_block(st, group))
        known.update(j.point for j in group.joints)
        known.update(p for l in group.links for p in spec.link(l).points)
    blocks.append(mass_centres(st, exact))
    return blocks
