"""The textbook's symbols on a solution sheet: F12 (force of link 1 on link 2), its components
F12x, F12y, Fin2, G2, Min2, M, r_BC, v_C2, omega_1 ... as typeset atoms (see :mod:`.expr`).

Unknown names (``joint.B.fx``, ``joint.C_T.moment``, ``driver.torque``) are looked up in one
table built from the spec (:class:`Names`), never taken apart as text.
"""
from __future__ import annotations

import re

from ...forces.context import DRIVER_TORQUE, reaction_unknowns
from ...quantities import unit_of as quantity_unit
from .expr import Point, Raw, Sym

# units: a thin space before them (Typst's implicit product has none)
N_ = Raw(r"\mathrm{N}", 'thin "N"', "N", "")
NM_ = Raw(r"\mathrm{N\,m}", 'thin "N·m"', "N·m", "")
M_ = Raw(r"\mathrm{m}", 'thin "m"', "m", "")
MS_ = Raw(r"\mathrm{m/s}", 'thin "m/s"', "m/s", "")
MS2_ = Raw(r"\mathrm{m/s^2}", 'thin "m/s"^2', "m/s^2", "")
RADS_ = Raw(r"\mathrm{rad/s}", 'thin "rad/s"', "rad/s", "")
RADS2_ = Raw(r"\mathrm{rad/s^2}", 'thin "rad/s"^2', "rad/s^2", "")
DEG_ = Raw(r"^\circ", "degree", "deg", "")
I_ = Sym("i", bold=True)
J_ = Sym("j", bold=True)
K_ = Sym("k", bold=True)


def R(tex: str, typ: str, plain: str | None = None) -> Raw:
    """An inline piece of math given in both notations."""
    return Raw(tex, typ, plain if plain is not None else
               re.sub(r"[\\{}]|mathbf|boldsymbol|mathrm", "", tex))


def split_symbol(symbol: str) -> tuple[str, str]:
    """``F12`` -> (F, 12), ``Fin2`` -> (F, in2), ``M03`` -> (M, 03); others as they are."""
    if symbol[:1] in "FGM":
        return symbol[0], symbol[1:]
    return symbol, ""


def vec_sym(symbol: str) -> Sym:
    """The bold vector of an action: **F**_12, **F**_in2, **G**_2."""
    base, sub = split_symbol(symbol)
    return Sym(base, sub, bold=True, py_name=symbol)


def comp_sym(symbol: str, axis: str) -> Sym:
    """A component: F_12x; F_3ext,x where the subscript does not end in a digit."""
    base, sub = split_symbol(symbol)
    sub = sub + ("," + axis if sub and not sub[-1].isdigit() else axis)
    return Sym(base, sub, py_name=symbol.replace(",", "_") + axis)


def scalar_sym(symbol: str) -> Sym:
    """A couple or a magnitude: M, M_03, M_in2, F_d."""
    base, sub = split_symbol(symbol)
    return Sym(base, sub, py_name=symbol.replace(",", "_"))


def omega(n: int | str) -> Sym:
    return Sym("omega", str(n), py_name=f"omega{n}")


def alpha(n: int | str) -> Sym:
    return Sym("alpha", str(n), py_name=f"alpha{n}")


def theta(n: int | str) -> Sym:
    return Sym("theta", str(n), py_name=f"theta{n}")


def point_vec(base: str, point: str) -> Raw:
    """A bold vector with a point subscript: **v**_(C_2), **a**_B."""
    p = Point(point)
    return Raw(rf"\mathbf{{{base}}}_{{{p.tex()}}}", f"bold({base})_({p.typ()})",
               f"{base}_{point}")


def delta_sym(joint: str) -> Raw:
    """The unit vector along a slider's line, **Δ**_(C_T)."""
    p = Point(joint)
    return Raw(r"\boldsymbol{\Delta}_{" + p.tex() + "}", f"bold(Delta)_({p.typ()})",
               f"Delta_{joint}")


def axis_atom(axis: str):
    """**i**, **j** or the **Δ** of a named sliding direction (``Delta_<joint>``)."""
    if axis == "x":
        return I_
    if axis == "y":
        return J_
    return delta_sym(axis[len("Delta_"):] if axis.startswith("Delta_") else axis)


