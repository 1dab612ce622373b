"""The Typst writer of a :class:`~.document.Doc` (compiled to PDF by :func:`.pdf.compile_typst`):
the page set up from the document's :class:`~.document.Layout`, user text escaped by the one
Typst escaper (:func:`.pdf.typst_escape` in markup, :func:`.pdf.typst_string` as a string;
a user's own Markdown through :func:`.pdf.typst_markdown`), math as Typst math."""
from __future__ import annotations

import re

from . import document as d
from .pdf import typst_escape, typst_markdown, typst_string

PASS_COLOUR, FAIL_COLOUR = "#1a7f1a", "#b00000"


def typst(doc: d.Doc) -> str:
    """``doc`` as Typst source."""
    out = [_preamble(doc)]
    out.extend(block(b, doc.layout) for b in doc.blocks)
    return "".join(out)


def _preamble(doc: d.Doc) -> str:
    lay = doc.layout
    m = [f"{_n(x)}cm" for x in lay.margin]
    margin = (m[0] if len(m) == 1 else f"(x: {m[0]}, y: {m[1]})" if len(m) == 2 else
              f"(x: {m[0]}, top: {m[1]}, bottom: {m[2]})")
    flipped = "flipped: true, " if lay.landscape else ""
    leading = f", leading: {_n(lay.leading)}em" if lay.leading is not None else ""
    leading += f", spacing: {_n(lay.spacing)}em" if lay.spacing is not None else ""
    lines = [f"#set document(title: {typst_string(doc.title)}, date: none)",
             f'#set page(paper: "a4", {flipped}margin: {margin}, numbering: "1 / 1")',
             f"#set text(size: {_n(lay.size)}pt)",
             f"#set par(justify: false{leading})"]
    if lay.title_heading:
        lines.append(f"#show heading.where(level: 1): set text(size: {_n(lay.title_size)}pt)")
    for level, size in lay.heading_sizes:
        lines.append(f"#show heading.where(level: {level}): set text(size: {_n(size)}pt)")
    if lay.heading_space is not None:
        above, below = lay.heading_space
        lines.append(f"#show heading: set block(above: {_n(above)}em, below: {_n(below)}em)")
    if lay.equations_left:
        lines += ["#show math.equation.where(block: true): set block(above: 0.25em, "
                  "below: 0.25em, breakable: true)",
                  "#show math.equation.where(block: true): set align(left)"]
    lines.append(HELPERS)
    title = (f"= {typst_escape(doc.title)}" if lay.title_heading else
             f'#text(size: {_n(lay.title_size)}pt, weight: "bold", {typst_string(doc.title)})')
    return "\n".join(lines) + "\n\n" + title + "\n\n"


#: a numbered equation with its numbers under it; a result set off on a grey ground
HELPERS = """#let eqn(n, sym, num) = block(breakable: false, above: 0.45em, below: 0.45em, grid(
  columns: (1fr, 2.6em), column-gutter: 4pt, row-gutter: 1pt,
  pad(left: 0.6em, sym), align(right + horizon, text(fill: luma(90))[(#n)]),
  pad(left: 1.6em, num), []))
#let found(body) = block(above: 0.5em, below: 0.7em, fill: luma(242), inset: (x: 6pt, y: 4pt),
  radius: 2pt, width: 100%, body)"""
_MINUS = re.compile(r"-\d")   # a negative number's sign
SMALL = 8   # pt: side notes, a sheet's tables


