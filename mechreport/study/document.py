"""A small document model written out both as Markdown and as Typst (study.md / study.pdf)
through the reports' Jinja2 environment (templates/study.md.j2, study.typ.j2), so the two say
the same thing. User text (names, keys, messages) is escaped for each format by
the report's one escaper of each (:func:`~mechreport.report.markdown.md_inline`,
:func:`~mechreport.report.pdf.typst_escape`).

Inline text is a list of parts: a plain string, or ``("b", text)`` (bold) or ``("code",
text)`` (monospace)."""
from __future__ import annotations

from dataclasses import dataclass, field

from ..report.markdown import md_inline
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

    def markdown(self) -> str:
        """study.md (templates/study.md.j2)."""
        return _render(self, "study.md.j2").rstrip() + "\n"

    def typst(self) -> str:
        """The Typst source of study.pdf (templates/study.typ.j2)."""
        return _render(self, "study.typ.j2")


def _render(doc: Doc, template: str) -> str:
    """``doc`` through ``template`` with the reports' Jinja2 environment and its escaping
    filters, plus this document's own: inline parts (``md_parts``, ``typ_parts``), header
    break points (``breakable``) and a wide table's parts (``column_parts``)."""
    from ..report.render import environment
    env = environment()
    env.filters.update(md_parts=_md_inline, typ_parts=_typ_inline, breakable=_breakable,
                       column_parts=_column_parts)
    return env.get_template(template).render(doc=doc)


def _column_parts(header: list[str]) -> list[list[int]]:
    """A page holds about ``MAX_COLUMNS`` columns of numbers: a wider table is split into
    parts (column indices) that each repeat the leading columns (rank and variant)."""
    lead = list(range(2 if header[1:2] == ["variant"] else 1))
    rest = list(range(len(lead), len(header)))
    step = MAX_COLUMNS - len(lead)
    return [lead + rest[a:a + step] for a in range(0, len(rest), step)] or [lead]


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
