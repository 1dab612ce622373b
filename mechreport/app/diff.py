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

A value that is or becomes non-finite (NaN, inf: mechreport never writes one, but a summary
edited or written by another tool may hold ``NaN``, ``Infinity`` or ``1e400``) has changed unless
both are NaN or both the same infinity; it is printed as ``NaN``, ``inf`` or ``-inf``.

Every summary.json is checked before anything is compared: it must be a regular file (not a
symbolic link, a folder or a pipe) of at most ``MAX_SUMMARY_BYTES`` (16 MiB; a real one is tens
of kB), checked with fstat before reading and never read beyond the cap, UTF-8 JSON holding an
object with every field diff reads, each of its type: ``status`` (a string), ``failures`` (a
list), ``quantities`` (an object of objects, each with ``value``: a number or null, ``unit``: a
string, and optionally ``angle_deg``: a finite number or null) and ``design.verdicts`` (a list
of objects, each with ``item``: a string, and ``passed``: true or false). Anything else is a
one-line error naming the file and what is wrong.

A spec whose latest build failed is a change too, whatever its folder still holds: a report
folder marked out of date by a failed build (its ``FAILED.json``, see :mod:`.outdir`), or a
spec the folder's ``index.json`` lists as FAIL without a report folder. Such a spec "no longer
builds" (with the build's reason) when it built in the old folder, "builds again" the other
way round, and its stale report is not compared. A spec in one folder only is "added" or
"removed". A report folder whose summary says PASS where ``index.json`` says FAIL is taken
as failed too (its build could not write the mark). ``index.json`` is read as summary.json is
(a regular file within the cap, UTF-8 JSON: an object whose ``specs`` is a list of objects
with ``folder`` and ``status`` strings, and ``message``, a string if given); it may be
missing.

