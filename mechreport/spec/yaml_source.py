"""Read YAML into plain Python values while remembering where each value came from.

The document is built straight from the parser's event stream (libyaml's when PyYAML has it),
so that every key path maps to its line, duplicate keys are reported instead of silently
overwritten, and hostile input is refused *before* anything is built from it:

- a file larger than ``MAX_FILE_BYTES``, or text that is not UTF-8 or holds characters YAML
  does not allow;
- nesting deeper than ``MAX_DEPTH`` collections;
- anchors and aliases (``&a`` / ``*a``): a spec never needs them, and an alias bomb ("billion
  laughs") expands a kilobyte into gigabytes;
- explicit tags other than the YAML core ones (``!!python/name:...`` and the like);
- keys that are not names (lists, mappings, numbers, booleans, null).

Plain scalars are resolved with the YAML 1.2 core schema, not YAML 1.1: ``1e-3`` is a number,
``10:00``, ``yes``, ``no``, ``on``, ``off``, ``1_000`` and dates stay text, only ``true`` and
``false`` are booleans, and ``010`` is ten. Problems that make the rest of the file unreadable
raise ``SpecError`` at once; the others are collected in ``Source.problems``.
"""
from __future__ import annotations

import re
from typing import Any

import yaml
from yaml.events import (AliasEvent, MappingEndEvent, MappingStartEvent, ScalarEvent,
                         SequenceEndEvent, SequenceStartEvent, StreamEndEvent)

from ..errors import Problem, SpecError

Path = tuple  # of str keys and int indices

MAX_FILE_BYTES = 128 * 1024   # a spec is a few KiB; even a 3600-point profile fits in 100 KiB
MAX_DEPTH = 32                # nested lists/mappings; a spec needs 5
MAX_INT_DIGITS = 1000         # longer integer literals are kept as text (HugeInteger)

CORE = "tag:yaml.org,2002:"
STR, NULL, BOOL, INT, FLOAT, SEQ, MAP = (CORE + t for t in
                                         ("str", "null", "bool", "int", "float", "seq", "map"))

# libyaml when available: 20 to 50 times faster than the pure-Python parser.
try:
    from yaml.cyaml import CParser as _CParser
except ImportError:   # pragma: no cover - PyYAML built without libyaml
    _CParser = None


class _PyParser(yaml.reader.Reader, yaml.scanner.Scanner, yaml.parser.Parser):
    def __init__(self, stream: str):
        yaml.reader.Reader.__init__(self, stream)
        yaml.scanner.Scanner.__init__(self)
        yaml.parser.Parser.__init__(self)


# Characters the YAML spec does not allow in a stream (as PyYAML's Reader checks); this also
# catches lone surrogates in text handed to parse_spec as a str.
_NON_PRINTABLE = re.compile("[^\x09\x0A\x0D\x20-\x7E\x85\xA0-\uD7FF\uE000-\uFFFD"
                            "\U00010000-\U0010FFFF]")
_BREAK = re.compile("\r\n|[\r\n\x85\u2028\u2029]")   # line breaks as YAML counts them

# YAML 1.2 core schema (https://yaml.org/spec/1.2.2/#1032-tag-resolution)
_NULLS = {"", "~", "null", "Null", "NULL"}
_BOOLS = {"true": True, "True": True, "TRUE": True, "false": False, "False": False,
          "FALSE": False}
# an int (group 1 matched) or a float in decimal notation, in one match
_NUMBER = re.compile(r"[-+]?(?:([0-9]+)|(?:\.[0-9]+|[0-9]+(?:\.[0-9]*)?)(?:[eE][-+]?[0-9]+)?)\Z")
_INT8 = re.compile(r"0o[0-7]+\Z")
_INT16 = re.compile(r"0x[0-9a-fA-F]+\Z")
_NUMERIC_START = frozenset("0123456789+-.")   # how a number (or .inf, .nan) can start
_INF, _NAN = float("inf"), float("nan")
_SPECIAL_FLOATS = {**{s + i: (-_INF if s == "-" else _INF) for s in ("", "+", "-")
                      for i in (".inf", ".Inf", ".INF")},
                   ".nan": _NAN, ".NaN": _NAN, ".NAN": _NAN}


