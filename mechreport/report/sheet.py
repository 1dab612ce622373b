"""Worked solution sheets (issue 5): every method's equations at each reference angle, in
symbols, then with numbers, then the results, as the textbook (4.6, 4.7) writes them.

One sheet model is built here from the ``Equation``/``Term`` objects each method solved
(``ForceResult.steps``), so a change in a method changes its sheet; Jinja2 renders it to
Markdown (GitHub math) and Typst (PDF) through ``templates/solution.md.j2`` and
``templates/solution.typ.j2``. Every number in a "with numbers" line is read from the Term
arrays at the angle's index: a known force's projection or moment is ``Term.const``; an unknown
force's coefficients ``Term.coeffs`` (shown as the lever components of r x F or the direction
components of F . Delta); unknowns solved by an earlier step are substituted with their values.
"""
from __future__ import annotations

import re
from dataclasses import dataclass, field
from pathlib import Path

import jinja2
import numpy as np

from .markdown import md_inline
from .templating import loader
from ..forces import METHODS
from ..forces.context import DRIVER_TORQUE
from ..forces.equations import Equation as FEquation
from ..forces.equations import Step, Term
from ..spec import GROUND
from .files import atomic_write_text
from .pdf import compile_typst, typst_escape
from .sheet_math import (Equation, Expr, Num, Op, Paren, Point, Raw, RVec, Sym, fmt, math)


N_ = Raw(r"\mathrm{N}", '"N"', "N", "")
NM_ = Raw(r"\mathrm{N\,m}", '"N·m"', "N·m", "")
M_ = Raw(r"\mathrm{m}", '"m"', "m", "")
I_ = Sym("i", bold=True)
J_ = Sym("j", bold=True)

METHOD_INTRO = {
    "newton_euler": "For every moving link, Newton's and Euler's equations of motion "
                    "m a_C = sum F and I_C alpha = sum M_C (moments about the link's own centre "
                    "of mass), with the joint reactions and the driver torque M as unknowns; all "
                    "links' equations are solved together.",
    "dalembert": "The inertia force Fin = -m a_C (at the centre of mass) and the inertia couple "
                 "Min = -I_C alpha are added to each link as loads; each link is then in static "
                 "equilibrium: its forces along x and y and its moments about one of its own "
                 "joints sum to zero. All links' equations are solved together.",
    "dyad": "The dyads (groups of two links and three joints) are solved from the last one back "
            "toward the driver, with d'Alembert loads: first the group's outer reactions, then "
            "its interior joint, and the driver link last.",
    "contour": "Each joint is cut in turn; walking the contour from it, a moment equation about "
               "each pin met (or a force projection on the sliding direction of each slider met) "
               "is written for the links left behind, so that the other joints' reactions do not "
               "enter.",
    "power": "Independent check, not in the textbook: ideal joints do no work, so with the "
             "d'Alembert loads the total power vanishes, M omega_1 + sum F . v + sum M omega = 0; "
             "it gives the driver torque without any joint reaction.",
}

T_NOTE = ("The textbook finds the point P (or Q) where a slider's reaction acts, which makes the "
          "equations nonlinear; here the reaction of a sliding joint is the force at the slider's "
          "point plus a couple M about that point (linear unknowns), which is equivalent to the "
          "same force acting at P.")


# ------------------------------------------------------------------------------ the model

@dataclass
class EqModel:
    number: int
    symbolic: Equation
    numeric: Equation
    unknowns: list            # Sym atoms of this step's unknowns that the equation contains
    source: FEquation | None = None


@dataclass
class StepModel:
    number: int
    title: str
    free_body: str
    unknowns: list
    notes: list               # list of (text, math-or-None)
    equations: list
    results: list             # list of (Equation, exact Equation list or None)
    points: list = field(default_factory=list)   # T-joint application points (text, Equation)


@dataclass
class MethodModel:
    name: str
    title: str
    section: str
    intro: str
    steps: list
    torque: Equation
    torque_exact: Equation | None = None
    check: list = field(default_factory=list)   # power: (text, Equation)


@dataclass
class AngleModel:
    angle: float
    skipped: str | None = None
    phi: str = ""
    links: list = field(default_factory=list)     # rows of strings
    points: list = field(default_factory=list)
    actions: list = field(default_factory=list)
    loads: list = field(default_factory=list)
    methods: list = field(default_factory=list)
    shown: list = field(default_factory=list)     # results in the report's units (rows)


