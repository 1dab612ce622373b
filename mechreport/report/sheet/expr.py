"""The math the solution sheets print, rendered four ways: LaTeX (GitHub Markdown), Typst,
plain text (tests, terminals) and Python (tests evaluate the printed equations).

An expression is a list of signed terms ``(sign, factors)``; an equation a list of such
expressions joined by ``=``. Long equations break before a top-level ``+``, ``-`` or ``=``.
Numbers go through the one number formatter (:func:`fmt`, with the sheets' digits).
"""
from __future__ import annotations

import math as _m
import re
from contextlib import contextmanager
from contextvars import ContextVar
from dataclasses import dataclass, field

ZERO = 1e-12          # |x| below this prints as 0 (SI), unless a sheet says otherwise
#: the sheet being built or rendered: |x| at or below this is round-off, printed as 0 (the
#: reports' rule: 1e-9 of the analysis' scale, see :func:`round_off`); per context, as
#: numpy's error state is
_ZERO: ContextVar[float] = ContextVar("mechreport_sheet_zero", default=ZERO)
WIDTH = 100           # plain-text characters per displayed line before breaking
_GLYPHS = re.compile(r"varphi|theta|omega|alpha|Delta|phi|sum|deg")


def fmt(x: float, zero: float | None = None) -> str:
    """The one number formatter (:func:`mechreport.units.fmt`) with the sheets' digits
    (``SHEET_DIGITS``: worked equations must balance to the textbook's rounding): never
    ``-0``, ``e`` notation for very small/large magnitudes, 0 below ``zero`` (default: the
    round-off of the sheet being built, :func:`round_off`)."""
    from ...units import SHEET_DIGITS, fmt as number
    x = float(x)
    if not _m.isfinite(x):
        return "nan"
    if abs(x) < (_ZERO.get() if zero is None else zero):
        return "0"
    return number(x, SHEET_DIGITS)


@contextmanager
def round_off(zero: float):
    """Numbers of magnitude below ``zero`` print as 0 in the block (a sheet's building,
    drawing and rendering)."""
    token = _ZERO.set(zero)
    try:
        yield
    finally:
        _ZERO.reset(token)


def sheet_zero(scales: dict[str, float]) -> float:
    """A sheet's round-off: 1e-9 (the reports' ``ZERO_RTOL``) of the smallest scale among
    the kinds it prints (lengths, velocities, accelerations, forces, moments [SI]), so
    that a value the reports print is never a 0 on the sheet."""
    from ...units import ZERO_RTOL
    kinds = ("length", "velocity", "acceleration", "force", "moment")
    return ZERO_RTOL * min(scales[k] for k in kinds if k in scales)


# --------------------------------------------------------------------------- atoms

class Atom:
    def tex(self) -> str: raise NotImplementedError
    def typ(self) -> str: raise NotImplementedError
    def plain(self) -> str: raise NotImplementedError
    def py(self) -> str: return self.plain()


def _tex_escape(s: str) -> str:
    return re.sub(r"([\\{}_^#$%&~])", r"\\\1", s)


def _typ_str(s: str) -> str:
    return '"' + s.replace("\\", "\\\\").replace('"', '\\"') + '"'


_WORD = re.compile(r"[A-Za-z]+|\d+|.", re.S)


def _typ_sub(text: str) -> str:
    """Subscript text for Typst math: digits and single letters as they are, words quoted;
    tokens are separated by spaces except next to a quoted word (which would show a gap)."""
    out: list[tuple[str, bool]] = []
    for tok in _WORD.findall(text):
        if tok.isdigit() or (tok.isalpha() and len(tok) == 1):
            out.append((tok, False))
        elif tok == ",":
            out.append((",", True))
        elif tok.isspace():
            out.append(("thin", False))
        else:
            out.append((_typ_str(tok), True))
    s = ""
    for i, (tok, quoted) in enumerate(out):
        if i and not quoted and not out[i - 1][1]:
            s += " "
        s += tok
    return s


def _tex_sub(text: str) -> str:
    out = []
    for tok in _WORD.findall(text):
        if tok.isspace():
            out.append(r"\,")
        elif tok.isalnum() or tok == ",":
            out.append(tok)
        else:
            out.append(_tex_escape(tok))
    return "".join(out)


@dataclass(frozen=True)
class Point(Atom):
    """A point name: ``C2`` -> C_2, ``C_T`` -> C_T, others as written."""
    name: str

    def _split(self):
        m = re.fullmatch(r"([A-Za-z])_?(\d+|[A-Za-z])", self.name)
        if m:
            return m.group(1), m.group(2)
        return None

    def tex(self):
        s = self._split()
        if s:
            return f"{s[0]}_{{{s[1]}}}"
        if re.fullmatch(r"[A-Za-z]", self.name):
            return self.name
        return r"\mathrm{" + _tex_escape(self.name) + "}"

    def typ(self):
        s = self._split()
        if s:
            return f"{s[0]}_{s[1]}"
        if re.fullmatch(r"[A-Za-z]", self.name):
            return self.name
        return _typ_str(self.name)

    def plain(self):
        return self.name


