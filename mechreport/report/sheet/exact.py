"""Exact closed forms of a sheet's values (``--exact``): a value that is a rational
combination of the square roots the spec itself gives rise to, such as 3 + 105 sqrt(2), is
recognised with sympy's ``nsimplify`` against those surds.

The surds of a spec are the square roots in the exact sines and cosines of its reference
angles and sliding-line angles (45 deg gives sqrt(2), 30 deg sqrt(3)), and in the distances
between the points of each link and between the ground points (taken as the rationals the
spec writes). A value is accepted only if it is a short sum of rationals times square roots
of products of those radicands and matches to ``RTOL``; otherwise there is none, and the
sheet says so.

sympy is an optional dependency (``pip install 'mechreport[exact]'``)."""
from __future__ import annotations

import math
from itertools import combinations

import numpy as np

from ...errors import MechreportError
from .expr import Raw

RTOL = 1e-12          # a closed form must match the computed value this closely
MAX_TERMS = 4         # at most this many terms (a + b sqrt2 + c sqrt3 + d sqrt6)
MAX_DIGITS = 8.0      # digits of all its numerators and denominators together: a double
                      # holds ~16, so a form with more could fit any number by chance
MAX_RADICANDS = 3     # surds tried at once (nsimplify slows down with many)


class ExactUnavailable(MechreportError):
    """--exact was asked for but sympy is not installed."""


def require_sympy():
    try:
        import sympy
    except ImportError:
        raise ExactUnavailable("--exact needs sympy, which is not installed; install it with "
                               "pip install 'mechreport[exact]' (or pip install sympy)") from None
    return sympy


def _square_free(n: int) -> int:
    """The square-free part of a positive integer (12 -> 3)."""
    out, p = 1, 2
    while p * p <= n:
        while n % (p * p) == 0:
            n //= p * p
        if n % p == 0:
            out *= p
            n //= p
        p += 1
    return out * n


def _rational_radicands(sp, q) -> set[int]:
    """Radicands of sqrt(q) for a rational q > 0: sqrt(a/b) = sqrt(a b)/b."""
    q = sp.Rational(q)
    if q <= 0:
        return set()
    r = _square_free(int(q.p * q.q))
    return {r} if r > 1 else set()


def spec_radicands(spec, angles) -> list[int]:
    """The square-free radicands of the spec's own surds (see the module docstring), the
    smallest first, at most ``MAX_RADICANDS``."""
    sp = require_sympy()
    found: dict[int, int] = {}

    def note(rs):
        for r in rs:
            found[r] = found.get(r, 0) + 1

    def trig(deg: float):
        a = sp.nsimplify(float(deg), rational=True)
        for f in (sp.cos, sp.sin):
            e = f(sp.pi * a / 180)
            for p in e.atoms(sp.Pow):
                if p.exp == sp.Rational(1, 2) and p.base.is_Integer:
                    note({_square_free(int(p.base))})

    for a in angles:
        if spec.driver.kind == "R":
            trig(a)
    for j in spec.joints:
        if j.type == "T":
            d = np.asarray(j.line.direction, float)
            trig(math.degrees(math.atan2(d[1], d[0])))
    groups = [list(l.points.values()) for l in spec.links] + [list(spec.ground.values())]
    for pts in groups:
        for p, q in combinations(pts, 2):
            d2 = sum((sp.nsimplify(float(a) - float(b), rational=True, tolerance=1e-12)) ** 2
                     for a, b in zip(p, q))
            if d2:
                note(_rational_radicands(sp, d2))
    return sorted(found, key=lambda r: (-found[r], r))[:MAX_RADICANDS]


class ExactForms:
    """``forms(x)``: the closed form of ``x`` in the spec's surds, or None."""

    def __init__(self, spec, angles):
        self.sp = require_sympy()
        self.radicands = sorted(spec_radicands(spec, angles))
        self.surds = [self.sp.sqrt(r) for r in self.radicands]
        # square roots allowed in a form: of every product of the radicands (sqrt2 sqrt3 =
        # sqrt6), square-free
        self.allowed = {_square_free(math.prod(c)) for n in range(1, len(self.radicands) + 1)
                        for c in combinations(self.radicands, n)}
        self.cache: dict[float, object] = {}

    def describe(self) -> str:
        """The surds tried, for a note: '√2 and √3', or 'no square roots'."""
        if not self.radicands:
            return "rationals (the spec gives rise to no square roots)"
        names = [f"√{r}" for r in self.radicands]
        return "rational combinations of " + (" and ".join(names) if len(names) < 3 else
                                              ", ".join(names[:-1]) + " and " + names[-1])

    def __call__(self, x: float):
        """A closed form matching ``x`` to ``RTOL`` (relative), or None; 0 for exact zero."""
        sp = self.sp
        x = float(x)
        if not np.isfinite(x):
            return None
        if x == 0:
            return sp.Integer(0)
        if x in self.cache:
            return self.cache[x]
        self.cache[x] = None
        try:
            e = sp.nsimplify(x, self.surds, tolerance=RTOL * abs(x) * 0.5, full=False)
            e = sp.expand(e)
        except Exception:       # noqa: BLE001 - nsimplify gives up in several ways
            return None
        if self._simple(e) and abs(float(e) - x) <= RTOL * abs(x):
            self.cache[x] = e
        return self.cache[x]

    def _simple(self, e) -> bool:
        sp = self.sp
        if e.free_symbols or e.has(sp.pi, sp.E):
            return False
        terms = sp.Add.make_args(e)
        if len(terms) > MAX_TERMS:
            return False
        digits = 0.0
        for t in terms:
            c, rest = t.as_coeff_Mul()
            if not c.is_Rational:
                return False
            digits += math.log10(abs(int(c.p)) + 1) + math.log10(int(c.q))
            if rest == 1:
                continue
            if not (rest.is_Pow and rest.exp == sp.Rational(1, 2) and rest.base.is_Integer):
                return False
            if int(rest.base) not in self.allowed:
                return False
        return digits <= MAX_DIGITS

    def atom(self, e) -> Raw:
        """``a + b√n`` with the rational part first, as the textbook writes 3 + 105√2."""
        sp = self.sp
        parts = []
        for t in sp.Add.make_args(e):
            c, rest = t.as_coeff_Mul()
            n = None if rest == 1 else int(rest.base)
            parts.append((sp.Rational(c), n))
        parts.sort(key=lambda p: (p[1] is not None, p[1] or 0))
        tex = typ = plain = ""
        for i, (c, n) in enumerate(parts):
            neg = c < 0
            c = abs(c)
            p, q = int(c.p), int(c.q)
            num_t = (("" if p == 1 else f"{p}") + rf"\sqrt{{{n}}}") if n else f"{p}"
            num_y = (("" if p == 1 else f"{p} ") + f"sqrt({n})") if n else f"{p}"
            bt = rf"\frac{{{num_t}}}{{{q}}}" if q != 1 else num_t
            by = f"({num_y})/{q}" if q != 1 else num_y
            bp = f"{num_y}/{q}" if q != 1 else num_y
            op = "-" if neg else "+"
            if i == 0:
                pre = "-" if neg else ""
                tex, typ, plain = pre + bt, pre + by, pre + bp
            else:
                tex += f" {op} {bt}"
                typ += f" {op} {by}"
                plain += f" {op} {bp}"
        return Raw(tex, typ, plain, repr(float(e)))
