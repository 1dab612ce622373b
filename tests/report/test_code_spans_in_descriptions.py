"""Code in a spec's description shows as written (issue 41): the HTML escaping that keeps
raw HTML out of report.md, problem.md and solution.md stops at code spans and fenced code,
where Markdown shows every character literally (toggle_press printed `joint.C.on.&lt;link&gt;`
in its report and sheets); the PDFs' Typst shows the same code."""
from __future__ import annotations

from pathlib import Path

import pytest
from markdown_it import MarkdownIt

from mechreport.report.markdown import md_text
from mechreport.report.pdf import typst_markdown

ROOT = Path(__file__).resolve().parents[2]


def html_of(markdown: str) -> str:
    """``markdown`` as a Markdown viewer that reads raw HTML shows it (GitHub's does)."""
    return MarkdownIt("commonmark", {"html": True}).render(markdown)


def test_toggle_press_description_shows_its_code_span_literally():
    from mechreport.spec import load_spec
    text = load_spec(ROOT / "specs" / "toggle_press.yaml").description
    assert "`joint.C.on.<link>`" in md_text(text)
    assert "<code>joint.C.on.&lt;link&gt;</code>" in html_of(md_text(text))
    assert 'raw("joint.C.on.<link>")' in typst_markdown(text)


@pytest.mark.parametrize("text, code", [
    ("a `<b>` c", "<b>"),
    ("a ``x ` <y>`` c", "x ` <y>"),
    ("a `x &amp; <y>` c", "x &amp; <y>"),
    ("two lines `<a\nb>` here", "<a b>"),
])
def test_code_spans_show_every_character_as_written(text, code):
    from html import escape
    assert f"<code>{escape(code, quote=False)}</code>" in html_of(md_text(text))


@pytest.mark.parametrize("text", [
    "<script>x</script> `<b>`",
    "`<b>` <i>x</i> & y",
    "\\`<b>` <i>",                   # an escaped backtick opens no span
    "un `<b> matched",              # an unmatched backtick is text
    "``<b>` x",                     # runs of different lengths do not match
    "<a href=\"`\">`</a>",          # a tag that starts before the backtick
    "```\n<b>\n```\n<i>x</i>",      # a fenced block, then prose
])
def test_no_raw_html_outside_code(text):
    """Outside code every < is an entity: no tag reaches the viewer (in a code span or a
    fenced block, < is shown, never read)."""
    out = html_of(md_text(text))
    for tag in ("<script", "<b>", "<i>", "<a "):
        body = out.replace("<code>", "").replace("</code>", "").replace("<pre>", "")
        assert tag not in body.replace("<p>", "").replace("</p>", ""), (text, out)


def test_fenced_code_in_a_description_is_kept_as_written():
    text = "Before <x>.\n\n```\na < b && c > d\n```\n\nAfter <y>."
    out = md_text(text)
    assert "a < b && c > d" in out and "&lt;x&gt;" in out and "&lt;y&gt;" in out