@dataclass
class SheetModel:
    name: str
    file: str
    description: str
    exact: bool
    link_names: list
    joints: list
    conventions: list
    t_note: str
    angles: list
    units: str = ""               # the report's display units, when they are not SI


# ------------------------------------------------------------------------------ symbols

def _split_symbol(symbol: str) -> tuple[str, str]:
    if symbol[:1] in "FGM" and not symbol.startswith(("m", "I")):
        return symbol[0], symbol[1:]
    return symbol, ""


def vec_sym(symbol: str) -> Sym:
    base, sub = _split_symbol(symbol)
    return Sym(base, sub, bold=True, py_name=symbol)


def comp_sym(symbol: str, axis: str) -> Sym:
    base, sub = _split_symbol(symbol)
    if sub and not sub[-1].isdigit():
        sub = sub + "," + axis
    else:
        sub = sub + axis
    return Sym(base, sub, py_name=symbol.replace(",", "_") + axis)


def scalar_sym(symbol: str) -> Sym:
    base, sub = _split_symbol(symbol)
    return Sym(base, sub, py_name=symbol.replace(",", "_"))


def lhs_sym(action, ctx, axis: str | None) -> Raw:
    """Newton-Euler left-hand sides, from the action's link and kind: m3 aC3 (a force, with
    its axis) or IC3 alpha3 (a couple)."""
    n = ctx.num(action.link)
    if action.kind == "force":
        ax = axis or ""
        return Raw(f"m_{{{n}}}\\,a_{{C_{{{n}}}{ax}}}", f"m_{n} a_(C_{n} {ax})",
                   f"m{n} aC{n}{ax}", f"m{n}_aC{n}{ax}")
    return Raw(f"I_{{C_{{{n}}}}}\\,\\alpha_{{{n}}}", f"I_(C_{n}) alpha_{n}",
               f"IC{n} alpha{n}", f"IC{n}_alpha{n}")


def point_vec(base: str, point: str) -> Raw:
    """Bold vector with a point subscript: v_{C_2}."""
    p = Point(point)
    return Raw(rf"\mathbf{{{base}}}_{{{p.tex()}}}", f"bold({base})_({p.typ()})",
               f"{base}_{point}")


def delta_sym(joint: str) -> Raw:
    p = Point(joint)
    return Raw(r"\boldsymbol{\Delta}_{" + p.tex() + "}", f"bold(Delta)_({p.typ()})",
               f"Delta_{joint}")


def axis_atom(axis: str):
    if axis == "x":
        return I_
    if axis == "y":
        return J_
    return delta_sym(axis[len("Delta_"):] if axis.startswith("Delta_") else axis)


def body_sup(nums) -> str:
    return "(" + "&".join(str(n) for n in nums) + ")"


def sum_label(kind: str, nums, about: str | None = None, axis: str | None = None) -> Raw:
    tag = body_sup(nums)
    tex_tag = tag.replace("&", r"\&")
    typ_tag = "(" + " \\& ".join(str(n) for n in nums) + ")"
    if kind == "moment":
        p = Point(about)
        return Raw(rf"\sum \mathbf{{M}}_{{{p.tex()}}}^{{{tex_tag}}}",
                   f"sum bold(M)_({p.typ()})^({typ_tag})", f"sum M_{about}^{tag}")
    ax = axis_atom(axis)
    return Raw(rf"\sum \mathbf{{F}}^{{{tex_tag}}} \cdot {ax.tex()}",
               f"sum bold(F)^({typ_tag}) dot {ax.typ()}", f"sum F^{tag} . {ax.plain()}")


class Names:
    """Textbook names of the unknowns: joint.B.fx -> F12x, joint.C_T.moment -> M03, M."""

    def __init__(self, spec):
        self.spec = spec
        # the driver's effort: the torque M (R driver) or the actuator's push Fd (T driver)
        self.sym: dict[str, Sym] = {DRIVER_TORQUE: Sym("M", py_name="M"),
                                    "driver.force": Sym("F", "d", py_name="Fd")}
        self.vec: dict[str, str] = {}
        for j in spec.joints:
            force = spec.symbol(*j.links)
            self.vec[j.name] = force
            self.sym[f"joint.{j.name}.fx"] = comp_sym(force, "x")
            self.sym[f"joint.{j.name}.fy"] = comp_sym(force, "y")
            if j.type == "T":
                self.sym[f"joint.{j.name}.moment"] = scalar_sym(spec.symbol(*j.links, "M"))

    def __getitem__(self, unknown: str) -> Sym:
        return self.sym[unknown]


