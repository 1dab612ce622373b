"""Worked solution sheets (issues 5 and 15): the textbook's equations and results of 4.6 and
4.7 as the sheet prints them, the kinematics derivation, the figures, the problem version,
exact mode, the sheet options, and that the sheet is generated from the equation objects."""
from __future__ import annotations

import math
import re
import copy
from dataclasses import fields, replace
from pathlib import Path

import pytest

from mechreport.pipeline.analysis import analyse
from mechreport.report.sheet import (SheetOptions, build_problem, build_sheet,
                                     render_markdown, render_problem_markdown, render_typst,
                                     sheet_analysis, sheet_spec, write_sheet)
from mechreport.report.sheet.expr import fmt, math as render

ROOT = Path(__file__).resolve().parents[2]
SPECS = sorted((ROOT / "specs").glob("*.yaml")) + [ROOT / "tests" / "data" /
                                                   "class_iii_triad.yaml"]
S2 = math.sqrt(2)


@pytest.fixture(scope="module")
def textbook(tmp_path_factory):
    """Analyses, sheet models and written sheets of 4.6 and 4.7 (built once)."""
    out = {}
    for key, stem in (("4.6", "slider_crank"), ("4.7", "r_rtr_rtr")):
        a = analyse(ROOT / "specs" / f"{stem}.yaml")
        d = tmp_path_factory.mktemp(stem)
        paths = write_sheet(a, d)
        out[key] = {"analysis": a, "model": build_sheet(a), "md": paths[0].read_text(),
                    "paths": paths, "dir": d}
    return out


def method(model, name, angle_index=0):
    return next(m for m in model.angles[angle_index].methods if m.name == name)


def equations(m):
    return [e for s in m.steps for e in s.equations]


def numeric_lines(m) -> list[str]:
    return [render(e.numeric, "plain") for e in equations(m)]


def result_lines(m) -> list[str]:
    return [render(r, "plain") for s in m.steps for r in s.results] + \
        [render(m.effort, "plain")]


def _namespace(a, k) -> dict:
    """Values of every printed symbol: F12x and F21x = -F12x, M03 and M30, M."""
    spec = a.spec
    ns = {"M": a.forces["newton_euler"].driver_torque[k]}
    vals = a.forces["newton_euler"].values()
    for j in spec.joints:
        p, q = (spec.number(l) for l in j.links)
        for c in ("x", "y"):
            v = vals[f"joint.{j.name}.f{c}"][k]
            ns[f"F{p}{q}{c}"], ns[f"F{q}{p}{c}"] = v, -v
        if j.type == "T":
            v = vals[f"joint.{j.name}.moment"][k]
            ns[f"M{p}{q}"], ns[f"M{q}{p}"] = v, -v
    return ns


def _pages(pdf: Path) -> int:
    return len(re.findall(rb"/Type\s*/Page(?![s\w])", pdf.read_bytes()))


# ------------------------------------------------------------------------------ 4.6

def linear_form(eq, ns: dict, keep: list[str]):
    """The printed numeric equation ``lhs = rhs`` as lhs - rhs = sum c_u u + c0 over the
    symbols ``keep``, every other symbol taken at its solved value."""
    import sympy
    syms = {u: sympy.Symbol(u) for u in keep}
    env = {**{k: v for k, v in ns.items() if k not in syms}, **syms}
    sides = [eval(render(side, "py") or "0", {}, dict(env)) for side in eq.numeric.sides]
    expr = sympy.expand(sympy.sympify(sides[0]) - sympy.sympify(sides[1]))
    coeffs = {u: float(expr.coeff(syms[u])) for u in keep}
    const = float(expr.subs({s: 0 for s in syms.values()}))
    return coeffs, const


