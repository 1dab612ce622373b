"""A method's equation objects as a worked solution writes them: in symbols, then with the
numbers of one reference angle.

Every term is read back by :func:`mechreport.forces.builders.read_term` into the products it
is made of (a lever component times a force component, a direction cosine times a
component, a mass times an acceleration ...), so nothing here inverts a coefficient layout.
The printed lines follow the textbook:

- moments as ``r_PQ x F``, known forces at one point grouped, ``r_BC2 x (Fin2 + G2)``, and
  with numbers ``r_x (F_y + ...) - r_y (F_x + ...)``;
- force projections by components, ``F23x + Fin3x + Fext``; on a sliding direction that is
  not i or j, ``(F23 + Fin3 + ...) . Delta``;
- Newton-Euler's left side ``m3 aC3x`` as ``1 · (-1.41421)``, ``IC2 alpha2`` likewise;
- coefficients simplified (``- (-0.35) F01x`` is ``+ 0.35 F01x``, ``1 F`` is ``F``), products
  of two numbers with a centre dot, terms that vanish left out: in symbols those that vanish
  at every analysed angle, with numbers those that vanish at the reference angle;
- a slider's reaction component that its normal constraint sets to zero (F03x when the
  guide is along i) is left out of the other equations.
"""
from __future__ import annotations

import numpy as np

from ...forces.builders import Piece, read_term
from ...forces.equations import Equation as FEquation
from ...forces.equations import Step, Term
from .expr import Equation, Expr, Num, Op, Paren, Point, Raw, RVec, Sym, fmt
from .symbols import (axis_atom, comp_sym, inertia_alpha, mass_accel, omega, point_vec,
                      scalar_sym, sum_label, vec_sym)

RTOL = 1e-12          # a product below this fraction of its equation's largest is round-off

def pieces(t: Term, cache: dict | None = None) -> tuple[Piece, ...]:
    """``read_term(t)``, kept in ``cache`` (by term) while one method's sheet is written."""
    if cache is None:
        return read_term(t)
    hit = cache.get(id(t))
    if hit is None or hit[0] is not t:
        hit = cache[id(t)] = (t, read_term(t))
    return hit[1]


def carries_sign(t: Term) -> bool:
    """A reaction's symbol says its side (F21 = -F12); the driver's M or Fd does not, so
    its sign goes into the printed coefficient."""
    return t.action.category == "reaction"


def axis_of(eq: FEquation, k=slice(None)) -> str | None:
    """``x`` or ``y`` when the equation projects on i or j (a sliding direction counts when
    it is i or j at the angles ``k``), else None."""
    if eq.axis in ("x", "y"):
        return eq.axis
    d = next((t.direction for t in eq.terms if t.direction is not None), None)
    if d is None:
        return None
    d = np.asarray(d)[k]
    for name, axis in (("x", (1.0, 0.0)), ("y", (0.0, 1.0))):
        if np.all(np.abs(d - np.asarray(axis)) <= 1e-12):
            return name
    return None


def zero_by_constraint(step: Step, k=slice(None)) -> set[str]:
    """Unknowns a slider's normal constraint sets to zero at angles ``k``: F . Delta = 0 with
    Delta along i or j has one component, so that component is 0 (textbook: F03 = F03y j)."""
    out = set()
    for eq in step.equations:
        if eq.kind != "constraint" or len(eq.terms) != 1:
            continue
        ps = pieces(eq.terms[0])
        live = [p for p in ps if p.unknown and np.any(np.abs(np.asarray(p.factor)[k]) > 1e-12)]
        if len(live) == 1:
            out.add(live[0].unknown)
    return out


def _scale(eq: FEquation, k, values: dict, cache: dict | None = None) -> float:
    """The largest product in ``eq`` at angles ``k`` (knowns, and unknowns at their values)."""
    s = 0.0
    for t in eq.terms:
        for p in pieces(t, cache):
            f = np.abs(np.asarray(p.factor)[k])
            if p.unknown is None:
                s = max(s, float(np.max(f * np.abs(np.asarray(p.value)[k]), initial=0.0)))
            elif p.unknown in values:
                s = max(s, float(np.max(f * np.abs(values[p.unknown][k]), initial=0.0)))
    return s


def _coef_scale(eq: FEquation, k, cache: dict | None = None) -> float:
    s = 0.0
    for t in eq.terms:
        for p in pieces(t, cache):
            if p.unknown is not None:
                s = max(s, float(np.max(np.abs(np.asarray(p.factor)[k]), initial=0.0)))
    return s