# ------------------------------------------------------------------------------ equations

def _tol(eq: FEquation, k: int | slice) -> float:
    scale = 0.0
    for t in eq.terms:
        if t.coeffs.size:
            scale = max(scale, float(np.max(np.abs(t.coeffs[k]))))
        scale = max(scale, float(np.max(np.abs(t.const[k]))))
    return 1e-12 * max(scale, 1.0)


def _structurally_zero(t: Term, tol: float) -> bool:
    """A force term that vanishes at every analysed angle (gravity . i, a force through the
    moment centre): left out of the symbolic line too. Couples and left sides are kept."""
    if t.side == "lhs" or t.action.kind != "force":
        return False
    if not t.action.unknowns and t.direction is None:
        return False            # moments and powers of known forces stay (r_AC1 x Fin1)
    if t.action.unknowns:
        return bool(np.all(np.abs(t.coeffs) <= tol))
    return bool(np.all(np.abs(t.const) <= tol))


def _symbolic(eq: FEquation, ctx, names: Names) -> Equation:
    tol = _tol(eq, slice(None))
    terms = [t for t in eq.terms if not _structurally_zero(t, tol)]
    lhs = [t for t in terms if t.side == "lhs"]
    rhs = [t for t in terms if t.side == "rhs"]
    nums = [ctx.num(b) for b in eq.bodies]
    if eq.kind == "power":
        e = Expr()
        for t in rhs:
            a = t.action
            if a.category == "driver":
                e.add(1, scalar_sym(a.symbol), Sym("omega", str(ctx.num(a.link))))
            elif a.kind == "force":
                e.add(1, vec_sym(a.symbol), Op("dot"), point_vec("v", a.at_name or ""))
            else:
                e.add(1, scalar_sym(a.symbol), Sym("omega", str(ctx.num(a.link))))
        label = Raw(r"\sum P", "sum P", "sum P")
        return Equation([Expr().add(1, label), e, Expr()])
    if eq.kind == "moment":
        e = Expr()
        groups: dict[str, list[Term]] = {}
        order: list = []
        for t in rhs:
            a = t.action
            if a.kind == "couple":
                order.append(("c", t))
            elif a.unknowns:
                order.append(("u", t))
            else:
                if a.at_name not in groups:
                    groups[a.at_name] = []
                    order.append(("g", a.at_name))
                groups[a.at_name].append(t)
        for kind, item in order:
            if kind == "c":
                e.add(1, vec_sym(item.action.symbol))
            elif kind == "u":
                e.add(1, RVec(eq.about, item.action.at_name), Op("times"),
                      vec_sym(item.action.symbol))
            else:
                ts = groups[item]
                inner = Expr()
                for t in ts:
                    inner.add(1, vec_sym(t.action.symbol))
                f = Paren(inner) if len(ts) > 1 else vec_sym(ts[0].action.symbol)
                e.add(1, RVec(eq.about, item), Op("times"), f)
        if lhs:
            left = Expr()
            for t in lhs:
                left.add(1, lhs_sym(t.action, ctx, None))
            return Equation([left, e])
        return Equation([Expr().add(1, sum_label("moment", nums, about=eq.about)), e, Expr()])
    # force projections and constraints
    axis = eq.axis or "x"
    if axis in ("x", "y"):
        e = Expr()
        for t in rhs:
            e.add(1, comp_sym(t.action.symbol, axis))
        if lhs:
            left = Expr()
            for t in lhs:
                left.add(1, lhs_sym(t.action, ctx, axis))
            return Equation([left, e])
        if eq.kind == "constraint":
            return Equation([e, Expr()])
        return Equation([Expr().add(1, sum_label("force", nums, axis=axis)), e, Expr()])
    inner = Expr()
    for t in rhs:
        inner.add(1, vec_sym(t.action.symbol))
    f = Paren(inner) if len(rhs) > 1 else vec_sym(rhs[0].action.symbol)
    e = Expr().add(1, f, Op("dot"), axis_atom(axis))
    if eq.kind == "constraint":
        return Equation([e, Expr()])
    return Equation([Expr().add(1, sum_label("force", nums, axis=axis)), e, Expr()])


def _signed(x: float) -> tuple[int, float]:
    return (-1, -x) if (x < 0 and fmt(x) != "0") else (1, abs(x) if fmt(x) == "0" else x)