Exit status: 0 nothing changed, 1 something changed, 2 a folder is not a build output, or a
summary.json or index.json in it cannot be read (not a regular file, too large, unreadable,
not JSON, not a mechreport summary or index).
"""
from __future__ import annotations

import errno
import json
import math
import os
import stat
import sys
from dataclasses import dataclass
from pathlib import Path

from ..errors import MechreportError
from ..report.markdown import md_inline
from . import outdir as od
from ..units import SIG_DIGITS, fmt

EXIT_CHANGED = 1
EXIT_USAGE = 2
#: the largest summary.json diff reads, in bytes (16 MiB: a real one is 10-30 kB)
MAX_SUMMARY_BYTES = 16 * 1024 * 1024


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
    """Folder name -> what diff reads of each spec of the build in ``out``: the summary.json
    of every report folder, checked (see the module docstring) and reduced to what diff
    reads, numbers as floats, with ``failed``: None, or the reason its latest build failed
    (a folder marked out of date, or one whose summary says PASS where index.json says FAIL);
    and ``{"failed": reason}`` for a spec index.json lists as failed that has no report
    folder. Raises ``MechreportError`` when ``out`` is not a
    folder, holds no spec, or a summary.json or index.json in it cannot be read."""
    out = Path(out)
    if not out.is_dir():
        raise MechreportError(f"{out}: not a folder (give two `mechreport build` output "
                              "folders)")
    try:
        subs = sorted(p for p in out.iterdir() if p.is_dir() and not p.name.startswith("."))
    except OSError as exc:
        raise MechreportError(f"{_shown(out)}: cannot list: {_why(exc)}") from None
    found: dict[str, dict] = {}
    for sub in subs:
        f = sub / "summary.json"
        data = _read_json(f)
        if data is _NONE:
            continue
        try:
            found[sub.name] = _checked_summary(data)
        except _Malformed as exc:
            raise MechreportError(f"{_shown(f)}: not a mechreport summary: {exc}") from None
        found[sub.name]["failed"] = od.failure_of(sub)
    for folder, reason in _index_failures(out).items():
        entry = found.setdefault(folder, {"failed": reason})
        if entry["failed"] is None and entry["status"] == "PASS":
            entry["failed"] = reason        # the build failed and could not mark the folder
    if not found:
        raise MechreportError(f"{out}: no report folder (no */summary.json): is it a "
                              "`mechreport build` output folder?")
    return found


def _index_failures(out: Path) -> dict[str, str]:
    """Folder -> message of each spec ``out/index.json`` lists as FAIL: its build failed, or
    its check (then its summary.json says FAIL too). Empty when there is no index.json."""
    f = out / "index.json"
    data = _read_json(f)
    if data is _NONE:
        return {}
    try:
        _typed(data, (dict,), "an object")
        specs = _typed(_field(data, "specs"), (list,), "a list", "specs")
        failed = {}
        for i, rec in enumerate(specs):
            try:
                _typed(rec, (dict,), "an object")
                folder = _typed(_field(rec, "folder"), (str,), "a string", ".folder")
                status = _typed(_field(rec, "status"), (str,), "a string", ".status")
                message = rec.get("message")
                message = "" if message is None else _typed(message, (str,), "a string",
                                                             ".message")
            except _Malformed as exc:
                raise exc.within(f"specs[{i}]") from None
            if status != "PASS":
                failed[folder] = "; ".join(" ".join(line.split())
                                           for line in message.splitlines()
                                           if line.strip()) or "no reason given"
    except _Malformed as exc:
        raise MechreportError(f"{_shown(f)}: not a mechreport index: {exc}") from None
    return failed


_NONE = object()        # no such file


def _read_json(f: Path):
    """The JSON value of file ``f`` (read as :func:`_read_summary` reads), or ``_NONE`` when
    there is no such file. Raises ``MechreportError`` when it is not JSON."""
    text = _read_summary(f)
    if text is None:
        return _NONE
    try:
        return json.loads(text)
    except ValueError as exc:
        raise MechreportError(f"{_shown(f)}: not JSON: {exc}") from None
    except RecursionError:
        raise MechreportError(f"{_shown(f)}: not JSON that can be read: nested too "
                              "deeply") from None


# ------------------------------------------------------------------ reading a summary

def _shown(path: Path) -> str:
    """``path`` for a one-line message: as it is, or escaped if it holds control characters."""
    text = str(path)
    return text if text.isprintable() else ascii(text)


def _why(exc: OSError) -> str:
    return exc.strerror or str(exc) or type(exc).__name__


def _read_summary(f: Path) -> str | None:
    """The text of summary.json (or index.json) ``f``; None when there is none (the folder is
    not a report).
    Only a regular file is opened (no link, folder, pipe or device), and at most
    ``MAX_SUMMARY_BYTES`` + 1 bytes of it are read."""
    cap = MAX_SUMMARY_BYTES
    where = _shown(f)
    try:
        st = os.lstat(f)
    except FileNotFoundError:
        return None
    except OSError as exc:
        raise MechreportError(f"{where}: cannot read: {_why(exc)}") from None
    _check_kind(st.st_mode, where)
    flags = (os.O_RDONLY | getattr(os, "O_NOFOLLOW", 0) | getattr(os, "O_NONBLOCK", 0)
             | getattr(os, "O_CLOEXEC", 0) | getattr(os, "O_BINARY", 0))
    try:
        fd = os.open(f, flags)
    except OSError as exc:
        if exc.errno == errno.ELOOP:            # replaced by a link since lstat
            _check_kind(stat.S_IFLNK, where)
        raise MechreportError(f"{where}: cannot read: {_why(exc)}") from None
    try:
        st = os.fstat(fd)
        _check_kind(st.st_mode, where)          # replaced since lstat
        if st.st_size > cap:
            raise MechreportError(_too_large(where, f"{st.st_size} bytes"))
        chunks, size = [], 0
        while size <= cap:
            chunk = os.read(fd, min(cap + 1 - size, 1 << 20))
            if not chunk:
                break
            chunks.append(chunk)
            size += len(chunk)
        if size > cap:                          # grew since fstat
            raise MechreportError(_too_large(where, f"more than {cap} bytes (it grew while "
                                                 "being read)"))
    except OSError as exc:
        raise MechreportError(f"{where}: cannot read: {_why(exc)}") from None
    finally:
        os.close(fd)
    try:
        return b"".join(chunks).decode("utf-8")
    except UnicodeDecodeError as exc:
        raise MechreportError(f"{where}: not UTF-8 text: {exc}") from None


def _check_kind(mode: int, where: str) -> None:
    if stat.S_ISREG(mode):
        return
    if stat.S_ISLNK(mode):
        what = "a symbolic link, not a file (a build writes summary.json as a file)"
    elif stat.S_ISDIR(mode):
        what = "a folder, not a file"
    else:
        what = "not a regular file"
    raise MechreportError(f"{where}: {what}")


def _too_large(where: str, size: str) -> str:
    cap = MAX_SUMMARY_BYTES
    shown = f"{cap // 2**20} MiB ({cap} bytes)" if cap % 2**20 == 0 else f"{cap} bytes"
    what = "an index.json" if where.endswith("index.json") else "a summary.json"
    return (f"{where}: too large: {size}, and {what} may have at most {shown} "
            "(a real one has tens of kB)")


class _Malformed(Exception):
    """What is wrong in a summary (``text``: 'is a string, not ...' or '"x" is missing') and
    where (``where``: a key path such as ``quantities["x"].value``, "" for the top level),
    the path put together on the way out (so that it costs nothing on valid files)."""

    def __init__(self, text: str, where: str = ""):
        super().__init__(text, where)
        self.text, self.where = text, where

    def within(self, prefix: str) -> "_Malformed":
        return _Malformed(self.text, prefix + self.where)

    def __str__(self) -> str:
        if self.text.startswith("is "):
            return f"{self.where or 'the top level'} {self.text}"
        return f"{self.where}: {self.text}" if self.where else self.text


def _kind(x) -> str:
    """The JSON type of ``x``, as a message names it."""
    if x is None:
        return "null"
    if isinstance(x, bool):
        return "true/false"
    if isinstance(x, (int, float)):
        return "a number"
    if isinstance(x, str):
        return "a string"
    if isinstance(x, list):
        return "a list"
    return "an object"


def _key(name: str) -> str:
    """A key as a message shows it: quoted, escaped, cut if long."""
    text = json.dumps(name if len(name) <= 60 else name[:60] + "…", ensure_ascii=False)
    return text if text.isprintable() else ascii(text)


def _field(obj: dict, key: str):
    if key not in obj:
        raise _Malformed(f"{_key(key)} is missing")
    return obj[key]


def _typed(x, types: tuple, what: str, where: str = ""):
    """``x`` if it is one of ``types`` (a bool only if ``bool`` is one)."""
    if isinstance(x, bool) and bool not in types or not isinstance(x, types):
        raise _Malformed(f"is {_kind(x)}, not {what}", where)
    return x


def _number(x, where: str) -> float | None:
    """A number or null -> float or None; an integer too large for a float is +-inf, as
    json reads 1e400."""
    if x is None:
        return None
    _typed(x, (int, float), "a number or null", where)
    try:
        return float(x)
    except OverflowError:
        return math.inf if x > 0 else -math.inf


def _checked_quantity(q) -> dict:
    _typed(q, (dict,), "an object")
    entry = {"value": _number(_field(q, "value"), ".value"),
             "unit": _typed(_field(q, "unit"), (str,), "a string", ".unit")}
    if "angle_deg" in q:
        angle = _number(q["angle_deg"], ".angle_deg")
        if angle is not None and not math.isfinite(angle):
            raise _Malformed(f"is {_show(angle)}, not a finite angle", ".angle_deg")
        entry["angle_deg"] = angle
    return entry


def _checked_verdict(v) -> dict:
    _typed(v, (dict,), "an object")
    return {"item": _typed(_field(v, "item"), (str,), "a string", ".item"),
            "passed": _typed(_field(v, "passed"), (bool,), "true/false", ".passed")}


def _checked_summary(data) -> dict:
    """What diff reads of a summary (status, the number of failures, design.verdicts,
    quantities), each checked for its type; raises ``_Malformed``. Nothing else of the file is
    kept."""
    _typed(data, (dict,), "an object")
    status = _typed(_field(data, "status"), (str,), "a string", "status")
    failures = _typed(_field(data, "failures"), (list,), "a list", "failures")
    design = _typed(_field(data, "design"), (dict,), "an object", "design")
    try:
        verdicts = _typed(_field(design, "verdicts"), (list,), "a list", ".verdicts")
    except _Malformed as exc:
        raise exc.within("design") from None
    checked_verdicts = []
    for i, v in enumerate(verdicts):
        try:
            checked_verdicts.append(_checked_verdict(v))
        except _Malformed as exc:
            raise exc.within(f"design.verdicts[{i}]") from None
    quantities = {}
    for name, q in _typed(_field(data, "quantities"), (dict,), "an object",
                          "quantities").items():
        try:
            quantities[name] = _checked_quantity(q)
        except _Malformed as exc:
            raise exc.within(f"quantities[{_key(name)}]") from None
    return {"status": status, "n_failures": len(failures),
            "design": {"verdicts": checked_verdicts}, "quantities": quantities}


# ------------------------------------------------------------------ comparing

def _show(x: float | None, digits: int = SIG_DIGITS) -> str:
    """A value as the table prints it: :func:`fmt`, but NaN, inf, -inf as such (not "—",
    which is a value that is not there)."""
    if x is not None and not math.isfinite(x):
        return "NaN" if math.isnan(x) else ("inf" if x > 0 else "-inf")
    return fmt(x, digits)


def _digits(a: float, b: float) -> int:
    diff = abs(a - b)
    top = max(abs(a), abs(b))
    if diff == 0 or top == 0 or math.isinf(diff):      # inf: a - b beyond the float range
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
            out.append(Change(spec, name, "—" if a is None else _show(a.get("value")) + u,
                              "—" if b is None else _show(b.get("value")) + u,
                              "added" if a is None else "removed"))
            continue
        va, vb = a.get("value"), b.get("value")
        if va is None or vb is None:
            if va != vb:
                out.append(Change(spec, name, _show(va) + u, _show(vb) + u, "now undefined"
                                  if vb is None else "now defined"))
            continue
        moved = (a.get("angle_deg") is not None and b.get("angle_deg") is not None
                 and abs(a["angle_deg"] - b["angle_deg"]) > 1e-9)
        finite = math.isfinite(va) and math.isfinite(vb)
        if finite:
            changed = abs(vb - va) > rtol * max(abs(va), abs(vb))
        else:                       # to or from NaN or inf: changed unless the very same
            changed = not (va == vb or (math.isnan(va) and math.isnan(vb)))
        if not (changed or moved):
            continue
        n = _digits(va, vb) if finite else SIG_DIGITS
        at_a = f" at {a['angle_deg']:g}°" if moved else ""
        at_b = f" at {b['angle_deg']:g}°" if moved else ""
        if not changed:
            change = "peak moved"
        elif not finite:
            change = f"now {_show(vb)}" if not math.isfinite(vb) else "now finite"
        else:
            rel = ((vb - va) / abs(va) * 100 if va else math.inf)
            change = (f"{rel:+.3g} %" if math.isfinite(rel) else
                      "from 0" if va == 0 else "sign and size changed")
        out.append(Change(spec, name, f"{_show(va, n)}{u}{at_a}", f"{_show(vb, n)}{u}{at_b}",
                          change))
    return out


def _verdicts(summary: dict) -> dict[str, bool]:
    design = summary.get("design") or {}
    return {v.get("item", "?"): bool(v.get("passed")) for v in design.get("verdicts") or []}


NO_BUILD = "does not build"


def _state(entry: dict | None) -> str:
    """A spec's state as the table shows it: its check status, "does not build" or "—"."""
    if entry is None:
        return "—"
    return NO_BUILD if entry.get("failed") is not None else str(entry.get("status", "?"))


