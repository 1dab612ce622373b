"""The one document model and its two writers: the same blocks in Markdown and in Typst, user
text escaped by each format's escaper, print-only hints ignored by Markdown."""
from __future__ import annotations

from mechreport.report.document import (Aside, Cell, Code, Doc, Either, Figure, Layout, Link,
                                        Print, Strong, Verdict, Wording)
from mechreport.report.pdf import compile_typst
from mechreport.report.write_markdown import markdown
from mechreport.report.write_typst import typst

HOSTILE = "*x* _y_ [l](u) #set $m$ <b> | `c` \\"


def _doc() -> Doc:
    doc = Doc(HOSTILE, layout=Layout(landscape=True))
    doc.h(HOSTILE)
    doc.p("plain ", Strong(HOSTILE), " and ", Code(HOSTILE), " ", Link(HOSTILE, "a b/r.pdf"))
    doc.items([HOSTILE, [Strong("b"), " tail"]], intro="Intro:")
    doc.items(["one", "two"], ordered=True)
    doc.table(["name", "check", "value"],
              [[[HOSTILE, Aside(HOSTILE)], Verdict("FAIL", HOSTILE), "1.5"],
               ["x", Cell(HOSTILE, span=2)]], right={2}, note=HOSTILE,
              print=Print(widths=(2, None, 1)))
    doc.table(["a", "b"], [["1", "2"]], print=Print(grid=True))
    doc.p(Either(Wording("[text]"), "print"))
    doc.add(Figure("fig.svg", HOSTILE, alt="alt", caption_below=True))
    return doc


def test_markdown_escapes_user_text_and_keeps_the_blocks():
    md = markdown(_doc())
    assert md.startswith("# \\*x\\* \\_y\\_ \\[l\\](u) \\#set \\$m\\$ &lt;b&gt; \\| \\`c\\` \\\\\n\n")
    assert "## \\*x\\*" in md
    assert "[\\*x\\*" in md and "(a%20b/r.pdf)" in md
    assert "Intro:\n\n- \\*x\\*" in md and "- **b** tail\n" in md
    assert "1. one\n2. two\n" in md
    assert "|---|---|---:|" in md
    assert "(\\*x\\*" in md and "FAIL: \\*x\\*" in md
    assert "| x | — | \\*x\\*" in md                  # a spanning cell: filler, then its text
    assert "[text]" in md and "print" not in md
    assert "![alt](fig.svg)\n\n*\\*x\\*" in md
    assert md.endswith("\n") and not md.endswith("\n\n")


def test_typst_escapes_user_text_and_compiles(tmp_path):
    (tmp_path / "fig.svg").write_text('<svg xmlns="http://www.w3.org/2000/svg" width="10" '
                                      'height="10"><rect width="10" height="10"/></svg>')
    src = typst(_doc())
    assert "flipped: true" in src
    assert "== \\*x\\* \\_y\\_" in src
    assert "table.cell(colspan: 2" in src and "columns: (2fr, auto, 1fr)" in src
    assert "\\[text\\]" not in src and "print" in src
    assert compile_typst(src, tmp_path / "d.pdf", tmp_path).stat().st_size > 1000


def test_sheet_blocks_in_both_formats():
    from mechreport.report.document import (Columns, Equation, Figures, Found, Gap, Math,
                                            NewLine, Number, Paragraph, Table)
    from mechreport.report.sheet.expr import Raw

    x = Raw(r"\alpha_{1}", "alpha_1", "alpha1")
    doc = Doc("Sheet", end_blank=True)
    doc.p("the report's ", Wording("the report's"), " ", Number("-1.5"), NewLine(), Math(x))
    doc.add(Equation(x, 3, x))
    doc.add(Found("(3) gives", [Math(x), Math(x)], [["more ", Math(x)]]))
    doc.add(Columns([Table(["a"], [["1"]], print=Print(grid=True))] * 2))
    doc.add(Figures([Figure("a.svg", "A"), Figure("b.svg", "B")]))
    doc.add(Paragraph("small", small=True))
    doc.add(Gap())
    md, typ = markdown(doc), typst(doc)
    assert "the report's the report's -1.5\n$\\alpha_{1}$\n\n" in md
    assert "$$\\alpha_{1} \\tag{3}$$\n\n$$\\Rightarrow\\quad \\alpha_{1}$$\n\n" in md
    assert "**(3) gives** $\\alpha_{1}$, $\\alpha_{1}$; more $\\alpha_{1}$\n\n" in md
    assert md.count("| a |\n|---|\n| 1 |\n\n") == 2
    assert "![A](a.svg) ![B](b.svg) \n\n" in md
    assert md.endswith("small\n\n\n")                       # end_blank and the Gap
    assert "the report\\'s the report's -1\\.5\n\\ $alpha_1$" in typ   # a true minus
    assert "#eqn(3, $ alpha_1 $, $ alpha_1 $)" in typ
    assert "#found[\\(3\\) gives #h(0.4em) $alpha_1$, #h(0.5em) $alpha_1$; #h(0.3em) more" in typ
    assert "#grid(columns: (auto, auto)" in typ and "#grid(columns: 3," in typ
    assert "#text(size: 8pt)[small]" in typ


def test_report_blocks_in_both_formats():
    from mechreport.report.document import (Blank, Box, Heading, Item, Items, Key, Only,
                                            Pairs, Paragraph, Ref, Space, Table)

    doc = Doc("Title", layout=Layout(title_center=True, numbered=True, heading_shift=1,
                                     header=("left", "right")),
              subtitle="sub", byline=["by ", Code("x.yaml")], author="me")
    doc.add(Pairs([["Date", "today"]], text_rows=[["Source", Link("a.csv", "a.csv")]]))
    doc.add(Box([Paragraph([Strong("Check:"), " PASS"])], "PASS"))
    doc.add(Only([Heading("Contents"), Items([Ref("Design", "design")])], print=False))
    doc.add(Space())
    doc.h("Design")
    doc.add(Table(["q", "name"], [[Blank(), Key("cycle.torque.rms")]], header_blank=True,
                  print=Print(keep=True, size=7.5)))
    doc.items([Item([Strong("Loads:")], ["one", "two"])])
    md, typ = markdown(doc), typst(doc)
    assert md.startswith("# Title\n\n**sub**\n\n| | |\n|---|---|\n| Date | today |\n"
                         "| Source | [a.csv](a.csv) |\n\n**Check:** PASS\n\n## Contents\n\n"
                         "- [Design](#design)\n\n## Design\n\n| q | name | \n")
    assert "| | `cycle.torque.rms` |\n" in md
    assert "- **Loads:**\n  - one\n  - two\n" in md
    assert "= Design" in typ and "== Contents" not in typ and "#v(1em)" in typ
    assert 'author: "me"' in typ and '#set heading(numbering: "1.1")' in typ
    assert "#align(center)[" in typ and "#raw(\"x.yaml\")" in typ
    assert 'rgb("#e6f4e6")' in typ and "a.csv" not in typ
    assert "#block(breakable: false)[\n#set text(size: 7.5pt)" in typ
