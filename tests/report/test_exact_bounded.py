"""``--exact`` does bounded work (the issue "`--exact` hangs on ordinary numbers"): a spec
coordinate such as 0.1234567891234 made ``exact._square_free`` trial-divide a ~9e42 integer
for minutes. The work is counted here, never timed: the lines of ``exact.py`` executed (a
budget that raises as soon as it is spent, so unbounded work fails at once instead of
hanging) and the integers handed to sympy's primality test. And what bounded work cannot
establish is "no closed form", never a guess, while the closed forms it finds stay right."""
from __future__ import annotations

import math
import random
import sys
from pathlib import Path

import pytest

sympy = pytest.importorskip("sympy")

from mechreport.report.sheet import exact                          # noqa: E402
from mechreport.report.sheet.exact import ExactForms, _square_free  # noqa: E402
from mechreport.spec import parse_spec                              # noqa: E402

ROOT = Path(__file__).resolve().parents[2]
SLIDER_CRANK = (ROOT / "specs" / "slider_crank.yaml").read_text()
CRANK_B = "B: [1, 0]}"

# Lines of exact.py one radicand may cost: a few per trial prime (1229 primes up to 10**4),
# and a spec has a handful of radicands. The code before the fix needed ~1e10 for the issue's
# spec, and a million for one 13-digit radicand with a square factor.
PER_RADICAND = 4 * 1229 + 100
SPEC_BUDGET = 12 * PER_RADICAND


class WorkExceeded(BaseException):
    """The budget of lines is spent (a BaseException: nothing in exact.py may swallow it)."""


class LinesOfExact:
    """Counts the lines of ``exact.py`` executed inside the ``with`` block, and raises
    ``WorkExceeded`` as soon as more than ``budget`` have run."""

    def __init__(self, budget: int):
        self.budget = budget
        self.lines = 0
        self.file = exact.__file__

    def _call(self, frame, event, arg):
        return self._line if frame.f_code.co_filename == self.file else None

    def _line(self, frame, event, arg):
        if event == "line":
            self.lines += 1
            if self.lines > self.budget:
                raise WorkExceeded(f"more than {self.budget} lines of exact.py executed")
        return self._line

    def __enter__(self):
        self.previous = sys.gettrace()
        sys.settrace(self._call)
        return self

    def __exit__(self, *exc):
        sys.settrace(self.previous)
        return False


@pytest.fixture
def primality_asked(monkeypatch):
    """The integers exact.py hands to sympy's isprime (whose answer is definitive only below
    2**64)."""
    asked = []
    real = sympy.isprime

    def isprime(n):
        asked.append(int(n))
        return real(n)

    monkeypatch.setattr(sympy, "isprime", isprime)
    return asked


def crank_at(b: str):
    """The 4.6 slider-crank with its crank's end B at ``b`` (the issue's sed command)."""
    text = SLIDER_CRANK.replace(CRANK_B, f"B: {b}}}")
    assert text != SLIDER_CRANK
    return parse_spec(text, "hostile.yaml")


def warm():
    """Compute exact.py's table of trial primes outside the count (it is made once)."""
    getattr(exact, "_trial_primes", lambda: None)()


def square_free(n: int):
    """``_square_free(n)`` within the budget of one radicand."""
    warm()
    with LinesOfExact(PER_RADICAND):
        return _square_free(n)


def forms_within_budget(spec, budget=SPEC_BUDGET):
    warm()
    with LinesOfExact(budget) as work:
        forms = ExactForms(spec, list(spec.at))
    return forms, work.lines


HOSTILE = {
    "the_issue_s_13_digit_coordinate": "[0.1234567891234, 0]",
    "a_nine_digit_coordinate": "[0.123456789, 0]",
    "nine_digit_coordinates": "[0.123456789, 0.987654321]",
    "twelve_digit_coordinates": "[0.123456789012, 0.987654321098]",
    "coordinates_near_1e_7": "[1.234567e-7, 0.7000001]",
    "a_nine_digit_length_at_45_degrees": "[0.123456789, 0.123456789]",
}


@pytest.mark.parametrize("b", list(HOSTILE.values()), ids=list(HOSTILE))
def test_exact_forms_of_hostile_coordinates_are_bounded_work(b, primality_asked):
    forms, lines = forms_within_budget(crank_at(b))
    assert lines <= SPEC_BUDGET
    assert all(n < 2**64 for n in primality_asked)
    # the reference angle 45 deg still gives sqrt2; a radicand left out is said to be
    assert forms.radicands == [2]
    assert ("too large to reduce" in forms.describe()) == (forms.unreduced > 0)


