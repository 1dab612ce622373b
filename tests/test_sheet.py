"""Worked solution sheets (issue 5): the textbook's equations and results of 4.6 and 4.7, a
sheet for every spec, exact mode, and that the sheet is generated from the equation objects."""
from __future__ import annotations

import re

import copy
from dataclasses import replace
from pathlib import Path

import pytest

from mechreport.analysis import analyse
from mechreport.report.sheet import build_sheet, render_markdown, write_sheet
from mechreport.report.sheet_math import math

ROOT = Path(__file__).resolve().parents[1]
SPECS = sorted((ROOT / "specs").glob("*.yaml"))


@pytest.fixture(scope="module")
def textbook(tmp_path_factory):
    """Analyses, sheet models and written sheets of 4.6 and 4.7 (built once)."""
    out = {}
    for key, stem in (("4.6", "slider_crank"), ("4.7", "r_rtr_rtr")):
        a = analyse(ROOT / "specs" / f"{stem}.yaml")
        d = tmp_path_factory.mktemp(stem)
        paths = write_sheet(a, d)
        out[key] = {"analysis": a, "model": build_sheet(a), "md": paths[0].read_text(),
                    "paths": paths}
    return out


def method(model, name, angle_index=0):
    return next(m for m in model.angles[angle_index].methods if m.name == name)


def numeric_lines(m) -> list[str]:
    return [math(e.numeric, "plain") for s in m.steps for e in s.equations]


def result_lines(m) -> list[str]:
    return [math(r, "plain") for s in m.steps for r, _ in s.results] + \
        [math(m.torque, "plain")]


def test_files_written(textbook):
    for item in textbook.values():
        md, pdf = item["paths"]
        assert md.name == "solution.md" and pdf.name == "solution.pdf"
        assert pdf.read_bytes().startswith(b"%PDF")


def test_slider_crank_newton_euler_equations(textbook):
    m = method(textbook["4.6"]["model"], "newton_euler")
    lines = numeric_lines(m)
    assert "(1)(-1.41421) = F23x + F03x + 100" in lines          # eq. 4.50 (plus F03x, = 0)
    assert "0 = F23y + F03y - 10" in lines                        # eq. 4.51
    assert "(1)(-1.06066) = F12x + F32x" in lines                 # eq. 4.52
    assert "(1)(-0.353553) = F12y + F32y - 10" in lines           # eq. 4.53
    # eq. 4.54: 0 = (xC - xC2) F32y - (yC - yC2) F32x + (xB - xC2) F12y - (yB - yC2) F12x
    assert ("0 = (-0.353553) F12y - (0.353553) F12x + (0.353553) F32y - (-0.353553) F32x"
            in lines)
    assert "M = 151.492 N·m" in result_lines(m)


def test_slider_crank_dalembert_equations(textbook):
    m = method(textbook["4.6"]["model"], "dalembert")
    lines = numeric_lines(m)
    assert "F23x + F03x + 1.41421 + 100 = 0" in lines             # eq. 4.58
    assert "F23y + F03y - 10 = 0" in lines                        # eq. 4.59
    assert "F12x + F32x + 1.06066 = 0" in lines                   # eq. 4.60
    assert "F12y + F32y + 0.353553 - 10 = 0" in lines             # eq. 4.61
    # eq. 4.62, moments about B
    assert "(0.707107) F32y - (-0.707107) F32x + 0.5 - 3.53553 = 0" in lines


def test_slider_crank_dyad_equations_and_results(textbook):
    m = method(textbook["4.6"]["model"], "dyad")
    lines = numeric_lines(m)
    assert "F12x + F03x + 1.06066 + 1.41421 + 100 = 0" in lines   # eq. 4.66
    assert "F12y + F03y + 0.353553 - 10 - 10 = 0" in lines        # eq. 4.67
    assert "(-0.707107) F12y - (0.707107) F12x - 0.5 + 3.53553 = 0" in lines   # eq. 4.68
    res = result_lines(m)
    assert "F12 = -102.475 i + 106.768 j N" in res
    assert "F03 = -87.1213 j N" in res
    assert "F01 = -102.828 i + 116.414 j N" in res
    assert "M = 151.492 N·m" in res
    # the crank step substitutes F21 = -F12 found by the dyad step
    assert "(0.707107)(-106.768) - (0.707107)(102.475) - 3.53553 + M = 0" in lines


