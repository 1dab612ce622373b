"""The HTML writer of a :class:`~.document.Doc`, the third beside Markdown and Typst: the
document's blocks as an HTML fragment (no page around it: :mod:`.html_page` adds the head,
the styles, the scripts and the data of an interactive page). Every string is escaped by the
one escaper, :func:`esc` (``& < > " '``), so user text never becomes markup; a user's own
Markdown (a spec's ``description``) is rendered by markdown-it with raw HTML and images off
(an image could only be a request the page's Content-Security-Policy blocks), and links that
markdown-it does not refuse (``javascript:`` and the like are refused) open as plain links.

Headings get the ids GitHub gives report.md's headings, so :class:`~.document.Ref` links work
the same; a verdict (a :class:`~.document.Verdict`, or a table cell that reads just PASS or
FAIL: a design verdict) is a PASS/FAIL badge; math is written in its plain-text form."""
from __future__ import annotations

import html as _html

from . import document as d


def esc(text) -> str:
    """``text`` as HTML text or attribute value: ``& < > " '`` escaped."""
    return _html.escape(str(text), quote=True)


def html_body(doc: d.Doc, before_sections: str = "", figure_class=None) -> str:
    """The blocks of ``doc`` (its title as the page's ``h1``) as an HTML fragment;
    ``before_sections``: HTML put before the first heading after the title (a page's own
    parts, after the report's first lines). ``figure_class(path)``: a CSS class for a
    figure's image, or None."""
    w = _Writer(figure_class or (lambda path: None))
    out = [f"<h1>{w.inline(doc.title)}</h1>\n"]
    if doc.subtitle:
        out.append(f"<p class=\"subtitle\"><strong>{w.inline(doc.subtitle)}</strong></p>\n")
    for b in doc.blocks:
        if before_sections and _opens_section(b):
            out.append(before_sections)
            before_sections = ""
        out.append(w.block(b))
    out.append(before_sections)
    return "".join(out)


def _opens_section(b) -> bool:
    """Whether block ``b`` starts with a heading (a heading, or a group of blocks that the
    text formats show, starting with one)."""
    if isinstance(b, d.Heading):
        return True
    if isinstance(b, (d.Only, d.Box)) and not getattr(b, "print", False) and b.blocks:
        return _opens_section(b.blocks[0])
    return False


