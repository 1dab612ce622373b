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
    author = f", author: {typst_string(doc.author)}" if doc.author else ""
    header = ""
    if lay.header:
        left, right = lay.header
        header = (",\n  header: context { if counter(page).get().first() > 1 [\n"
                  f"    #set text(7.5pt, fill: luma(90)); {typst_escape(left)} #h(1fr) "
                  f"{typst_escape(right)} ] }}")
    lines = [f"#set document(title: {typst_string(doc.title)}{author}, date: none)",
             f'#set page(paper: "a4", {flipped}margin: {margin}, numbering: "1 / 1"{header})',
             f"#set text(size: {_n(lay.size)}pt)",
             f"#set par(justify: {'true' if lay.justify else 'false'}{leading})"]
    if lay.numbered:
        lines.append('#set heading(numbering: "1.1")')
    for level, above, below in lay.level_spaces:
        lines.append(f"#show heading.where(level: {level}): "
                     f"set block(above: {_n(above)}em, below: {_n(below)}em)")
    if lay.figures_whole:
        lines += ["#show figure: set block(breakable: false)",
                  "#show figure.caption: set text(size: 8.5pt)", "#set figure(gap: 0.5em)"]
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
    if lay.title_heading:
        title = f"= {typst_escape(doc.title)}"
    elif lay.title_center:
        title = _title_block(doc)
    else:
        title = f'#text(size: {_n(lay.title_size)}pt, weight: "bold", {typst_string(doc.title)})'
    return "\n".join(lines) + "\n\n" + title + "\n\n"


def _title_block(doc: d.Doc) -> str:
    """The title centred, the subtitle and the byline under it."""
    lines = ["#align(center)[",
             f'  #text(size: {_n(doc.layout.title_size)}pt, weight: "bold", '
             f"{typst_string(doc.title)}) \\"]
    if doc.subtitle:
        lines += ["  #v(0.15em)", f"  #text(size: 11pt, {typst_string(doc.subtitle)}) \\"]
    if doc.byline is not None:
        lines += ["  #v(0.2em)", f"  #text(size: 9pt, fill: luma(80))[{inline(doc.byline)}]"]
    return "\n".join(lines + ["]"])


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
        return "=" * (b.level - layout.heading_shift) + " " + inline(b.text) + "\n\n"
    if isinstance(b, d.Paragraph):
        if b.small:
            size = SMALL if b.small is True else b.small
            return f"#text(size: {_n(size)}pt)[{inline(b.text)}]\n\n"
        return inline(b.text) + "\n\n"
    if isinstance(b, d.Items):
        mark = "+ " if b.ordered else "- "
        intro = inline(b.intro) + "\n" if b.intro is not None else ""
        text = "".join(_item(item, mark) for item in b.items)
        if b.small:
            text = f"#text(size: {SMALL}pt)[\n{text}]\n"
        return intro + text + "\n"
    if isinstance(b, d.Table):
        return "#" + _grid(b) + "\n\n" if b.print.grid else _table(b)
    if isinstance(b, d.Figure):
        size = f"height: {_n(b.height)}in" if b.height else f"width: {_n(b.width * 100)}%"
        if isinstance(b.path, list):            # frames side by side, one caption
            body = ("grid(columns: (1fr, 1fr), gutter: 8pt,\n" + "".join(
                f"  image({typst_string(p)}, width: 100%),\n" for p in b.path) + ")")
        else:
            body = f"image({typst_string(b.path)}, {size})"
        return f"#figure({body}, caption: [{inline(b.caption)}])\n\n"
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
        widths = b.widths or (None,) * len(b.blocks)
        cols = ", ".join("auto" if w is None else f"{_n(w)}fr" for w in widths)
        cols += "," if len(widths) == 1 else ""
        return (f"#grid(columns: ({cols}), column-gutter: {_n(b.gutter)}pt,\n"
                + ",\n".join(_column(x, layout) for x in b.blocks) + ")\n\n")
    if isinstance(b, d.Only):
        return "".join(block(x, layout) for x in b.blocks) if b.print else ""
    if isinstance(b, d.Space):
        return f"#v({_n(b.em)}em)\n\n"
    if isinstance(b, d.Box):
        fill = "#e6f4e6" if b.tone == "PASS" else "#fbe3e3"
        return (f'#block(fill: rgb("{fill}"), inset: 7pt, radius: 3pt, width: 100%)[\n'
                "#set text(size: 8.5pt)\n#set par(justify: false)\n"
                + "".join(block(x, layout) for x in b.blocks) + "]\n\n")
    if isinstance(b, d.Pairs):
        return ("#block(width: 100%, inset: (y: 2pt))[\n#set text(size: 8pt)\n"
                "#set par(justify: false)\n#grid(columns: (auto, 1fr), column-gutter: 8pt, "
                "row-gutter: 3.5pt,\n" + "".join(
                    f'  text(weight: "bold", {typst_string(k)}), [{inline(v)}],\n'
                    for k, v in b.rows) + ")\n]\n\n")
    if isinstance(b, d.Gap):
        return ""
    if isinstance(b, d.Description):
        return typst_markdown(b.text) + "\n\n"
    raise TypeError(f"no Typst for the block {b!r}")