# eq. -> (link, axis or "moment", {unknown: coefficient of lhs - rhs}, constant), the book's
# numbers: m a = sum F with the values found before substituted (4.55-4.57), corrected by
# the errata (4.57 has F01x, not F01y twice). 6 printed digits: compared to 1e-5.
F21x, F21y = (400 + 7 * S2) / 4, -5 * (84 + S2) / 4
BOOK_4_6_1 = {
    "4.50": (3, "x", {"F23x": -1}, -S2 - 100),
    "4.51": (3, "y", {"F23y": -1, "F03y": -1}, 10),
    "4.52": (2, "x", {"F32x": -1, "F12x": -1}, -3 * S2 / 4),
    "4.53": (2, "y", {"F32y": -1, "F12y": -1}, -S2 / 4 + 10),
    "4.54": (2, "moment", {"F32y": -S2 / 4, "F32x": -S2 / 4, "F12y": S2 / 4, "F12x": S2 / 4},
             0),
    "4.55": (1, "x", {"F01x": -1}, -S2 / 4 - F21x),
    "4.56": (1, "y", {"F01y": -1}, -S2 / 4 - F21y + 10),
    "4.57": (1, "moment", {"F01y": S2 / 4, "F01x": -S2 / 4, "M": -1},
             -((S2 / 2 - S2 / 4) * F21y - (S2 / 2 - S2 / 4) * F21x)),
}


def _ne_equation(m, link: int, what: str):
    for e in equations(m):
        src = e.source
        if src.bodies != ((("crank", "rod", "slider")[link - 1]),):
            continue
        if (what == "moment") == (src.kind == "moment") and (what == "moment" or
                                                             src.axis == what):
            return e
    raise AssertionError(f"no equation of link {link} {what}")


@pytest.mark.parametrize("eq_no", list(BOOK_4_6_1))
def test_4_6_1_newton_euler_prints_eqs_4_50_to_4_57_with_the_book_coefficients(textbook,
                                                                              eq_no):
    a = textbook["4.6"]["analysis"]
    k = a.kinematics.at(45)
    m = method(textbook["4.6"]["model"], "newton_euler")
    link, what, coeffs, const = BOOK_4_6_1[eq_no]
    e = _ne_equation(m, link, what)
    got, got_const = linear_form(e, _namespace(a, k), list(coeffs))
    for u, c in coeffs.items():
        assert got[u] == pytest.approx(c, abs=1e-5), (eq_no, u, render(e.numeric, "plain"))
    assert got_const == pytest.approx(const, abs=1e-4), (eq_no, render(e.numeric, "plain"))
    # nothing else: no F03x (the slider's reaction is normal to i), no zero terms; the book
    # substitutes F21 found from links 3 and 2, one system here keeps it a symbol
    names = set(re.findall(r"[A-Z]\w*", render(e.numeric, "py")))
    assert names <= set(coeffs) | ({"F21x", "F21y"} if link == 1 else set()), (eq_no, names)


def test_4_6_1_newton_euler_textbook_form(textbook):
    """The lines as the book writes them: unit mass times acceleration with a centre dot,
    coefficients simplified (no '- (-0.35)'), zero terms and F03x left out."""
    lines = numeric_lines(method(textbook["4.6"]["model"], "newton_euler"))
    assert "1 · (-1.41421) = F23x + 100" in lines                          # 4.50
    assert "0 = F23y + F03y - 10" in lines                                  # 4.51
    assert ("0 = -0.353553 F12y - 0.353553 F12x + 0.353553 F32y + 0.353553 F32x"
            in lines)                                                       # 4.54
    assert ("0 = -0.353553 F01y + 0.353553 F01x + 0.353553 F21y - 0.353553 F21x + M"
            in lines)                                                       # 4.57
    assert not any("(-" in l.replace("· (-", "") or "+ -" in l or "- -" in l for l in lines)
    assert "M = 151.492 N·m" in result_lines(method(textbook["4.6"]["model"], "newton_euler"))


def test_4_6_2_dalembert_groups_the_forces_at_C2_as_the_book(textbook):
    lines = numeric_lines(method(textbook["4.6"]["model"], "dalembert"))
    assert "F23x + 1.41421 + 100 = 0" in lines                             # 4.58
    assert "F12x + F32x + 1.06066 = 0" in lines                            # 4.60
    # 4.62: r_BC x F32 + r_BC2 x (Fin2 + G2) about B
    assert ("0.707107 F32y + 0.707107 F32x + 0.353553 (0.353553 - 10) + 0.353553 · 1.06066 "
            "= 0" in lines)
    # 4.65: the crank about A
    assert ("0.707107 F21y - 0.707107 F21x + 0.353553 (0.353553 - 10) - 0.353553 · 0.353553 "
            "+ M = 0" in lines)
    sym = [render(e.symbolic, "plain") for e in equations(method(
        textbook["4.6"]["model"], "dalembert"))]
    assert "sum M_B^(2) = r_BC x F32 + r_BC2 x (Fin2 + G2) = 0" in sym


