"""Exact closed forms of a sheet's values (``--exact``): a value that is a rational
combination of the square roots the spec itself gives rise to, such as 3 + 105 sqrt(2), is
recognised with sympy's ``nsimplify`` against those surds.

The surds of a spec are the square roots in the exact sines and cosines of its reference
angles and sliding-line angles (45 deg gives sqrt(2), 30 deg sqrt(3)), and in the distances
between the points of each link and between the ground points (taken as the rationals the
spec writes). A value is accepted only if it is a short sum of rationals times square roots
of products of those radicands and matches to ``RTOL``; otherwise there is none, and the
sheet says so.

Reducing a radicand to its square-free part is factoring, so the work is bounded: trial
division by the primes up to ``TRIAL_LIMIT`` only, of integers of at most
``MAX_RADICAND_DIGITS`` digits, and a primality test of what is left only below
``PRIME_TEST_BELOW`` (see ``_square_free``). A radicand whose square-free part that work does not
establish is left out: values that would need its surd are "none found", and the note says
that a square root was left out. A radicand is never guessed, so a closed form is never
wrong for want of work, only missing.

sympy is an optional dependency (``pip install 'mechreport[exact]'``)."""
from __future__ import annotations

import math
from functools import lru_cache, reduce
from itertools import combinations

import numpy as np

from ...errors import MechreportError
from .expr import Raw

RTOL = 1e-12          # a closed form must match the computed value this closely
MAX_TERMS = 4         # at most this many terms (a + b sqrt2 + c sqrt3 + d sqrt6)
MAX_DIGITS = 8.0      # digits of all its numerators and denominators together: a double
                      # holds ~16, so a form with more could fit any number by chance
MAX_RADICANDS = 3     # surds tried at once (nsimplify slows down with many)
TRIAL_LIMIT = 10_000  # square factors are looked for by trial division by the primes up to
                      # this (1229 of them): the bound on the work per radicand
MAX_RADICAND_DIGITS = 100  # integers with more digits are not tried at all
PRIME_TEST_BELOW = 2 ** 64  # what trial division leaves is tested for primality only below
                            # this, where sympy's isprime is definitive, not probabilistic


class ExactUnavailable(MechreportError):
    """--exact was asked for but sympy is not installed."""


def require_sympy():
    try:
        import sympy
    except ImportError:
        raise ExactUnavailable("--exact needs sympy, which is not installed; install it with "
                               "pip install 'mechreport[exact]' (or pip install sympy)") from None
    return sympy


@lru_cache(maxsize=1)
def _trial_primes() -> tuple[int, ...]:
    """The primes up to ``TRIAL_LIMIT`` (sympy's sieve)."""
    return tuple(int(p) for p in require_sympy().sieve.primerange(2, TRIAL_LIMIT + 1))


def _is_square(n: int) -> bool:
    return math.isqrt(n) ** 2 == n


def _square_free(n: int) -> int | None:
    """The square-free part of a positive integer (12 -> 3), or None where bounded work
    does not establish it: never a guess.

    A perfect square gives 1 at any size. Otherwise an integer of more than
    ``MAX_RADICAND_DIGITS`` digits is not tried; a smaller one is trial-divided by the primes
    up to L = ``TRIAL_LIMIT`` only. What is left, m, has only prime factors > L, so: m = 1 or
    a perfect square adds nothing; m < (L+1)**3 has at most two prime factors and, not a
    square, is square-free; a prime m is square-free (sympy's isprime, asked only below
    ``PRIME_TEST_BELOW``); any other m (p**2 q, say) is undecided, and so is n."""
    n = int(n)
    if n < 1:
        raise ValueError(f"the square-free part of {n} is not defined")
    if _is_square(n):
        return 1
    if n >= 10 ** MAX_RADICAND_DIGITS:
        return None
    out = 1
    for p in _trial_primes():
        if p * p > n:
            break
        if n % p == 0:
            e = 0
            while n % p == 0:
                n //= p
                e += 1
            if e % 2:
                out *= p
    if n == 1 or _is_square(n):
        return out
    if n < (TRIAL_LIMIT + 1) ** 3 or (n < PRIME_TEST_BELOW and require_sympy().isprime(n)):
        return out * n
    return None


def _square_free_product(a: int, b: int) -> int:
    """The square-free part of a b for square-free a and b (sqrt2 sqrt6 = 2 sqrt3): no
    factoring, the common primes are the gcd's."""
    g = math.gcd(a, b)
    return (a // g) * (b // g)


def _rational_radicands(sp, q) -> set[int] | None:
    """Radicands of sqrt(q) for a rational q > 0: sqrt(a/b) = sqrt(a b)/b, and as a and b
    are coprime the square-free part of a b is theirs multiplied. None: not established."""
    q = sp.Rational(q)
    if q <= 0:
        return set()
    a, b = _square_free(int(q.p)), _square_free(int(q.q))
    if a is None or b is None:
        return None
    r = a * b
    return {r} if r > 1 else set()


def spec_radicands(spec, angles) -> list[int]:
    """The square-free radicands of the spec's own surds (see the module docstring), the
    smallest first, at most ``MAX_RADICANDS``."""
    return spec_surds(spec, angles)[0]


def spec_surds(spec, angles) -> tuple[list[int], int]:
    """``spec_radicands``, and how many of the spec's surds were left out because bounded
    work did not reduce their radicands (see ``_square_free``)."""
    sp = require_sympy()
    found: dict[int, int] = {}
    unreduced: set = set()          # the radicands left out, each once

    def note(rs, radicand):
        if rs is None:
            unreduced.add(radicand)
            return
        for r in rs:
            found[r] = found.get(r, 0) + 1

    def trig(deg: float):
        a = sp.nsimplify(float(deg), rational=True)
        for f in (sp.cos, sp.sin):
            e = f(sp.pi * a / 180)
            for p in e.atoms(sp.Pow):
                if p.exp == sp.Rational(1, 2) and p.base.is_Integer and p.base > 0:
                    r = _square_free(int(p.base))
                    note(None if r is None else {r} - {1}, p.base)

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
                note(_rational_radicands(sp, d2), d2)
    return sorted(found, key=lambda r: (-found[r], r))[:MAX_RADICANDS], len(unreduced)


class ExactForms:
    """``forms(x)``: the closed form of ``x`` in the spec's surds, or None."""

    def __init__(self, spec, angles):
        self.sp = require_sympy()
        radicands, self.unreduced = spec_surds(spec, angles)
        self.radicands = sorted(radicands)
        self.surds = [self.sp.sqrt(r) for r in self.radicands]
        # square roots allowed in a form: of every product of the radicands (sqrt2 sqrt3 =
        # sqrt6), square-free
        self.allowed = {reduce(_square_free_product, c)
                        for n in range(1, len(self.radicands) + 1)
                        for c in combinations(self.radicands, n)}
        self.cache: dict[float, object] = {}

    def describe(self) -> str:
        """The surds tried, for a note: '√2 and √3', or 'no square roots'; and how many
        were left out as too large to reduce."""
        left = ""
        if self.unreduced:
            k = self.unreduced
            left = (f" (not of {k} more square root{'s' if k > 1 else ''} the spec gives "
                    f"rise to, too large to reduce)")
        if not self.radicands:
            if left:
                return "rationals" + left
            return "rationals (the spec gives rise to no square roots)"
        names = [f"√{r}" for r in self.radicands]
        return "rational combinations of " + (" and ".join(names) if len(names) < 3 else
                                              ", ".join(names[:-1]) + " and " + names[-1]) + left

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