class Translator:
    """Symbolic and numeric lines of the equations of one method at angle index ``k``.

    ``values`` every unknown the method solved (n,); ``zero_all`` / ``zero_k`` the unknowns
    a normal constraint sets to zero at every angle / at ``k``."""

    def __init__(self, spec, values: dict, k: int):
        self.spec, self.values, self.k = spec, values, k
        self.cache: dict = {}

    def pieces(self, t: Term) -> tuple[Piece, ...]:
        return pieces(t, self.cache)

    # ---------------------------------------------------------------- helpers
    def _live(self, eq: FEquation, t: Term, p: Piece, k, zero: set, scale: float,
              cscale: float) -> bool:
        f = np.abs(np.asarray(p.factor)[k])
        if p.unknown is not None:
            if p.unknown in zero:
                return False
            return bool(np.any(f > RTOL * cscale)) and bool(np.any(f > 1e-300))
        v = np.abs(np.asarray(p.value)[k])
        return bool(np.any(f * v > RTOL * scale))

    def _term_live(self, eq, t, k, zero, scale, cscale) -> bool:
        if t.side == "lhs":
            return True
        return any(self._live(eq, t, p, k, zero, scale, cscale) for p in self.pieces(t))

    # ---------------------------------------------------------------- symbols
    def symbolic(self, eq: FEquation, zero: set) -> Equation:
        """The equation in symbols (terms that vanish at every analysed angle left out)."""
        allk = slice(None)
        scale = _scale(eq, allk, self.values, self.cache)
        cscale = _coef_scale(eq, allk, self.cache)
        terms = [t for t in eq.terms if self._term_live(eq, t, allk, zero, scale, cscale)]
        lhs = [t for t in terms if t.side == "lhs"]
        rhs = [t for t in terms if t.side == "rhs"]
        nums = [self.spec.number(b) for b in eq.bodies]
        if eq.kind == "power":
            e = Expr()
            for t in rhs:
                e.add(1, *self._power_symbol(t))
            lead = (Raw(r"\sum \delta W / \delta q", r"sum delta W \/ delta q", "sum dW/dq")
                    if self.spec.driver.at_rest else Raw(r"\sum P", "sum P", "sum P"))
            return Equation([Expr().add(1, lead), e, Expr()])
        if eq.kind == "moment":
            e = Expr()
            for item in self._moment_groups(rhs):
                if isinstance(item, list):            # known forces at one point
                    inner = Expr()
                    for t in item:
                        inner.add(1, vec_sym(t.action.symbol))
                    f = Paren(inner) if len(item) > 1 else vec_sym(item[0].action.symbol)
                    e.add(1, RVec(eq.about, item[0].action.at_name), Op("times"), f)
                elif item.kind == "couple":
                    e.add(1, self._scalar(item))
                else:
                    e.add(1, RVec(eq.about, item.action.at_name), Op("times"),
                          vec_sym(item.action.symbol))
            if lhs:
                return Equation([Expr().add(1, inertia_alpha(self.spec.number(eq.bodies[0]))), e])
            return Equation([Expr().add(1, sum_label("moment", nums, about=eq.about)), e,
                             Expr()])
        axis = axis_of(eq)
        if axis is not None:
            e = Expr()
            for t in rhs:
                if t.action.direction is not None or (t.action.unknowns and
                                                      t.action.kind == "force" and
                                                      len(t.action.unknowns) == 1):
                    e.add(1, comp_sym(t.action.symbol, axis))
                    continue
                comp = 0 if axis == "x" else 1
                if t.action.unknowns and t.action.unknowns[comp] in zero:
                    continue
                e.add(1, comp_sym(t.action.symbol, axis))
            if eq.kind == "constraint":
                return Equation([Expr().add(1, vec_sym(rhs[0].action.symbol), Op("dot"),
                                            axis_atom(eq.axis)), Expr()])
            if lhs:
                return Equation([Expr().add(1, mass_accel(self.spec.number(eq.bodies[0]), axis)),
                                 e])
            label = sum_label("force", nums, axis=axis)
            return Equation([Expr().add(1, label), e, Expr()])
        inner = Expr()
        for t in rhs:
            inner.add(1, vec_sym(t.action.symbol))
        f = Paren(inner) if len(rhs) > 1 else vec_sym(rhs[0].action.symbol)
        e = Expr().add(1, f, Op("dot"), axis_atom(eq.axis))
        if eq.kind == "constraint":
            return Equation([e, Expr()])
        return Equation([Expr().add(1, sum_label("force", nums, axis=eq.axis)), e, Expr()])

    def _scalar(self, t: Term):
        sym = scalar_sym(t.action.symbol)
        return sym

    def _power_symbol(self, t: Term) -> list:
        """A term of the power balance in symbols: an action times its rate; at zero speed
        (virtual work) times its velocity coefficient, the rate per unit rate of the driven
        coordinate (the driver's is 1)."""
        a, spec = t.action, self.spec
        if a.category == "friction":
            return self._friction_power(a)
        if spec.driver.at_rest:
            if a.category == "driver":
                return [scalar_sym(a.symbol)]
            if a.kind == "force":
                p = Point(a.at_name or "")
                return [vec_sym(a.symbol), Op("dot"),
                        Raw(rf"\mathbf{{v}}'_{{{p.tex()}}}", f"bold(v)'_({p.typ()})",
                            f"v'_{a.at_name or ''}")]
            n = self.spec.number(a.link)
            return [scalar_sym(a.symbol), Raw(rf"\omega'_{{{n}}}", f"omega'_({n})", f"omega'_{n}")]
        if a.category == "driver":
            d = spec.driver
            if d.kind == "T":
                rate = Raw(r"\dot{s}", "dot(s)", "s'", "sdot")
            elif d.crank:
                rate = omega(spec.number(d.link))
            else:
                rate = Sym("omega", "rel", py_name="omega_rel")
            return [scalar_sym(a.symbol), rate]
        if a.kind == "force":
            return [vec_sym(a.symbol), Op("dot"), point_vec("v", a.at_name or "")]
        return [scalar_sym(a.symbol), omega(self.spec.number(a.link))]

    def _friction_power(self, a) -> list:
        """A joint's friction in the power balance: its value on the joint's second link j
        times j's rate relative to the first link i, M_fij (omega_j - omega_i) for a couple
        (the frame's omega_0 = 0 left out), F_fij . v_j/i for a force along a slider's line;
        at zero speed the velocity coefficients' (omega', v')."""
        i, j = (self.spec.number(x) for x in friction_links(self.spec, a.symbol))
        prime = "'" if self.spec.driver.at_rest else ""
        if a.kind == "force":
            return [vec_sym(a.symbol), Op("dot"),
                    Raw(rf"\mathbf{{v}}{prime}_{{{j}/{i}}}", f"bold(v){prime}_({j} \\/ {i})",
                        f"v{prime}_{j}/{i}", f"v{j}_{i}")]
        rates = Expr()
        for sign, n in ((1, j), (-1, i)):
            if n != 0:
                rates.add(sign, Raw(rf"\omega{prime}_{{{n}}}", f"omega{prime}_({n})",
                                    f"omega{prime}_{n}", f"omega{n}"))
        if len(rates.terms) == 1 and rates.terms[0][0] > 0:
            return [scalar_sym(a.symbol), *rates.terms[0][1]]
        return [scalar_sym(a.symbol), Paren(rates)]

    @staticmethod
    def _moment_groups(terms: list[Term]) -> list:
        """Terms in order, known forces acting at the same point (at every angle) gathered
        into one list: the book's r_BC2 x (Fin2 + G2). A point's name is preferred to a mass
        centre's (C, not C3, when the slider's centre of mass is at C)."""
        out: list = []
        groups: list[list] = []
        for t in terms:
            a = t.action
            if t.kind == "moment" and not a.unknowns and a.at is not None:
                for g in groups:
                    b = g[0].action
                    if b.at is a.at or (np.shape(b.at) == np.shape(a.at) and
                                        np.allclose(b.at, a.at, rtol=0, atol=1e-12 *
                                                    (1.0 + float(np.max(np.abs(a.at)))))):
                        g.append(t)
                        break
                else:
                    groups.append([t])
                    out.append(groups[-1])
            else:
                out.append(t)
        for g in groups:                      # the name the group is written with first
            g.sort(key=lambda t: _is_centre(t.action.at_name))
        return out

    # ---------------------------------------------------------------- numbers
    def numeric(self, eq: FEquation, step_unknowns: set, zero: set) -> Equation:
        """The equation with the numbers at ``k``: unknowns of this step stay symbols, those
        found earlier are substituted; terms that vanish at ``k`` are left out."""
        k = self.k
        scale = _scale(eq, k, self.values, self.cache)
        cscale = _coef_scale(eq, k, self.cache)
        tol = RTOL * scale
        sides = {"lhs": Expr(), "rhs": Expr()}

        def known(p: Piece, t: Term) -> float:
            if p.unknown is None:
                return float(p.value[k])
            s = p.sign if carries_sign(t) else 1.0
            return float(s * self.values[p.unknown][k])

        def factor(p: Piece, t: Term) -> float:
            f = float(p.factor[k])
            return f if carries_sign(t) or p.unknown is None else f * p.sign

        groups = self._moment_groups(eq.terms) if eq.kind == "moment" else eq.terms
        for item in groups:
            if isinstance(item, list):                 # known forces at one point
                e = sides[item[0].side]
                for idx in (0, 1):                     # r_x (sum F_y), then -r_y (sum F_x)
                    f = float(self.pieces(item[0])[idx].factor[k])
                    vals = [float(self.pieces(t)[idx].value[k]) for t in item]
                    vals = [v for v in vals if abs(f * v) > tol and fmt(v) != "0"]
                    _product_sum(e, f, vals, tol)
                continue
            t = item
            e = sides[t.side]
            if t.kind == "inertia":
                p = self.pieces(t)[0]
                m, a = float(p.factor[k]), float(p.value[k])
                if abs(m * a) > tol and fmt(m * a) != "0":
                    e.add(1, Num(m), Op("mul"), Num(a, paren=a < 0))
                continue
            for p in self.pieces(t):
                if p.unknown is not None and p.unknown in zero:
                    continue
                f = factor(p, t)
                if p.unknown is not None and p.unknown in step_unknowns:
                    if abs(f) <= RTOL * cscale or fmt(f) == "0":
                        continue
                    _product(e, f, self._unknown_symbol(t, p))
                    continue
                v = known(p, t)
                if abs(f * v) <= tol or fmt(f) == "0" or fmt(v) == "0":
                    continue
                _product(e, f, v)
        if any(t.side == "lhs" for t in eq.terms):
            return Equation([sides["lhs"], sides["rhs"]])
        return Equation([sides["rhs"], Expr()])

    @staticmethod
    def _unknown_symbol(t: Term, p: Piece):
        if p.comp in ("x", "y"):
            return comp_sym(t.action.symbol, p.comp)
        return scalar_sym(t.action.symbol)


