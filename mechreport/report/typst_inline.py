"""Inline text of a :class:`~.document.Doc` as Typst markup (for :mod:`.write_typst`): user
text through the one Typst escaper (:func:`.pdf.typst_escape` in markup,
:func:`.pdf.typst_string` as a string), math as Typst math."""
from __future__ import annotations

import re

from . import document as d
from .pdf import typst_escape, typst_string

PASS_COLOUR, FAIL_COLOUR = "#1a7f1a", "#b00000"
SMALL = 8   # pt: side notes, a sheet's tables
_MINUS = re.compile(r"-\d")   # a negative number's sign


def inline(text) -> str:
    """Inline text (a string, a run or a list of them) as Typst markup."""
    return "".join(_run(r) for r in d.runs(text))


def _run(r) -> str:
    if isinstance(r, str):
        return typst_escape(r)
    write = _RUNS.get(type(r))
    if write is None:
        raise TypeError(f"no Typst for the inline run {r!r}")
    return write(r)


def _math(r: d.Math) -> str:
    from .sheet.expr import math
    return "$" + math(r.value, "typ") + "$"


def _verdict(r: d.Verdict) -> str:
    colour = PASS_COLOUR if r.passed else FAIL_COLOUR
    badge = f'#text(fill: rgb("{colour}"), weight: "bold", {typst_string(r.status)})'
    return badge + (f" #text(size: 7pt, {typst_string(r.detail)})" if r.detail else "")


def _number(r: d.Number) -> str:
    text = str(r.text)
    if _MINUS.match(text):                  # markup sets "-1" with a minus sign
        return "-" + typst_escape(text[1:])
    return typst_escape(text)


_RUNS = {
    d.Code: lambda r: f"#raw({typst_string(' '.join(str(r.text).split()))})",
    d.Strong: lambda r: f"#strong[{typst_escape(r.text)}]",
    d.Emph: lambda r: f"#emph[{typst_escape(r.text)}]",
    d.Link: lambda r: f"#link({typst_string(r.target)}, {typst_string(r.text)})",
    d.Math: _math,
    d.Aside: lambda r: f" \\ #text(size: 7pt, fill: luma(90), raw({typst_string(r.text)}))",
    d.Verdict: _verdict,
    d.Key: lambda r: f"#text(size: 6.5pt, fill: luma(90), raw({typst_string(r.text)}))",
    d.Ref: lambda r: typst_escape(r.text),
    d.Number: _number,
    d.NewLine: lambda r: "\n\\ " if r.hard else "\n",
    # the program's own wording: its apostrophes typeset as such (’)
    d.Wording: lambda r: typst_escape(r.text).replace("\\'", "'"),
    d.Either: lambda r: inline(r.print),
}


def n(x: float) -> str:
    """A number as Typst writes a length: no trailing zeros."""
    return f"{x:g}"
