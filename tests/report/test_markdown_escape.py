"""User text in reports (issue 9, item 13): names with newlines, ``|``, HTML, links, math or
Typst code stay plain text in report.md, index.md and the Typst source of the PDFs."""
from __future__ import annotations

import json
import re
from pathlib import Path

import pytest

from mechreport.report.markdown import md_inline, md_text, md_url
from mechreport.report.pdf import typst_escape, typst_string

pytestmark = pytest.mark.slow      # builds reports, starts processes or fuzzes: not in the fast tier

ROOT = Path(__file__).resolve().parents[2]
EVIL = "evil | name\n# <script>alert(1)</script> [x](y) $x$ #set"
LINK = "r|o*d_[x](y)"          # a link name
JOINT = "a|b"                  # a joint (and point) name
#: characters that are Markdown syntax wherever they stand
SPECIAL = set("\\`*_{}[]|~$#<>")


def unescaped(md: str) -> list[str]:
    """Markdown syntax characters of ``md`` that are not backslash-escaped."""
    out, i = [], 0
    while i < len(md):
        if md[i] == "\\" and i + 1 < len(md):
            i += 2
            continue
        if md[i] in SPECIAL:
            out.append(md[i])
        i += 1
    return out


def cells(row: str) -> list[str]:
    """The cells of a Markdown table row (split on unescaped pipes)."""
    parts, cur, i = [], "", 0
    while i < len(row):
        if row[i] == "\\" and i + 1 < len(row):
            cur += row[i:i + 2]
            i += 2
            continue
        if row[i] == "|":
            parts.append(cur)
            cur = ""
        else:
            cur += row[i]
        i += 1
    parts.append(cur)
    assert parts[0].strip() == "" and parts[-1].strip() == "", row
    return [p.strip() for p in parts[1:-1]]


# ------------------------------------------------------------------------------ Markdown

def test_md_inline_hostile_name_is_one_line_of_plain_text():
    out = md_inline(EVIL)
    assert "\n" not in out
    assert unescaped(out) == []                       # no |, #, [, ], $, raw < > left
    assert "<script" not in out and "&lt;script&gt;" in out
    assert r"\[x\](y)" in out and r"\$x\$" in out and r"\#set" in out


@pytest.mark.parametrize("text, expected", [
    ("- item", r"\- item"), ("+ item", r"\+ item"), ("1. item", r"1\. item"),
    ("2) item", r"2\) item"), ("---", r"\---"), ("==", r"\=="), ("> quote", "&gt; quote"),
    ("   - x", r"\- x"), ("a\r\n\r\n  b", "a b"), ("x\u2028y", "x y"),
])
def test_md_inline_escapes_block_markers_at_the_start(text, expected):
    assert md_inline(text) == expected


@pytest.mark.parametrize("text", ["-102.828", "0.0833417", "F01 = -102.828 i + 116.414 j N",
                                  "(0.5, 0)", "12.5°"])
def test_md_inline_leaves_numbers_readable(text):
    assert md_inline(text) == text


def test_md_text_keeps_markdown_but_not_html():
    assert md_text("*kept* <script>x</script> & [a](b)") == \
        "*kept* &lt;script&gt;x&lt;/script&gt; &amp; [a](b)"


def test_md_url_percent_encodes_link_targets():
    assert md_url("a b/(x)|[y].md") == "a%20b/%28x%29%7C%5By%5D.md"
    assert md_url("slider_crank/report.pdf") == "slider_crank/report.pdf"


# --------------------------------------------------------------------------------- Typst

def _typst_plain(markup: str) -> str:
    """Typeset ``markup`` as content and read it back as text; markup elements (headings,
    math, emphasis, code, labels, ...) show as <name> instead of text."""
    import typst

    src = ("#let plain(c) = if c.func() in (text, [\\#].func()) { c.text } "
           "else if c.func() == [ ].func() { \" \" } "
           "else if c.has(\"children\") { c.children.map(plain).join(\"\") } "
           "else { \"<\" + repr(c.func()) + \">\" }\n"
           "#let body = [" + markup + "]\n#metadata(plain(body)) <out>\n")
    return json.loads(typst.query(src.encode("utf-8"), "<out>", field="value", one=True))


@pytest.mark.parametrize("text", [
    EVIL, "= heading", "1. enum", "- list", "/ term: x", "a // comment", "*strong* _emph_",
    "`raw` <label> @ref", "#set text(red)", "$ x^2 $", "a \\ b", "#{ panic() }", "~--...'\"",
    "x]#panic()[", "\\u{41}", LINK, JOINT,
])
def test_typst_escape_yields_plain_text(text):
    expected = re.sub(r"\s*\n\s*", " ", text)
    assert _typst_plain(typst_escape(text)) == expected