def friction_links(spec, symbol: str) -> tuple[str, str]:
    """The links (i, j) of the joint whose friction is named ``symbol`` (Mf12, Ff03: of link
    i on link j, the joint's first link on its second)."""
    for fr in spec.friction:
        a, b = spec.joint(fr.joint).links
        for i, j in ((a, b), (b, a)):
            if spec.symbol(i, j, symbol[:2]) == symbol:
                return i, j
    raise KeyError(f"no friction named {symbol}")


def _is_one(x: float) -> bool:
    return fmt(abs(x)) == "1"


def _product(e: Expr, f: float, x) -> None:
    """Add ``f x`` to ``e`` with the signs folded into the operator: ``- 0.35 F12x``,
    ``+ 0.35 · 10``, ``- 100``."""
    if isinstance(x, (int, float, np.floating)):
        sign = np.sign(f) * np.sign(x)
        if _is_one(f):
            e.add(sign, Num(abs(x)))
        else:
            e.add(sign, Num(abs(f)), Op("mul"), Num(abs(x)))
        return
    if _is_one(f):
        e.add(np.sign(f), x)
    else:
        e.add(np.sign(f), Num(abs(f)), x)


def _product_sum(e: Expr, f: float, vals: list[float], tol: float) -> None:
    """``f (v1 + v2 + ...)``: one value folds into a product, several stay in parentheses
    (the book's ``r_x (F_in2y + G_2y)``)."""
    if not vals or abs(f) <= 0 or fmt(f) == "0":
        return
    if len(vals) == 1:
        _product(e, f, vals[0])
        return
    inner = Expr()
    for v in vals:
        inner.add(np.sign(v), Num(abs(v)))
    if _is_one(f):
        e.add(np.sign(f), Paren(inner))
    else:
        e.add(np.sign(f), Num(abs(f)), Paren(inner))


def _is_centre(name: str | None) -> bool:
    """A mass centre's name, C1, C2 ...: another point's name is preferred for a group."""
    return bool(name) and name[0] == "C" and name[1:].isdigit()
