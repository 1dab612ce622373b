"""moodle.xml and the answer key of a problem's variants (issue 46): valid XML, one numerical
question per variant and asked quantity with its tolerance and unit, the figure embedded, and
a hostile spec name or statement escaped (never markup)."""
from __future__ import annotations

import base64
import re
import xml.etree.ElementTree as ET
from pathlib import Path

import pytest

from mechreport.study.sheet_variants import make_variants
from mechreport.report.sheet.variants_out import moodle_xml, write_variants

ROOT = Path(__file__).resolve().parents[2]
HOSTILE = "<script>alert(1)</script> ]]> & \"q\""
SPEC_TAIL = """sheet:
  statement: |
    Find <script>alert(2)</script> the torque ]]> & the *reactions*.
  variants:
    vary:
      - {key: driver.rpm, values: [10, 20, 30]}
      - {key: links.slider.mass, from: 1, to: 2}
    count: 2
    seed: 3
"""


@pytest.fixture(scope="module")
def bank(tmp_path_factory):
    d = tmp_path_factory.mktemp("moodle")
    text = (ROOT / "specs" / "slider_crank.yaml").read_text(encoding="utf-8")
    text = re.sub(r"(?m)^sheet: true.*$", "", text)
    text = re.sub(r"(?m)^name: .*$", "name: '" + HOSTILE.replace("'", "''") + "'", text)
    path = d / "hostile.yaml"
    path.write_text(text + SPEC_TAIL, encoding="utf-8")
    variants = make_variants(path)
    write_variants(variants, d / "out", name=HOSTILE)
    return variants, d / "out" / "variants"


def test_moodle_xml_parses_with_a_question_per_variant_and_quantity(bank):
    variants, out = bank
    root = ET.parse(out / "moodle.xml").getroot()
    assert root.tag == "quiz"
    cats = root.findall("question[@type='category']")
    assert len(cats) == 1 and cats[0].findtext("category/text").endswith(HOSTILE)
    questions = root.findall("question[@type='numerical']")
    asked = sum(len(v.answers) for v in variants)
    assert len(questions) == asked == len(variants) * len(variants[0].answers)
    answers = [(v, a) for v in variants for a in v.answers]
    for q, (v, a) in zip(questions, answers):
        ans = q.find("answer")
        assert ans.get("fraction") == "100"
        assert float(ans.findtext("text")) == a.value
        assert float(ans.findtext("tolerance")) == a.tolerance > 0
        assert q.findtext("units/unit/unit_name") == a.unit
        f = q.find("questiontext/file")
        assert f is not None and base64.b64decode(f.text).lstrip().startswith(b"<?xml")
        assert f"@@PLUGINFILE@@/{f.get('name')}" in q.findtext("questiontext/text")


def test_hostile_name_and_statement_are_escaped(bank):
    _, out = bank
    raw = (out / "moodle.xml").read_bytes()
    assert b"<script>" not in raw and b"]]>" not in raw
    root = ET.parse(out / "moodle.xml").getroot()
    q = root.find("question[@type='numerical']")
    assert HOSTILE in q.findtext("name/text")            # the text, read back as written
    html = q.findtext("questiontext/text")
    assert "<script>" not in html                         # in the HTML, only as escaped text
    assert "&lt;script&gt;alert(2)&lt;/script&gt;" in html
    assert "<em>reactions</em>" in html                  # Markdown still rendered
    key = (out / "answers.md").read_text(encoding="utf-8")
    assert "<script>" not in key


def test_moodle_xml_alone_is_valid_for_no_figure():
    from types import SimpleNamespace
    a = SimpleNamespace(label="M at φ = 0° <&>", value=1.5, unit="N·m", tolerance=0.015,
                        angle=0.0)
    v = SimpleNamespace(number=1, answers=[a])
    root = ET.fromstring(moodle_xml([v], [{"html": "<p>x &amp; y</p>", "figures": {}}], "a&b"))
    assert root.find("question[@type='numerical']/name/text").text.endswith("M at φ = 0° <&>")


def test_a_question_states_the_drive_once_and_how_the_torque_is_signed(tmp_path):
    """A statement written from the data already says how the mechanism is driven (the
    question text said it twice); the driver torque is asked signed, and the question says
    so (a student who finds 694.9 N·m for a torque of -694.9 N·m must know the sign counts)."""
    from types import SimpleNamespace
    import html as _html
    import mechreport
    from mechreport.report.sheet.model import build_problem, build_sheet
    from mechreport.report.sheet.statement import driver_statement
    from mechreport.report.sheet.variants_out import problem_html
    from mechreport.study.sheet_variants import answers_of
    a = mechreport.analyse(ROOT / "specs" / "slider_crank.yaml")
    prob = problem_html(build_sheet(a), build_problem(a), tmp_path, a.spec)
    assert prob["html"].count(_html.escape(driver_statement(a.spec))) == 1
    v = SimpleNamespace(number=1, answers=answers_of(a, [45.0]))
    root = ET.fromstring(moodle_xml([v], [prob], "slider-crank"))
    texts = [q.findtext("questiontext/text") for q in root.findall("question[@type='numerical']")]
    torque = [t for t, ans in zip(texts, v.answers) if ans.quantity == "driver.torque"]
    assert len(torque) == 1 and "counter-clockwise positive" in torque[0]
    assert all("counter-clockwise positive" not in t for t in texts if t not in torque)


def test_the_key_says_the_problems_print_their_data_in_si(bank):
    """A mm or inch spec's key lists its varied data in the spec's units while each problem
    prints SI (the key said 'as printed on each problem')."""
    _, out = bank
    key = (out / "answers.md").read_text(encoding="utf-8")
    assert "each problem gives its data in SI units" in key
