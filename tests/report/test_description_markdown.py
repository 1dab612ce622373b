"""A spec's ``description`` is Markdown: report.pdf renders it (emphasis in italics, lists,
links, code) as the Markdown viewers of report.md do, through markdown-it-py, and whatever
the user wrote stays text: no Typst markup or code, no HTML, comes out of it."""
from __future__ import annotations

import dataclasses
import re
import shutil
import subprocess
from pathlib import Path

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from helpers import tiny_spec

pytestmark = pytest.mark.slow      # builds reports: not in the fast tier

needs_poppler = pytest.mark.skipif(shutil.which("pdftotext") is None,
                                   reason="needs pdftotext (poppler-utils)")


@pytest.fixture(scope="module")
def report(tmp_path_factory):
    """(model, folder): the report model of a small slider-crank (its description is the
    textbook's, with *Dynamic Force Analysis* in it) and a folder holding its figures, so
    that report.typ compiles there."""
    from mechreport.pipeline.analysis import analyse
    from mechreport.report.animation import write_animation
    from mechreport.report.drawing import write_drawings
    from mechreport.report.model import build_model
    from mechreport.report.plots import write_plots

    folder = tmp_path_factory.mktemp("description")
    spec = tiny_spec(folder / "spec" / "tiny.yaml")
    model = build_model(analyse(spec), spec)
    write_plots(model, folder / "figures")
    write_drawings(model, folder / "figures")
    write_animation(model, folder)
    return model, folder


def typst_source(model, description=None) -> str:
    from mechreport.report.render import report_markdown, report_typst

    if description is not None:
        model = dataclasses.replace(model, description=description)
    return report_typst(model)


def report_md(model, description) -> str:
    from mechreport.report.render import report_markdown, report_typst

    return report_markdown(dataclasses.replace(model, description=description))


def pdf_text(report, description, tmp_path: Path) -> str:
    """report.pdf of the model with ``description``, compiled by the report's compiler,
    as text with its blanks collapsed."""
    from mechreport.report.pdf import compile_typst

    model, folder = report
    pdf = compile_typst(typst_source(model, description), tmp_path / "report.pdf", folder)
    text = subprocess.run(["pdftotext", "-l", "1", str(pdf), "-"], check=True,
                          capture_output=True, text=True).stdout
    return " ".join(text.split())


def page_size(pdf: Path) -> str:
    info = subprocess.run(["pdfinfo", str(pdf)], check=True, capture_output=True,
                          text=True).stdout
    return re.search(r"Page size:\s*(.*)", info).group(1)


# ----------------------------------------------------------------------------- the PDF

def test_emphasis_in_a_description_is_italic_in_the_pdf_source(report):
    model, _ = report
    assert "*Dynamic Force Analysis*" in "\n\n".join(model.description)   # as the spec says
    source = typst_source(model)
    assert "#emph[Dynamic Force Analysis]" in source
    assert "*Dynamic Force Analysis*" not in source.replace("\\", "")


@needs_poppler
def test_emphasis_in_a_description_shows_without_its_asterisks_in_the_pdf(report, tmp_path):
    text = pdf_text(report, report[0].description, tmp_path)
    assert "Marghitu, Dynamic Force Analysis, section 4.6" in text
    assert "*Dynamic" not in text


@needs_poppler
def test_typst_markup_in_a_description_stays_literal(report, tmp_path):
    shown = ["kept #set page(width: 1cm) $x$ @ref <label>",
             "x]#panic()[ C:\\temp\\new a\\b // not a comment",
             "= not a heading #{ panic() }",
             "a -- b ... c ~ d 'q' \"q\" /* e */"]
    written = ["*kept* " + shown[0][len("kept "):]] + shown[1:]
    source = typst_source(report[0], written)
    assert "#emph[kept]" in source                 # the Markdown is rendered, the rest is text
    text = pdf_text(report, written, tmp_path)
    for line in shown:
        assert line in text
    assert "*kept*" not in text
    assert page_size(tmp_path / "report.pdf").startswith("595")   # still A4, not 1 cm wide