def block(b, layout: d.Layout) -> str:
    """One block, with the blank line after it."""
    if isinstance(b, d.Heading):
        return "=" * b.level + " " + inline(b.text) + "\n\n"
    if isinstance(b, d.Paragraph):
        if b.small:
            return f"#text(size: {SMALL}pt)[{inline(b.text)}]\n\n"
        return inline(b.text) + "\n\n"
    if isinstance(b, d.Items):
        mark = "+ " if b.ordered else "- "
        intro = inline(b.intro) + "\n" if b.intro is not None else ""
        text = "".join(mark + inline(item) + "\n" for item in b.items)
        if b.small:
            text = f"#text(size: {SMALL}pt)[\n{text}]\n"
        return intro + text + "\n"
    if isinstance(b, d.Table):
        return "#" + _grid(b) + "\n\n" if b.print.grid else _table(b)
    if isinstance(b, d.Figure):
        size = f"height: {_n(b.height)}in" if b.height else f"width: {_n(b.width * 100)}%"
        return (f"#figure(image({typst_string(b.path)}, {size}), "
                f"caption: [{inline(b.caption)}])\n\n")
    if isinstance(b, d.Figures):
        return (f"#grid(columns: {b.columns}, column-gutter: 8pt, row-gutter: 6pt,\n"
                + "".join(f"  figure(image({typst_string(f.path)}, width: 100%), caption: "
                          f"[{inline(f.caption)}], supplement: none, numbering: none),\n"
                          for f in b.figures) + ")\n\n")
    if isinstance(b, d.Equation):
        from .sheet.expr import math
        if b.number is None:
            return f"$ {math(b.value, 'typ')} $\n\n"
        return (f"#eqn({b.number}, $ {math(b.value, 'typ')} $, "
                f"$ {math(b.numeric, 'typ')} $)\n\n")
    if isinstance(b, d.Found):
        label = inline(b.label) + " #h(0.4em) " if b.label and b.print_label else ""
        return ("#found[" + label + f", #h({_n(b.gap)}em) ".join(inline(i) for i in b.items)
                + "".join("; #h(0.3em) " + inline(m) for m in b.more) + "]\n\n")
    if isinstance(b, d.Columns):
        return ("#grid(columns: (" + ", ".join("auto" for _ in b.blocks)
                + "), column-gutter: 10pt,\n" + ",\n".join(_grid(x) for x in b.blocks)
                + ")\n\n")
    if isinstance(b, d.Gap):
        return ""
    if isinstance(b, d.Description):
        return typst_markdown(b.text) + "\n\n"
    raise TypeError(f"no Typst for the block {b!r}")


def _table(t: d.Table) -> str:
    """A table with rules above, under the header and below, and shaded even rows; a table
    wider than ``print.max_columns`` in parts that repeat its leading columns."""
    pr = t.print
    parts = [list(range(len(t.header)))]
    if pr.max_columns:
        lead = list(range(pr.lead))
        rest = list(range(pr.lead, len(t.header)))
        step = pr.max_columns - pr.lead
        parts = [lead + rest[a:a + step] for a in range(0, len(rest), step)] or [lead]
    out = []
    for cols in parts:
        columns = (str(len(cols)) if pr.widths is None else
                   "(" + ", ".join("auto" if w is None else f"{_n(w)}fr" for w in pr.widths) + ")")
        right = t.right if pr.right is None else pr.right
        align = ", ".join("right" if i in right else "left" for i in cols)
        align += "," if len(cols) == 1 else ""
        head = ", ".join(f'text(weight: "bold", {typst_string(_wrap(t.header[i]) if pr.wrap else t.header[i])})'
                         for i in cols)
        lines = ["#block(breakable: true, table(",
                 f"  columns: {columns}, align: ({align}), stroke: none,",
                 f"  inset: (x: 4pt, y: {_n(pr.inset)}pt),",
                 "  fill: (_, y) => if y > 0 and calc.even(y) { luma(244) },",
                 "  table.hline(stroke: 0.8pt),",
                 f"  table.header({head}),",
                 "  table.hline(stroke: 0.5pt),"]
        for row in t.rows:
            lines.append("  " + ", ".join(_cell(row, cols)) + ",")
        lines += ["  table.hline(stroke: 0.8pt),", "))"]
        out.append("\n".join(lines) + "\n")
    if t.note:
        out.append(f"#text(size: 8pt)[{inline(t.note)}]\n")
    return "".join(out) + "\n"


