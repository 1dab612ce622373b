"""Typeset Typst source to PDF with the ``typst`` package (bundled compiler and fonts: no
system packages, no network)."""
from __future__ import annotations

import re
import string
from pathlib import Path

import typst

from ..errors import MechreportError
from .files import atomic_write_bytes


class RenderError(MechreportError):
    """The Typst compiler rejected a generated document (a bug in a template)."""


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


def compile_typst(source: str, out_pdf: Path, root: Path) -> Path:
    """Compile ``source`` to ``out_pdf``; images are resolved relative to ``root`` (the
    folder the source would live in). Written atomically. With ``SOURCE_DATE_EPOCH`` set the
    PDF carries that date, so the same input gives the same bytes."""
    try:
        pdf = typst.compile(source.encode("utf-8"), root=str(root), ignore_system_fonts=True,
                            font_paths=figure_fonts(), timestamp=source_date_epoch())
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