@needs_poppler
def test_html_in_a_description_is_not_interpreted(report, tmp_path):
    written = ["**<b>bold</b>** <script>alert(1)</script> <!-- note -->",
               "<div>\n*x*\n</div>",
               "<img src=\"figures/torque.svg\"> <a href=\"http://e.org\">link</a>"]
    source = typst_source(report[0], written)
    assert "#strong[\\<b\\>bold\\<\\/b\\>]" in source
    assert "#image" not in source.split("= Design summary")[0].split("#strong[Left out\\:]")[1]
    text = pdf_text(report, written, tmp_path)
    assert "<b>bold</b> <script>alert(1)</script> <!-- note -->" in text
    assert "<div> x </div>" in text
    assert '<img src="figures/torque.svg"> <a href="http://e.org">link</a>' in text
    assert "**" not in text
    # report.md keeps the description's Markdown, with & < > as entities: no raw HTML
    md = report_md(report[0], written)
    assert "<script" not in md and "<div" not in md and "<img" not in md
    assert "**&lt;b&gt;bold&lt;/b&gt;** &lt;script&gt;alert(1)&lt;/script&gt;" in md


def test_report_md_keeps_the_description_markdown(report):
    model, _ = report
    md = report_md(model, model.description)
    assert "Marghitu, *Dynamic Force Analysis*, section 4.6" in md


# ------------------------------------------------------------------ the token mapping

@pytest.mark.parametrize("markdown, typst", [
    ("a *em* b", "a #emph[em] b"),
    ("a _em_ b", "a #emph[em] b"),
    ("**strong** and ***both***", "#strong[strong] and #emph[#strong[both]]"),
    ("`x[0] = \"#y\"`", '#raw("x[0] = \\"#y\\"")'),
    ("[docs](<https://e.org/a b>) <https://e.org>",
     '#link("https://e.org/a%20b")[docs] #link("https://e.org")[https\\:\\/\\/e\\.org]'),
    ("[no target]()", "no target"),
    ("[js](javascript:alert(1))", "\\[js\\]\\(javascript\\:alert\\(1\\)\\)"),
    ("one\ntwo", "one two"),
    ("one  \ntwo\\\nthree", "one#linebreak()two#linebreak()three"),
    ("p1\n\np2", "p1\n\np2"),
    ("- a\n- *b*", "#list(tight: true, [a], [#emph[b]])"),
    ("- a\n\n- b", "#list(tight: false, [a], [b])"),
    ("3. a\n4. b", "#enum(tight: true, start: 3, [a], [b])"),
    ("1) a", '#enum(tight: true, start: 1, numbering: "1)", [a])'),
    ("- a\n  1. b", "#list(tight: true, [a\n\n#enum(tight: true, start: 1, [b])])"),
    ("# Title *x*", "Title #emph[x]"),
    ("Title\n===", "Title"),
    ("![alt *x*](figures/torque.svg)", "alt x"),
    ("| a | b |\n|---|---|", "\\| a \\| b \\| \\|\\-\\-\\-\\|\\-\\-\\-\\|"),
    ("<b>x</b> &amp; &lt;", "\\<b\\>x\\<\\/b\\> \\& \\<"),
    ("```typst\n#panic()\n```", '#raw(block: true, "#panic()")'),
    ("> said", "#quote(block: true)[said]"),
    ("", ""),
])
def test_description_markdown_maps_to_typst_markup_per_token(markdown, typst):
    from mechreport.report.pdf import typst_markdown

    assert typst_markdown(markdown) == typst


def test_the_reports_description_is_rendered_as_typst_markup(report):
    """report.typ renders the description's Markdown as Typst markup (the sheets, documents
    of their own, add nothing to the reports' template environment)."""
    assert "#emph[Dynamic Force Analysis]" in typst_source(report[0])


@settings(max_examples=150, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(st.lists(st.sampled_from(list("ab1 *_`[]()<>!#$@\\/-+=.:;~'\"&{}|^\n")
                                + ["\n\n", "- ", "1. ", "0) ", "> ", "```", "<b>", "](",
                                   "http://e.org", "    ", "**", "  \n", "# ", "![", "&amp;"]),
                max_size=40).map("".join))
def test_any_description_compiles(text):
    import typst

    from mechreport.report.pdf import typst_markdown

    typst.compile(typst_markdown(text).encode("utf-8"), format="pdf")