@dataclass(frozen=True)
class Sym(Atom):
    """``base`` with subscript ``sub`` (text; see _typ_sub) and optional superscript."""
    base: str
    sub: str = ""
    bold: bool = False
    sup: str = ""
    py_name: str = ""

    _GREEK = {"alpha": ("\\alpha", "alpha"), "omega": ("\\omega", "omega"),
              "Delta": ("\\Delta", "Delta"), "Sigma": ("\\Sigma", "Sigma"),
              "theta": ("\\theta", "theta"), "phi": ("\\varphi", "phi")}

    def _base(self, tex: bool) -> str:
        if self.base in self._GREEK:
            b = self._GREEK[self.base][0 if tex else 1]
            return (r"\boldsymbol{" + b + "}") if (tex and self.bold) else \
                (f"bold({b})" if self.bold else b)
        if tex:
            return r"\mathbf{" + self.base + "}" if self.bold else self.base
        return f"bold({self.base})" if self.bold else self.base

    def tex(self):
        s = self._base(True)
        if self.sub:
            s += "_{" + _tex_sub(self.sub) + "}"
        if self.sup:
            s += "^{" + _tex_sub(self.sup) + "}"
        return s

    def typ(self):
        s = self._base(False)
        if self.sub:
            sub = _typ_sub(self.sub)
            s += "_(" + sub + ")" if len(self.sub) > 1 else "_" + sub
        if self.sup:
            s += "^(" + _typ_sub(self.sup) + ")"
        return s

    def plain(self):
        return self.base + self.sub.replace(" ", "") + (f"^{self.sup}" if self.sup else "")

    def py(self):
        return self.py_name or re.sub(r"\W", "_", self.plain())


@dataclass(frozen=True)
class RVec(Atom):
    """Position vector r_PQ = r_Q - r_P (from P to Q)."""
    frm: str
    to: str

    def tex(self):
        return r"\mathbf{r}_{" + Point(self.frm).tex() + " " + Point(self.to).tex() + "}"

    def typ(self):
        return "bold(r)_(" + Point(self.frm).typ() + " " + Point(self.to).typ() + ")"

    def plain(self):
        return f"r_{self.frm}{self.to}"


@dataclass(frozen=True)
class Num(Atom):
    """A number; ``paren`` wraps it in parentheses (a factor)."""
    value: float
    paren: bool = False

    def _s(self):
        return fmt(self.value)

    def _parts(self):
        s = self._s()
        if "e" in s:
            mant, exp = s.split("e")
            return mant, str(int(exp))
        return s, None

    def tex(self):
        mant, exp = self._parts()
        s = mant + (r" \times 10^{" + exp + "}" if exp else "")
        return f"({s})" if self.paren else s

    def typ(self):
        mant, exp = self._parts()
        s = mant + (f" times 10^({exp})" if exp else "")
        return f"({s})" if self.paren else s

    def plain(self):
        return f"({self._s()})" if self.paren else self._s()

    def py(self):
        return f"({float(self.value)!r})"


@dataclass(frozen=True)
class Op(Atom):
    """times, dot, or a literal small operator."""
    name: str
    _T = {"times": (r"\times", "times", "x", "*"), "dot": (r"\cdot", "dot", ".", "*"),
          "mul": (r"\cdot", "dot.op", "·", "*")}

    def tex(self): return self._T[self.name][0]
    def typ(self): return self._T[self.name][1]
    def plain(self): return self._T[self.name][2]
    def py(self): return self._T[self.name][3]


@dataclass(frozen=True)
class Raw(Atom):
    t: str
    y: str
    p: str
    q: str = ""

    def tex(self): return self.t
    def typ(self): return self.y
    def plain(self): return self.p
    def py(self): return self.q or self.p


@dataclass(frozen=True)
class Text(Atom):
    s: str

    def tex(self): return r"\text{" + _tex_escape(self.s) + "}"
    def typ(self): return _typ_str(self.s)
    def plain(self): return self.s


@dataclass
class Expr:
    """Signed terms: ``[(sign, [atoms...]), ...]``; empty means 0."""
    terms: list = field(default_factory=list)

    def add(self, sign: float, *factors) -> "Expr":
        self.terms.append((1 if sign >= 0 else -1, list(factors)))
        return self

    def __bool__(self):
        return bool(self.terms)


@dataclass(frozen=True)
class Paren(Atom):
    expr: Expr

    def tex(self): return "(" + _join(self.expr, "tex") + ")"
    def typ(self): return "(" + _join(self.expr, "typ") + ")"
    def plain(self): return "(" + _join(self.expr, "plain") + ")"
    def py(self): return "(" + _join(self.expr, "py") + ")"


