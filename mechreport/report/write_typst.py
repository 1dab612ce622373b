"""The Typst writer of a :class:`~.document.Doc` (compiled to PDF by :func:`.pdf.compile_typst`):
the page set up from the document's :class:`~.document.Layout`, then each block; inline text
by :mod:`.typst_inline` (the one Typst escaper), tables by :mod:`.typst_tables`.

A writer of another format dispatches on the same block and run classes of :mod:`.document`
(``markdown(doc)``, ``typst(doc)``: a document in, a string out)."""
from __future__ import annotations

from . import document as d
from .pdf import typst_escape, typst_markdown, typst_string
from .typst_inline import SMALL, inline, n
from .typst_tables import grid, table


def typst(doc: d.Doc) -> str:
    """``doc`` as Typst source."""
    out = [_preamble(doc)]
    out.extend(block(b, doc.layout) for b in doc.blocks)
    return "".join(out)


def _preamble(doc: d.Doc) -> str:
    lay = doc.layout
    m = [f"{n(x)}cm" for x in lay.margin]
    margin = (m[0] if len(m) == 1 else f"(x: {m[0]}, y: {m[1]})" if len(m) == 2 else
              f"(x: {m[0]}, top: {m[1]}, bottom: {m[2]})")
    flipped = "flipped: true, " if lay.landscape else ""
    leading = f", leading: {n(lay.leading)}em" if lay.leading is not None else ""
    leading += f", spacing: {n(lay.spacing)}em" if lay.spacing is not None else ""
    author = f", author: {typst_string(doc.author)}" if doc.author else ""
    header = ""
    if lay.header:
        left, right = lay.header
        header = (",\n  header: context { if counter(page).get().first() > 1 [\n"
                  f"    #set text(7.5pt, fill: luma(90)); {typst_escape(left)} #h(1fr) "
                  f"{typst_escape(right)} ] }}")
    lines = [f"#set document(title: {typst_string(doc.title)}{author}, date: none)",
             f'#set page(paper: "a4", {flipped}margin: {margin}, numbering: "1 / 1"{header})',
             f"#set text(size: {n(lay.size)}pt)",
             f"#set par(justify: {'true' if lay.justify else 'false'}{leading})"]
    if lay.numbered:
        lines.append('#set heading(numbering: "1.1")')
    for level, above, below in lay.level_spaces:
        lines.append(f"#show heading.where(level: {level}): "
                     f"set block(above: {n(above)}em, below: {n(below)}em)")
    if lay.figures_whole:
        lines += ["#show figure: set block(breakable: false)",
                  "#show figure.caption: set text(size: 8.5pt)", "#set figure(gap: 0.5em)"]
    if lay.title_heading:
        lines.append(f"#show heading.where(level: 1): set text(size: {n(lay.title_size)}pt)")
    for level, size in lay.heading_sizes:
        lines.append(f"#show heading.where(level: {level}): set text(size: {n(size)}pt)")
    if lay.heading_space is not None:
        above, below = lay.heading_space
        lines.append(f"#show heading: set block(above: {n(above)}em, below: {n(below)}em)")
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
        title = f'#text(size: {n(lay.title_size)}pt, weight: "bold", {typst_string(doc.title)})'
    return "\n".join(lines) + "\n\n" + title + "\n\n"