def test_4_6_3_dyad_equations_and_results(textbook):
    m = method(textbook["4.6"]["model"], "dyad")
    lines = numeric_lines(m)
    assert "F12x + 1.06066 + 1.41421 + 100 = 0" in lines                  # 4.66
    assert "F12y + F03y + 0.353553 - 10 - 10 = 0" in lines                # 4.67
    assert ("-0.707107 F12y - 0.707107 F12x - 0.353553 (0.353553 - 10) - 0.353553 · 1.06066 "
            "= 0" in lines)                                               # 4.68
    res = result_lines(m)
    for r in ("F12 = -102.475 i + 106.768 j N", "F03 = -87.1213 j N",
              "F01 = -102.828 i + 116.414 j N", "M = 151.492 N·m"):
        assert r in res
    # the crank's step substitutes F21 = -F12 found by the dyad's step
    assert any(l.startswith("-0.707107 · 106.768 - 0.707107 · 102.475") for l in lines)


def test_4_6_4_contour_equations_corrected_by_the_errata(textbook):
    m = method(textbook["4.6"]["model"], "contour")
    lines = numeric_lines(m)
    assert "F23x + 1.41421 + 100 = 0" in lines                             # 4.69
    assert "F12x + 1.06066 + 1.41421 + 100 = 0" in lines                   # 4.72 (errata)
    assert "F01x + 0.353553 + 1.06066 + 1.41421 + 100 = 0" in lines        # 4.75 (errata)
    # F03y from the moments of 3&2 about B, Fin3, G3 and Fext grouped at C
    assert any(l.startswith("0.707107 F03y") and "0.707107 (100 + 1.41421)" in l
               for l in lines)
    res = result_lines(m)
    for r in ("F03 = -87.1213 j N", "F23 = -101.414 i + 97.1213 j N",
              "F12 = -102.475 i + 106.768 j N", "F01 = -102.828 i + 116.414 j N",
              "M = 151.492 N·m"):
        assert r in res


def test_4_6_kinematics_derivation(textbook):
    """r_B, v_B, a_B of the crank, then the dyad's velocity and acceleration loops: omega_2 =
    -1, v_C = -sqrt2, alpha_2 = 0, a_C = -sqrt2 (textbook 4.6)."""
    blocks = textbook["4.6"]["model"].angles[0].kinematics
    text = "\n".join(render(x if kind == "found" else y, "plain")
                     for b in blocks for kind, x, y in b.items if kind != "text")
    assert "r_B = AB (cos theta1 i + sin theta1 j) = 1 (cos 45deg i + sin 45deg j)" in text
    assert "= -0.707107 i + 0.707107 j m/s" in text                        # v_B
    assert "omega2 = -1 rad/s, v30 = -1.41421 m/s" in text
    assert "alpha2 = 0 rad/s^2, a30 = -1.41421 m/s^2" in text
    assert "a_C2 = a_B + alpha2 k x r_BC2 - omega2^2 r_BC2" in text


@pytest.mark.parametrize("key", ["4.6", "4.7"])
def test_every_printed_equation_balances(textbook, key):
    """Evaluate every 'with numbers' line with the solved values: it must balance to the
    rounding of its 6-digit numbers, and agree with Equation.evaluate; likewise every
    component line of the kinematics derivation with the rates it solves for."""
    a, model = textbook[key]["analysis"], textbook[key]["model"]
    k = a.kinematics.at(a.spec.at[0])
    ns = _namespace(a, k)
    values = a.forces["newton_euler"].values()
    scale = max(1.0, *(abs(float(v)) for v in ns.values()))
    count = 0
    for m in model.angles[0].methods:
        for e in equations(m):
            sides = [eval(render(side, "py") or "0", {}, dict(ns)) for side in e.numeric.sides]
            assert abs(sides[0] - sides[1]) < 1e-4 * scale, render(e.numeric, "plain")
            assert abs(e.source.evaluate(values)[k]) < 1e-6 * scale
            count += 1
    assert count > 20
    loops = 0
    for b in model.angles[0].kinematics:
        for kind, lead, mth in b.items:
            if kind == "eq" and lead and lead[0].startswith("projected"):
                for e in mth:
                    sides = [eval(render(s, "py") or "0", {}, dict(b.values)) for s in e.sides]
                    assert abs(sides[0] - sides[1]) < 1e-4 * max(1.0, abs(sides[0])), \
                        render(e, "plain")
                    loops += 1
    assert loops >= 4


