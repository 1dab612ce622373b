"""``mechreport diff OLD_OUT NEW_OUT``: what changed between two builds, as a Markdown table
ready for a pull-request comment.

Both folders are ``mechreport build`` outputs; each report folder's summary.json is read. For
every spec (by folder name) it compares the check status, each design verdict, the number of
failed expectations and every key figure of ``summary["quantities"]`` (SI, with units: driver
torque statistics, peak and RMS joint loads, shaking force and moment, every cycle quantity).
A quantity has changed when ``|new - old| > rtol * max(|old|, |new|)`` (round-off is already
stored as 0), or when the angle of its peak moved. Diagnostics of numerical agreement
(method disagreement, residuals) are not compared: ``status`` carries them. Metadata (date,
version, spec hash) are not quantities either.

Exit status: 0 nothing changed, 1 something changed, 2 a folder is not a build output.
"""
from __future__ import annotations

import json
import math
import sys
from dataclasses import dataclass
from pathlib import Path

from ..errors import MechreportError
from ..report.markdown import md_inline
from ..units import fmt

EXIT_CHANGED = 1
EXIT_USAGE = 2


@dataclass(frozen=True)
class Change:
    """One row: ``spec`` (folder), ``what`` (quantity, status, verdict ...), ``old``/``new``
    as printed, and ``change`` (relative change or a word)."""

    spec: str
    what: str
    old: str
    new: str
    change: str


def read_build(out: Path) -> dict[str, dict]:
    """Folder name -> summary.json of every report folder in ``out``. Raises
    ``MechreportError`` when ``out`` is not a folder or holds no report."""
    out = Path(out)
    if not out.is_dir():
        raise MechreportError(f"{out}: not a folder (give two `mechreport build` output "
                              "folders)")
    found: dict[str, dict] = {}
    for sub in sorted(p for p in out.iterdir() if p.is_dir() and not p.name.startswith(".")):
        f = sub / "summary.json"
        if not f.is_file():
            continue
        try:
            data = json.loads(f.read_text(encoding="utf-8"))
        except (OSError, ValueError) as exc:
            raise MechreportError(f"{f}: cannot read: {exc}") from None
        if isinstance(data, dict):
            found[sub.name] = data
    if not found:
        raise MechreportError(f"{out}: no report folder (no */summary.json): is it a "
                              "`mechreport build` output folder?")
    return found


def _digits(a: float, b: float) -> int:
    diff = abs(a - b)
    top = max(abs(a), abs(b))
    if diff == 0 or top == 0:
        return 4
    return int(min(12, max(4, math.ceil(math.log10(top / diff)) + 2)))


def _quantity_changes(spec: str, old: dict, new: dict, rtol: float) -> list[Change]:
    out = []
    qo, qn = old.get("quantities") or {}, new.get("quantities") or {}
    for name in sorted(set(qo) | set(qn)):
        a, b = qo.get(name), qn.get(name)
        unit = ((b or a) or {}).get("unit") or ""
        u = f" {unit}" if unit else ""
        if a is None or b is None:
            out.append(Change(spec, name, "—" if a is None else fmt(a.get("value")) + u,
                              "—" if b is None else fmt(b.get("value")) + u,
                              "added" if a is None else "removed"))
            continue
        va, vb = a.get("value"), b.get("value")
        if va is None or vb is None:
            if va != vb:
                out.append(Change(spec, name, fmt(va) + u, fmt(vb) + u, "now undefined"
                                  if vb is None else "now defined"))
            continue
        moved = (a.get("angle_deg") is not None and b.get("angle_deg") is not None
                 and abs(a["angle_deg"] - b["angle_deg"]) > 1e-9)
        changed = abs(vb - va) > rtol * max(abs(va), abs(vb))
        if not (changed or moved):
            continue
        n = _digits(va, vb)
        at_a = f" at {a['angle_deg']:g}°" if moved else ""
        at_b = f" at {b['angle_deg']:g}°" if moved else ""
        rel = ((vb - va) / abs(va) * 100 if va else math.inf)
        change = (f"{rel:+.3g} %" if math.isfinite(rel) else "from 0") if changed else \
            "peak moved"
        out.append(Change(spec, name, f"{fmt(va, n)}{u}{at_a}", f"{fmt(vb, n)}{u}{at_b}",
                          change))
    return out


def _verdicts(summary: dict) -> dict[str, bool]:
    design = summary.get("design") or {}
    return {v.get("item", "?"): bool(v.get("passed")) for v in design.get("verdicts") or []}


def compare(old: dict[str, dict], new: dict[str, dict], rtol: float) -> list[Change]:
    """Every change between two builds (folder name -> summary.json)."""
    out: list[Change] = []
    for spec in sorted(set(old) | set(new), key=str.casefold):
        a, b = old.get(spec), new.get(spec)
        if a is None or b is None:
            out.append(Change(spec, "spec", "—" if a is None else a.get("status", "?"),
                              "—" if b is None else b.get("status", "?"),
                              "added" if a is None else "removed"))
            continue
        if a.get("status") != b.get("status"):
            out.append(Change(spec, "check status", str(a.get("status")),
                              str(b.get("status")), "changed"))
        fa, fb = len(a.get("failures") or []), len(b.get("failures") or [])
        if fa != fb:
            out.append(Change(spec, "failed expectations", str(fa), str(fb), "changed"))
        va, vb = _verdicts(a), _verdicts(b)
        for item in sorted(set(va) | set(vb)):
            if va.get(item) != vb.get(item):
                word = {True: "PASS", False: "FAIL", None: "—"}
                out.append(Change(spec, f"verdict {item}", word[va.get(item)],
                                  word[vb.get(item)], "changed"))
        out += _quantity_changes(spec, a, b, rtol)
    return out


def markdown(changes: list[Change], old: Path, new: Path, rtol: float, n_specs: int) -> str:
    """The Markdown table (or a one-line "nothing changed")."""
    head = (f"**mechreport diff** `{old}` → `{new}` (relative tolerance {rtol:g}, "
            f"{n_specs} spec(s))")
    if not changes:
        return f"{head}: nothing changed.\n"
    specs = len({c.spec for c in changes})
    lines = [f"{head}: {len(changes)} change(s) in {specs} spec(s).", "",
             "| spec | quantity | old | new | change |", "|---|---|---:|---:|---:|"]
    for c in changes:
        lines.append("| " + " | ".join(md_inline(x) for x in (c.spec, c.what, c.old, c.new,
                                                               c.change)) + " |")
    return "\n".join(lines) + "\n"


def diff_command(old: Path, new: Path, rtol: float) -> int:
    try:
        a, b = read_build(old), read_build(new)
    except MechreportError as exc:
        print(f"error: {exc}", file=sys.stderr)
        return EXIT_USAGE
    changes = compare(a, b, rtol)
    sys.stdout.write(markdown(changes, old, new, rtol, len(set(a) | set(b))))
    return EXIT_CHANGED if changes else 0