def _factors(factors, how: str) -> str:
    parts = [getattr(f, how)() for f in factors]
    if how == "py":
        out = []
        for i, p in enumerate(parts):
            if i and not isinstance(factors[i], Op) and not isinstance(factors[i - 1], Op):
                out.append("*")
            out.append(p)
        return "".join(out)
    out = []
    for i, p in enumerate(parts):
        if i:
            a, b = factors[i - 1], factors[i]
            if isinstance(a, Num) and a.paren and isinstance(b, Num) and b.paren:
                sep = ""
            elif isinstance(b, Raw) and b.t == r"^\circ" and how != "plain":
                sep = ""                # 45°, not 45 °
            elif how == "tex" and not isinstance(a, Op) and not isinstance(b, Op):
                sep = r"\,"
            elif how == "typ" and isinstance(a, Num) and not isinstance(b, Op):
                sep = " thin "          # 0.707107 F_21y, not 0.707107F_21y
            else:
                sep = " "
            out.append(sep)
        out.append(p)
    return "".join(out)


def _term_strings(expr: Expr, how: str) -> list[tuple[str, str]]:
    """[(operator, body)] with the first term's '+' left out."""
    if not expr.terms:
        return [("", "0")]
    out = []
    for i, (sign, factors) in enumerate(expr.terms):
        body = _factors(factors, how)
        out.append(("-" if sign < 0 else ("" if i == 0 else "+"), body))
    return out


def _join(expr: Expr, how: str) -> str:
    s = ""
    for op, body in _term_strings(expr, how):
        if op == "-" and not s:
            s = "-" + body
        elif op:
            s += f" {op} {body}"
        else:
            s += body
    return s


@dataclass
class Equation:
    """``sides[0] = sides[1] = ...``."""
    sides: list

    @staticmethod
    def _vlen(plain: str) -> int:
        """About how wide a plain rendering prints: a Greek letter's name is one glyph."""
        return len(_GLYPHS.sub("x", plain))

    def chunks(self, how: str):
        """Breakable chunks: (kind, text, plain_len); kind 'eq' | 'op' | 'first'."""
        out = []
        for si, side in enumerate(self.sides):
            terms = _term_strings(side, how)
            plain = _term_strings(side, "plain")
            for ti, ((op, body), (_, pb)) in enumerate(zip(terms, plain)):
                n = self._vlen(pb)
                if ti == 0 and si > 0:
                    out.append(("eq", op, body, n + 3 + len(op)))
                else:
                    out.append(("op" if op and (ti or si) else "first", op, body, n + 3))
        return out

    def lines(self, how: str, width: int = WIDTH) -> list[list[tuple[str, str, str]]]:
        lines: list[list] = [[]]
        used = 0
        for ch in self.chunks(how):
            trailing_zero = ch[0] == "eq" and ch[2] == "0"
            if lines[-1] and used + ch[3] > width and ch[0] in ("op", "eq") \
                    and not trailing_zero:
                lines.append([])
                used = 8
            lines[-1].append(ch[:3])
            used += ch[3]
        return lines

    def render(self, how: str, width: int = WIDTH) -> str:
        lines = self.lines(how, width)
        if how in ("plain", "py"):
            return _flat(lines, how)
        if len(lines) == 1:
            return _flat(lines, how)
        rows = []
        for li, line in enumerate(lines):
            s = ""
            for ci, (kind, op, body) in enumerate(line):
                lead = li > 0 and ci == 0
                if kind == "eq":
                    eq = "=" if how == "typ" else "="
                    if lead:
                        s += f"&{eq} " + (f"{op}" if op else "") + body
                    else:
                        s += f" {eq} " + (f"{op}" if op else "") + body
                elif kind == "op":
                    if lead:
                        o = op if how == "tex" else f'class("binary", {op})'
                        pre = r"&\quad {} " if how == "tex" else "& quad "
                        s += f"{pre}{o} {body}"
                    else:
                        s += f" {op} {body}"
                else:
                    s += (op if op == "-" else "") + body
            rows.append(s)
        if how == "tex":
            return r"\begin{aligned} & " + r" \\ ".join(
                r if i else r for i, r in enumerate(rows)) + r" \end{aligned}"
        return "& " + " \\\n  ".join(rows)


def _flat(lines, how: str) -> str:
    s = ""
    for line in lines:
        for kind, op, body in line:
            if kind == "eq":
                s += (" == " if how == "py" else " = ") + (op if op == "-" else "") + body
            elif kind == "op":
                s += f" {op} {body}"
            else:
                s += (op if op == "-" else "") + body
    return s.strip()


def math(x, how: str) -> str:
    """Render an Atom, Expr or Equation (or a list of them, comma-separated)."""
    if x is None:
        return ""
    if isinstance(x, (list, tuple)):
        sep = {"tex": ",\\ ", "typ": ", thick ", "plain": ", ", "py": ", "}[how]
        return sep.join(math(i, how) for i in x)
    if isinstance(x, Equation):
        return x.render(how)
    if isinstance(x, Expr):
        return _join(x, how)
    return getattr(x, how)()
