"""Problem sheets (issue 46): never the spec's description; a statement written from the data
that defines its coordinates, or the spec's own ``sheet.statement``; a static problem asks for
no velocity, acceleration or inertia force and draws no speed; textbook notation."""
from __future__ import annotations

import re
from pathlib import Path

import pytest

from mechreport.pipeline import analyse
from mechreport.report.sheet import build_problem, render_problem_markdown, render_problem_typst
from mechreport.report.sheet.statement import eng, sci
from mechreport.spec import parse_spec

ROOT = Path(__file__).resolve().parents[2]
SPECS = sorted((ROOT / "specs").glob("*.yaml"))


def problem_md(analysis) -> str:
    return render_problem_markdown(build_problem(analysis))


def _description_lines(spec) -> list[str]:
    return [line.strip() for line in spec.description.splitlines() if len(line.strip()) > 25]


def test_static_press_asks_no_velocity_and_never_copies_its_description():
    a = analyse(ROOT / "specs" / "static_press.yaml")
    md = problem_md(a)
    for line in _description_lines(a.spec):
        assert line not in md
    assert "two-force member" not in md and "mass: 0" not in md
    find = md.split("## Find", 1)[1].lower()
    assert "velocit" not in find and "acceleration" not in find and "inertia" not in find
    assert "positions" in find
    assert "at rest" in md


def test_a_stroke_is_defined(tmp_path):
    a = analyse(ROOT / "specs" / "hydraulic_boom.yaml")
    md = problem_md(a)
    assert "s = 300 mm" in md
    assert re.search(r"The stroke s is the displacement of point E of link 3 \(rod\) along the "
                     r"line of joint cyl, measured from point P", md)


def test_strength_data_in_engineering_notation():
    a = analyse(ROOT / "specs" / "crank_press_strength.yaml")
    md = problem_md(a)
    assert "E = 210 GPa" in md and "yield 490 MPa" in md
    assert not re.search(r"\d(\.\d+)?e[+-]\d\d", md)


@pytest.mark.parametrize("x, unit, text", [(2.1e11, "Pa", "210 GPa"), (4.9e8, "Pa", "490 MPa"),
                                           (4.5e-8, "m⁴", "4.5·10⁻⁸ m⁴"), (0, "Pa", "0 Pa"),
                                           (1500, "N", "1.5 kN")])
def test_eng(x, unit, text):
    assert eng(x, unit) == text


def test_sci():
    assert sci(1.89708e-05) == "1.89708·10⁻⁵" and sci(0.25) == "0.25"


def test_own_statement_replaces_the_written_one_and_is_never_markup():
    text = (ROOT / "specs" / "slider_crank.yaml").read_text(encoding="utf-8")
    text = re.sub(r"(?m)^sheet: true.*$", "", text)
    text += 'sheet: {statement: "Find <script>x</script> the *torque* #set page(width: 1pt)"}\n'
    spec = parse_spec(text, "own.yaml")
    a = analyse(spec)
    p = build_problem(a)
    md = render_problem_markdown(p)
    assert "Find" in md and "Marghitu" not in md
    assert "<script>" not in md                        # raw HTML is never passed through
    typ = render_problem_typst(p)
    assert "#set page(width: 1pt)" not in typ


@pytest.mark.slow
@pytest.mark.parametrize("path", SPECS, ids=lambda p: p.stem)
def test_no_problem_sheet_contains_its_description(path):
    a = analyse(path)
    md = problem_md(a)
    for line in _description_lines(a.spec):
        assert line not in md
    assert "`" not in md.split("## Data", 1)[0]        # no YAML keys in the statement
    if a.spec.driver.at_rest:
        assert "velocit" not in md.split("## Find", 1)[1].lower()
