"""Typeset Typst source to PDF with the ``typst`` package (bundled compiler and fonts: no
system packages, no network)."""
from __future__ import annotations

from pathlib import Path

import typst

from ..errors import MechreportError
from .files import atomic_write_bytes


class RenderError(MechreportError):
    """The Typst compiler rejected a generated document (a bug in a template)."""


def compile_typst(source: str, out_pdf: Path, root: Path) -> Path:
    """Compile ``source`` to ``out_pdf``; images are resolved relative to ``root`` (the
    folder the source would live in). Written atomically."""
    try:
        pdf = typst.compile(source.encode("utf-8"), root=str(root), ignore_system_fonts=True)
    except typst.TypstError as exc:
        raise RenderError(f"{out_pdf}: Typst could not typeset the report: {exc}") from None
    return atomic_write_bytes(Path(out_pdf), pdf)


def typst_string(text: str) -> str:
    """``text`` as a Typst string literal."""
    return '"' + text.replace("\\", "\\\\").replace('"', '\\"') + '"'


def typst_escape(text: str) -> str:
    """``text`` safe in Typst markup (no accidental emphasis, math, labels or code)."""
    out = []
    for ch in text:
        if ch in "\\*_`$#@<>[]~/=-+":
            out.append("\\" + ch)
        else:
            out.append(ch)
    return "".join(out)
