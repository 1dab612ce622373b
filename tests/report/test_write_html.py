"""The HTML writer, the document model's third: every block written, user text escaped (a
name with ``<script>`` is text), the same numbers as report.md, the page's safety (its
Content-Security-Policy, no inline script, a data block nothing can close) and sizes."""
from __future__ import annotations

import html
import json
import re
from collections import Counter
from pathlib import Path

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import mechreport
from mechreport.report.document import (Aside, Blank, Box, Cell, Code, Columns, Doc, Either,
                                        Equation, Figure, Figures, Found, Gap, Heading, Item,
                                        Items, Key, Link, Math, NewLine, Number, Only, Pairs,
                                        Paragraph, Print, Ref, Space, Strong, Table, Verdict,
                                        Wording, Description)
from mechreport.report.write_html import html_body

ROOT = Path(__file__).resolve().parents[2]
HOSTILE = "<script>alert(1)</script> \"q\" 'a' & <b>x</b>"


def _every_block() -> Doc:
    from mechreport.report.sheet.expr import Raw
    x = Raw(r"\alpha_{1}", "alpha_1", "alpha1")
    doc = Doc(HOSTILE, subtitle=HOSTILE)
    doc.add(Pairs([[HOSTILE, HOSTILE]], text_rows=[["Source", Link(HOSTILE, "a b.csv")]]))
    doc.add(Box([Paragraph([Strong(HOSTILE), " ", Verdict("FAIL", HOSTILE)])], "FAIL"))
    doc.add(Only([Items([Ref(HOSTILE, "design")])], print=False))
    doc.add(Only([Paragraph("print only")], print=True))
    doc.add(Heading(HOSTILE))
    doc.add(Table(["a", "b", "c"], [[[HOSTILE, Aside(HOSTILE)], Blank(), Key(HOSTILE)],
                                     ["x", "y", "PASS"],
                                     [Cell(HOSTILE, span=3, small=True)]],
                  right={1}, note=HOSTILE, print=Print()))
    doc.add(Items([Item(HOSTILE, [HOSTILE]), [Code(HOSTILE), NewLine()]], intro=HOSTILE))
    doc.add(Figure("figures/x.svg", HOSTILE))
    doc.add(Figures([Figure("a.svg", HOSTILE)]))
    doc.add(Equation(x, 3, x))
    doc.add(Found(HOSTILE, [Math(x)], [[HOSTILE]]))
    doc.add(Columns([Paragraph(Number("-1.5")), [Paragraph(Wording(HOSTILE))]]))
    doc.add(Space())
    doc.add(Gap())
    doc.add(Paragraph([Either(HOSTILE, "print"), " ", Emph_(HOSTILE)], small=True))
    doc.add(Description([HOSTILE + " *kept* [l](javascript:alert(1)) ![i](http://x/i.png)"]))
    return doc


def Emph_(text):
    from mechreport.report.document import Emph
    return Emph(text)


def test_every_block_is_written_and_user_text_is_escaped():
    out = html_body(_every_block())
    assert "<script" not in out and "<b>" not in out
    assert out.count("&lt;script&gt;alert(1)&lt;/script&gt;") >= 15
    assert "javascript:" not in out.replace("[l](javascript", "")   # the link refused
    assert "<img src=\"http" not in out                                 # no image fetched
    assert "<em>kept</em>" in out                                       # the user's Markdown
    assert "print only" not in out
    assert "<span class=\"badge fail\">FAIL</span>" in out
    assert "<td><span class=\"badge pass\">PASS</span></td>" in out       # a verdict cell
    assert "colspan=\"3\"" in out and "href=\"a%20b.csv\"" in out
    assert "<h2 id=\"scriptalert1script-q-a--bxb\">" in out             # GitHub's anchor


def test_an_unknown_block_is_an_error():
    with pytest.raises(TypeError):
        html_body(Doc("t", blocks=[object()]))


@pytest.fixture(scope="module")
def four_bar():
    from mechreport.report.model import build_model
    a = mechreport.analyse(ROOT / "specs" / "four_bar.yaml")
    return a, build_model(a, "specs/four_bar.yaml")


def _numbers(text: str) -> Counter:
    return Counter(re.findall(r"\d+(?:\.\d+)?(?:e[-+]?\d+)?", text))


def test_the_page_has_report_md_s_numbers(four_bar):
    from mechreport.report.html_data import html_data
    from mechreport.report.html_page import report_html
    from mechreport.report.render import report_markdown
    from mechreport.report.report_doc import report_document
    a, m = four_bar
    md = report_markdown(m)
    md = re.sub(r"\]\([^)]*\)", "]", md).replace("\\", "")          # link targets, escapes
    page = report_html(report_document(m), html_data(a, m))
    body = page[page.index("<main>"):page.index("</main>")]
    body = re.sub(r"<section class=\"live\".*?</section>", "", body, flags=re.S)
    def text(h):
        return html.unescape(re.sub(r"<[^>]+>", " ", h))

    # every number of report.md is on the page (which captions every figure, where
    # report.md has some captions only as the image's text), and every number of the page
    # but its captions is in report.md
    assert not _numbers(re.sub(r"!\[[^\]]*\]", "", md)) - _numbers(text(body))
    assert not _numbers(text(re.sub(r"<figcaption>.*?</figcaption>", "", body))) - _numbers(md)