def vec_expr(x: float, y: float, unit=None) -> Expr:
    """x i + y j with zero components left out (0 if both vanish)."""
    e = Expr()
    for v, u in ((x, I_), (y, J_)):
        if fmt(v) == "0":
            continue
        sg, mag = _signed(v)
        e.add(sg, u) if fmt(mag) == "1" else e.add(sg, Num(mag), u)
    if not e.terms:
        e.add(1, Num(0.0))
    return _with_unit(e, unit) if unit is not None else e


def scalar_expr(x: float, unit=None) -> Expr:
    sg, mag = _signed(x)
    e = Expr().add(sg, Num(mag))
    return _with_unit(e, unit) if unit is not None else e


def unit_of(unknown: str):
    return N_ if unknown.endswith((".fx", ".fy")) else NM_


def _numeric(eq: FEquation, k: int, step_unknowns: set, known: dict, names: Names, ctx
             ) -> tuple[Equation, list]:
    """The equation with the numbers at index ``k``; terms zero at this angle are left out."""
    tol = _tol(eq, k)
    sides = {"lhs": Expr(), "rhs": Expr()}
    used: list[str] = []
    for t in eq.terms:
        a = t.action
        e = sides[t.side]
        if not a.unknowns:
            c = float(t.const[k])
            if abs(c) <= tol:
                continue
            if t.side == "lhs":
                s = ctx.links[a.link]
                m = s.mass if a.symbol.startswith("m") else s.inertia
                if m:
                    e.add(1, Num(m, True), Num(c / m, True))
                    continue
            sg, mag = _signed(c)
            e.add(sg, Num(mag))
            continue
        here = [u in step_unknowns for u in a.unknowns]

        def use(u):
            if u in step_unknowns and u not in used:
                used.append(u)
        co = t.coeffs[k] * a.sign          # coefficients on the action's own components
        if a.kind == "couple" or len(a.unknowns) == 1:   # one scalar unknown: M, M03, Fd
            c = float(co[0])
            if abs(c) <= tol:
                continue
            u = a.unknowns[0]
            use(u)
            sym = scalar_sym(a.symbol)
            if t.rate is not None:          # power: omega_1 M
                if u in step_unknowns:
                    e.add(1, Num(c, True), sym)
                else:
                    e.add(1, Num(c, True), Num(a.sign * known[u][k], True))
                continue
            if u in step_unknowns:
                if abs(c - 1) <= tol:
                    e.add(1, sym)
                elif abs(c + 1) <= tol:
                    e.add(-1, sym)
                else:
                    e.add(*_signed(c)[:1], Num(abs(c)), sym)
            else:
                e.add(1, Num(c, True), Num(a.sign * known[u][k], True))
            continue
        comps = [comp_sym(a.symbol, "x"), comp_sym(a.symbol, "y")]
        vals = [None, None] if all(here) else [a.sign * known[u][k] for u in a.unknowns[:2]]
        if t.lever is not None:             # moment of an unknown force: (lx) Fy - (ly) Fx
            lx, ly = float(co[1]), float(-co[0])
            for sign, lev, j in ((1, lx, 1), (-1, ly, 0)):
                if abs(lev) <= tol:
                    continue
                if vals[j] is None:
                    use(a.unknowns[j])
                    e.add(sign, Num(lev, True), comps[j])
                else:
                    e.add(sign, Num(lev, True), Num(vals[j], True))
            continue
        for j in (0, 1):                     # projection: d_x Fx + d_y Fy
            d = float(co[j])
            if abs(d) <= tol:
                continue
            if vals[j] is None:
                use(a.unknowns[j])
                if abs(abs(d) - 1) <= tol:
                    e.add(np.sign(d), comps[j])
                else:
                    e.add(np.sign(d), Num(abs(d)), comps[j])
            elif abs(abs(d) - 1) <= tol:
                e.add(*_signed(d * vals[j])[:1], Num(abs(d * vals[j])))
            else:
                e.add(1, Num(d, True), Num(vals[j], True))
    if any(t.side == "lhs" for t in eq.terms):
        return Equation([sides["lhs"], sides["rhs"]]), used
    return Equation([sides["rhs"], Expr()]), used


# ------------------------------------------------------------------------------ results