def _build_change(spec: str, a: dict, b: dict) -> list[Change]:
    """The change of a spec whose latest build failed in one folder or both."""
    fa, fb = a.get("failed"), b.get("failed")
    if fa is None:
        return [Change(spec, "build", _state(a), NO_BUILD, f"no longer builds: {fb}")]
    if fb is None:
        return [Change(spec, "build", NO_BUILD, _state(b), "builds again")]
    if fa != fb:
        return [Change(spec, "build", NO_BUILD, NO_BUILD, f"still does not build: {fb}")]
    return []


def compare(old: dict[str, dict], new: dict[str, dict], rtol: float) -> list[Change]:
    """Every change between two builds (folder name -> entry, as :func:`read_build` gives
    it)."""
    out: list[Change] = []
    for spec in sorted(set(old) | set(new), key=str.casefold):
        a, b = old.get(spec), new.get(spec)
        if a is None or b is None:
            why = (b or {}).get("failed")
            added = "added" + (f" ({NO_BUILD}: {why})" if why is not None else "")
            out.append(Change(spec, "spec", _state(a), _state(b),
                              added if a is None else "removed"))
            continue
        if a.get("failed") is not None or b.get("failed") is not None:
            out += _build_change(spec, a, b)            # a stale report is not compared
            continue
        if a.get("status") != b.get("status"):
            out.append(Change(spec, "check status", str(a.get("status")),
                              str(b.get("status")), "changed"))
        fa, fb = a["n_failures"], b["n_failures"]
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


