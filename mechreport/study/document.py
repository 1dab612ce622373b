"""A small document model written out both as Markdown and as Typst (study.md / study.pdf),
so the two say the same thing. User text (names, keys, messages) is escaped for each format by
the report's one escaper of each (:func:`~mechreport.report.markdown.md_inline`,
:func:`~mechreport.report.pdf.typst_escape`).

Inline text is a list of parts: a plain string, or ``("b", text)`` (bold) or ``("code",
text)`` (monospace)."""
from __future__ import annotations

from dataclasses import dataclass, field

from ..report.markdown import md_inline, md_url
from ..report.pdf import typst_escape, typst_string

Inline = list  # of str | tuple[str, str]


@dataclass
class Doc:
    title: str
    blocks: list = field(default_factory=list)

    def h(self, text: str) -> None:
        self.blocks.append(("h", text))

    def p(self, *parts) -> None:
        self.blocks.append(("p", list(parts)))

    def items(self, items: list[Inline]) -> None:
        self.blocks.append(("ul", items))

    def table(self, header: list[str], rows: list[list[str]], right: set[int] = frozenset(),
              note: str = "") -> None:
        self.blocks.append(("table", header, rows, set(right), note))

    def image(self, path: str, caption: str, height: float | None = None) -> None:
        self.blocks.append(("img", path, caption, height))

    # ----------------------------------------------------------------------- Markdown

    def markdown(self) -> str:
        out = [f"# {md_inline(self.title)}", ""]
        for block in self.blocks:
            kind = block[0]
            if kind == "h":
                out += [f"## {md_inline(block[1])}", ""]
            elif kind == "p":
                out += [_md_inline(block[1]), ""]
            elif kind == "ul":
                out += [f"- {_md_inline(item)}" for item in block[1]] + [""]
            elif kind == "table":
                _, header, rows, right, note = block
                out.append("| " + " | ".join(md_inline(h) for h in header) + " |")
                out.append("|" + "|".join("---:" if i in right else "---"
                                          for i in range(len(header))) + "|")
                for row in rows:
                    out.append("| " + " | ".join(md_inline(c) for c in row) + " |")
                out.append("")
                if note:
                    out += [md_inline(note), ""]
            elif kind == "img":
                _, path, caption, _h = block
                out += [f"![{md_inline(caption)}]({md_url(path)})", "", f"*{md_inline(caption)}*",
                        ""]
        return "\n".join(out).rstrip() + "\n"

    # -------------------------------------------------------------------------- Typst

    def typst(self) -> str:
        out = [
            f"#set document(title: {typst_string(self.title)}, date: none)",
            '#set page(paper: "a4", margin: (x: 1.8cm, y: 1.8cm), numbering: "1 / 1")',
            "#set text(size: 9pt)",
            "#set par(justify: false)",
            "#show heading.where(level: 2): set text(size: 11.5pt)",
            "#show heading: set block(above: 1.3em, below: 0.7em)",
            "",
            f"#text(size: 16pt, weight: \"bold\", {typst_string(self.title)})",
            "",
        ]
        for block in self.blocks:
            kind = block[0]
            if kind == "h":
                out += [f"== {typst_escape(block[1])}", ""]
            elif kind == "p":
                out += [_typ_inline(block[1]), ""]
            elif kind == "ul":
                out += [f"- {_typ_inline(item)}" for item in block[1]] + [""]
            elif kind == "table":
                _, header, rows, right, note = block
                # a page holds about MAX_COLUMNS columns of numbers: a wider table is split
                # into parts that each repeat the leading columns (rank and variant)
                lead = list(range(2 if header[1:2] == ["variant"] else 1))
                rest = list(range(len(lead), len(header)))
                step = MAX_COLUMNS - len(lead)
                parts = [lead + rest[a:a + step] for a in range(0, len(rest), step)] or [lead]
                for cols in parts:
                    out += _typ_table([header[i] for i in cols],
                                      [[row[i] for i in cols] for row in rows],
                                      {k for k, i in enumerate(cols) if i in right})
                if note:
                    out.append(f"#text(size: 8pt)[{typst_escape(note)}]")
                out.append("")
            elif kind == "img":
                _, path, caption, height = block
                size = f"height: {height:g}in" if height else "width: 100%"
                out += [f"#figure(image({typst_string(path)}, {size}), "
                        f"caption: [{typst_escape(caption)}])", ""]
        return "\n".join(out) + "\n"


def _breakable(text: str) -> str:
    """``text`` with break opportunities (zero-width spaces) after dots and underscores and
    before units, so that a long key path in a narrow column header wraps instead of
    overlapping."""
    text = str(text)
    head, sep, unit = text.partition(" [")
    if sep:                                   # the unit stays whole: [N m] never splits
        text = head + sep + unit.replace(" ", "\u00a0")
    return text.replace(".", ".\u200b").replace("_", "_\u200b").replace(" [", "\u200b [")


def _md_inline(parts: Inline) -> str:
    out = []
    for part in parts:
        if isinstance(part, tuple):
            kind, text = part
            out.append(f"**{md_inline(text)}**" if kind == "b" else f"`{_md_code(text)}`")
        else:
            text = " ".join(str(part).split("\n"))
            lead = " " if text[:1] == " " else ""
            tail = " " if text[-1:] == " " and text.strip() else ""
            out.append(lead + md_inline(text) + tail)
    return "".join(out)


def _md_code(text: str) -> str:
    """Text for a code span: backticks and line breaks cannot end it early."""
    return " ".join(str(text).replace("`", "'").split())


def _typ_inline(parts: Inline) -> str:
    out = []
    for part in parts:
        if isinstance(part, tuple):
            kind, text = part
            out.append(f"#strong[{typst_escape(text)}]" if kind == "b"
                       else f"#raw({typst_string(' '.join(str(text).split()))})")
        else:
            out.append(typst_escape(part))
    return "".join(out)


MAX_COLUMNS = 8   # columns of a study table that fit a page side by side


def _typ_table(header: list[str], rows: list[list[str]], right: set[int]) -> list[str]:
    """One Typst table (striped, header repeated on each page)."""
    n = len(header)
    align = "(" + ", ".join("right" if i in right else "left"
                            for i in range(n)) + ("," if n == 1 else "") + ")"
    out = ["#block(breakable: true, table(",
           f"  columns: {n}, align: {align}, stroke: none,",
           "  inset: (x: 4pt, y: 2.5pt),",
           "  fill: (_, y) => if y > 0 and calc.even(y) { luma(244) },",
           "  table.hline(stroke: 0.8pt),",
           "  table.header(" + ", ".join(
               f"text(weight: \"bold\", {typst_string(_breakable(h))})" for h in header) + "),",
           "  table.hline(stroke: 0.5pt),"]
    out += ["  " + ", ".join(f"[{typst_escape(c)}]" for c in row) + "," for row in rows]
    out += ["  table.hline(stroke: 0.8pt),", "))"]
    return out