def _title_block(doc: d.Doc) -> str:
    """The title centred, the subtitle and the byline under it."""
    lines = ["#align(center)[",
             f'  #text(size: {n(doc.layout.title_size)}pt, weight: "bold", '
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


def block(b, layout: d.Layout) -> str:
    """One block, with the blank line after it."""
    write = _BLOCKS.get(type(b))
    if write is None:
        raise TypeError(f"no Typst for the block {b!r}")
    return write(b, layout)


def _heading(b: d.Heading, layout) -> str:
    return "=" * (b.level - layout.heading_shift) + " " + inline(b.text) + "\n\n"


def _paragraph(b: d.Paragraph, layout) -> str:
    if b.small:
        size = SMALL if b.small is True else b.small
        return f"#text(size: {n(size)}pt)[{inline(b.text)}]\n\n"
    return inline(b.text) + "\n\n"


def _items(b: d.Items, layout) -> str:
    mark = "+ " if b.ordered else "- "
    intro = inline(b.intro) + "\n" if b.intro is not None else ""
    text = "".join(_item(item, mark) for item in b.items)
    if b.small:
        text = f"#text(size: {SMALL}pt)[\n{text}]\n"
    return intro + text + "\n"


def _item(item, mark: str) -> str:
    if isinstance(item, d.Item):
        return (mark + inline(item.text) + "\n"
                + "".join(f"  {mark}{inline(s)}\n" for s in item.sub))
    return mark + inline(item) + "\n"


def _table(b: d.Table, layout) -> str:
    return "#" + grid(b) + "\n\n" if b.print.grid else table(b)


def _figure(b: d.Figure, layout) -> str:
    size = f"height: {n(b.height)}in" if b.height else f"width: {n(b.width * 100)}%"
    if isinstance(b.path, list):            # frames side by side, one caption
        body = ("grid(columns: (1fr, 1fr), gutter: 8pt,\n" + "".join(
            f"  image({typst_string(p)}, width: 100%),\n" for p in b.path) + ")")
    else:
        body = f"image({typst_string(b.path)}, {size})"
    return f"#figure({body}, caption: [{inline(b.caption)}])\n\n"


def _figures(b: d.Figures, layout) -> str:
    return (f"#grid(columns: {b.columns}, column-gutter: 8pt, row-gutter: 6pt,\n"
            + "".join(f"  figure(image({typst_string(f.path)}, width: 100%), caption: "
                      f"[{inline(f.caption)}], supplement: none, numbering: none),\n"
                      for f in b.figures) + ")\n\n")


def _equation(b: d.Equation, layout) -> str:
    from .sheet.expr import math
    if b.number is None:
        return f"$ {math(b.value, 'typ')} $\n\n"
    return f"#eqn({b.number}, $ {math(b.value, 'typ')} $, $ {math(b.numeric, 'typ')} $)\n\n"


def _found(b: d.Found, layout) -> str:
    label = inline(b.label) + " #h(0.4em) " if b.label and b.print_label else ""
    return ("#found[" + label + f", #h({n(b.gap)}em) ".join(inline(i) for i in b.items)
            + "".join("; #h(0.3em) " + inline(m) for m in b.more) + "]\n\n")


def _columns(b: d.Columns, layout) -> str:
    widths = b.widths or (None,) * len(b.blocks)
    cols = ", ".join("auto" if w is None else f"{n(w)}fr" for w in widths)
    cols += "," if len(widths) == 1 else ""
    return (f"#grid(columns: ({cols}), column-gutter: {n(b.gutter)}pt,\n"
            + ",\n".join(_column(x, layout) for x in b.blocks) + ")\n\n")


def _column(col, layout) -> str:
    """A column of a grid: a ruled table as it is, other blocks as content."""
    if isinstance(col, d.Table) and col.print.grid:
        return grid(col)
    blocks = col if isinstance(col, list) else [col]
    return "[\n" + "".join(block(x, layout) for x in blocks) + "]"


def _box(b: d.Box, layout) -> str:
    fill = "#e6f4e6" if b.tone == "PASS" else "#fbe3e3"
    return (f'#block(fill: rgb("{fill}"), inset: 7pt, radius: 3pt, width: 100%)[\n'
            "#set text(size: 8.5pt)\n#set par(justify: false)\n"
            + "".join(block(x, layout) for x in b.blocks) + "]\n\n")


def _pairs(b: d.Pairs, layout) -> str:
    return ("#block(width: 100%, inset: (y: 2pt))[\n#set text(size: 8pt)\n"
            "#set par(justify: false)\n#grid(columns: (auto, 1fr), column-gutter: 8pt, "
            "row-gutter: 3.5pt,\n"
            + "".join(f'  text(weight: "bold", {typst_string(k)}), [{inline(v)}],\n'
                      for k, v in b.rows) + ")\n]\n\n")


_BLOCKS = {
    d.Heading: _heading,
    d.Paragraph: _paragraph,
    d.Items: _items,
    d.Table: _table,
    d.Figure: _figure,
    d.Figures: _figures,
    d.Equation: _equation,
    d.Found: _found,
    d.Columns: _columns,
    d.Only: lambda b, layout: "".join(block(x, layout) for x in b.blocks) if b.print else "",
    d.Space: lambda b, layout: f"#v({n(b.em)}em)\n\n",
    d.Box: _box,
    d.Pairs: _pairs,
    d.Gap: lambda b, layout: "",
    d.Description: lambda b, layout: typst_markdown(b.text) + "\n\n",
}