def test_4_6_sheet_fits_in_8_pages_with_its_figures(textbook):
    """Issue 15: the slider-crank sheet at 45 deg, every method, figures included."""
    paths = textbook["4.6"]["paths"]
    assert [p.name for p in paths] == ["solution.md", "solution.pdf", "problem.md",
                                       "problem.pdf"]
    assert all(p.read_bytes().startswith(b"%PDF") for p in paths if p.suffix == ".pdf")
    assert 1 <= _pages(paths[1]) <= 8
    md = textbook["4.6"]["md"]
    for ascii_math in (r"(?<!\\)omega_1", r"sum F \. v", "M_newton_euler", r"\(1\)\(",
                       r"- \(-[\d.]+\)(?!\^)"):        # - (-0.35) F, but - (-1)^2 r is a square
        assert not re.search(ascii_math, md), ascii_math


@pytest.mark.parametrize("key", ["4.6", "4.7"])
def test_one_free_body_diagram_per_link_and_reference_angle(textbook, key):
    a, model, d = textbook[key]["analysis"], textbook[key]["model"], textbook[key]["dir"]
    links = len(a.spec.links)
    for am in model.angles:
        assert len(am.fbds) == links
        for f in am.fbds + [am.figure]:
            assert (d / f.path).is_file() and (d / f.path).read_bytes().startswith(b"<?xml")
    assert len(list((d / "figures").glob("sheet-*-fbd-*.svg"))) == links * len(a.spec.at)
    # the slider's diagram names the actions its equations use
    svg = (d / model.angles[0].fbds[-1].path).read_text()
    assert "ext" in svg and "in" in svg
    assert render_markdown(model).count("figures/sheet-") == links + 1


def test_the_verb_agrees_with_the_number_of_equations(textbook):
    """"(41) gives M = ..." for the power balance's one equation, "(38)–(40) give" for
    several."""
    model, md = textbook["4.6"]["model"], textbook["4.6"]["md"]
    steps = [s for m in model.angles[0].methods for s in m.steps]
    power = method(model, "power").steps[0]
    n = power.equations[0].number
    assert f"**({n}) gives** $M = 151.492" in md
    assert not re.search(r"\*\*\(\d+\) give\*\*", md)
    assert not re.search(r"\*\*\(\d+\)–\(\d+\) gives\*\*", md)
    assert len(power.equations) == 1 and power.cited == f"({n}) gives"
    assert all(s.cited.endswith(" give") for s in steps if len(s.equations) > 1)


@pytest.mark.parametrize("key", ["4.6", "4.7"])
def test_free_body_sentence_names_the_bodies_its_equations_use(textbook, key):
    """A step's "Free body" sentence lists the free bodies of its equations (a slider's normal
    constraint is not one), each once: the contour's step for joint C of 4.6 writes one
    equation for the slider and one for the rod, not one for the rod and slider together."""
    a, model = textbook[key]["analysis"], textbook[key]["model"]
    spec = a.spec
    if key == "4.6":
        md = textbook[key]["md"]
        assert "#### Step 2: Joint C (loop 0-1-2-3-0)\n\nFree bodies: link 3 (slider) and " \
            "link 2 (rod). Unknowns" in md
        assert "Free bodies: link 2 (rod) and links 2 &amp; 3 (rod, slider). Unknowns" in md
        assert "Free body: links 1 &amp; 2 &amp; 3 (crank, rod, slider). Unknowns: $M$." in md

    def said(bodies):
        ls = sorted((spec.link(b) for b in bodies), key=lambda l: l.number)
        return (f"link {ls[0].number} ({ls[0].name})" if len(ls) == 1 else
                "links " + " & ".join(str(l.number) for l in ls) + " ("
                + ", ".join(l.name for l in ls) + ")")

    for m in model.angles[0].methods:
        for s in m.steps:
            used = list(dict.fromkeys(frozenset(e.source.bodies) for e in s.equations
                                      if e.source.kind != "constraint"))
            assert s.free_body.startswith("Free body: " if len(used) == 1 else "Free bodies: ")
            rest = s.free_body.split(": ", 1)[1]
            for b in used:
                assert said(b) in rest, (m.name, s.number, said(b), s.free_body)
                rest = rest.replace(said(b), "", 1)
            assert re.fullmatch(r"(, | and )*", rest), (m.name, s.number, s.free_body)