class Exact:
    """Closed forms of result values in the textbook's radicals (sympy, exact mode only)."""

    def __init__(self):
        import sympy
        self.sp = sympy
        self.radicals = [sympy.sqrt(2), sympy.sqrt(3)]
        self.cache: dict[float, object] = {}

    def __call__(self, x: float):
        """A short closed form a + b sqrt(2) or a + b sqrt(3) (a, b rationals with small
        denominators) that matches ``x`` to 1e-12 relative; None otherwise or for integers."""
        sp = self.sp
        x = float(x)
        if not np.isfinite(x) or abs(x) < 1e-12:
            return None
        if x in self.cache:
            return self.cache[x]
        self.cache[x] = None
        for tol in (1e-10 * abs(x),):
            try:
                e = sp.expand(sp.nsimplify(x, self.radicals, tolerance=tol))
            except Exception:       # nsimplify gives up in several ways
                continue
            if self._simple(e) and abs(float(e) - x) <= 1e-12 * abs(x):
                self.cache[x] = None if (e.is_Rational and e.q == 1) else e
        return self.cache[x]

    def _simple(self, e) -> bool:
        sp = self.sp
        if e.free_symbols:
            return False
        terms = sp.Add.make_args(e)
        if len(terms) > 2:
            return False
        for t in terms:
            c, rest = t.as_coeff_Mul()
            if rest != 1 and rest not in self.radicals:
                return False
            if not c.is_Rational or c.q > 12 or abs(c.p) > 100000:
                return False
        return True

    def atom(self, e) -> Raw:
        """a + b sqrt(n) with the rational part first, as the textbook writes 3 + 105 sqrt2."""
        sp = self.sp
        parts = []
        for t in sp.Add.make_args(e):
            c, rest = t.as_coeff_Mul()
            n = None if rest == 1 else int(rest.args[0])
            parts.append((sp.Rational(c), n))
        parts.sort(key=lambda p: p[1] is not None)
        tex = typ = plain = ""
        for i, (c, n) in enumerate(parts):
            neg = c < 0
            c = abs(c)
            p, q = int(c.p), int(c.q)
            num_t = (("" if p == 1 else f"{p}") + rf"\sqrt{{{n}}}") if n else f"{p}"
            num_y = (("" if p == 1 else f"{p} ") + f"sqrt({n})") if n else f"{p}"
            num_p = (("" if p == 1 else f"{p} ") + f"sqrt({n})") if n else f"{p}"
            bt = rf"\frac{{{num_t}}}{{{q}}}" if q != 1 else num_t
            by = f"({num_y})/{q}" if q != 1 else num_y
            bp = f"{num_p}/{q}" if q != 1 else num_p
            op = "-" if neg else "+"
            if i == 0:
                pre = "-" if neg else ""
                tex, typ, plain = pre + bt, pre + by, pre + bp
            else:
                tex += f" {op} {bt}"
                typ += f" {op} {by}"
                plain += f" {op} {bp}"
        return Raw(tex, typ, plain, repr(float(e)))


def _result_lines(unknowns, values: dict, k: int, names: Names, ctx, result, exact):
    """Solved unknowns grouped by joint: F12 = Fx i + Fy j N (|F12| = ...), M03, M."""
    lines = []
    points = []
    done = set()
    for u in unknowns:
        if u in done:
            continue
        if u.startswith("joint.") and u.endswith((".fx", ".fy")):
            jn = u[len("joint."):].rsplit(".", 1)[0]
            fx, fy = values[f"joint.{jn}.fx"][k], values[f"joint.{jn}.fy"][k]
            done.update({f"joint.{jn}.fx", f"joint.{jn}.fy"})
            v = vec_sym(names.vec[jn])
            eq = Equation([Expr().add(1, v), vec_expr(fx, fy, N_)])
            ex = None
            if exact:
                parts = []
                for comp, val in (("x", fx), ("y", fy)):
                    c = exact(val)
                    if c is not None:
                        parts.append(Equation([Expr().add(1, comp_sym(names.vec[jn], comp)),
                                               Expr().add(1, exact.atom(c))]))
                ex = parts or None
            lines.append((eq, ex))
        else:
            done.add(u)
            val = values[u][k]
            unit = NM_
            eq = Equation([Expr().add(1, names[u]), scalar_expr(val, unit)])
            ex = None
            if exact:
                c = exact(val)
                if c is not None:
                    ex = [Equation([Expr().add(1, names[u]), Expr().add(1, exact.atom(c))])]
            lines.append((eq, ex))
            if u.endswith(".moment") and result is not None:
                jn = u[len("joint."):].rsplit(".", 1)[0]
                r = result.reactions.get(jn)
                if r is not None and r.px is not None:
                    if np.isfinite(r.px[k]):
                        pe = Equation([Expr().add(1, Raw(r"\mathbf{r}_{P}", "bold(r)_P",
                                                         "r_P")),
                                       vec_expr(r.px[k], r.py[k], M_)])
                        points.append((jn, vec_sym(names.vec[jn]), pe))
                    else:
                        points.append((jn, vec_sym(names.vec[jn]), None))
    return lines, points


