"""The one Markdown escaper for user text (spec, link, joint, point and load names, file
paths, error messages) and the link-target encoder; the Markdown writer of the documents
(:mod:`mechreport.report.write_markdown`) uses them for every string it writes.

``md_inline`` makes a string plain inline text in CommonMark / GitHub Markdown, wherever a
writer puts it (a heading, a table cell, a list item, a paragraph):

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


#: a fenced code block's opening or closing line: up to 3 spaces, then 3 or more ` or ~
_FENCE = re.compile(r"^ {0,3}(`{3,}|~{3,})")
#: a backslash escape, or a run of backticks (a code span's delimiter, if one matches it)
_TICKS = re.compile(r"\\.|`+", re.S)


def md_text(text) -> str:
    """Markdown written by the user (a spec's ``description``): kept as Markdown, but with
    ``& < >`` as entities so it cannot carry raw HTML; except in code (code spans and
    fenced code blocks), where Markdown shows every character as written (an entity there
    would be printed as ``&lt;``) and reads no HTML."""
    out, prose, fence = [], [], None
    for line in str(text).splitlines(keepends=True):
        m = _FENCE.match(line)
        if fence is None and m and not (m.group(1)[0] == "`" and "`" in line[m.end():]):
            out.append(_escape_prose("".join(prose)))       # a fence opens
            prose, fence = [], m.group(1)
            out.append(line)
        elif fence is not None:
            out.append(line)
            if (m and m.group(1)[0] == fence[0] and len(m.group(1)) >= len(fence)
                    and not line[m.end():].strip()):
                fence = None                                # and closes
        else:
            prose.append(line)
    return "".join(out) + _escape_prose("".join(prose))


def _escape_prose(text: str) -> str:
    """``text`` (Markdown outside fenced code) with ``& < >`` as entities outside its code
    spans: a run of backticks opens a span that the next run of as many closes (CommonMark);
    an unmatched run, and a backslash-escaped backtick, are plain text."""
    out, pos, i = [], 0, 0
    while True:
        m = _TICKS.search(text, i)
        if m is None:
            break
        if m.group().startswith("\\"):
            i = m.end()
            continue
        n = len(m.group())
        close = re.compile(r"(?<!`)`{%d}(?!`)" % n).search(text, m.end())
        if close is None:
            i = m.end()
            continue
        out.append(html.escape(text[pos:m.start()], quote=False))
        out.append(text[m.start():close.end()])            # the code span, as written
        pos = i = close.end()
    out.append(html.escape(text[pos:], quote=False))
    return "".join(out)


def md_url(target) -> str:
    """A relative link target (``name/report.pdf``), percent-encoded for a Markdown link."""
    return quote(str(target), safe="/")