def test_joint_names_and_coinciding_mass_centres_read_as_the_textbook_writes_them(textbook):
    """C_T is typeset C with subscript T in the tables and messages (a method's name such as
    newton_euler stays text); a centre of mass on a joint is said to be there."""
    from mechreport.report.sheet.symbols import rich_label
    md = textbook["4.6"]["md"]
    assert "| $C_{T}$ | T | 0 (ground) on 3 (slider) | $\\mathbf{F}_{03}$ |" in md
    assert "C\\_T" not in md and "$C_{3}$ is at $C$." in md and "C_{3} = C" not in md
    assert "| $\\mathbf{F}_{3ext}$ | 3 (slider) |" in md
    assert [render(x, "plain") for x in rich_label("dyad B_R C_R C_T: singular")[1::2]] == \
        ["B_R", "C_R", "C_T"]
    assert rich_label("force equations singular (newton_euler)") == \
        ["force equations singular (newton_euler)"]
    assert "| $C_{T}$ | slider (T) |" in render_problem_markdown(
        build_problem(textbook["4.6"]["analysis"]))


# ------------------------------------------------------------------------------ 4.7

R_RTR_RTR = ["F05 = 268.165 i + 135.057 j N", "F34 = -268.072 i - 134.583 j N",
             "F03 = -256.745 i - 272.179 j N", "F12 = -11.4028 i + 137.993 j N",
             "F01 = -11.4214 i + 138.092 j N", "M = 17.5356 N·m",
             # our joints report F54 = -F45 and F32 = -F23
             "F54 = 268.109 i + 134.647 j N", "F32 = 11.3762 i - 137.93 j N"]


@pytest.mark.parametrize("name", ["newton_euler", "dalembert", "dyad", "contour"])
def test_4_7_r_rtr_rtr_results(textbook, name):
    res = result_lines(method(textbook["4.7"]["model"], name))
    for r in R_RTR_RTR:
        assert r in res, (name, r)


def test_4_7_kinematics_omega5_alpha3_alpha5(textbook):
    """Textbook 4.7 (three printed decimals, truncated: errata): omega_5 = 0.917,
    alpha_3 = 14.568, alpha_5 = -5.771 rad/s^2, from the dyads' loop equations."""
    found = {}
    for b in textbook["4.7"]["model"].angles[0].kinematics:
        found.update(b.values)
    assert found["omega5"] == pytest.approx(0.917, abs=1e-3)
    assert found["alpha3"] == pytest.approx(14.568, abs=1e-3)
    assert found["alpha5"] == pytest.approx(-5.771, abs=1e-3)


def test_4_7_application_points(textbook):
    m = method(textbook["4.7"]["model"], "newton_euler")
    pts = [render(pe, "plain") for s in m.steps for _, _, pe in s.points]
    assert "r_P = -0.149492 i + 0.0476701 j m" in pts             # P of F45, textbook 4.7.1
    assert "r_P = 0.121243 i + 0.07 j m" in pts                   # Q of F23


# ------------------------------------------------------------------------------ structure

def test_sheet_follows_the_equation_objects(textbook):
    """Change one Term's constant in a copy of a method's steps: the printed number changes."""
    a = textbook["4.6"]["analysis"]
    steps = copy.deepcopy(a.worked_steps("dyad"))
    eq = steps[0].equations[0]                    # sum F^(2&3) . i
    t = next(t for t in eq.terms if t.action.symbol == "F3ext")
    eq.terms[eq.terms.index(t)] = replace(t, action=replace(t.action, value=t.action.value * 0
                                                            + (123.5, 0.0)),
                                          const=t.const * 0 + 123.5)

    class Changed(type(a)):
        def worked_steps(self, method):
            return steps if method == "dyad" else super().worked_steps(method)
    changed = Changed(**{f.name: getattr(a, f.name) for f in fields(a)})
    m = method(build_sheet(changed, SheetOptions(methods=("dyad",))), "dyad")
    assert "F12x + 1.06066 + 1.41421 + 123.5 = 0" in numeric_lines(m)
    assert "F12x + 1.06066 + 1.41421 + 123.5 = 0" not in \
        numeric_lines(method(textbook["4.6"]["model"], "dyad"))