def _with_unit(e: Expr, unit) -> Expr:
    if e.terms:
        sign, factors = e.terms[-1]
        e.terms[-1] = (sign, factors + [unit])
    return e


# ------------------------------------------------------------------------------ builders

def _free_body(ctx, bodies) -> str:
    links = [ctx.spec.link(b) for b in bodies]
    if len(links) == 1:
        return f"link {links[0].number} ({links[0].name})"
    return "links " + " & ".join(str(l.number) for l in links) + \
        " (" + ", ".join(l.name for l in links) + ")"


def _step_model(number: int, step: Step, k: int, known: dict, origin: dict, names: Names,
                ctx, result, eq_counter: list, exact) -> StepModel:
    step_unknowns = set(step.unknowns)
    eqs = []
    for eq in step.equations:
        eq_counter[0] += 1
        numeric, used = _numeric(eq, k, step_unknowns, known, names, ctx)
        eqs.append(EqModel(eq_counter[0], _symbolic(eq, ctx, names), numeric,
                           [names[u] for u in step.unknowns if u in used], eq))
    notes = []
    pairs = []
    # action-reaction pairs used with the second link's sign, and earlier results
    seen = set()
    earlier: dict[int, list] = {}
    for eq in step.equations:
        for t in eq.terms:
            a = t.action
            if not a.unknowns or a.symbol in seen:
                continue
            if a.sign < 0 and a.category == "reaction":
                jn = a.unknowns[0].split(".")[1]
                seen.add(a.symbol)
                pairs.append((Equation([Expr().add(1, vec_sym(a.symbol)),
                                            Expr().add(-1, vec_sym(
                                                names.vec[jn] if a.kind == "force"
                                                else "M" + names.vec[jn][1:]))])))
            for u in a.unknowns:
                if u not in step_unknowns and u in origin:
                    earlier.setdefault(origin[u], [])
                    if u not in earlier[origin[u]]:
                        earlier[origin[u]].append(u)
    if pairs:
        notes.append(("action and reaction:", pairs))
    for s, us in sorted(earlier.items()):
        vals = [Equation([Expr().add(1, names[u]), scalar_expr(known[u][k], unit_of(u))])
                for u in us]
        notes.append((f"known from step {s}:", vals))
    deltas = {}
    for eq in step.equations:
        if eq.axis and eq.axis.startswith("Delta_"):
            d = next((t.direction for t in eq.terms if t.direction is not None), None)
            if d is not None:
                deltas[eq.axis] = d[k]
    for ax, d in deltas.items():
        notes.append(("sliding direction (unit vector):",
                      Equation([Expr().add(1, axis_atom(ax)), vec_expr(d[0], d[1])])))
    values = {u: known[u] for u in step.unknowns}
    results, points = _result_lines(step.unknowns, values, k, names, ctx, result, exact)
    return StepModel(number, step.title, _free_body(ctx, step.bodies),
                     [names[u] for u in step.unknowns], notes, eqs, results, points)


def _method_model(name: str, result, k: int, names: Names, ctx, exact, torques: dict
                  ) -> MethodModel:
    mod = METHODS[name]
    values = result.values()
    origin: dict[str, int] = {}
    steps = []
    counter = [0]
    for i, step in enumerate(result.steps, 1):
        steps.append(_step_model(i, step, k, values, origin, names, ctx, result, counter,
                                 exact))
        for u in step.unknowns:
            origin[u] = i
    m = float(result.driver_torque[k])
    effort = result.driver_quantity
    torque = Equation([Expr().add(1, names[effort]),
                       scalar_expr(m, NM_ if effort == DRIVER_TORQUE else N_)])
    tex = None
    if exact:
        c = exact(m)
        if c is not None:
            tex = Equation([Expr().add(1, names[effort]), Expr().add(1, exact.atom(c))])
    check = []
    if name == "power":
        for other, mo in torques.items():
            diff = m - mo
            if abs(diff) <= 1e-9 * max(1.0, abs(m)):
                diff = 0.0
            check.append((METHODS[other].TITLE, Equation(
                [Expr().add(1, Raw(r"M - M_{\text{" + other.replace("_", r"\_") + "}}",
                                   f'M - M_("{other}")', f"M - M_{other}")),
                 scalar_expr(diff, NM_)])))
    section = mod.SECTION.strip("()")
    if section[:1].isdigit():
        section = "textbook " + section
    return MethodModel(name, mod.TITLE, section, METHOD_INTRO.get(name, ""), steps, torque,
                       tex, check)


