"""The Markdown writer of a :class:`~.document.Doc`: GitHub Markdown, user text escaped by the
one Markdown escaper (:func:`.markdown.md_inline`; a user's own Markdown by
:func:`.markdown.md_text`, link targets by :func:`.markdown.md_url`), math as TeX between
dollars. Each block ends with a blank line; the file ends with one line break (with an empty
line after it where the document asks for one: the sheets)."""
from __future__ import annotations

from . import document as d
from .markdown import md_inline, md_text, md_url


def markdown(doc: d.Doc) -> str:
    """``doc`` as Markdown."""
    out = [f"# {_trim(doc.title)}\n\n"]
    if doc.subtitle:
        out.append(f"**{_trim(doc.subtitle)}**\n\n")
    out.extend(block(b) for b in doc.blocks)
    text = "".join(out)
    return text if doc.end_blank else text.rstrip() + "\n"


def block(b) -> str:
    """One block, with the blank line after it."""
    if isinstance(b, d.Heading):
        return "#" * b.level + " " + _trim(b.text) + "\n\n"
    if isinstance(b, d.Paragraph):
        return inline(b.text) + ("\n" if b.tight else "\n\n")
    if isinstance(b, d.Items):
        intro = inline(b.intro) + "\n\n" if b.intro is not None else ""
        return intro + "".join(_item(item, f"{i}. " if b.ordered else "- ")
                               for i, item in enumerate(b.items, 1)) + "\n"
    if isinstance(b, d.Table):
        return _table(b)
    if isinstance(b, d.Figure):
        alt = _trim(b.caption if b.alt is None else b.alt)
        paths = b.path if isinstance(b.path, list) else [b.path]
        text = "".join(f"![{alt}]({md_url(p)})\n\n" for p in paths)
        return text + (f"*{_trim(b.caption)}*\n\n" if b.caption_below else "")
    if isinstance(b, d.Figures):
        return "".join(f"![{_trim(f.caption if f.alt is None else f.alt)}]({md_url(f.path)}) "
                       for f in b.figures) + "\n\n"
    if isinstance(b, d.Equation):
        from .sheet.expr import math
        tag = f" \\tag{{{b.number}}}" if b.number is not None else ""
        text = f"$${math(b.value, 'tex')}{tag}$$\n\n"
        if b.numeric is not None:
            text += f"$$\\Rightarrow\\quad {math(b.numeric, 'tex')}$$\n\n"
        return text
    if isinstance(b, d.Found):
        label = f"**{_trim(b.label)}** " if b.label else ""
        return (label + ", ".join(inline(i) for i in b.items)
                + "".join("; " + inline(m) for m in b.more) + "\n\n")
    if isinstance(b, d.Columns):
        return "".join(block(x) for col in b.blocks
                       for x in (col if isinstance(col, list) else [col]))
    if isinstance(b, d.Gap):
        return "\n"
    if isinstance(b, d.Description):
        return "".join(md_text(p) + "\n\n" for p in b.paragraphs)
    if isinstance(b, d.Only):
        return "" if b.print else "".join(block(x) for x in b.blocks)
    if isinstance(b, d.Space):
        return ""
    if isinstance(b, d.Box):
        return "".join(block(x) for x in b.blocks)
    if isinstance(b, d.Pairs):
        return ("| | |\n|---|---|\n" + "".join(f"| {_trim(k)} | {_trim(v)} |\n"
                                                for k, v in [*b.rows, *b.text_rows]) + "\n")
    raise TypeError(f"no Markdown for the block {b!r}")


def _item(item, mark: str) -> str:
    if isinstance(item, d.Item):
        return mark + inline(item.text) + "\n" + "".join(f"  - {inline(s)}\n" for s in item.sub)
    return mark + inline(item) + "\n"


def _table(t: d.Table) -> str:
    lines = ["| " + " | ".join(_trim(h) for h in t.header) + " |" + (" " if t.header_blank else ""),
             "|" + "".join("---:|" if i in t.right else "---|" for i in range(len(t.header)))]
    lines += ["|" + "|".join(" " if c is None else f" {c} " for c in _cells(row)) + "|"
              for row in t.rows]
    text = "\n".join(lines) + "\n\n"
    return text + (_trim(t.note) + "\n\n" if t.note else "")


def _cells(row) -> list[str]:
    """A row's cells (None: a blank one); a spanning cell as its filler cells, then its
    text."""
    out = []
    for cell in row:
        if isinstance(cell, d.Blank):
            out.append(None)
        elif isinstance(cell, d.Cell):
            out += [_trim(cell.fill)] * (cell.span - 1) + [_trim(cell.text)]
        else:
            out.append(_trim(cell))
    return out


def inline(text) -> str:
    """Inline text (a string, a run or a list of them) as Markdown."""
    return "".join(_run(r) for r in d.runs(text))


def _trim(text) -> str:
    """Inline text where it stands alone (a heading, a table cell, a caption, a note): without
    blanks at either end."""
    return inline(text).strip()


def _run(r) -> str:
    if isinstance(r, str):
        return _plain(r)
    if isinstance(r, d.Code):
        return f"`{_code(r.text)}`"
    if isinstance(r, d.Strong):
        return f"**{md_inline(r.text)}**"
    if isinstance(r, d.Emph):
        return f"*{md_inline(r.text)}*"
    if isinstance(r, d.Link):
        return f"[{md_inline(r.text)}]({md_url(r.target)})"
    if isinstance(r, d.Math):
        from .sheet.expr import math
        return "$" + math(r.value, "tex") + "$"
    if isinstance(r, d.Aside):
        return f" ({md_inline(r.text)})"
    if isinstance(r, d.Verdict):
        return md_inline(r.status) + (f": {md_inline(r.detail)}" if r.detail else "")
    if isinstance(r, d.Key):
        return f"`{_code(r.text)}`"
    if isinstance(r, d.Ref):
        return f"[{md_inline(r.text)}](#{r.anchor})"
    if isinstance(r, d.Number):
        return md_inline(r.text)
    if isinstance(r, d.NewLine):
        return "\n"
    if isinstance(r, d.Wording):
        return r.text
    if isinstance(r, d.Either):
        return inline(r.text)
    raise TypeError(f"no Markdown for the inline run {r!r}")


def _plain(text: str) -> str:
    """Plain text, escaped; one blank kept at either end where it has one (the escaper trims,
    but text next to a run needs its space)."""
    text = str(text)
    core = md_inline(text)
    lead = " " if text[:1].isspace() else ""
    tail = " " if text[-1:].isspace() and core else ""
    return lead + core + tail


def _code(text: str) -> str:
    """Text for a code span: backticks and line breaks cannot end it early."""
    return " ".join(str(text).replace("`", "'").split())