def test_the_page_is_safe_and_small(four_bar, tmp_path):
    from mechreport.report.html_data import html_data
    from mechreport.report.html_page import CSP, asset_bytes, report_html
    from mechreport.report.report_doc import report_document
    a, m = four_bar
    data = html_data(a, m)
    data["title"] = "</script><script>alert(1)</script>"
    page = report_html(report_document(m), data)
    assert f"content=\"{CSP}\"" in page and "'unsafe-inline'" not in CSP
    scripts = re.findall(r"<script([^>]*)>(.*?)</script>", page, flags=re.S)
    assert [attrs for attrs, body in scripts if body.strip()] == [
        ' type="application/json" id="mr-data"']                        # no inline code
    assert json.loads(scripts[0][1])["title"] == data["title"]          # not closed early
    assert len(data["angles"]) == 360 and len(page.encode()) <= 1_000_000
    assert sum(len(asset_bytes(n)) for n in ("report.js", "report.css")) <= 500_000


def test_the_slider_shows_the_report_s_numbers(four_bar):
    """The value beside the slider at the peak bearing load is results.csv's, as the report
    prints it."""
    from mechreport.report.html_data import html_data
    a, m = four_bar
    data = html_data(a, m)
    big = m.summary["largest_bearing_load"]
    k = data["angles"].index(big["angle_deg"])
    joint = next(j for j in data["joints"] if j["name"] == big["joint"])
    assert joint["text"]["f"][k] == m.display.num(big["value"], "force")


def test_the_page_draws_in_the_figures_colours(four_bar):
    """The page's curves and arrows take the figures' colours (report/mpl.py's palette):
    the script names no colour of a series of its own."""
    from mechreport.report.html_data import html_data
    from mechreport.report.html_page import asset_bytes
    from mechreport.report.mpl import INK, LOAD_COLOR, MOMENT_COLOR
    a, m = four_bar
    data = html_data(a, m)
    assert data["effort"]["color"] == MOMENT_COLOR and data["shaking"]["color"] == INK
    assert {ld["color"] for ld in data["geometry"]["loads"]} == {LOAD_COLOR}
    assert [j["color"] for j in data["joints"]] == [j.color for j in m.sweep.joints]
    script = asset_bytes("report.js").decode()
    assert "data.effort.color" in script and "data.shaking.color" in script
    assert not re.findall(r"color: \"#|color \|\|", script)
    # a value under the pointer is the report's text of it, not the script's own formatting
    assert "s.text[i]" in script and "fmt(s.values" not in script


@pytest.mark.slow
@pytest.mark.parametrize("spec", sorted(p.name for p in (ROOT / "specs").glob("*.yaml")))
def test_every_shipped_spec_has_its_page(spec):
    """Every shipped spec's page data (pins joining three links, T drivers, short sweeps):
    one position per joint and angle, under the size budget."""
    from mechreport.report.html_data import html_data
    from mechreport.report.html_page import report_html
    from mechreport.report.model import build_model
    from mechreport.report.report_doc import report_document
    a = mechreport.analyse(ROOT / "specs" / spec)
    m = build_model(a, spec)
    data = html_data(a, m)
    n = len(data["angles"])
    assert n and all(len(j["at"]) == len(j["text"]["f"]) == n for j in data["joints"])
    assert len(report_html(report_document(m), data).encode()) <= 1_000_000


ALLOWED = {"p", "em", "strong", "code", "a", "ul", "ol", "li", "pre", "blockquote", "hr",
           "br", "h1", "h2", "h3", "h4", "h5", "h6"}


@settings(max_examples=150, deadline=None)
@given(st.lists(st.sampled_from(["<script>", "</p>", "<img src=x onerror=a()>", "[l](",
                                 "javascript:alert(1)", ")", "![i](http://x/i.png)", "*",
                                 "`", "\n\n", "- ", "# ", "&", "\"", "'", "a", " ",
                                 "<a href='javascript:x'>", "vbscript:", "data:text/html,"]),
                max_size=25).map("".join))
def test_any_description_is_harmless_html(text):
    from mechreport.report.write_html import description_html
    out = description_html(text)
    assert {t.lower() for t in re.findall(r"<\s*/?\s*([A-Za-z0-9]+)", out)} <= ALLOWED
    for href in re.findall(r"href=\"([^\"]*)\"", out):
        assert not re.match(r"\s*(javascript|vbscript|data):", href, re.I), href
    assert " on" not in re.sub(r">[^<]*<", "><", out)     # no event attribute in a tag


@pytest.mark.slow                 # 3600 angles: about 1.5 s
def test_a_fine_sweep_is_thinned_keeping_its_peaks(tmp_path):
    """A 0.1-degree sweep (3600 angles) makes a page under 1 MB that still holds the peak
    bearing load's angle, with the report's value there."""
    from mechreport.report.html_data import MAX_ANGLES, html_data
    from mechreport.report.html_page import report_html
    from mechreport.report.model import build_model
    from mechreport.report.report_doc import report_document
    text = (ROOT / "specs" / "four_bar.yaml").read_text(encoding="utf-8")
    assert "step: 1}" in text
    spec = tmp_path / "fine.yaml"
    spec.write_text(text.replace("step: 1}", "step: 0.1}"), encoding="utf-8")
    a = mechreport.analyse(spec)
    m = build_model(a, "fine.yaml")
    data = html_data(a, m)
    assert a.kinematics.n == 3600 and len(data["angles"]) <= MAX_ANGLES + 20
    big = m.summary["largest_bearing_load"]
    k = data["angles"].index(big["angle_deg"])
    joint = next(j for j in data["joints"] if j["name"] == big["joint"])
    assert joint["text"]["f"][k] == m.display.num(big["value"], "force")
    assert all(len(j["at"]) == len(data["angles"]) for j in data["joints"])
    assert len(report_html(report_document(m), data).encode()) <= 1_000_000