def _vec(v) -> str:
    return f"({fmt(v[0])}, {fmt(v[1])})"


def _angle_model(analysis, angle: float, names: Names, exact, display=None) -> AngleModel:
    kin, ctx, spec = analysis.kinematics, analysis.context, analysis.spec
    k = kin.index_of(angle)
    if k is None:
        reasons = [f.reason for f in analysis.flags if abs(f.angle - angle) < 1e-9]
        return AngleModel(angle, skipped="; ".join(reasons) or "left out of the analysis")
    am = AngleModel(angle)
    drv = spec.link(spec.driver.link)
    am.phi = (f"{fmt(angle)} deg; the driver link {drv.number} ({drv.name}) turns at "
              f"omega_{drv.number} = {fmt(kin.omega[k, drv.number])} rad/s, "
              f"alpha_{drv.number} = {fmt(kin.alpha[k, drv.number])} rad/s^2")
    for link in spec.links:
        s = ctx.links[link.name]
        am.links.append([str(link.number), link.name, fmt(s.mass), fmt(s.inertia), _vec(s.r[k]),
                         _vec(s.v[k]), _vec(s.a[k]), fmt(s.omega[k]), fmt(s.alpha[k])])
        fin, mi = ctx.inertia_actions(link.name)
        g = ctx.gravity_action(link.name)
        am.actions.append([str(link.number), link.name, _vec(fin.value[k]), fmt(mi.value[k]),
                           _vec(g.value[k])])
    seen = set()
    for j in spec.joints:
        if j.point in seen:
            continue
        seen.add(j.point)
        am.points.append([j.point, _vec(ctx.joint_points[j.name][k])])
    elements = {"spring": "spring force k (L - L0) along its line",
                "damper": "damper force c dL/dt along its line",
                "torsion_spring": "torsion spring couple k (theta_rel - a0)"}
    for ld in ctx.loads:
        load = ld.load
        if ld.link == GROUND:            # a spring or damper's frame end acts on the frame
            continue
        link = spec.link(ld.link)
        if ld.force is not None:
            v = kin.named_point(ld.point, ld.link).v[k]
            rule = (f"opposes the velocity of {ld.point}, v = {_vec(v)} m/s"
                    if load.oppose == "velocity" else elements.get(load.kind, "as given"))
            am.loads.append([ld.symbol, f"{link.number} ({link.name})", ld.point or "",
                             f"{_vec(ld.force[k])} N", rule])
        else:
            w = kin.omega[k, link.number]
            rule = (f"opposes the rotation of link {link.number}, omega = {fmt(w)} rad/s"
                    if load.oppose == "rotation" else elements.get(load.kind, "as given"))
            am.loads.append([ld.symbol, f"{link.number} ({link.name})", "",
                             f"{fmt(ld.moment[k])} N·m", rule])
    if display is not None:
        from ..post import reference_method
        ref = analysis.forces[reference_method(analysis.forces)]
        F, M = display.unit("force"), display.unit("moment")
        for j in spec.joints:
            r = ref.reactions.get(j.name)
            if r is None:
                continue
            sym = spec.symbol(*j.links)
            am.shown.append([sym, f"{display.num(r.fx[k], 'force')} {F}",
                             f"{display.num(r.fy[k], 'force')} {F}",
                             f"{display.num(r.f[k], 'force')} {F}",
                             f"{display.num(r.moment[k], 'moment')} {M}"
                             if r.moment is not None else ""])
        am.shown.append(["M (driver)", "", "", "", f"{display.num(ref.driver_torque[k], 'moment')} {M}"])
    torques = {}
    for name in METHODS:
        res = analysis.forces.get(name)
        if res is None:
            continue
        mm = _method_model(name, res, k, names, ctx, exact, torques if name == "power" else {})
        if name != "power":
            torques[name] = float(res.driver_torque[k])
        am.methods.append(mm)
    return am