def test_slider_crank_contour_equations_and_results(textbook):
    m = method(textbook["4.6"]["model"], "contour")
    lines = numeric_lines(m)
    # F03y from moments of 3&2 about B: 3/2 - 5/sqrt2 + 45 sqrt2 + F03y/sqrt2 = 0
    assert any(l.startswith("(0.707107) F03y") and "70.7107" in l for l in lines)
    assert "F23x + 1.41421 + 100 = 0" in lines                    # eq. 4.69
    assert "(0.707107) F32y - (-0.707107) F32x + 0.5 - 3.53553 = 0" in lines     # eq. 4.70
    assert "(-0.707107) F12y - (0.707107) F12x - 0.5 + 3.53553 = 0" in lines     # eq. 4.71
    assert "F12x + 1.06066 + 1.41421 + 100 = 0" in lines          # eq. 4.72 (corrected)
    assert "(-0.707107) F01y - (-0.707107) F01x + 3.53553 + M = 0" in lines     # eq. 4.73
    assert "(-1.41421) F01y - 0.5 + 10.6066 + M - 0.5 + 3.53553 = 0" in lines   # eq. 4.74
    assert "F01x + 0.353553 + 1.06066 + 1.41421 + 100 = 0" in lines             # eq. 4.75
    res = result_lines(m)
    for r in ("F03 = -87.1213 j N", "F23 = -101.414 i + 97.1213 j N",
              "F12 = -102.475 i + 106.768 j N", "F01 = -102.828 i + 116.414 j N",
              "M = 151.492 N·m"):
        assert r in res


def test_slider_crank_markdown(textbook):
    md = textbook["4.6"]["md"]
    assert r"(1)(-1.41421) = F_{23x} + F_{03x} + 100" in md
    assert r"M = 151.492\,\mathrm{N\,m}" in md
    assert r"\mathbf{F}_{01} = -102.828\,\mathbf{i} + 116.414\,\mathbf{j}" in md
    assert md.count("$$") % 2 == 0
    for heading in ("Newton-Euler", "D'Alembert", "Dyad", "Contour", "Power balance"):
        assert f"### {heading}" in md


def test_power_balance_last(textbook):
    methods = textbook["4.6"]["model"].angles[0].methods
    assert [m.name for m in methods] == ["newton_euler", "dalembert", "dyad", "contour",
                                         "power"]
    assert "M = 151.492 N·m" in result_lines(methods[-1])


R_RTR_RTR = ["F05 = 268.165 i + 135.057 j N", "F34 = -268.072 i - 134.583 j N",
             "F03 = -256.745 i - 272.179 j N", "F12 = -11.4028 i + 137.993 j N",
             "F01 = -11.4214 i + 138.092 j N", "M = 17.5356 N·m",
             # our joints report F54 = -F45 and F32 = -F23
             "F54 = 268.109 i + 134.647 j N", "F32 = 11.3762 i - 137.93 j N"]


@pytest.mark.parametrize("name", ["newton_euler", "dalembert", "dyad", "contour"])
def test_r_rtr_rtr_results(textbook, name):
    res = result_lines(method(textbook["4.7"]["model"], name))
    for r in R_RTR_RTR:
        assert r in res, (name, r)


def test_r_rtr_rtr_application_points(textbook):
    m = method(textbook["4.7"]["model"], "newton_euler")
    pts = [math(pe, "plain") for s in m.steps for _, _, pe in s.points]
    assert "r_P = -0.149492 i + 0.0476701 j m" in pts             # P of F45, textbook 4.7.1
    assert "r_P = 0.121243 i + 0.07 j m" in pts                   # Q of F23


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