def test_power_balance_last_and_in_real_symbols(textbook):
    methods = textbook["4.6"]["model"].angles[0].methods
    assert [m.name for m in methods] == ["newton_euler", "dalembert", "dyad", "contour",
                                         "power"]
    power = methods[-1]
    assert "M = 151.492 N·m" in result_lines(power)
    sym = render(equations(power)[0].symbolic, "tex")
    assert r"\omega_{1}" in sym and r"\mathbf{v}_{C_{2}}" in sym


# ------------------------------------------------------------------------------ problem

def _answers(a, k) -> set[str]:
    """Every result a student is asked to find, as the sheets print them (6 and 4 digits):
    reactions, their magnitudes, the driver's effort, link rates, point velocities and
    accelerations, inertia forces and couples."""
    out = set()
    kin = a.kinematics

    def add(x):
        x = float(x)
        if abs(x) > 1e-9 and abs(abs(x) - 1) > 1e-9:    # 0 and 1 are everywhere in data
            out.update({fmt(abs(x)), fmt(abs(x)).rstrip("0"), f"{abs(x):.4g}"})
    for res in a.forces.values():
        for v in res.values().values():
            add(v[k])
        for r in res.reactions.values():
            add(r.f[k])
    for link in a.spec.links:
        if link.name != a.spec.driver.link:
            add(kin.omega[k, link.number])
            add(kin.alpha[k, link.number])
        s = a.link_state(link.name)
        for v in (*s.v[k], *s.a[k], *(-s.mass * s.a[k])):
            add(v)
    return out


@pytest.mark.parametrize("key", ["4.6", "4.7"])
def test_problem_version_contains_none_of_the_answers(textbook, key):
    a, d = textbook[key]["analysis"], textbook[key]["dir"]
    k = a.kinematics.at(a.spec.at[0])
    md = (d / "problem.md").read_text()
    svg = (d / "figures" / f"sheet-{fmt(a.spec.at[0])}-mechanism.svg").read_text()
    tokens = set(re.findall(r"\d+(?:\.\d+)?(?:e[-+]\d+)?", md + svg))
    leaked = _answers(a, k) & tokens
    assert not leaked, leaked
    # ... but it is a problem: data, figure, what to find
    assert "## Data" in md and "## Find" in md and "sheet-" in md
    assert "reaction of every joint" in md
    if key == "4.6":
        assert "AB = 1 m" in md and "(100, 0) N" in md
    # the check can fail: the answer key holds them
    assert _answers(a, k) & set(re.findall(r"\d+(?:\.\d+)?", textbook[key]["md"]))


# ------------------------------------------------------------------------------ exact

def test_exact_closed_forms_4_6(textbook):
    pytest.importorskip("sympy")
    model = build_sheet(textbook["4.6"]["analysis"], SheetOptions(exact=True))
    md = render_markdown(model)
    assert r"M = 3 + 105\sqrt{2}" in md                           # textbook 4.6
    assert r"F_{01x} = -100 - 2\sqrt{2}" in md                    # -2 (50 + sqrt2)
    assert r"F_{12x} = -100 - \frac{7\sqrt{2}}{4}" in md           # -(400 + 7 sqrt2)/4
    assert r"\omega_{2} = -1" in md                               # the kinematics too
    assert "rational combinations of √2" in md


def test_exact_says_when_there_is_none_4_7(textbook):
    pytest.importorskip("sympy")
    model = build_sheet(textbook["4.7"]["analysis"], SheetOptions(exact=True))
    rows = model.angles[0].answers
    assert all("none found" in "".join(x for x in r[-1] if isinstance(x, str))
               for r in rows)
    assert "rational combinations of √3" in model.exact_note


def test_exact_without_sympy_says_how_to_install(monkeypatch):
    import sys
    from mechreport.report.sheet.exact import ExactUnavailable, require_sympy
    monkeypatch.setitem(sys.modules, "sympy", None)
    with pytest.raises(ExactUnavailable, match=r"pip install 'mechreport\[exact\]'"):
        require_sympy()


# ------------------------------------------------------------------------------ choice

def for_sheet(a, options):
    """What `build` hands the sheet: ``a``, or the spec analysed again with the sheet's
    angles the sweep does not have."""
    spec = sheet_spec(a.spec, options)
    return a if spec is a.spec else analyse(spec, tol=a.tol)


