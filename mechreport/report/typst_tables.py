"""Tables of a :class:`~.document.Doc` in Typst (for :mod:`.write_typst`): ruled above, under
the header and below with shaded rows (:func:`table`), or ruled cells (:func:`grid`, a sheet's
data)."""
from __future__ import annotations

from . import document as d
from .pdf import typst_string
from .typst_inline import SMALL, inline, n


def _head(h, wrap: bool) -> str:
    """A header cell, bold."""
    if isinstance(h, str):
        return f'text(weight: "bold", {typst_string(_wrap(h) if wrap else h)})'
    return f'text(weight: "bold")[{inline(h)}]'


def table(t: d.Table) -> str:
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
                   "(" + ", ".join("auto" if w is None else f"{n(w)}fr" for w in pr.widths) + ")")
        right = t.right if pr.right is None else pr.right
        align = ", ".join("right" if i in right else "left" for i in cols)
        align += "," if len(cols) == 1 else ""
        head = ", ".join(_head(t.header[i], pr.wrap) for i in cols)
        breakable = "true" if not pr.keep or len(t.rows) > 30 else "false"
        size = f"#set text(size: {n(pr.size)}pt)\n" if pr.size else ""
        lines = [f"#block(breakable: {breakable})[\n{size}#set par(justify: false)\n#table(",
                 f"  columns: {columns}, align: ({align}), stroke: none,",
                 f"  inset: (x: {n(pr.inset_x)}pt, y: {n(pr.inset)}pt),",
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


def grid(t: d.Table) -> str:
    """A table of ruled cells, its header in bold (a code expression)."""
    pr = t.print
    right = t.right if pr.right is None else pr.right
    align = ", ".join("right" if i in right else "left" for i in range(len(t.header)))
    lines = [f"text(size: {n(pr.size or SMALL)}pt, table(stroke: 0.4pt + luma(170), "
             f"inset: {n(pr.inset)}pt, columns: {len(t.header)}, align: ({align}),",
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