@pytest.mark.parametrize("key", ["4.6", "4.7"])
def test_every_printed_equation_holds(textbook, key):
    """Evaluate every 'with numbers' line with the solved values: it must balance to the
    rounding of its 6-digit numbers, and agree with Equation.evaluate."""
    a, model = textbook[key]["analysis"], textbook[key]["model"]
    k = a.kinematics.at(a.spec.at[0])
    ns = _namespace(a, k)
    values = {u: v for u, v in a.forces["newton_euler"].values().items()}
    count = 0
    for m in model.angles[0].methods:
        for s in m.steps:
            for e in s.equations:
                sides = [eval(math(side, "py") or "0", {}, dict(ns)) for side in e.numeric.sides]
                scale = max(1.0, *(abs(float(v)) for v in ns.values()))
                assert abs(sides[0] - sides[1]) < 1e-4 * scale, math(e.numeric, "plain")
                ref = e.source.evaluate(values)[k]
                assert abs(ref) < 1e-6 * scale
                count += 1
    assert count > 20


def test_sheet_follows_the_equation_objects(textbook):
    """Change one Term's constant in a copy of a method's steps: the printed number changes."""
    a = textbook["4.6"]["analysis"]
    res = a.forces["dyad"]
    steps = copy.deepcopy(res.steps)
    eq = steps[0].equations[0]                    # sum F^(2&3) . i
    t = next(t for t in eq.terms if t.action.symbol == "F3ext")
    eq.terms[eq.terms.index(t)] = replace(t, const=t.const * 0 + 123.5)
    forces = dict(a.forces)
    forces["dyad"] = res.with_steps(steps)
    changed = replace(a, forces=forces)
    m = method(build_sheet(changed), "dyad")
    assert "F12x + F03x + 1.06066 + 1.41421 + 123.5 = 0" in numeric_lines(m)
    assert "F12x + F03x + 1.06066 + 1.41421 + 123.5 = 0" not in \
        numeric_lines(method(textbook["4.6"]["model"], "dyad"))


def test_exact_mode_slider_crank(textbook):
    model = build_sheet(textbook["4.6"]["analysis"], exact=True)
    m = method(model, "contour")
    assert math(m.torque_exact, "plain") == "M = 3 + 105 sqrt(2)"
    md = render_markdown(model)
    assert r"3 + 105\sqrt{2}" in md
    assert r"F_{01x} = -100 - 2\sqrt{2}" in md


def test_exact_mode_rejects_non_closed_forms(textbook):
    model = build_sheet(textbook["4.7"]["analysis"], exact=True)
    assert all(m.torque_exact is None for m in model.angles[0].methods)


@pytest.mark.parametrize("spec", SPECS, ids=[p.stem for p in SPECS])
def test_sheet_renders_for_every_spec(spec, tmp_path):
    a = analyse(spec)
    md, pdf = write_sheet(a, tmp_path)
    text = md.read_text()
    assert pdf.read_bytes().startswith(b"%PDF")
    # no "-0" printed as a number (a description's "0-1-2-3-0 loop" is not one)
    assert not re.search(r"(?<![\w.])-0(?:[ $]|$)", text, re.M) and "nan" not in text
    assert text.count("$$") % 2 == 0
    for angle in a.spec.at:
        assert f"## Crank angle {angle:g} deg" in text


def test_flagged_reference_angle_is_skipped_with_a_note(tmp_path):
    from mechreport.spec import load_spec
    spec = load_spec(ROOT / "specs" / "slider_crank.yaml")
    spec = replace(spec, at=(45.0, 90.0))         # 90 deg: the slider sits on A (singular)
    a = analyse(spec)
    model = build_sheet(a)
    assert model.angles[1].skipped
    md = render_markdown(model)
    assert "## Crank angle 90 deg" in md and "left out" in md