def _item(item, mark: str) -> str:
    if isinstance(item, d.Item):
        return (mark + inline(item.text) + "\n"
                + "".join(f"  {mark}{inline(s)}\n" for s in item.sub))
    return mark + inline(item) + "\n"


def _column(col, layout) -> str:
    """A column of a grid: a ruled table as it is, other blocks as content."""
    if isinstance(col, d.Table) and col.print.grid:
        return _grid(col)
    blocks = col if isinstance(col, list) else [col]
    return "[\n" + "".join(block(x, layout) for x in blocks) + "]"


def _head(h, wrap: bool) -> str:
    """A header cell, bold."""
    if isinstance(h, str):
        return f'text(weight: "bold", {typst_string(_wrap(h) if wrap else h)})'
    return f'text(weight: "bold")[{inline(h)}]'


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
        head = ", ".join(_head(t.header[i], pr.wrap) for i in cols)
        breakable = "true" if not pr.keep or len(t.rows) > 30 else "false"
        size = f"#set text(size: {_n(pr.size)}pt)\n" if pr.size else ""
        lines = [f"#block(breakable: {breakable})[\n{size}#set par(justify: false)\n#table(",
                 f"  columns: {columns}, align: ({align}), stroke: none,",
                 f"  inset: (x: {_n(pr.inset_x)}pt, y: {_n(pr.inset)}pt),",
                 "  fill: (_, y) => if y > 0 and calc.even(y) { luma(244) },",
                 "  table.hline(stroke: 0.8pt),",
                 f"  table.header({head}),",
                 "  table.hline(stroke: 0.5pt),"]
        for row in t.rows:
            lines.append("  " + ", ".join(_cell(row, cols)) + ",")
        lines += ["  table.hline(stroke: 0.8pt),", ")]"]
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
        if isinstance(cell, d.Blank):
            cell = ""
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
    if isinstance(r, d.Key):
        return f"#text(size: 6.5pt, fill: luma(90), raw({typst_string(r.text)}))"
    if isinstance(r, d.Ref):
        return typst_escape(r.text)
    if isinstance(r, d.Number):
        text = str(r.text)
        if _MINUS.match(text):                  # markup sets "-1" with a minus sign
            return "-" + typst_escape(text[1:])
        return typst_escape(text)
    if isinstance(r, d.NewLine):
        return "\n\\ " if r.hard else "\n"
    if isinstance(r, d.Wording):              # its apostrophes typeset as such (’)
        return typst_escape(r.text).replace("\\'", "'")
    if isinstance(r, d.Either):
        return inline(r.print)
    raise TypeError(f"no Typst for the inline run {r!r}")


def _n(x: float) -> str:
    """A number as Typst writes a length: no trailing zeros."""
    return f"{x:g}"