def test_exact_forms_of_a_nine_digit_coordinate_are_bounded_work():
    """The issue's reproduction: B: [0.1234567891234, 0] (and its 9-digit variant) cost a
    few hundred lines, as the distance is a rational squared."""
    for b in ("[0.1234567891234, 0]", "[0.123456789, 0]"):
        forms, lines = forms_within_budget(crank_at(b), budget=2_000)
        assert forms.radicands == [2] and forms.unreduced == 0


def test_a_large_square_factor_is_still_found_and_cheaply():
    """2 P**2 with P a 9-digit prime: the code before the fix trial-divided up to P."""
    p = sympy.prevprime(10**9)
    assert square_free(2 * p * p) == 2
    assert square_free(p * p) == 1
    assert square_free(3 * 7**3 * p * p) == 21


def test_a_radicand_beyond_the_bound_is_no_closed_form_not_a_guess(primality_asked):
    p, q = sympy.nextprime(10**6), 1000033            # q = 408**2 + 913**2, a prime
    assert square_free(p * p * q) is None               # p**2 q: its square is past the bound
    assert square_free(sympy.prevprime(10**9) * sympy.nextprime(10**9)) is None
    assert square_free(sympy.nextprime(2**64)) is None  # a prime, but not certainly
    assert square_free(10**150 + 1) is None             # too many digits to try at all
    assert square_free(3 * sympy.nextprime(10**15)) == 3 * sympy.nextprime(10**15)
    assert primality_asked and all(n < 2**64 for n in primality_asked)

    # a ground point at distance p sqrt(q): that surd is left out, and said to be; a value
    # in it has no closed form rather than a wrong one, and sqrt2 still works
    text = SLIDER_CRANK.replace("  O: [0, 0]\n", f"  O: [0, 0]\n  Z: [{408 * p}, {913 * p}]\n")
    spec = parse_spec(text, "far.yaml")
    forms, _ = forms_within_budget(spec)
    assert forms.radicands == [2] and forms.unreduced == 1
    assert forms.describe() == ("rational combinations of √2 (not of 1 more square root the "
                                "spec gives rise to, too large to reduce)")
    assert forms(float(p * sympy.sqrt(q))) is None
    assert forms(math.sqrt(8)) == 2 * sympy.sqrt(2)


def test_square_free_parts_found_are_right():
    """Wherever bounded work gives a square-free part (within the budget of one radicand
    each), it is sympy's (factorint); and bounded work decides most integers up to 19 digits."""
    def truth(n):
        return math.prod(p for p, e in sympy.factorint(n).items() if e % 2)

    rng = random.Random(46)
    big = [sympy.nextprime(10**4), sympy.prevprime(10**6), sympy.prevprime(10**9)]
    cases = list(range(1, 3000)) + [rng.randrange(1, 10**k) for k in range(4, 20)
                                    for _ in range(25)]
    cases += [rng.choice(big) ** e * rng.randrange(1, 10**4) for e in (1, 2, 3)
              for _ in range(30)]
    decided = 0
    for n in cases:
        r = square_free(n)
        if r is not None:
            decided += 1
            assert r == truth(n), n
    assert decided > 0.9 * len(cases)
    assert _square_free(8) == 2 and _square_free(12) == 3 and _square_free(1) == 1


def test_sqrt8_is_still_2_sqrt2_and_sqrt_products_reduce():
    forms, _ = forms_within_budget(parse_spec(SLIDER_CRANK, "slider_crank.yaml"))
    assert forms.radicands == [2] and forms.unreduced == 0
    e = forms(math.sqrt(8))
    assert e == 2 * sympy.sqrt(2)
    assert forms.atom(e).plain() == "2 sqrt(2)"
    assert forms(3 + 105 * math.sqrt(2)) == 3 + 105 * sympy.sqrt(2)


def test_the_4_6_answer_key_keeps_its_closed_forms():
    from mechreport.pipeline.analysis import analyse
    from mechreport.report.sheet import SheetOptions, build_sheet, render_markdown
    analysis = analyse(ROOT / "specs" / "slider_crank.yaml")
    warm()
    with LinesOfExact(SPEC_BUDGET + 20_000):     # ExactForms and its ~50 calls
        model = build_sheet(analysis, SheetOptions(exact=True))
    md = render_markdown(model)
    assert r"M = 3 + 105\sqrt{2}" in md
    assert r"F_{01x} = -100 - 2\sqrt{2}" in md
    assert r"F_{12x} = -100 - \frac{7\sqrt{2}}{4}" in md
    assert "Exact values are rational combinations of √2 that match" in md
