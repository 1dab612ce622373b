"""Typeset Typst source to PDF with the ``typst`` package (bundled compiler and fonts: no
system packages, no network)."""
from __future__ import annotations

import re
import string
import threading
from pathlib import Path

import typst
from markdown_it import MarkdownIt

from ..errors import MechreportError
from .files import atomic_write_bytes


class RenderError(MechreportError):
    """The Typst compiler rejected a generated document (a bug in its writer)."""


def figure_fonts() -> list[str]:
    """The folder of matplotlib's DejaVu fonts (the figures' SVG text is set in DejaVu Sans),
    when matplotlib is installed; no system fonts are ever used."""
    try:
        import matplotlib
    except ImportError:      # pragma: no cover - a dependency
        return []
    import os
    folder = os.path.join(matplotlib.get_data_path(), "fonts", "ttf")
    return [folder] if os.path.isdir(folder) else []


def source_date_epoch() -> int | None:
    """``SOURCE_DATE_EPOCH`` (reproducible builds: the PDF's creation date) or None."""
    import os
    try:
        value = int(os.environ.get("SOURCE_DATE_EPOCH", "").strip())
    except ValueError:
        return None
    return value if value >= 0 else None


#: one Typst compiler per thread, kept for the process (a batch's every report, sheet and
#: index): its fonts are read once and its memoised layout work is shared between documents.
#: Measured (issue 48, 5 documents of two specs, CPU): 0.59 s compiled one by one, 0.54 s by
#: one compiler; the same PDF bytes. It reads every file afresh on each compile (a figure
#: written again is seen) and its memory stays flat (118 MB over 60 documents).
_COMPILERS = threading.local()


def typst_compiler():
    """This thread's :class:`typst.Compiler`: the bundled fonts and matplotlib's DejaVu fonts,
    no system fonts (a compiler is not shared between threads)."""
    compiler = getattr(_COMPILERS, "compiler", None)
    if compiler is None:
        fonts = typst.Fonts(include_system_fonts=False, font_paths=figure_fonts())
        compiler = _COMPILERS.compiler = typst.Compiler(font_paths=fonts,
                                                        ignore_system_fonts=True)
    return compiler


def compile_typst(source: str, out_pdf: Path, root: Path) -> Path:
    """Compile ``source`` to ``out_pdf``; images are resolved relative to ``root`` (the
    folder the source would live in). Written atomically. With ``SOURCE_DATE_EPOCH`` set the
    PDF carries that date, so the same input gives the same bytes."""
    try:
        pdf = typst_compiler().compile(input=source.encode("utf-8"), root=str(root),
                                       timestamp=source_date_epoch())
    except typst.TypstError as exc:
        raise RenderError(f"{out_pdf}: Typst could not typeset the report: {exc}") from None
    return atomic_write_bytes(Path(out_pdf), pdf)


#: line breaks of any kind, with the blanks around them
_BREAKS = re.compile(r"[ \t]*(?:\r\n|[\r\n\v\f\x1c-\x1e\x85\u2028\u2029])\s*")
#: every ASCII punctuation character: each is markup somewhere in Typst (code ``#``, math
#: ``$``, labels ``<>``, references ``@``, content ``[]``, emphasis ``*_``, raw `` ` ``,
#: headings ``=``, lists ``-+/``, numbered lists ``1.``, shorthands ``~ ... -- -?``, smart
#: quotes ``' "``, comments ``//``, escapes ``\``); ``\`` before any of them prints it as is
_PUNCT = frozenset(string.punctuation)
_STRING_ESCAPES = {"\\": "\\\\", '"': '\\"', "\n": "\\n", "\r": "\\r", "\t": "\\t"}


def typst_string(text: str) -> str:
    """``text`` as a Typst string literal (quotes, backslashes and line breaks escaped): user
    text passed this way is data, never markup or code."""
    return '"' + "".join(_STRING_ESCAPES.get(ch, ch) for ch in str(text)) + '"'


def typst_escape(text: str) -> str:
    """``text`` as plain text in Typst markup: every ASCII punctuation character
    backslash-escaped, line breaks collapsed to one space (no markup, math, labels, code,
    paragraph breaks or line-start constructs can come out of it)."""
    s = _BREAKS.sub(" ", str(text))
    return "".join("\\" + ch if ch in _PUNCT else ch for ch in s)


