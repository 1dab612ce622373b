"""The one Markdown escaper for user text (spec, link, joint, point and load names, file
paths, error messages) and the link-target encoder; every Markdown template uses them through
the ``md``, ``md_text`` and ``url`` filters of :func:`mechreport.report.render.environment`.

``md_inline`` makes a string plain inline text in CommonMark / GitHub Markdown, wherever a
template puts it (a heading, a table cell, a list item, a paragraph):

- line breaks (and the whitespace around them) become one space, so a string never starts a
  new block and a table row never splits; blanks at either end are dropped;
- ``& < >`` become HTML entities (no raw HTML, no autolinks);
- ``\\ ` * _ { } [ ] | ~ $ #`` are backslash-escaped everywhere (code spans, emphasis, links
  and images, table cells, strikethrough, GitHub math, heading closers);
- ``+ - = .`` and ``!``/``(``/``)`` act only at the start of a line (lists, setext headings,
  thematic breaks, ordered lists) or next to a bracket (links, images, which the escaped
  brackets already rule out), so they are escaped only where they lead the string as a block
  marker (``- x``, ``--``, ``1. x``, ``2) x``): numbers such as ``-102.8`` or ``0.5`` stay
  readable in the Markdown source.
"""
from __future__ import annotations

import html
import re
from urllib.parse import quote

#: escaped wherever they occur
_ALWAYS = set("\\`*_{}[]|~$#")
#: line breaks of any kind, with the blanks around them
_BREAKS = re.compile(r"[ \t]*(?:\r\n|[\r\n\v\f\x1c-\x1e\x85\u2028\u2029])[\s]*")
#: a block marker at the start of the string: a bullet (``- x``, ``+ x``), a setext underline
#: or thematic break (``==``, ``--``), an ordered list item (``1. x``, ``2) x``)
_LEADING = re.compile(r"^(?:([-+=])(?=\s|$|\1)|\d{1,9}(?=[.)](?:\s|$)))")


def md_inline(text) -> str:
    """``text`` as literal inline Markdown (see the module docstring)."""
    s = _BREAKS.sub(" ", str(text)).strip(" \t")   # leading blanks could make a code block
    s = html.escape(s, quote=False)                      # & < >
    s = "".join("\\" + ch if ch in _ALWAYS else ch for ch in s)
    m = _LEADING.match(s)
    if m:                        # "-x" -> "\-x", "1. x" -> "1\. x"
        k = m.end() if m.group().isdigit() else 0
        s = s[:k] + "\\" + s[k:]
    return s


def md_text(text) -> str:
    """Markdown written by the user (a spec's ``description``): kept as Markdown, but with
    ``& < >`` as entities so it cannot carry raw HTML."""
    return html.escape(str(text), quote=False)


def md_url(target) -> str:
    """A relative link target (``name/report.pdf``), percent-encoded for a Markdown link."""
    return quote(str(target), safe="/")