class _Writer:
    """One document's writer: it remembers the heading ids given (repeats get ``-1``,
    ``-2``, as on GitHub)."""

    def __init__(self, figure_class):
        self.ids: dict[str, int] = {}
        self.figure_class = figure_class

    # ------------------------------------------------------------------------- blocks
    def block(self, b) -> str:
        if isinstance(b, d.Heading):
            text = plain(b.text)
            base = d.heading_id(text)
            n = self.ids.get(base, 0)
            self.ids[base] = n + 1
            hid = base if n == 0 else f"{base}-{n}"
            level = min(max(b.level, 1), 6)
            return f"<h{level} id=\"{esc(hid)}\">{self.inline(b.text)}</h{level}>\n"
        if isinstance(b, d.Paragraph):
            cls = " class=\"small\"" if b.small else ""
            return f"<p{cls}>{self.inline(b.text)}</p>\n"
        if isinstance(b, d.Items):
            intro = f"<p>{self.inline(b.intro)}</p>\n" if b.intro is not None else ""
            tag = "ol" if b.ordered else "ul"
            return (intro + f"<{tag}>" + "".join(self._item(i) for i in b.items)
                    + f"</{tag}>\n")
        if isinstance(b, d.Table):
            return self._table(b)
        if isinstance(b, d.Figure):
            paths = b.path if isinstance(b.path, list) else [b.path]
            alt = plain(b.caption if b.alt is None else b.alt)
            imgs = "".join(self._img(p, alt) for p in paths)
            return (f"<figure>{imgs}<figcaption>{self.inline(b.caption)}</figcaption>"
                    "</figure>\n")
        if isinstance(b, d.Figures):
            return ("<div class=\"figures\">" + "".join(
                f"<figure>{self._img(f.path, plain(f.caption if f.alt is None else f.alt))}"
                f"<figcaption>{self.inline(f.caption)}</figcaption></figure>"
                for f in b.figures) + "</div>\n")
        if isinstance(b, d.Equation):
            from .sheet.expr import math
            tag = f" <span class=\"tag\">({b.number})</span>" if b.number is not None else ""
            text = f"<p class=\"equation\">{esc(math(b.value, 'plain'))}{tag}</p>\n"
            if b.numeric is not None:
                text += f"<p class=\"equation\">⇒ {esc(math(b.numeric, 'plain'))}</p>\n"
            return text
        if isinstance(b, d.Found):
            label = f"<strong>{self.inline(b.label)}</strong> " if b.label else ""
            return (f"<p class=\"found\">{label}" + ", ".join(self.inline(i) for i in b.items)
                    + "".join("; " + self.inline(m) for m in b.more) + "</p>\n")
        if isinstance(b, d.Columns):
            return "".join(self.block(x) for col in b.blocks
                           for x in (col if isinstance(col, list) else [col]))
        if isinstance(b, (d.Gap, d.Space)):
            return ""
        if isinstance(b, d.Description):
            return "<div class=\"description\">" + "".join(
                description_html(p) for p in b.paragraphs) + "</div>\n"
        if isinstance(b, d.Only):
            return "" if b.print else "".join(self.block(x) for x in b.blocks)
        if isinstance(b, d.Box):
            tone = "pass" if b.tone == "PASS" else "fail"
            return (f"<div class=\"box {tone}\">" + "".join(self.block(x) for x in b.blocks)
                    + "</div>\n")
        if isinstance(b, d.Pairs):
            return ("<table class=\"pairs\"><tbody>" + "".join(
                f"<tr><th>{self.inline(k)}</th><td>{self.inline(v)}</td></tr>"
                for k, v in [*b.rows, *b.text_rows]) + "</tbody></table>\n")
        raise TypeError(f"no HTML for the block {b!r}")

    def _img(self, path: str, alt: str) -> str:
        cls = self.figure_class(path)
        attr = f" class=\"{esc(cls)}\"" if cls else ""
        return f"<img src=\"{esc(path)}\" alt=\"{esc(alt)}\"{attr} loading=\"lazy\">"

    def _item(self, item) -> str:
        if isinstance(item, d.Item):
            sub = ("<ul>" + "".join(f"<li>{self.inline(s)}</li>" for s in item.sub) + "</ul>"
                   if item.sub else "")
            return f"<li>{self.inline(item.text)}{sub}</li>"
        return f"<li>{self.inline(item)}</li>"

    def _table(self, t: d.Table) -> str:
        def cls(i: int) -> str:
            return " class=\"num\"" if i in t.right else ""

        head = "".join(f"<th{cls(i)}>{self.inline(h)}</th>" for i, h in enumerate(t.header))
        rows = []
        for row in t.rows:
            cells, i = [], 0
            for cell in row:
                if isinstance(cell, d.Blank):
                    cells.append(f"<td{cls(i)}></td>")
                    i += 1
                elif isinstance(cell, d.Cell):
                    small = " small" if cell.small else ""
                    cells.append(f"<td colspan=\"{cell.span}\" class=\"span{small}\">"
                                 f"{self.inline(cell.text)}</td>")
                    i += cell.span
                elif isinstance(cell, str) and cell.strip() in ("PASS", "FAIL"):
                    cells.append(f"<td{cls(i)}>{badge(cell.strip())}</td>")   # a verdict
                    i += 1
                else:
                    cells.append(f"<td{cls(i)}>{self.inline(cell)}</td>")
                    i += 1
            rows.append("<tr>" + "".join(cells) + "</tr>")
        note = f"<p class=\"small note\">{self.inline(t.note)}</p>\n" if t.note else ""
        return (f"<div class=\"table\"><table><thead><tr>{head}</tr></thead><tbody>"
                + "\n".join(rows) + "</tbody></table></div>\n" + note)

    # ------------------------------------------------------------------------- inline
    def inline(self, text) -> str:
        return "".join(self._run(r) for r in d.runs(text))

    def _run(self, r) -> str:
        if isinstance(r, str):
            return esc(r)
        if isinstance(r, (d.Code, d.Key)):
            return f"<code>{esc(r.text)}</code>"
        if isinstance(r, d.Strong):
            return f"<strong>{esc(r.text)}</strong>"
        if isinstance(r, d.Emph):
            return f"<em>{esc(r.text)}</em>"
        if isinstance(r, d.Link):
            return f"<a href=\"{esc(_target(r.target))}\">{esc(r.text)}</a>"
        if isinstance(r, d.Ref):
            return f"<a href=\"#{esc(r.anchor)}\">{esc(r.text)}</a>"
        if isinstance(r, d.Math):
            from .sheet.expr import math
            return f"<span class=\"math\">{esc(math(r.value, 'plain'))}</span>"
        if isinstance(r, d.Aside):
            return f" <span class=\"aside\">({esc(r.text)})</span>"
        if isinstance(r, d.Verdict):
            return badge(r.status) + (f" {esc(r.detail)}" if r.detail else "")
        if isinstance(r, d.Number):
            return f"<span class=\"number\">{esc(r.text)}</span>"
        if isinstance(r, d.NewLine):
            return "<br>" if r.hard else "\n"
        if isinstance(r, d.Wording):
            return esc(r.text)
        if isinstance(r, d.Either):
            return self.inline(r.text)
        raise TypeError(f"no HTML for the inline run {r!r}")


def badge(status: str) -> str:
    """A PASS / FAIL badge (any other status as a neutral one)."""
    tone = {"PASS": "pass", "FAIL": "fail"}.get(str(status), "other")
    return f"<span class=\"badge {tone}\">{esc(status)}</span>"


def plain(text) -> str:
    """Inline text without markup (a heading's id, an image's alt text)."""
    out = []
    for r in d.runs(text):
        if isinstance(r, str):
            out.append(r)
        elif isinstance(r, d.Either):
            out.append(plain(r.text))
        elif isinstance(r, d.Math):
            from .sheet.expr import math
            out.append(math(r.value, "plain"))
        elif isinstance(r, d.Verdict):
            out.append(r.status + (f": {r.detail}" if r.detail else ""))
        elif isinstance(r, d.Aside):
            out.append(f" ({r.text})")
        elif isinstance(r, d.NewLine):
            out.append(" ")
        else:
            out.append(str(getattr(r, "text", "")))
    return "".join(out)


def _target(target: str) -> str:
    """A relative link target as a URL path (spaces and the like percent-encoded)."""
    from urllib.parse import quote
    return quote(str(target), safe="/#.-_~")


def description_html(markdown: str) -> str:
    """A user's Markdown paragraph as HTML: no raw HTML, no images, unsafe links refused."""
    from markdown_it import MarkdownIt
    md = MarkdownIt("commonmark", {"html": False})
    md.disable("image")
    return md.render(str(markdown))