def test_typst_string_round_trips_any_text():
    import typst

    text = EVIL + '\r\t"\\ " + ")\n#panic()'
    src = f"#metadata({typst_string(text)}) <out>\n"
    assert json.loads(typst.query(src.encode("utf-8"), "<out>", field="value",
                                  one=True)) == text


# ---------------------------------------------------------------------- whole reports

def hostile_spec(folder: Path) -> Path:
    """specs/slider_crank.yaml on a coarse sweep, with hostile spec, link and joint names
    and an HTML-carrying description; the file name has | and a Markdown link in it."""
    text = (ROOT / "specs" / "slider_crank.yaml").read_text(encoding="utf-8")
    text = text[:text.index("# Textbook 4.6")]                      # no expectations
    text = text.replace("sweep: {start: 0, stop: 360, step: 1}",
                        "sweep: {start: 0, stop: 360, step: 30}")
    text = text.replace("sheet: true ", "sheet: false")
    text = text.replace("name: R-RRT slider-crank", "name: " + json.dumps(EVIL))
    text = text.replace("description: |\n",
                        "description: |\n  <script>alert(2)</script> & *kept*.\n\n")
    q = json.dumps(LINK)
    text = (text.replace("  rod:\n", f"  {q}:\n").replace("[crank, rod]", f"[crank, {q}]")
            .replace("[rod, slider]", f"[{q}, slider]"))
    text = (text.replace("  B:   {type: R", f"  {json.dumps(JOINT)}: {{type: R")
            .replace("B: [1, 0]}", f"{json.dumps(JOINT)}: [1, 0]}}")
            .replace("{B: [0, 0]", f"{{{json.dumps(JOINT)}: [0, 0]"))
    path = folder / "ev|il [x](y).yaml"
    path.write_text(text, encoding="utf-8")
    return path


@pytest.fixture(scope="module")
def hostile_build(tmp_path_factory):
    from mechreport.app.build import build_files

    folder = tmp_path_factory.mktemp("hostile")
    spec = hostile_spec(folder)
    out = folder / "out"
    code = build_files([spec], out, jobs=1)
    return code, out, spec


def test_hostile_names_build_and_typeset(hostile_build):
    code, out, _ = hostile_build
    assert code == 0
    folder = out / "ev_il__x__y_"                     # | [ ] ( ) and blanks -> _
    assert (folder / "report.pdf").stat().st_size > 0     # Typst accepted the escaped text
    assert (out / "index.pdf").stat().st_size > 0
    assert json.loads((folder / "summary.json").read_text())["name"] == EVIL


def test_report_md_keeps_hostile_names_inert(hostile_build):
    _, out, _ = hostile_build
    md = (out / "ev_il__x__y_" / "report.md").read_text(encoding="utf-8")
    lines = md.splitlines()
    assert lines[0] == "# " + md_inline(EVIL)
    assert [l for l in lines if l.startswith("# ")] == [lines[0]]      # one title, no other
    assert "<script" not in md and "&lt;script&gt;alert(2)&lt;/script&gt; &amp; *kept*." in md
    assert "](y)" not in md.replace(r"\](y)", "")                       # no link made
    # every table row has as many cells as its header
    width = None
    for line in lines:
        if not line.startswith("|"):
            width = None
            continue
        n = len(cells(line))
        if width is None:
            width = n
        assert n == width, line
    joint_row = next(l for l in lines if l.startswith("| a\\|b | pin (R)"))
    assert cells(joint_row)[:3] == [md_inline(JOINT), "pin (R)",
                                    f"crank (1) → {md_inline(LINK)} (2)"]
    assert f"- {md_inline(JOINT)}: F12 = " in md                    # the vector list


def test_index_md_keeps_hostile_names_and_file_names_inert(hostile_build):
    _, out, _ = hostile_build
    index = (out / "index.md").read_text(encoding="utf-8")
    assert "<script" not in index
    row = next(l for l in index.splitlines() if l.startswith("| evil"))
    c = cells(row)
    assert len(c) == 9 and c[0].startswith(md_inline(EVIL) + " (")   # name (spec path)
    assert c[-1] == ("[md](ev_il__x__y_/report.md) · [pdf](ev_il__x__y_/report.pdf) · "
                     "[html](ev_il__x__y_/report.html) · [animation](ev_il__x__y_/animation.gif)")


def test_index_md_failure_row_escapes_the_file_name(tmp_path):
    from mechreport.app.build import build_files

    bad = tmp_path / "a|b [x](y).yaml"
    bad.write_text("mechreport: 1\nname: [unclosed\n", encoding="utf-8")
    assert build_files([bad], tmp_path / "out", jobs=1) == 1
    index = (tmp_path / "out" / "index.md").read_text(encoding="utf-8")
    row = next(l for l in index.splitlines() if "FAIL" in l)
    c = cells(row)
    assert len(c) == 9 and c[0] == md_inline(str(bad))
    assert c[1] == "FAIL: could not be built"
    assert "](y)" not in row.replace(r"\](y)", "")