def build_sheet(analysis, exact: bool = False) -> SheetModel:
    """The sheet model of an analysis (every reference angle, every method)."""
    spec = analysis.spec
    names = Names(spec)
    ex = Exact() if exact else None
    link_names = [(l.number, l.name) for l in spec.links]
    joints = []
    for j in spec.joints:
        a, b = j.links
        joints.append((j.name, j.type, f"{spec.number(a)} ({a}) on {spec.number(b)} ({b})",
                       names.vec[j.name]))
    def R(t, y):
        return Raw(t, y, re.sub(r"[\\{}]|mathbf|boldsymbol", "", t))

    conventions = [
        ["Links are numbered in the spec's order, the ground is 0. ", R(r"\mathbf{F}_{ij}",
         "bold(F)_(i j)"), " is the force of link i on link j (", R(r"\mathbf{F}_{ji} = "
         r"-\mathbf{F}_{ij}", "bold(F)_(j i) = -bold(F)_(i j)"), "); its components ",
         R(r"F_{ijx}, F_{ijy}", "F_(i j x), F_(i j y)"), " are global, along ",
         R(r"\mathbf{i}", "bold(i)"), " and ", R(r"\mathbf{j}", "bold(j)"), "."],
        ["Moments and couples are about the z-axis, counterclockwise positive; ",
         R(r"\mathbf{r}_{PQ} = \mathbf{r}_Q - \mathbf{r}_P", "bold(r)_(P Q) = bold(r)_Q - "
           "bold(r)_P"), ", so the moment about P of a force F applied at Q is ",
         R(r"\mathbf{r}_{PQ} \times \mathbf{F} = (x_Q - x_P) F_y - (y_Q - y_P) F_x",
           "bold(r)_(P Q) times bold(F) = (x_Q - x_P) F_y - (y_Q - y_P) F_x"), "."],
        [R(r"\mathbf{F}_{in\,i} = -m_i \mathbf{a}_{C_i}", 'bold(F)_("in" i) = -m_i bold(a)_(C_i)'),
         " is the inertia force of link i at its centre of mass ", R("C_i", "C_i"), ", ",
         R(r"M_{in\,i} = -I_{C_i} \alpha_i", 'M_("in" i) = -I_(C_i) alpha_i'),
         " its inertia couple, ", R(r"\mathbf{G}_i = m_i \mathbf{g}", "bold(G)_i = m_i bold(g)"),
         " its weight; ", R("M", "M"), " is the driver torque on the driver link."],
        ["Each method states its equations in symbols (the very equation objects the program "
         "solves), then with the numbers at the reference angle (terms that vanish at that "
         "angle are left out; values found in an earlier step are substituted), then the "
         "unknowns found. Numbers have 6 significant digits; SI units (m, kg, s, N, N·m)."],
    ]
    from .model import display_of
    display = display_of(analysis)
    si = (display.length, display.force, display.moment, display.mass) == ("m", "N", "N*m", "kg")
    angles = [_angle_model(analysis, float(a), names, ex, None if si else display)
              for a in spec.at]
    return SheetModel(spec.name, str(spec.file), spec.description.strip(), exact, link_names,
                      joints, conventions, T_NOTE if any(j.type == "T" for j in spec.joints)
                      else "", angles, "" if si else display.describe())


# ------------------------------------------------------------------------------ rendering

def _env() -> jinja2.Environment:
    env = jinja2.Environment(loader=loader(),
                             autoescape=False, trim_blocks=True, lstrip_blocks=True,
                             keep_trailing_newline=True, undefined=jinja2.StrictUndefined)
    env.filters["tex"] = lambda x: math(x, "tex")
    env.filters["typ"] = lambda x: math(x, "typ")
    env.filters["plain"] = lambda x: math(x, "plain")
    env.filters["esc"] = lambda s: typst_escape(str(s))
    env.filters["fmt"] = fmt
    env.filters["mdcell"] = md_inline
    return env


def render_markdown(model: SheetModel) -> str:
    return _env().get_template("solution.md.j2").render(sheet=model)


def render_typst(model: SheetModel) -> str:
    return _env().get_template("solution.typ.j2").render(sheet=model)


def write_sheet(analysis, outdir: Path, exact: bool = False) -> list[Path]:
    """Write ``outdir/solution.md`` and ``outdir/solution.pdf``; returns both paths."""
    outdir = Path(outdir)
    model = build_sheet(analysis, exact)
    md = atomic_write_text(outdir / "solution.md", render_markdown(model))
    pdf = compile_typst(render_typst(model), outdir / "solution.pdf", outdir)
    return [md, pdf]