def _grid(t: d.Table) -> str:
    """A table of ruled cells, its header in bold (a code expression)."""
    pr = t.print
    right = t.right if pr.right is None else pr.right
    align = ", ".join("right" if i in right else "left" for i in range(len(t.header)))
    lines = [f"text(size: {_n(pr.size or SMALL)}pt, table(stroke: 0.4pt + luma(170), "
             f"inset: {_n(pr.inset)}pt, columns: {len(t.header)}, align: ({align}),",
             "  " + ", ".join(f"[#strong[{inline(h)}]]" for h in t.header) + ","]
    cols = range(len(t.header))
    lines += ["  " + ", ".join(_cell(row, cols)) + "," for row in t.rows]
    out = "\n".join(lines) + "\n))"
    if t.note:
        out += f"\n#text(size: {SMALL}pt)[{inline(t.note)}]"
    return out


def _cell(row, cols) -> list[str]:
    """The cells of ``row`` in the columns ``cols`` (a spanning cell covers the next ones)."""
    out, col = [], 0
    for cell in row:
        if isinstance(cell, d.Cell):
            if col in cols:
                text = inline(cell.text)
                text = f"#text(size: {SMALL}pt)[{text}]" if cell.small else text
                out.append(f"table.cell(colspan: {cell.span}, [{text}])")
            col += cell.span
        else:
            if col in cols:
                out.append(f"[{inline(cell)}]")
            col += 1
    return out


def _wrap(text) -> str:
    """A header with break opportunities (zero-width spaces) after dots and underscores and
    before its unit, so that a long key path in a narrow column wraps instead of overlapping."""
    text = str(text)
    head, sep, unit = text.partition(" [")
    if sep:                                   # the unit stays whole: [N m] never splits
        text = head + sep + unit.replace(" ", "\u00a0")
    return text.replace(".", ".\u200b").replace("_", "_\u200b").replace(" [", "\u200b [")


def inline(text) -> str:
    """Inline text (a string, a run or a list of them) as Typst markup."""
    return "".join(_run(r) for r in d.runs(text))


def _run(r) -> str:
    if isinstance(r, str):
        return typst_escape(r)
    if isinstance(r, d.Code):
        return f"#raw({typst_string(' '.join(str(r.text).split()))})"
    if isinstance(r, d.Strong):
        return f"#strong[{typst_escape(r.text)}]"
    if isinstance(r, d.Emph):
        return f"#emph[{typst_escape(r.text)}]"
    if isinstance(r, d.Link):
        return f"#link({typst_string(r.target)}, {typst_string(r.text)})"
    if isinstance(r, d.Math):
        from .sheet.expr import math
        return "$" + math(r.value, "typ") + "$"
    if isinstance(r, d.Aside):
        return f" \\ #text(size: 7pt, fill: luma(90), raw({typst_string(r.text)}))"
    if isinstance(r, d.Verdict):
        colour = PASS_COLOUR if r.passed else FAIL_COLOUR
        badge = f'#text(fill: rgb("{colour}"), weight: "bold", {typst_string(r.status)})'
        return badge + (f" #text(size: 7pt, {typst_string(r.detail)})" if r.detail else "")
    if isinstance(r, d.Number):
        text = str(r.text)
        if _MINUS.match(text):                  # markup sets "-1" with a minus sign
            return "-" + typst_escape(text[1:])
        return typst_escape(text)
    if isinstance(r, d.NewLine):
        return "\n\\ "
    if isinstance(r, d.Wording):              # its apostrophes typeset as such (’)
        return typst_escape(r.text).replace("\\'", "'")
    if isinstance(r, d.Either):
        return inline(r.print)
    raise TypeError(f"no Typst for the inline run {r!r}")


def _n(x: float) -> str:
    """A number as Typst writes a length: no trailing zeros."""
    return f"{x:g}"