def html(changes: list[Change], old: Path, new: Path, rtol: float, n_specs: int) -> str:
    """The same table as a page of its own (``--html``): the document model's HTML writer,
    its style inline (allowed by its hash), no script; every string escaped."""
    from ..report.document import Code, Doc, Paragraph, Table
    from ..report.html_page import table_page
    doc = Doc("mechreport diff")
    intro = [Code(str(old)), " → ", Code(str(new)), f" (relative tolerance {rtol:g}, "
             f"{n_specs} spec(s))"]
    if not changes:
        doc.add(Paragraph([*intro, ": nothing changed."]))
    else:
        specs = len({c.spec for c in changes})
        doc.add(Paragraph([*intro, f": {len(changes)} change(s) in {specs} spec(s)."]))
        doc.add(Table(["spec", "quantity", "old", "new", "change"],
                      [[c.spec, c.what, _badge(c.old), _badge(c.new), c.change]
                       for c in changes],
                      right={2, 3, 4}))
    return table_page(doc)


def _badge(value: str):
    """A PASS or FAIL as a badge on the page; any other value as it is."""
    from ..report.document import Verdict
    return Verdict(value) if value in ("PASS", "FAIL") else value


def diff_command(old: Path, new: Path, rtol: float | None = None, as_html: bool = False) -> int:
    """``rtol`` None: the accuracy every printed value promises (``kinematics.TRUST_RTOL``)."""
    if rtol is None:
        from ..kinematics import TRUST_RTOL
        rtol = TRUST_RTOL
    try:
        a, b = read_build(old), read_build(new)
    except MechreportError as exc:
        print(f"error: {exc}", file=sys.stderr)
        return EXIT_USAGE
    changes = compare(a, b, rtol)
    write = html if as_html else markdown
    sys.stdout.write(write(changes, old, new, rtol, len(set(a) | set(b))))
    return EXIT_CHANGED if changes else 0