#: CommonMark, raw HTML off: ``<b>`` and ``<!-- -->`` are text, never HTML
_MARKDOWN = MarkdownIt("commonmark", {"html": False})


def typst_markdown(text) -> str:
    """User Markdown (a spec's ``description``) as Typst markup, from markdown-it-py's token
    stream; every piece of user text goes through :func:`typst_escape` (markup) or
    :func:`typst_string` (a string literal), so it never becomes Typst markup or code.

    Interpreted: paragraphs, ``*emphasis*`` (``#emph``), ``**strong**`` (``#strong``),
    `` `code` `` (``#raw``), links and autolinks (``#link`` to the URL markdown-it validated
    and normalised), bullet and numbered lists (``#list``, ``#enum`` with the list's start,
    tight or loose), hard line breaks (``#linebreak()``); also block quotes (``#quote``),
    code blocks (``#raw(block: true)``) and thematic breaks. Shown as plain text: headings
    (their text, as a paragraph: a description never adds a section to a report) and images
    (their alt text: no file is read). Raw HTML is off, so HTML, and tables (not CommonMark),
    stay literal text."""
    return _typst_blocks(_MARKDOWN.parse(str(text)))


def _closing(tokens, i: int) -> int:
    """The index of the token closing the block ``tokens[i]`` opens."""
    depth = 0
    for j in range(i, len(tokens)):
        depth += tokens[j].nesting
        if depth == 0:
            return j
    return len(tokens) - 1          # pragma: no cover - markdown-it closes every block


def _typst_blocks(tokens) -> str:
    """Block tokens as Typst markup, blocks separated by a blank line (a paragraph break)."""
    out, i = [], 0
    while i < len(tokens):
        tok = tokens[i]
        if tok.nesting == 1:
            end = _closing(tokens, i)
            out.append(_typst_container(tok, tokens[i + 1:end]))
            i = end + 1
            continue
        if tok.type == "inline":
            out.append(_typst_inline(tok.children or []))
        elif tok.type in ("fence", "code_block"):
            out.append("#raw(block: true, " + typst_string(tok.content.rstrip("\n")) + ")")
        elif tok.type == "hr":
            out.append("#line(length: 100%)")
        elif tok.content:                             # html_block (html is off), anything new
            out.append(typst_escape(tok.content))
        i += 1
    return "\n\n".join(b for b in out if b)


def _typst_container(tok, inner) -> str:
    if tok.type in ("bullet_list_open", "ordered_list_open"):
        items, i = [], 0
        while i < len(inner):                         # list_item_open ... list_item_close
            end = _closing(inner, i)
            items.append("[" + _typst_blocks(inner[i + 1:end]) + "]")
            i = end + 1
        tight = all(t.hidden for t in inner                # the items' own paragraphs
                    if t.type == "paragraph_open" and t.level == tok.level + 2)
        args = [f"tight: {'true' if tight else 'false'}"]
        if tok.type == "ordered_list_open":
            start = tok.attrGet("start")              # "0." starts at 0
            args.append(f"start: {1 if start is None else int(start)}")
            if tok.markup == ")":
                args.append('numbering: "1)"')
        return "#" + ("list" if tok.type == "bullet_list_open" else "enum") + "(" + \
            ", ".join(args + items) + ")"
    if tok.type == "blockquote_open":
        return "#quote(block: true)[" + _typst_blocks(inner) + "]"
    return _typst_blocks(inner)        # paragraph, heading (as plain text), anything new


_INLINE_MARKS = {"em_open": "#emph[", "em_close": "]", "strong_open": "#strong[",
                 "strong_close": "]", "softbreak": " ", "hardbreak": "#linebreak()"}


def _typst_inline(children) -> str:
    out, links = [], []
    for t in children:
        if t.type in _INLINE_MARKS:
            out.append(_INLINE_MARKS[t.type])
        elif t.type == "code_inline":
            out.append("#raw(" + typst_string(t.content) + ")")
        elif t.type == "link_open":                   # [text]() has no URL: its text only
            href = t.attrGet("href") or ""
            out.append("#link(" + typst_string(href) + ")[" if href else "")
            links.append("]" if href else "")
        elif t.type == "link_close":
            out.append(links.pop() if links else "")
        elif t.type == "image":                       # its alt text, plain
            out.append(typst_escape("".join(c.content for c in t.children or [])))
        else:                                         # text, html_inline (html is off), ...
            out.append(typst_escape(t.content))
    return "".join(out)