class HugeInteger:
    """An integer literal of more than ``MAX_INT_DIGITS`` digits, kept as its text (Python
    refuses to convert decimal literals above 4300 digits). Never a valid value in a spec."""

    __slots__ = ("text",)

    def __init__(self, text: str):
        self.text = text

    @property
    def negative(self) -> bool:
        return self.text.startswith("-")

    def __str__(self) -> str:
        digits = self.text.lstrip("+-").lstrip("0") or "0"
        if not digits.isdigit():                     # 0x... or 0o...
            return f"{self.text[:12]}... ({len(self.text)} characters)"
        return f"{'-' if self.negative else ''}{digits[0]}.{digits[1:3]}e+{len(digits) - 1}"

    __repr__ = __str__


def _integer(text: str, base: int) -> int | HugeInteger:
    if len(text) > MAX_INT_DIGITS:
        return HugeInteger(text)
    return int(text, base) if base == 10 else int(text[2:], base)


def resolve_plain(value: str) -> Any:
    """The value of a plain (unquoted, untagged) scalar under the YAML 1.2 core schema."""
    if value in _NULLS:
        return None
    if value in _BOOLS:
        return _BOOLS[value]
    if value[0] in _NUMERIC_START:
        number = _NUMBER.match(value)
        if number is not None:
            return _integer(value, 10) if number.lastindex else float(value)
        if value in _SPECIAL_FLOATS:
            return _SPECIAL_FLOATS[value]
        if _INT16.match(value):
            return _integer(value, 16)
        if _INT8.match(value):
            return _integer(value, 8)
    return value


def _is_plain(event) -> bool:
    """Whether ``event`` is a plain scalar (no quotes, tag or anchor): its value is
    :func:`resolve_plain` of its text, with nothing to check."""
    return (type(event) is ScalarEvent and event.tag is None and event.anchor is None
            and event.implicit[0])


def _plain_name(event) -> str | None:
    """The key ``event`` names when it is a plain scalar that reads as text; None when it
    needs :meth:`Source._key` (quoted, tagged, a number, a collection ...)."""
    if _is_plain(event):
        value = resolve_plain(event.value)
        if isinstance(value, str):
            return value
    return None


def _kind(value: Any) -> str:
    return "true/false" if isinstance(value, bool) else "a number"


def _show_tag(tag: str) -> str:
    return "!!" + tag[len(CORE):] if tag.startswith(CORE) else tag


def format_path(path: Path) -> str:
    """``('links', 'rod', 'mass')`` -> ``links.rod.mass``; ``('loads', 0)`` -> ``loads[0]``.
    A character that does not print (a control, a bidirectional override) is escaped as in
    Python: ``ro\\u202ed``, so that a message shows the key as it is."""
    out = ""
    for part in path:
        if isinstance(part, int):
            out += f"[{part}]"
        else:
            out += ("." if out else "") + _printable(str(part))
    return out


def _printable(text: str) -> str:
    if text.isprintable():
        return text
    return "".join(c if c.isprintable() else c.encode("unicode_escape").decode("ascii")
                   for c in text)


def line_at(text: str, offset: int) -> int:
    """1-based line of character ``offset`` in ``text``."""
    return len(_BREAK.findall(text, 0, offset)) + 1


def decode(data: bytes, filename: str) -> str:
    """UTF-8 bytes -> text (a leading byte-order mark is dropped); anything else is refused
    with the offset and line of the first bad byte."""
    try:
        text = data.decode("utf-8")
    except UnicodeDecodeError as exc:
        line = data.count(b"\n", 0, exc.start) + 1
        hint = ""
        if data[:2] in (b"\xff\xfe", b"\xfe\xff"):
            hint = " (it looks like UTF-16)"
        raise SpecError([Problem(filename, line, "",
                                 f"the file is not UTF-8 text{hint}: byte 0x{data[exc.start]:02x}"
                                 f" at offset {exc.start} cannot be decoded; save the file as "
                                 "UTF-8")]) from None
    return text[1:] if text.startswith("\ufeff") else text


def too_big(size: int, filename: str, at_least: bool = False) -> SpecError:
    return SpecError([Problem(filename, None, "",
                              f"the file is {'at least ' if at_least else ''}{size} bytes; a "
                              f"spec file may be at most {MAX_FILE_BYTES} bytes "
                              f"({MAX_FILE_BYTES // 1024} KiB)")])