def body_tag(nums) -> tuple[str, str, str]:
    """The free body's superscript, (2&3), in TeX, Typst and plain text."""
    plain = "(" + "&".join(str(n) for n in nums) + ")"
    return (plain.replace("&", r"\&"), "(" + " \\& ".join(str(n) for n in nums) + ")", plain)


def sum_label(kind: str, nums, about: str | None = None, axis: str | None = None) -> Raw:
    """ΣM_B^(2) or ΣF^(2&3)·i."""
    tex_tag, typ_tag, tag = body_tag(nums)
    if kind == "moment":
        p = Point(about)
        return Raw(rf"\sum \mathbf{{M}}_{{{p.tex()}}}^{{{tex_tag}}}",
                   f"sum bold(M)_({p.typ()})^({typ_tag})", f"sum M_{about}^{tag}")
    ax = axis_atom(axis)
    return Raw(rf"\sum \mathbf{{F}}^{{{tex_tag}}} \cdot {ax.tex()}",
               f"sum bold(F)^({typ_tag}) dot {ax.typ()}", f"sum F^{tag} . {ax.plain()}")


def mass_accel(n: int, axis: str = "") -> Raw:
    """Newton-Euler's left side of a force equation: m_3 a_(C_3 x)."""
    return Raw(f"m_{{{n}}}\\,a_{{C_{{{n}}}{axis}}}", f"m_{n} a_(C_{n} {axis})",
               f"m{n} aC{n}{axis}", f"m{n}_aC{n}{axis}")


def inertia_alpha(n: int) -> Raw:
    """Newton-Euler's left side of a moment equation: I_(C_3) alpha_3."""
    return Raw(f"I_{{C_{{{n}}}}}\\,\\alpha_{{{n}}}", f"I_(C_{n}) alpha_{n}",
               f"IC{n} alpha{n}", f"IC{n}_alpha{n}")


def unit_atom(unknown: str):
    """The printed unit of an unknown (its SI unit by :func:`mechreport.quantities.unit_of`):
    N for a force component, N·m for a couple or torque."""
    return N_ if quantity_unit(unknown) == "N" else NM_


class Names:
    """The textbook's names of the unknowns, from the spec: joint.B.fx -> F12x,
    joint.C_T.moment -> M03, driver.torque -> M, driver.force -> Fd. ``joint_of`` and
    ``comp_of`` say which joint and which component an unknown is (one table, no parsing)."""

    def __init__(self, spec):
        self.spec = spec
        # the driver's effort: the torque M (R driver) or the actuator's push Fd (T driver)
        self.sym: dict[str, Sym] = {DRIVER_TORQUE: Sym("M", py_name="M"),
                                    "driver.force": Sym("F", "d", py_name="Fd")}
        self.vec: dict[str, str] = {}           # joint -> its force symbol (F12)
        self.couple: dict[str, str] = {}        # T joint -> its couple symbol (M03)
        self.joint_of: dict[str, str] = {}
        self.comp_of: dict[str, str] = {}
        for j in spec.joints:
            force = spec.symbol(*j.links)
            self.vec[j.name] = force
            for u, comp in zip(reaction_unknowns(j), ("x", "y", "moment")):
                self.joint_of[u] = j.name
                self.comp_of[u] = comp
            self.sym[f"joint.{j.name}.fx"] = comp_sym(force, "x")
            self.sym[f"joint.{j.name}.fy"] = comp_sym(force, "y")
            if j.type == "T":
                self.couple[j.name] = spec.symbol(*j.links, "M")
                self.sym[f"joint.{j.name}.moment"] = scalar_sym(self.couple[j.name])

    def __getitem__(self, unknown: str) -> Sym:
        return self.sym[unknown]


_LABEL = re.compile(r"\b([A-Za-z][A-Za-z0-9]*_[A-Za-z0-9]+)\b")


def rich_label(text: str) -> list:
    """Text with joint names such as C_T or B_R typeset as the textbook's C_T (subscript);
    other words with an underscore (a message's ``newton_euler``) stay text."""
    out: list = []
    pos = 0
    for m in _LABEL.finditer(text):
        if Point(m.group(1))._split() is None:
            continue
        if m.start() > pos:
            out.append(text[pos:m.start()])
        out.append(Point(m.group(1)))
        pos = m.end()
    if pos < len(text):
        out.append(text[pos:])
    return out