def test_sheet_methods_and_angles_are_chosen(textbook):
    a = textbook["4.6"]["analysis"]
    options = SheetOptions(methods=("contour", "dyad"), angles=(30.0, 45.0))
    model = build_sheet(sheet_analysis(for_sheet(a, options), options), options)
    assert [am.angle for am in model.angles] == [30.0, 45.0]
    assert [m.name for m in model.angles[0].methods] == ["contour", "dyad"]
    problem = render_problem_markdown(build_problem(a, options))
    assert "φ = 30°, φ = 45°" in problem and "Newton" not in problem


def test_sheet_angle_outside_the_sweep_is_analysed(textbook):
    a = textbook["4.6"]["analysis"]
    options = SheetOptions(methods=("dyad",), angles=(37.5,))
    b = sheet_analysis(for_sheet(a, options), options)
    assert b is not a and b.kinematics.index_of(37.5) is not None
    model = build_sheet(b, options)
    assert model.angles[0].title == "Crank angle 37.5°" and model.angles[0].methods


def test_cli_sheet_options_are_checked(tmp_path, capsys):
    from mechreport.app.cli import main
    spec = str(ROOT / "specs" / "slider_crank.yaml")
    assert main(["build", spec, "-o", str(tmp_path), "--exact"]) == 2
    assert "--exact needs --sheet" in capsys.readouterr().err
    with pytest.raises(SystemExit) as exc:
        main(["build", spec, "-o", str(tmp_path), "--sheet", "--sheet-methods", "dyads"])
    assert exc.value.code == 2
    err = capsys.readouterr().err
    assert "unknown method 'dyads'" in err and "newton_euler, dalembert, dyad" in err
    for bad in ("45,x", "45,45"):
        with pytest.raises(SystemExit):
            main(["build", spec, "-o", str(tmp_path), "--sheet", "--sheet-angles", bad])
        assert "separated by commas, each once" in capsys.readouterr().err
    assert not any(tmp_path.iterdir())


def test_a_sheet_at_a_singular_angle_is_an_error_not_an_empty_answer_key(textbook):
    """4.6 at 90 deg: the slider-crank's dead centre is left out of the analysis; a sheet
    there would be a problem without an answer. Both explicit angles and the spec's own are
    refused when nothing can be solved; a problem lists only angles that have answers."""
    from mechreport.errors import AnalysisError
    a = textbook["4.6"]["analysis"]
    with pytest.raises(AnalysisError, match=r"--sheet-angles: φ = 90°: .*singular"):
        options = SheetOptions(angles=(45.0, 90.0))
        sheet_analysis(for_sheet(a, options), options)
    options = SheetOptions(angles=(45.0,))
    assert sheet_analysis(for_sheet(a, options), options).kinematics.index_of(45) is not None
    options = SheetOptions(angles=(45.0, 89.0))
    b = sheet_analysis(for_sheet(a, options), options)
    assert b.kinematics.index_of(89.0) is not None


# ------------------------------------------------------------------------------ every spec

@pytest.mark.parametrize("spec", SPECS, ids=[p.stem for p in SPECS])
def test_sheet_model_for_every_spec(spec):
    a = analyse(spec)
    model = build_sheet(a)
    text = render_markdown(model)
    render_typst(model)
    # no "-0" printed as a number (a description's "0-1-2-3-0 loop" is not one)
    assert not re.search(r"(?<![\w.])-0(?:[ $]|$)", text, re.M) and "nan" not in text
    for angle in a.spec.at:
        assert any(am.angle == angle and am.title in text for am in model.angles)
    assert all(len(am.fbds) == len(a.spec.links) for am in model.angles if not am.skipped)


@pytest.mark.parametrize("stem", ["hydraulic_boom", "class_iii_triad"])
def test_sheet_pdf_for_a_linear_actuator_and_a_triad(stem, tmp_path):
    spec = next(p for p in SPECS if p.stem == stem)
    paths = write_sheet(analyse(spec), tmp_path)
    assert all(p.read_bytes().startswith(b"%PDF") for p in paths if p.suffix == ".pdf")


def test_flagged_reference_angle_is_skipped_with_a_note():
    from mechreport.spec import load_spec
    spec = load_spec(ROOT / "specs" / "slider_crank.yaml")
    spec = replace(spec, at=(45.0, 90.0))         # 90 deg: the slider sits on A (singular)
    model = build_sheet(analyse(spec), SheetOptions(methods=("dyad",)))
    assert model.angles[1].skipped
    md = render_markdown(model)
    assert "## Crank angle 90°" in md and "left out" in md