def check_text(text: str, filename: str) -> None:
    """Refuse text that is too long or holds characters YAML does not allow."""
    if len(text) > MAX_FILE_BYTES:   # characters <= UTF-8 bytes: surely too big
        raise too_big(len(text), filename, at_least=not text.isascii())
    bad = _NON_PRINTABLE.search(text)
    if bad is not None:
        char = bad.group()
        what = ("a lone surrogate (not a Unicode character)" if "\ud800" <= char <= "\udfff"
                else "a control character" if char < "\x80" or "\x80" <= char < "\xa0"
                else "a non-character")
        raise SpecError([Problem(filename, line_at(text, bad.start()), "",
                                 f"character U+{ord(char):04X} ({what}) is not allowed in YAML "
                                 "text")])
    size = len(text.encode("utf-8"))
    if size > MAX_FILE_BYTES:
        raise too_big(size, filename)


class Source:
    """The parsed document plus the line of every key path in it.

    ``text`` must already have passed ``check_text`` (``parse_spec`` and ``load_spec`` do it).
    """

    def __init__(self, filename: str, text: str):
        self.filename = filename
        self.text = text
        self.lines: dict[Path, int] = {}
        self.problems: list[Problem] = []
        self._parser = _CParser(text) if _CParser is not None else _PyParser(text)
        self._next = self._parser.get_event     # the next event (malformed YAML raises)
        try:
            self.data = self._document()
        except yaml.YAMLError as exc:
            raise self._malformed(exc) from None
        finally:
            dispose = getattr(self._parser, "dispose", None)
            if dispose is not None:
                dispose()
            self._parser = self._next = None

    def line(self, path: Path) -> int | None:
        """Line of ``path``, or of its nearest ancestor that has one."""
        path = tuple(path)
        while path:
            if path in self.lines:
                return self.lines[path]
            path = path[:-1]
        return self.lines.get(())

    # -- errors -----------------------------------------------------------------------------

    _too_deep = f"nested more than {MAX_DEPTH} levels deep; a spec needs only a few levels"

    def _fatal(self, event, path: Path | None, message: str) -> SpecError:
        line = event.start_mark.line + 1 if event is not None else None
        return SpecError([Problem(self.filename, line, format_path(path or ()), message)])

    def _malformed(self, exc: yaml.YAMLError) -> SpecError:
        mark = getattr(exc, "problem_mark", None)
        line = mark.line + 1 if mark is not None else None
        what = getattr(exc, "problem", None) or str(exc)
        # libyaml words a few messages differently from PyYAML; say what PyYAML says
        if what == "mapping values are not allowed in this context":
            what = "mapping values are not allowed here"
        elif what in ("found character that cannot start any token",
                      "found unknown escape character") and mark is not None:
            char = self._char_at(mark)
            if char is not None:
                what = what.replace("character", f"character {char!r}", 1)
        context = getattr(exc, "context", None)
        if what == "exceeded maximum nesting depth":
            # libyaml (PyYAML >= 6.0.4) caps nesting itself, at 1000 levels: still far past
            # ours, and it can stop scanning before the event that reaches MAX_DEPTH
            return SpecError([Problem(self.filename, line, "", self._too_deep)])
        msg = f"malformed YAML: {what}" + (f" ({context})" if context else "")
        return SpecError([Problem(self.filename, line, "", msg)])

    def _char_at(self, mark) -> str | None:
        lines = _BREAK.split(self.text, maxsplit=mark.line + 1)
        if mark.line < len(lines) and mark.column < len(lines[mark.line]):
            return lines[mark.line][mark.column]
        return None

    # -- events -----------------------------------------------------------------------------

    def _document(self) -> Any:
        self._next()                                   # stream start
        if isinstance(self._next(), StreamEndEvent):   # no document at all
            return None
        data = self._node(self._next(), (), 0, True)
        self._next()                                   # document end
        second = self._next()
        if not isinstance(second, StreamEndEvent):
            raise self._fatal(second, (), "a spec file holds one YAML document; a second one "
                                          "starts here (after '---')")
        return data

    def _node(self, event, path: Path, depth: int, record: bool) -> Any:
        """Build the node that starts with ``event``; ``depth`` collections enclose it.
        ``record``: keep the lines (False while skipping a refused key and its value)."""
        if isinstance(event, AliasEvent):
            raise self._fatal(event, path, f"alias '*{event.anchor}': anchors and aliases "
                                           "(&name, *name) are not allowed in a spec; write "
                                           "each value out in full")
        if event.anchor is not None:
            raise self._fatal(event, path, f"anchor '&{event.anchor}': anchors and aliases "
                                           "(&name, *name) are not allowed in a spec; write "
                                           "each value out in full")
        if record:
            self.lines.setdefault(path, event.start_mark.line + 1)
        if isinstance(event, ScalarEvent):
            return self._scalar(event, path)
        if depth >= MAX_DEPTH:
            raise self._fatal(event, path, self._too_deep)
        tag = event.tag
        next_event = self._next
        if isinstance(event, SequenceStartEvent):
            if tag not in (None, "!", SEQ):
                raise self._tag_error(event, path)
            out: list = []
            item = next_event()
            while type(item) is not SequenceEndEvent:
                out.append(self._node(item, path + (len(out),), depth + 1, record))
                item = next_event()
            return out
        if not isinstance(event, MappingStartEvent):   # pragma: no cover - parser guarantees
            raise self._fatal(event, path, "malformed YAML: unexpected event")
        if tag not in (None, "!", MAP):
            raise self._tag_error(event, path)
        mapping: dict = {}
        key_event = next_event()
        while type(key_event) is not MappingEndEvent:
            key = _plain_name(key_event)
            if key is None:                       # quoted, tagged, a number ...: checked
                key = self._key(key_event, path, depth, record)
            value_event = next_event()
            if key is None:                       # refused (reported): skip its value
                self._node(value_event, path, depth + 1, False)
            elif key in mapping:
                child = path + (key,)
                if record:
                    self.problems.append(Problem(self.filename, key_event.start_mark.line + 1,
                                                 format_path(child), "duplicate key"))
                self._node(value_event, child, depth + 1, False)
            else:
                child = path + (key,)
                if record:                        # a value's line is its key's
                    self.lines[child] = key_event.start_mark.line + 1
                mapping[key] = self._node(value_event, child, depth + 1, record)
            key_event = next_event()
        return mapping

    def _key(self, event, path: Path, depth: int, record: bool) -> str | None:
        """Read the mapping key that starts with ``event``: its text, or None (reported) if it
        is not a name."""
        line = event.start_mark.line + 1
        value = self._node(event, path, depth + 1, False)   # checks aliases, depth, tags
        if isinstance(value, str):
            return value
        if not isinstance(event, ScalarEvent):
            message = "keys must be plain names, not lists or mappings"
        elif value is None:
            shown = f"'{event.value}'" if event.value else "an empty key"
            message = f"keys must be names; {shown} reads as null (no value)"
        else:
            message = (f"keys must be names; {event.value} reads as {_kind(value)}: quote "
                       f"it ('{event.value}') if it is a name")
        if record:
            self.problems.append(Problem(self.filename, line, format_path(path), message))
        return None

    def _tag_error(self, event, path: Path) -> SpecError:
        return self._fatal(event, path, f"tag '{_show_tag(event.tag)}' is not allowed: a spec "
                                        "holds plain values (text, numbers, true/false, lists "
                                        "and mappings) and needs no tags")

    def _scalar(self, event: ScalarEvent, path: Path) -> Any:
        tag, text = event.tag, event.value
        if event.style == '"':   # escapes can write any code point: the same rule applies
            bad = _NON_PRINTABLE.search(text)
            if bad is not None:
                raise self._fatal(event, path, f"escaped character U+{ord(bad.group()):04X} is "
                                               "not allowed: spec text must be printable")
        if tag is None:
            return resolve_plain(text) if event.implicit[0] else text
        if tag in ("!", STR):
            return text
        if tag in (NULL, BOOL, INT, FLOAT):
            value = resolve_plain(text) if text else None
            ok = {NULL: value is None,
                  BOOL: isinstance(value, bool),
                  INT: isinstance(value, (int, HugeInteger)) and not isinstance(value, bool),
                  FLOAT: isinstance(value, (int, float, HugeInteger))
                  and not isinstance(value, bool)}[tag]
            if not ok:
                raise self._fatal(event, path, f"'{text}' is not a valid {_show_tag(tag)} value")
            return float(value) if tag == FLOAT and isinstance(value, int) else value
        raise self._tag_error(event, path)
