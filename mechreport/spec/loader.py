"""Load and validate a spec file (format version 1, documented in docs/spec.md).

Every problem of a file is collected and raised together as one ``SpecError``; each names the
file, line, key path and what was expected. Whatever the input, loading ends in a ``Spec`` or a
``SpecError``, quickly and in little memory: the reader (``yaml_source``) caps the file size
and the nesting depth and refuses aliases, tags and non-UTF-8 text; this module checks every
value's type and every number's range (docs/spec.md, "What the loader refuses, and why").

The format's shape (its keys, which are required, their types, enumerations and number
ranges) is declared once, by the pydantic models of :mod:`.schema`: the key tables below come
from them, and their validation runs on every file after the checks here, so that a shape
problem these checks do not see is reported too, in the same ``file:line: key.path: message``
form (:func:`_shape_check`). What needs more than one value at a time (references between
names, mobility, cycle quantities, units to SI) is checked here in plain Python.
"""
from __future__ import annotations

import difflib
import math
import os
import re
import unicodedata
from dataclasses import replace
from pathlib import Path as FsPath
from typing import Any

from ..errors import Problem, SpecError
from ..quantities import (CYCLE_UNITS, DYNAMICS_INSTANT, JOINT_CYCLE_UNITS, MECHANISM_UNITS,
                          MEMBER_UNITS, is_cycle, is_member, joint_unit, unit_of, split as split_quantity)
from ..units import EXPECT_UNITS, SPEC_UNITS, UNIT_TABLES, rpm_to_rad_s
import mechreport.spec.schema as schema   # the models (not `from . import`: spec/__init__)
from .schema import (MAX_STUDY_VARIANTS, NUMBER_MAX, NUMBER_MIN, choices_of, keys_of,
                     required_of)
from .strength import strength_links
from .types import ReportSettings
from .types import (GROUND, BearingSpec, Design, Driver, Dynamics, Expectation, Friction, Joint,
                    Line, Link, Load, MotorCurve, Pin, Shape, Spec, Study, Sweep, Vary, Vec)
from .yaml_source import (MAX_DEPTH, MAX_FILE_BYTES, HugeInteger, Source, check_text, decode,
                          format_path, too_big)

#: the units a spec's numbers may be written in, to SI (factors from the one unit table)
LENGTH_UNITS = {u: UNIT_TABLES["length"][u] for u in SPEC_UNITS["length"]}
MASS_UNITS = {u: UNIT_TABLES["mass"][u] for u in SPEC_UNITS["mass"]}

# Every number in a spec is finite and, unless exactly zero, has a magnitude between
# NUMBER_MIN and NUMBER_MAX (declared in .schema), as written and in SI.
NUMBER_RANGE = (f"between {-NUMBER_MAX:g} and {NUMBER_MAX:g} "
                f"(nonzero magnitudes at least {NUMBER_MIN:g})")
POSITIVE_RANGE = f"between {NUMBER_MIN:g} and {NUMBER_MAX:g}"
MAX_PROBLEMS = 100   # listed per file; the rest are counted

__all__ = ["load_spec", "parse_spec", "load_source", "parse_source", "spec_from_data",
           "LENGTH_UNITS", "MASS_UNITS", "NUMBER_MAX", "NUMBER_MIN",
           "MAX_FILE_BYTES", "MAX_DEPTH", "MAX_PROBLEMS"]

# The key tables, from the models of .schema (the one place a key is declared): the keys a
# mapping may have, in their order, and those it must have.
TOP_KEYS, TOP_REQUIRED = keys_of(schema.SpecFile), required_of(schema.SpecFile)
POLAR_KEYS, POLAR_REQUIRED = keys_of(schema.Polar), required_of(schema.Polar)
LINK_KEYS, LINK_REQUIRED = keys_of(schema.Link), required_of(schema.Link)
SHAPE_KEYS = {"bar": keys_of(schema.Bar), "block": keys_of(schema.Block)}
JOINT_KEYS = {"R": keys_of(schema.RJoint), "T": keys_of(schema.TJoint)}
LINE_KEYS, LINE_REQUIRED = keys_of(schema.Line), required_of(schema.Line)
DRIVER_REQUIRED = required_of(schema.Driver)
LOAD_KEYS = {kind: keys_of(model) for kind, model in schema.LOAD_MODELS.items()}
LOAD_REQUIRED = {kind: tuple(k for k in required_of(model) if k != "type")
                 for kind, model in schema.LOAD_MODELS.items()}
OPPOSE = {kind: choices_of(schema.LOAD_MODELS[kind], "oppose") for kind in ("force", "moment")}
REACTS_ON = choices_of(schema.ForceLoad, "reacts_on")
FRICTION_KEYS = {"R": keys_of(schema.RFriction), "T": keys_of(schema.TFriction)}
DYN_MOTOR_KEYS = schema.DYNAMICS_MOTOR_KINDS
FRICTION_REQUIRED = {"R": required_of(schema.RFriction), "T": required_of(schema.TFriction)}
EXPECT_REQUIRED = required_of(schema.Expectation)
REPORT_TEXT_KEYS = tuple(k for k in keys_of(schema.Report) if k not in ("units", "animation",
                                                                      "dxf"))
STUDY_REQUIRED = required_of(schema.Study)
VARY_KEYS, VARY_REQUIRED = keys_of(schema.Vary), required_of(schema.Vary)
SAMPLES = choices_of(schema.Study, "sample")
JOINT_TYPES = tuple(JOINT_KEYS)
LOAD_TYPES = tuple(LOAD_KEYS)
POINT_QUANTITIES = ("x", "y", "vx", "vy", "ax", "ay", "v", "a")
LINK_QUANTITIES = ("angle", "omega", "alpha")
R_QUANTITIES = ("fx", "fy", "f", "angle", "friction")
T_QUANTITIES = ("fx", "fy", "f", "moment", "px", "py", "friction")
ON_QUANTITIES = ("fx", "fy", "f")     # joint.J.on.<link>.*: the force on one link

_YAML11_BOOLS = {"yes", "no", "on", "off", "y", "n"}
_SEXAGESIMAL = re.compile(r"[-+]?[0-9][0-9_]*(?::[0-5]?[0-9])+(?:\.[0-9_]*)?\Z")
_NUMBER_TEXT = re.compile(r"\s*[-+]?(?:\.[0-9]+|[0-9]+(?:\.[0-9]*)?)(?:[eE][-+]?[0-9]+)?\s*\Z")


MAX_SWEEP_ANGLES = 1_000_000   # about 2.5 GB and a minute of CPU for a full analysis

def _show(value: Any) -> str:
    if value is None:
        text = "null"
    elif isinstance(value, bool):
        text = "true" if value else "false"
    elif isinstance(value, str):
        text = repr(value)
    elif isinstance(value, int) and abs(value) > 10**30:
        text = str(HugeInteger(str(value)))
    else:
        text = str(value)
    return text if len(text) <= 40 else text[:37] + "..."


def _unknown_key(key: str, allowed: tuple[str, ...]) -> str:
    """What is said of a key that ``allowed`` does not have: the nearest allowed key, or the
    list of them."""
    near = difflib.get_close_matches(key, allowed, n=1)
    return "unknown key" + (f"; did you mean '{near[0]}'?" if near
                            else f"; allowed: {', '.join(allowed)}")


def _number_problem(value: Any, positive: bool = False) -> str | None:
    """Why ``value`` is not a number in range (greater than zero if ``positive``), or None."""
    if isinstance(value, bool) or not isinstance(value, (int, float, HugeInteger)):
        kind = "a positive number" if positive else "a number"
        return f"must be {kind}, got {_show(value)}{_text_hint(value)}"
    wanted = (f"must be a positive number {POSITIVE_RANGE}" if positive else
              f"must be a number {NUMBER_RANGE}")
    # compare ints exactly: float() of a 400-digit integer overflows
    if isinstance(value, HugeInteger) or (isinstance(value, int) and abs(value) > NUMBER_MAX):
        return f"{wanted}, got {_show(value)}"
    if not _in_range(float(value)):
        return f"{wanted}, got {_show(value)}"
    if positive and value <= 0:
        return f"must be a positive number, got {_show(value)}"
    return None


def _is_whole(value: Any) -> bool:
    """An int, or a float with a whole value (``3.0``: the same number in JSON, as a YAML
    language server checks it)."""
    return type(value) is int or type(value) is float and value.is_integer()


def _whole_problem(value: Any, low: int, high: int) -> str | None:
    """Why ``value`` is not a whole number in [low, high], or None."""
    if not _is_whole(value) or not low <= value <= high:
        return f"must be a whole number from {low} to {high}, got {_show(value)}" \
               f"{_text_hint(value)}"
    return None


def _in_range(x: float) -> bool:
    """Zero, or a magnitude in [NUMBER_MIN, NUMBER_MAX] (False for inf and nan)."""
    return x == 0 or NUMBER_MIN <= abs(x) <= NUMBER_MAX


def _text_hint(value: Any, boolean: bool = False) -> str:
    """Why a text value that looks like something else is text (YAML 1.1 habits)."""
    if not isinstance(value, str):
        return ""
    if value.strip().lower() in _YAML11_BOOLS:
        if boolean:
            return (" (YAML 1.1 read yes/no/on/off as true/false; a spec does not: write true "
                    "or false)")
        return " (yes/no/on/off are text in a spec, not true/false)"
    if boolean:
        return ""
    if _SEXAGESIMAL.match(value.strip()):
        return (" (YAML 1.1 reads this as a base-60 number; mechreport reads it as text: write "
                "the number in plain digits)")
    if _NUMBER_TEXT.match(value):
        return " (a quoted number is text: remove the quotes)"
    if "_" in value and _NUMBER_TEXT.match(value.replace("_", "")):
        return " (write numbers without '_')"
    return ""


class _Checker:
    """Typed access to the parsed document that records problems instead of raising."""

    def __init__(self, src: Source):
        self.src = src
        self.problems: list[Problem] = list(src.problems[:MAX_PROBLEMS])
        self.dropped = max(0, len(src.problems) - MAX_PROBLEMS)
        # Names written in the spec whose definitions failed (already reported): later checks
        # skip them instead of reporting follow-on errors such as "unknown link".
        self.invalid_links: set[str] = set()
        self.invalid_joints: set[str] = set()
        self.invalid_points: set[str] = set()
        # the models' errors (pydantic's) and the key paths they are at, once validated
        self.shape: list[dict] | None = None
        self.refused_paths: list[tuple] = []

    def validate(self, data: Any) -> None:
        """Validate ``data`` with the models of :mod:`.schema` (their problems are reported
        later, by :func:`_shape_check`): a section the models refuse is not converted."""
        self.shape = schema.shape_errors(data) if isinstance(data, dict) else []
        self.refused_paths = [schema.locate(tuple(e["loc"])).path for e in self.shape]

    def refused(self, path: tuple) -> bool:
        """Whether the models refused the value at ``path`` or something in it."""
        n = len(path)
        return any(tuple(p[:n]) == path for p in self.refused_paths)

    def error(self, path: tuple, message: str) -> None:
        if len(self.problems) >= MAX_PROBLEMS:
            self.dropped += 1
            return
        self.problems.append(Problem(self.src.filename, self.src.line(path),
                                     format_path(path), message))

    def mapping(self, value: Any, path: tuple, allowed: tuple[str, ...],
                required: tuple[str, ...] = ()) -> dict | None:
        if not isinstance(value, dict):
            self.error(path, f"must be a mapping of keys ({', '.join(allowed)}), got {_show(value)}")
            return None
        for key in value:
            if key not in allowed:
                self.error(path + (key,), _unknown_key(key, allowed))
        for key in required:
            if key not in value:
                self.error(path, f"missing required key '{key}'")
        return value

    def number(self, value: Any, path: tuple, *, positive: bool = False,
               nonzero: bool = False, scale: float = 1.0, unit: str = "") -> float | None:
        """A finite number in range, times ``scale`` (to SI; ``unit`` names the written unit);
        None (reported) otherwise."""
        if (isinstance(value, bool) or not isinstance(value, (int, float, HugeInteger))) \
                and len(self.problems) >= MAX_PROBLEMS:   # not listed: skip the message
            self.dropped += 1
            return None
        problem = _number_problem(value, positive)
        if problem is not None:
            self.error(path, problem)
            return None
        number = float(value)
        if nonzero and number == 0:
            self.error(path, "must not be zero")
            return None
        return self.si(value, path, scale=scale, unit=unit)

    def si(self, value: Any, path: tuple, *, scale: float = 1.0,
           unit: str = "") -> float | None:
        """A number the models validated, times ``scale`` (to SI; ``unit`` names the written
        unit); None (reported) when it leaves the range of numbers in SI units."""
        si = float(value) * scale
        if not _in_range(si):
            self.error(path, f"{_show(value)} {unit} is {si:g} in SI units; numbers must lie "
                             f"{NUMBER_RANGE} in SI units too")
            return None
        return si

    def vec2(self, value: Any, path: tuple, what: str = "[x, y]", *, scale: float = 1.0,
             unit: str = "") -> Vec | None:
        if not isinstance(value, list) or len(value) != 2:
            self.error(path, f"must be a pair {what}, got {_show(value)}")
            return None
        x = self.number(value[0], path + (0,), scale=scale, unit=unit)
        y = self.number(value[1], path + (1,), scale=scale, unit=unit)
        return None if x is None or y is None else (x, y)

    def point(self, value: Any, path: tuple, what: str = "[x, y]", *, scale: float = 1.0,
              unit: str = "") -> Vec | None:
        """A point written ``[x, y]`` or, in polar form, ``{r: R, angle: A}`` (R in the
        length unit, A in degrees from the frame's x-axis, CCW), to SI. At a multiple of 90
        degrees the zero coordinate is exactly 0 (cos 90 deg is 6e-17 in floating point)."""
        if not isinstance(value, dict) or not ({"r", "angle"} & set(value)):
            return self.vec2(value, path, f"{what} or {{r: R, angle: A}}", scale=scale,
                             unit=unit)
        body = self.mapping(value, path, POLAR_KEYS, required=POLAR_REQUIRED)
        if body is None or any(k not in body for k in POLAR_REQUIRED):
            return None
        r = self.number(body["r"], path + ("r",), scale=scale, unit=unit)
        if r is not None and r < 0:
            self.error(path + ("r",), f"must be a distance (not negative), got {_show(body['r'])}")
            r = None
        angle = self.number(body["angle"], path + ("angle",))
        if r is None or angle is None:
            return None
        quarter = angle / 90.0
        if quarter == round(quarter):        # exact on the axes
            c, s = ((1.0, 0.0), (0.0, 1.0), (-1.0, 0.0), (0.0, -1.0))[int(round(quarter)) % 4]
        else:
            c, s = math.cos(math.radians(angle)), math.sin(math.radians(angle))
        return (r * c + 0.0, r * s + 0.0)

    def name(self, value: Any, path: tuple) -> str | None:
        if not isinstance(value, str) or not value:
            hint = (" (quote a name that looks like a number, true/false or null)"
                    if value is None or isinstance(value, (bool, int, float)) else "")
            self.error(path, f"must be a name, got {_show(value)}{hint}")
            return None
        self.no_bidi_control(value, path)
        return value

    def no_bidi_control(self, name: str, path: tuple) -> None:
        """A name (a value, or a mapping's key at ``path``) must not hold a bidirectional
        control character: it would show the name in the report as other than it is (the
        "Trojan Source" trick)."""
        bad = _BIDI_CONTROL.search(name)
        if bad is not None:
            char = bad.group()
            self.error(path, f"must not hold U+{ord(char):04X} "
                             f"({unicodedata.name(char, 'a bidirectional control')}), a "
                             "bidirectional control character that makes a name display as "
                             "other than it is; remove it")

    def choice(self, value: Any, path: tuple, options: tuple[str, ...]) -> str | None:
        if not isinstance(value, str) or value not in options:
            self.error(path, f"must be one of {', '.join(options)}, got {_show(value)}")
            return None
        return value

    def derived(self, value: float, path: tuple, what: str, unit: str) -> float | None:
        """A value computed from others (a mass from density x volume, an inertia from a shape)
        must lie in range too."""
        if not _in_range(value):
            self.error(path, f"{what} {value:g} {unit}; numbers must lie {NUMBER_RANGE}")
            return None
        return value


def load_spec(path: str | FsPath) -> Spec:
    """Read, validate and convert a spec file to SI. Raises ``SpecError`` listing every problem.

    The size is checked before reading (at most ``MAX_FILE_BYTES``), and at most one byte more
    is ever read, so a huge file or a device such as /dev/zero is refused at once."""
    return parse_spec(_read_file(path), str(path))


def load_source(path: str | FsPath) -> Source:
    """Read a spec file into a :class:`Source` (its data tree and the line of every key path)
    without validating it, under the same limits as :func:`load_spec`; with
    :func:`spec_from_data` it gives the Spec. Raises ``SpecError``."""
    return parse_source(_read_file(path), str(path))


def _read_file(path: str | FsPath) -> bytes:
    filename = str(path)
    try:
        with open(path, "rb") as fh:
            size = os.fstat(fh.fileno()).st_size
            if size > MAX_FILE_BYTES:
                raise too_big(size, filename)
            data = fh.read(MAX_FILE_BYTES + 1)
    except (OSError, ValueError) as exc:   # ValueError: a NUL character in the path
        reason = getattr(exc, "strerror", None) or str(exc)
        raise SpecError([Problem(filename, None, "", f"cannot read file: {reason}")]) from None
    if len(data) > MAX_FILE_BYTES:
        raise too_big(len(data), filename)
    return data


def parse_spec(text: str | bytes, filename: str = "<spec>") -> Spec:
    """Validate spec text (or UTF-8 bytes); ``filename`` is used in messages.

    Raises ``SpecError`` and nothing else, whatever the input."""
    def work() -> Spec:
        src = _source(text, filename)
        return _checked(src.data, src)
    return _guarded(filename, work)


def parse_source(text: str | bytes, filename: str = "<spec>") -> Source:
    """Read spec text (or UTF-8 bytes) into a :class:`Source` without validating it (the same
    limits as :func:`parse_spec`). Raises ``SpecError`` and nothing else."""
    return _guarded(filename, lambda: _source(text, filename))


def spec_from_data(data: Any, src: Source) -> Spec:
    """Validate a spec's data tree and convert it to SI: ``src.data``, or a copy of it with
    leaves replaced (a study's variant, in the spec's own units). Messages name ``src``'s file
    and the lines of ``src``'s key paths. Raises ``SpecError`` and nothing else."""
    return _guarded(src.filename, lambda: _checked(data, src))


def _source(text: str | bytes, filename: str) -> Source:
    if isinstance(text, (bytes, bytearray, memoryview)):
        data = bytes(text)
        if len(data) > MAX_FILE_BYTES:
            raise too_big(len(data), filename)
        text = decode(data, filename)
    elif not isinstance(text, str):
        raise SpecError([Problem(filename, None, "", "spec text must be str or bytes, got "
                                                     f"{type(text).__name__}")])
    check_text(text, filename)
    return Source(filename, text)


def _checked(data: Any, src: Source) -> Spec:
    ck = _Checker(src)
    ck.validate(data)
    spec = _build(data, ck)
    _shape_check(data, ck)
    if spec is None or ck.problems:
        if not ck.problems:   # pragma: no cover - every refusal records its reason
            ck.error((), "internal error: the spec was refused without a reason; please "
                         "report this")
        raise SpecError(_listed(ck))
    return spec


# ------------------------------------------------------------------ the models' verdict

def _shape_check(data: Any, ck: _Checker) -> None:
    """Validate ``data`` with the models of :mod:`.schema` and report each problem they find
    that the checks of this module did not: at the line of its key path, in their wording.
    A problem is not reported twice: nothing is added at a key path that has a problem,
    below one (unless that one is only a missing key) or above one."""
    if not isinstance(data, dict) or len(ck.problems) >= MAX_PROBLEMS:
        return              # a document that is not a mapping is reported as it is
    if ck.shape is None:
        ck.validate(data)
    reported = [(p.path, p.message) for p in ck.problems]
    added: set[tuple[str, str]] = set()
    for error in ck.shape:
        path, message = _shape_problem(error)
        shown = format_path(path)
        if (shown, message) in added or _already_reported(shown, message, reported):
            continue
        added.add((shown, message))
        ck.error(path, message)


def _already_reported(path: str, message: str, reported: list[tuple[str, str]]) -> bool:
    """Whether a problem ``message`` at ``path`` (formatted) repeats one of ``reported``: the
    same key path (at the top level, the same message), a path below it, or a path above it
    whose problem is more than a missing key (then what is below was not looked at, or is
    that problem)."""
    for other, text in reported:
        if other == path and (path or text == message):
            return True
        if path and _below(other, path):
            return True
        if other and _below(path, other) and not text.startswith("missing required key"):
            return True
    return False


def _below(path: str, ancestor: str) -> bool:
    """Whether formatted key path ``path`` lies strictly below ``ancestor``."""
    return path.startswith(ancestor) and path[len(ancestor):len(ancestor) + 1] in (".", "[")


def _shape_problem(error: dict) -> tuple[tuple, str]:
    """A pydantic error (``loc``, ``type``, ``input``) as a key path and a message in the
    wording of this module's checks."""
    loc, kind, value = tuple(error["loc"]), error["type"], error.get("input")
    if kind == schema.WORDED:                # said in the house wording where it is found
        key = (error.get("ctx") or {}).get("key")
        return schema.locate(loc).path + ((key,) if key else ()), error["msg"]
    if kind == "missing" and loc and isinstance(loc[-1], int):    # a short pair
        where = schema.locate(loc[:-1])
        return where.path, f"must be {_wording(where, 'a longer list')}, got {_show(value)}"
    where = schema.locate(loc)
    if kind == "missing":
        return where.path[:-1], f"missing required key '{where.path[-1]}'"
    if kind == "extra_forbidden" and where.owner is not None:
        return where.path, _unknown_key(str(where.path[-1]), keys_of(where.owner))
    if kind in ("union_tag_invalid", "union_tag_not_found"):
        return _tag_problem(where, value)
    refusal = where.marker(schema.Refusal)
    if refusal is not None and refusal.says(kind):
        return where.path, refusal.text.format(value=_show(value))
    return where.path, _value_problem(where, kind, value, error.get("msg", ""))


def _tag_problem(where: schema.Located, value: Any) -> tuple[tuple, str]:
    """A mapping whose tag (a joint's or load's ``type``, a shape's kind ...) picks none of
    the models it may be."""
    picker = where.picker()
    if isinstance(picker, schema.ByKey) and isinstance(value, dict):
        options = ", ".join(picker.tags)
        if picker.key in value:
            return (where.path + (picker.key,),
                    f"must be one of {options}, got {_show(value[picker.key])}")
        return where.path, f"missing required key '{picker.key}' ({' or '.join(picker.tags)})"
    return where.path, f"must be {_wording(where, 'a mapping')}, got {_show(value)}"


def _value_problem(where: schema.Located, kind: str, value: Any, fallback: str) -> str:
    """What is wrong with a value of the wrong type, out of range or not one of a list."""
    options = schema.literal_values(where.annotation)
    if options:
        return f"must be one of {', '.join(map(str, options))}, got {_show(value)}"
    if where.annotation is float:
        return _range_problem(where, value) or _fallback(fallback)
    if where.annotation is int:
        return (_whole_problem(value, where.constraint("ge"), where.constraint("le"))
                or _fallback(fallback))
    if where.annotation is bool:
        return f"must be true or false, got {_show(value)}{_text_hint(value, boolean=True)}"
    if kind in ("string_too_long", "string_pattern_mismatch"):
        return f"must be one line of at most {where.constraint('max_length')} characters"
    if where.is_model():
        keys = ", ".join(keys_of(where.annotation))
        return f"must be a mapping of keys ({keys}), got {_show(value)}"
    what = _wording(where, {"dict_type": "a mapping", "list_type": "a list",
                            "string_type": "text"}.get(kind, ""))
    if not what:
        return _fallback(fallback)
    quote = (" (quote a name that looks like a number, true/false or null)"
             if what == "a name" and (value is None or isinstance(value, (bool, int, float)))
             else "")
    return f"must be {what}, got {_show(value)}{quote}"


def _range_problem(where: schema.Located, value: Any) -> str | None:
    """A number's problem: not a number, out of the range every number keeps, or out of the
    range of its key (greater than zero, 0 or more, at most some limit)."""
    low, high = where.constraint("ge"), where.constraint("le")
    problem = _number_problem(value, positive=low is not None and low > 0)
    if problem is not None:
        return problem
    if low == 0 and value < 0:
        return f"must be 0 or more, got {_show(value)}"
    if high is not None and value > high:
        return f"must be at most {high:g}, got {_show(value)}"
    return None


def _wording(where: schema.Located, default: str) -> str:
    """What the value at ``where`` must be, as the models word it (``default`` if they do
    not)."""
    wording = where.marker(schema.Wording)
    return wording.text if wording is not None else default


def _fallback(message: str) -> str:
    """pydantic's own message, in the house form ("must be ...")."""
    message = message.replace("Input should be", "must be").replace("Value error, ", "")
    return message[:1].lower() + message[1:]


def _guarded(filename: str, work):
    """``work()``, with any failure but a ``SpecError`` turned into one (never a traceback
    for a user's file)."""
    try:
        return work()
    except SpecError:
        raise
    except RecursionError:
        raise SpecError([Problem(filename, None, "", "the spec is nested too deeply to read")]) \
            from None
    except MemoryError:
        raise SpecError([Problem(filename, None, "", "out of memory while reading the spec")]) \
            from None
    except Exception as exc:   # never a traceback for a user's file; tests assert this is unused
        raise SpecError([Problem(filename, None, "", f"internal error while loading the spec "
                                                     f"({type(exc).__name__}: {exc}); please "
                                                     "report this")]) from exc


def _listed(ck: _Checker) -> list[Problem]:
    problems = _sorted(ck.problems)
    if ck.dropped:
        problems.append(Problem(ck.src.filename, None, "",
                                f"... and {ck.dropped} more problem(s); only the first "
                                f"{MAX_PROBLEMS} are listed"))
    return problems


def _sorted(problems: list[Problem]) -> list[Problem]:
    return sorted(problems, key=lambda p: (p.line or 10**9))


_ABSENT = object()


def _build(data: Any, ck: _Checker) -> Spec | None:
    if data is None:
        ck.error((), "the file is empty; a spec starts with 'mechreport: 1'")
        return None
    top = ck.mapping(data, (), TOP_KEYS, required=TOP_REQUIRED)
    if top is None:
        return None
    _key_names(top, (), ck)

    name = ck.name(top.get("name"), ("name",)) if "name" in top else None
    description = top.get("description")
    if description is None or ck.refused(("description",)):
        description = ""

    length_scale, mass_scale, units = _units(top.get("units"), ck)
    gravity = _default_gravity()
    if "gravity" in top and not ck.refused(("gravity",)):
        gravity = (float(top["gravity"][0]), float(top["gravity"][1]))

    ground = _ground(top.get("ground", {}), ck, length_scale, units["length"])
    links = _links(top.get("links", _ABSENT), ck, length_scale, mass_scale, units)
    link_names = {link.name for link in links}
    joints, pins = _joints(top.get("joints", _ABSENT), ck, ground, {l.name: l for l in links},
                           length_scale, units["length"])
    links = strength_links(top.get("links"), top.get("materials"), ck, links, joints,
                           length_scale, units["length"])
    driver = (_driver(top.get("driver"), ck, joints, length_scale, pins) if "driver" in top
              else None)
    cycle = _cycle(top, ck)
    sweep = _sweep(top.get("sweep"), ck, cycle)
    at = _angle_list(top.get("at"), ("at",), ck) if "at" in top else (sweep.start,)
    assembly = _assembly(top.get("assembly"), ck, links, length_scale, units["length"])
    loads = _loads(top.get("loads"), ck, {l.name: l for l in links}, joints, ground,
                   length_scale, pins)
    if driver is not None and driver.kind == "T":
        if "sweep" not in top:
            ck.error((), "a T driver needs a 'sweep': a plain range of strokes in the length "
                         "unit, e.g. {start: 0, stop: 300, step: 5}")
        sweep = replace(sweep, wraps=False)
        for ld in loads:
            if ld.profile is not None:
                ck.error(("loads", ld.index, "profile"), "a profile is given over the crank "
                                                          "angle: it needs an R driver")
    friction = (_friction(top["friction"], ck, joints, pins, length_scale)
                if "friction" in top else ())
    dynamics = (_dynamics(top["dynamics"], ck, driver, sweep)
                if "dynamics" in top else None)
    expect = _expect(top.get("expect"), ck, links, joints, src_lines=ck.src, driver=driver,
                     pins=pins)
    design = _design(top.get("design"), ck, joints, pins) if "design" in top else Design()
    report = (_report(top.get("report"), ck, units, sweep.whole_turn) if "report" in top
              else ReportSettings(animation=sweep.whole_turn))
    study = _study(top["study"], ck, top) if "study" in top else None
    sheet = (schema.SpecFile.model_fields["sheet"].default if ck.refused(("sheet",))
             else top.get("sheet", schema.SpecFile.model_fields["sheet"].default))

    if links and joints:
        _zero_length(ck, links, joints)
    if links and joints is not None and link_names and not (ck.invalid_links or
                                                            ck.invalid_joints):
        _structure(ck, links, joints)

    if ck.problems or name is None or driver is None or joints is None:
        # what the sweep alone says is still said, so that every problem is listed at once
        if "design" in top and (driver is None or driver.kind == "R") \
                and _cycle_design(top.get("design")):
            why = sweep.cycle_problem()
            if why is not None:
                ck.error(("design",), f"the design review is undefined: {why}")
        return None
    spec = Spec(file=ck.src.filename, name=name, description=description.strip(),
                gravity=gravity, ground=ground, links=tuple(links), joints=tuple(joints),
                driver=driver, sweep=sweep, at=at, assembly=assembly, loads=tuple(loads),
                expect=tuple(expect), sheet=sheet, units=units, design=design,
                report=report, study=study, pins=tuple(pins), friction=friction,
                dynamics=dynamics, cycle=cycle)
    _cycle_requests(spec, ck)
    if study is not None:
        _study_requests(spec, ck)
    return None if ck.problems else spec


def _friction(value: Any, ck: _Checker, joints: list[Joint] | None, pins: list[Pin],
              ls: float) -> tuple[Friction, ...]:
    """``friction:`` by joint name (a pin joining several links: each of its two-link
    joints), in spec order; entries with ``mu: 0`` add no friction (the frictionless
    analysis, unchanged)."""
    path = ("friction",)
    if not isinstance(value, dict) or not value:
        ck.error(path, "must map joint names to {mu, radius} (R) or {mu, length} (T), got "
                       f"{_show(value)}")
        return ()
    known = {j.name: j for j in joints or ()}
    pinned = {p.name: p for p in pins}
    out: dict[str, Friction] = {}
    for name, body in value.items():
        where = path + (name,)
        targets = ([known[p] for p in (pinned[name].joint_name(x)
                                       for x in pinned[name].others)] if name in pinned
                   else [known[name]] if name in known else [])
        if not targets:
            if joints is not None and name not in ck.invalid_joints:
                near = difflib.get_close_matches(str(name), [*known, *pinned], n=1)
                hint = f"; did you mean '{near[0]}'?" if near else \
                    f" (joints: {', '.join(sorted({*known, *pinned}))})"
                ck.error(where, f"no joint named '{name}'{hint}")
            continue
        jtype = targets[0].type
        required = FRICTION_REQUIRED[jtype]
        entry = ck.mapping(body, where, FRICTION_KEYS[jtype], required=required)
        if entry is None or any(k not in entry for k in required):
            continue
        if ck.refused(where):
            continue            # the models say what is wrong
        mu = float(entry["mu"])
        size_key = "radius" if jtype == "R" else "length"
        size = (ck.si(entry[size_key], where + (size_key,), scale=ls)
                if size_key in entry else None)
        sense = entry.get("friction_sense")
        if (size_key in entry and size is None) or mu == 0:
            continue
        for joint in targets:
            out[joint.name] = Friction(joint.name, mu, size if jtype == "R" else None,
                                       size if jtype == "T" else None,
                                       None if sense is None else int(sense),
                                       str(entry.get("model") or "couple"))
    order = [j.name for j in joints or ()]
    return tuple(sorted(out.values(), key=lambda f: order.index(f.joint)))


def _dynamics(value: Any, ck: _Checker, driver: Driver | None, sweep: Sweep
              ) -> Dynamics | None:
    """``dynamics:`` (docs/spec.md, "Machine dynamics"): the motor, flywheel, initial state,
    end and output step; the driver must be a crank (an R joint with ground)."""
    path = ("dynamics",)
    body = value if isinstance(value, dict) else {}
    if ("motor" in body) == ("mean_rpm" in body):
        return None             # the models say what is wrong
    ok = True
    if driver is not None and not driver.crank:
        ck.error(path, "machine dynamics needs a crank: the driver an R joint with ground (the "
                       f"motor turns it); '{driver.joint}' is "
                       + ("a slider (T)" if driver.kind == "T" else "between two moving links"))
        ok = False
    elif driver is not None and driver.omega < 0:
        ck.error(path, "machine dynamics turns the crank counter-clockwise (the motor's "
                       "positive sense); write the driver's speed positive and the mechanism "
                       "mirrored, or leave dynamics out")
        ok = False
    motor = (_dynamics_motor(body["motor"], path + ("motor",), ck) if "motor" in body
             else None)
    if not ok or (motor is None and "motor" in body) or ck.refused(path):
        return None
    start = body.get("start") or {}
    until = body.get("until")
    fly = body.get("flywheel", 0.0)
    geared = (float(fly["inertia"]), float(fly["ratio"])) if isinstance(fly, dict) else None
    return Dynamics(motor, geared[1] ** 2 * geared[0] if geared else float(fly),
                    float(start.get("angle", sweep.start)), float(start.get("rpm", 0.0)),
                    None if until in (None, "steady") else float(until),
                    None if body.get("output_step") is None else float(body["output_step"]),
                    None if body.get("mean_rpm") is None else float(body["mean_rpm"]),
                    geared)


def _dynamics_motor(value: Any, path: tuple, ck: _Checker) -> MotorCurve | None:
    """The motor of ``dynamics:``: exactly one of ``torque``, ``curve``, ``linear``."""
    body = ck.mapping(value, path, DYN_MOTOR_KEYS + ("ratio", "efficiency"))
    if body is None:
        return None
    given = [k for k in DYN_MOTOR_KEYS if k in body]
    if len(given) != 1:
        ck.error(path, "give exactly one of torque (N·m), curve ([[rpm, N·m], ...]) or linear "
                       "({stall_torque, no_load_rpm})" + (f", not {' and '.join(given)}"
                                                          if given else ""))
        return None
    if ck.refused(path):
        return None
    kind = given[0]
    gear = {k: float(body[k]) for k in ("ratio", "efficiency") if k in body}
    if kind == "torque":
        return MotorCurve(constant=float(body["torque"]), **gear)
    if kind == "linear":
        return MotorCurve(stall_torque=float(body["linear"]["stall_torque"]),
                          no_load_rpm=float(body["linear"]["no_load_rpm"]), **gear)
    points = [(float(a), float(b)) for a, b in body["curve"]]
    for i in range(1, len(points)):
        if not points[i][0] > points[i - 1][0]:
            ck.error(path + ("curve", i, 0), f"the speeds must increase: {points[i][0]:g} rpm "
                                             f"follows {points[i - 1][0]:g} rpm")
            return None
    return MotorCurve(curve=tuple(points), **gear)


def _design(value: Any, ck: _Checker, joints: list[Joint] | None, pins=()) -> Design:
    """The design review's inputs, SI as written (their types and ranges are the models';
    a part they refuse is left out); a bearing must name a joint."""
    path = ("design",)
    body = value if isinstance(value, dict) else {}

    def numbers(key: str, model) -> dict[str, float]:
        raw = body.get(key)
        if not isinstance(raw, dict) or ck.refused(path + (key,)):
            return {}
        return {k: float(raw[k]) for k in keys_of(model) if k in raw}

    cs = body.get("speed_fluctuation")
    cs = None if cs is None or ck.refused(path + ("speed_fluctuation",)) else float(cs)
    bearings: dict[str, BearingSpec] = {}
    raw = body.get("bearings")
    names = {j.name for j in joints or ()}
    for jname, item in (raw.items() if isinstance(raw, dict) else ()):
        where = path + ("bearings", jname)
        if joints is not None and jname not in names:
            if jname not in ck.invalid_joints:
                ck.error(where, _pin_hint(jname, pins, "bearing")
                         or f"no joint named '{jname}' (joints: {', '.join(sorted(names))})")
        elif not ck.refused(where):
            life = item.get("life_h")
            bearings[jname] = BearingSpec(float(item["rating"]),
                                          None if life is None else float(life))
    return Design(cs, numbers("motor", schema.Motor), bearings, numbers("limits", schema.Limits))


def _pin_hint(name: str, pins, what: str) -> str | None:
    """Why ``name`` does not name one joint, for a ``what`` that sits between two links,
    when it is a pin joining several links; None when it is not one."""
    pin = next((p for p in pins if p.name == name), None)
    if pin is None:
        return None
    choices = ", ".join(f"'{pin.joint_name(link)}' ({pin.hub} and {link})"
                        for link in pin.others)
    return (f"'{name}' is a pin joining {', '.join(pin.links)}: a {what} sits between two of "
            f"them; name one of {choices}")


def _cycle_requests(spec: Spec, ck: _Checker) -> None:
    """Cycle quantities asked for (``design``, angle-less ``expect``) where none is defined,
    or that need a design input the spec does not give, are errors."""
    why = spec.cycle_problem()
    asked = [(("expect", i), e.quantity) for i, e in enumerate(spec.expect)
             if e.angle is None and not is_member(e.quantity)]
    for i, e in enumerate(spec.expect):          # the steady cycle's speed at an angle
        need = _dynamics_need(spec, e.quantity) if e.quantity in DYNAMICS_INSTANT else None
        if need:
            ck.error(("expect", i), need)
    strength = [k for k in STRENGTH_LIMITS if k in spec.design.limits]
    if strength and not any(link.strength for link in spec.links):
        ck.error(("design", "limits", strength[0]), "needs a link with a 'section' and a "
                 "'material' (the members' safety factors it limits)")
    if why is not None:
        for path, quantity in asked:
            ck.error(path, f"'{quantity}' is undefined: {why}")
        if not cycle_design(spec.design).empty:
            ck.error(("design",), f"the design review is undefined: {why}")
        return
    for path, quantity in asked:
        need = _cycle_need(spec, quantity)
        if need:
            ck.error(path, need)
    if "efficiency" in spec.design.limits and not spec.friction:
        ck.error(("design", "limits", "efficiency"), "needs friction in a joint (a "
                 "'friction:' entry with mu > 0): without it the efficiency is 1")
    if spec.driver.at_rest and spec.design.speed_fluctuation:
        ck.error(("design", "speed_fluctuation"),
                 f"the flywheel inertia it sizes is undefined: {_at_rest(spec)}")
    if spec.driver.at_rest and spec.design.bearings:
        ck.error(("design", "bearings"), f"a bearing's rating life is undefined: {_at_rest(spec)}")
    if "speed_fluctuation" in spec.design.limits:
        need = _dynamics_need(spec, "dynamics.speed_fluctuation")
        if need:
            ck.error(("design", "limits", "speed_fluctuation"), need)


def _dynamics_need(spec: Spec, quantity: str) -> str | None:
    """What a ``dynamics.*`` quantity needs that ``spec`` does not give (None when nothing)."""
    if spec.dynamics is None:
        return (f"'{quantity}' needs a 'dynamics:' section (a motor, and the steady state it "
                "reaches)")
    if quantity == "dynamics.startup_time" and spec.dynamics.mean_rpm is not None:
        return (f"'{quantity}' is undefined with dynamics.mean_rpm: the steady state is "
                "found directly, with no start-up (give a motor to simulate one)")
    if spec.dynamics.until is not None:
        return (f"'{quantity}' is a quantity of the steady cycle: with dynamics.until a time "
                "the simulation gives the transient only (write until: steady)")
    return None


#: the design limits on the members' safety factors: defined for any sweep
STRENGTH_LIMITS = ("static_safety", "fatigue_safety", "buckling_safety")


def cycle_design(design: Design) -> Design:
    """``design`` without the limits on the members' safety factors (what needs a cycle)."""
    return replace(design, limits={k: v for k, v in design.limits.items()
                                   if k not in STRENGTH_LIMITS})


def _cycle_design(raw: Any) -> bool:
    """Whether a ``design:`` as written asks for anything but the members' safety limits."""
    if not isinstance(raw, dict):
        return True
    limits = raw.get("limits")
    return any(k != "limits" for k in raw) or not isinstance(limits, dict) or any(
        k not in STRENGTH_LIMITS for k in limits)


def _at_rest(spec: Spec) -> str:
    """Why quantities that divide by the driver's speed are undefined for ``spec``."""
    key = "speed" if spec.driver.kind == "T" else ("rpm" if spec.driver.rpm_given is not None
                                                   else "omega")
    return (f"the driver is at rest (driver.{key}: 0), and it divides by the speed; give the "
            "speed the machine runs at")


def _cycle_need(spec: Spec, quantity: str) -> str | None:
    """What a cycle quantity needs that ``spec`` does not give (None when nothing)."""
    kind, name, attr = split_quantity(quantity) or ("", "", "")
    life = kind == "joint" and attr == "life_h"
    if spec.driver.at_rest and (quantity == "cycle.flywheel_inertia" or life):
        return f"'{quantity}' is undefined: {_at_rest(spec)}"
    if quantity.startswith("dynamics."):
        return _dynamics_need(spec, quantity)
    if quantity in ("cycle.friction.energy", "cycle.efficiency") and not spec.friction:
        return f"'{quantity}' needs friction in a joint (a 'friction:' entry with mu > 0)"
    if quantity == "cycle.flywheel_inertia" and not spec.design.speed_fluctuation:
        return ("'cycle.flywheel_inertia' needs design.speed_fluctuation (the coefficient of "
                "speed fluctuation Cs)")
    if life and name not in spec.design.bearings:
        return (f"'{quantity}' needs design.bearings.{name}.rating (the bearing's dynamic "
                "load rating C)")
    return None


# --------------------------------------------------------------------------------- study

#: top-level keys whose numbers a study does not vary: they describe the file, not the machine
NOT_VARIED = ("mechreport", "study", "expect", "report")


def _study(value: Any, ck: _Checker, top: dict) -> Study | None:
    """The ``study`` section (docs/spec.md, section 17): every key path must lead to a number
    of this spec; values are kept as written (the spec's own units)."""
    path = ("study",)
    body = value if isinstance(value, dict) else {}
    if any(k not in body for k in STUDY_REQUIRED):
        return None             # the models say what is wrong

    def given(key: str) -> Any:
        """The value of ``key`` as validated (the model's default if absent), None if the
        models refused it."""
        if ck.refused(path + (key,)):
            return None
        return body.get(key, schema.Study.model_fields[key].default)

    ok = not any(ck.refused(path + (key,)) for key in ("sample", "count", "seed"))
    sample, count, seed = given("sample"), given("count"), given("seed")
    count = None if count is None else int(count)
    seed = None if seed is None else int(seed)
    if "count" not in body and sample in ("random", "lhs"):
        ck.error(path, f"missing required key 'count' (how many variants {sample} sampling "
                       "draws)")
        ok = False
    vary = _vary(body["vary"], path + ("vary",), ck, top, sample or "grid")
    keep = _keep(body["keep"], path + ("keep",), ck)
    if not ok or vary is None or keep is None:
        return None
    study = Study(vary, keep, sample, count, seed, ck.src.line(path))
    if sample == "grid" and study.size > MAX_STUDY_VARIANTS:
        ck.error(path + ("vary",), f"the grid has {study.size} combinations; a study may have "
                                   f"at most {MAX_STUDY_VARIANTS} variants (fewer counts or "
                                   "values, or sample: random or lhs)")
        return None
    return study


def _vary(value: Any, path: tuple, ck: _Checker, top: dict,
          sample: str) -> tuple[Vary, ...] | None:
    if not isinstance(value, list) or not value:
        return None             # the models say what is wrong
    out: list[Vary] = []
    seen: dict[tuple, int] = {}
    ok = True
    for i, item in enumerate(value):
        where = path + (i,)
        body = item if isinstance(item, dict) else {}
        if any(k not in body for k in VARY_REQUIRED):
            ok = False          # the models say what is wrong
            continue
        leaf = _key_path(body["key"], where + ("key",), ck, top)
        if leaf is not None and leaf in seen:
            ck.error(where + ("key",), f"'{body['key']}' is varied by study.vary[{seen[leaf]}] "
                                       "too: vary each key once")
            leaf = None
        if leaf is not None:
            seen[leaf] = i
        # a mistake the models see (an unknown key, a value's type) is said by them alone
        entry = None if ck.refused(where) else _vary_values(body, where, ck, sample)
        if leaf is None or entry is None:
            ok = False
            continue
        out.append(Vary(body["key"], leaf, line=ck.src.line(where), **entry))
    return tuple(out) if ok else None


def _vary_values(body: dict, where: tuple, ck: _Checker, sample: str) -> dict | None:
    """``values`` (kept as written), or ``from``/``to`` (and ``count`` for a grid)."""
    has_values = "values" in body
    has_range = "from" in body or "to" in body
    if has_values == has_range:
        ck.error(where, "give either 'values: [...]' or 'from', 'to' (and 'count' for a grid), "
                        "not " + ("both" if has_values else "neither"))
        return None
    if has_values:
        if "count" in body:
            ck.error(where + ("count",), "'count' goes with 'from' and 'to'; with 'values' the "
                                         "grid takes every value")
            return None
        if ck.refused(where + ("values",)):
            return None
        return {"values": tuple(body["values"])}
    missing = [k for k in ("from", "to") if k not in body]
    if missing:
        ck.error(where, f"missing required key '{missing[0]}' (a range needs 'from' and 'to')")
        return None
    refused = any(ck.refused(where + (key,)) for key in ("from", "to", "count"))
    start = None if refused else float(body["from"])
    stop = None if refused else float(body["to"])
    count = None if refused or "count" not in body else int(body["count"])
    if refused:
        return None
    if count is None and sample == "grid":
        ck.error(where, "missing required key 'count' (how many grid values from 'from' to "
                        "'to', both included)")
        return None
    if start is None or stop is None:
        return None
    if start == stop:
        ck.error(where + ("to",), f"equals 'from' ({_show(body['from'])}): a range needs two "
                                  "different ends; for one value write values: [x]")
        return None
    if count == 1 and sample == "grid":
        ck.error(where + ("count",), "must be at least 2 for a range (both ends are values); "
                                     "for one value write values: [x]")
        return None
    return {"start": start, "stop": stop, "count": count}


def _key_path(key: Any, where: tuple, ck: _Checker, top: dict) -> tuple | None:
    """The key path of ``key`` (``links.rod.points.C.0``: names, and list indices as numbers)
    if it leads to a number of the spec; None (reported) otherwise."""
    if not isinstance(key, str) or not key:
        ck.error(where, f"must be a key path into this spec such as links.rod.mass or "
                        f"links.rod.points.C.0, got {_show(key)}")
        return None
    parts = key.split(".")
    if parts[0] in NOT_VARIED:
        ck.error(where, f"'{key}': a study varies the mechanism, not '{parts[0]}'")
        return None
    node: Any = top
    leaf: list = []
    for depth, part in enumerate(parts):
        here = ".".join(parts[:depth]) or "the spec"
        if isinstance(node, dict):
            if part not in node:
                near = difflib.get_close_matches(part, [str(k) for k in node], n=1)
                hint = (f"; did you mean '{near[0]}'?" if near else
                        f" (it has {', '.join(str(k) for k in list(node)[:12])})")
                ck.error(where, f"'{key}': {here} has no key '{part}'{hint}")
                return None
            leaf.append(part)
            node = node[part]
        elif isinstance(node, list):
            if not part.isdigit() or int(part) >= len(node):
                ck.error(where, f"'{key}': {here} is a list of {len(node)}: '{part}' must be "
                                f"an index from 0 to {len(node) - 1}")
                return None
            leaf.append(int(part))
            node = node[int(part)]
        else:
            ck.error(where, f"'{key}': {here} is a single value ({_show(node)}), it has no "
                            f"'{part}'")
            return None
    if isinstance(node, bool) or not isinstance(node, (int, float)):
        what = ("a list" if isinstance(node, list) else "a mapping" if isinstance(node, dict)
                else _show(node))
        ck.error(where, f"'{key}' must lead to a number of the spec, but it is {what}")
        return None
    return tuple(leaf)


def _keep(value: Any, path: tuple, ck: _Checker) -> tuple[str, ...] | None:
    """Cycle quantity names (checked against the mechanism by :func:`_study_requests`)."""
    if not isinstance(value, list) or not value:
        ck.error(path, "must be a list of cycle quantities such as [cycle.torque.rms, "
                       "joint.B.f_max]" + ("" if isinstance(value, list)
                                           else f", got {_show(value)}"))
        return None
    out, ok = [], True
    for i, q in enumerate(value):
        if not isinstance(q, str) or not is_cycle(q):
            near = (difflib.get_close_matches(q, list(CYCLE_UNITS), n=1)
                    if isinstance(q, str) else [])
            hint = f"; did you mean '{near[0]}'?" if near else ""
            ck.error(path + (i,), f"must be a cycle quantity (cycle.*, balance.*, "
                                  f"joint.J.{'|'.join(JOINT_CYCLE_UNITS)}) or a member's "
                                  f"(member.L.{'|'.join(MEMBER_UNITS)}), got {_show(q)}"
                                  f"{hint}")
            ok = False
        elif q in out:
            ck.error(path + (i,), f"'{q}' is kept twice")
            ok = False
        else:
            out.append(q)
    return tuple(out) if ok else None


def _study_requests(spec: Spec, ck: _Checker) -> None:
    """A study tabulates cycle quantities: they must be defined for the spec, and each kept
    one must name a joint of the mechanism and have the design inputs it needs."""
    why = spec.cycle_problem()
    if why is not None and not (all(is_member(q) for q in spec.study.keep)
                                and cycle_design(spec.design).empty):
        ck.error(("study",), f"a study tabulates cycle quantities, which are undefined here: "
                             f"{why}")
        return
    joints = set(spec.reported_reactions())
    for i, q in enumerate(spec.study.keep):
        kind, name, attr = split_quantity(q) or ("", "", "")
        if kind == "member":
            problem = _member_quantity_problem(q, name, attr, list(spec.links), ck)
            if problem:
                ck.error(("study", "keep", i), problem)
            continue
        if kind == "joint" and name not in joints:
            ck.error(("study", "keep", i), f"'{q}': no joint named '{name}' (joints: "
                                           f"{', '.join(sorted(joints))})")
            continue
        need = _cycle_need(spec, q)
        if need:
            ck.error(("study", "keep", i), need)


def _units(value: Any, ck: _Checker) -> tuple[float, float, dict[str, str]]:
    """The factors of the spec's length and mass units to m and kg, and their names (the
    model's defaults where absent or refused)."""
    given = value if isinstance(value, dict) else {}
    names = {key: (given[key] if key in given and not ck.refused(("units", key))
                   else field.default)
             for key, field in schema.Units.model_fields.items()}
    return LENGTH_UNITS[names["length"]], MASS_UNITS[names["mass"]], names


def _ground(value: Any, ck: _Checker, s: float, unit: str) -> dict[str, Vec]:
    if value is None:
        return {}
    if not isinstance(value, dict):
        ck.error(("ground",), f"must be a mapping of point names to [x, y], got {_show(value)}")
        return {}
    out = {}
    for pname, pvalue in value.items():
        v = ck.point(pvalue, ("ground", pname), scale=s, unit=unit)
        if v is not None:
            out[pname] = v
        else:
            ck.invalid_points.add(pname)
    return out


def _links(value: Any, ck: _Checker, ls: float, ms: float, units: dict[str, str]) -> list[Link]:
    if value is _ABSENT:
        return []
    if not isinstance(value, dict) or not value:
        ck.error(("links",), "must be a mapping of link names to link definitions"
                             + ("" if isinstance(value, dict) else f", got {_show(value)}"))
        return []
    links = []
    for number, (lname, body) in enumerate(value.items(), start=1):
        path = ("links", lname)
        if lname == GROUND:
            ck.error(path, "'ground' is the reserved name of the frame; name moving links otherwise")
            continue
        link = _link(lname, number, body, path, ck, ls, ms, units)
        if link is not None:
            links.append(link)
        else:
            ck.invalid_links.add(lname)
            raw = body.get("points") if isinstance(body, dict) else None
            ck.invalid_points.update(raw if isinstance(raw, dict) else ())
    return links


def _link(lname: str, number: int, body: Any, path: tuple, ck: _Checker,
          ls: float, ms: float, units: dict[str, str]) -> Link | None:
    body = ck.mapping(body, path, LINK_KEYS, required=LINK_REQUIRED)
    if body is None:
        return None
    lu, mu = units["length"], units["mass"]
    points: dict[str, Vec] = {}
    raw_points = body.get("points")
    points_ok = "points" in body
    if "points" in body:
        if not isinstance(raw_points, dict) or not raw_points:
            ck.error(path + ("points",), "must map at least one point name to [x, y]"
                     + ("" if isinstance(raw_points, dict) else f", got {_show(raw_points)}"))
            points_ok = False
        else:
            for pname, pv in raw_points.items():
                v = ck.point(pv, path + ("points", pname), scale=ls, unit=lu)
                if v is not None:
                    points[pname] = v
                else:
                    points_ok = False
    shape = _shape(body.get("shape"), path + ("shape",), ck, ls, lu) if "shape" in body else None
    massless = "mass" in body and type(body["mass"]) in (int, float) and body["mass"] == 0
    mass = (ck.number(body["mass"], path + ("mass",), positive=True, scale=ms, unit=mu)
            if "mass" in body and not massless else 0.0 if massless else None)
    density = (ck.number(body["density"], path + ("density",), positive=True)
               if "density" in body else None)
    com = ck.point(body["com"], path + ("com",), scale=ls, unit=lu) if "com" in body else None
    point_mass = ("inertia" in body and type(body["inertia"]) in (int, float)
                  and body["inertia"] == 0)
    inertia = (0.0 if point_mass else
               ck.number(body["inertia"], path + ("inertia",), positive=True)
               if "inertia" in body else None)
    bad = any(k in body and v is None for k, v in
              (("shape", shape), ("mass", mass), ("density", density), ("com", com),
               ("inertia", inertia))) or not points_ok
    if bad:
        return None
    if massless:            # a massless link (a two-force member when it carries no load)
        extra = [k for k in ("density", "shape", "com", "inertia") if k in body]
        if extra:
            them = "it" if len(extra) == 1 else "them"
            ck.error(path + ("mass",), f"0 makes link '{lname}' massless: it has no "
                                       f"{', '.join(extra)} (leave {them} out)")
            return None
        return Link(lname, number, points, 0.0, (0.0, 0.0), 0.0, None)
    if point_mass and mass is None and density is None:   # (density x shape gives one)
        ck.error(path + ("inertia",), "0 (a point mass) needs the link's 'mass'")
        return None
    if mass is None:
        if density is None or shape is None:
            ck.error(path, f"link '{lname}' needs 'mass', or 'density' with a 'shape'")
            return None
        mass = ck.derived(density * shape.volume, path + ("density",),
                          "density x shape volume gives a mass of", "kg")
        if mass is None:
            return None
    if com is None:
        if shape is None:
            ck.error(path, f"link '{lname}' needs 'com' (centre of mass) or a 'shape'")
            return None
        com = shape.centroid
    if inertia is None:
        if shape is None:
            ck.error(path, f"link '{lname}' needs 'inertia' or a 'shape'")
            return None
        c = shape.centroid
        if math.hypot(com[0] - c[0], com[1] - c[1]) > 1e-12:
            ck.error(path + ("com",), f"is off the shape's centroid {list(c)}: give 'inertia' "
                                      "too (a shape's inertia is about its own centroid)")
            return None
        inertia = ck.derived(shape.inertia(mass), path + ("shape",),
                             "the shape gives an inertia of", "kg m^2")
        if inertia is None:
            return None
    return Link(lname, number, points, mass, com, inertia, shape)


def _shape(value: Any, path: tuple, ck: _Checker, ls: float, unit: str) -> Shape | None:
    if not isinstance(value, dict) or len(value) != 1 or next(iter(value)) not in SHAPE_KEYS:
        ck.error(path, "must be {bar: {length, height, depth}} or {block: {width, height, depth}}")
        return None
    kind, dims = next(iter(value.items()))
    keys = SHAPE_KEYS[kind]
    dims = ck.mapping(dims, path + (kind,), keys, required=keys)
    if dims is None or any(k not in dims for k in keys):
        return None
    sizes = [ck.number(dims[k], path + (kind, k), positive=True, scale=ls, unit=unit)
             for k in keys]
    if any(v is None for v in sizes):
        return None
    return Shape(kind, sizes[0], sizes[1], sizes[2])


def _link_points(lname: str, ground: dict[str, Vec], links: dict[str, Link]) -> dict[str, Vec]:
    return ground if lname == GROUND else links[lname].points


def _joints(value: Any, ck: _Checker, ground: dict[str, Vec], links: dict[str, Link],
            ls: float, unit: str) -> tuple[list[Joint] | None, list[Pin]]:
    """The joints as the methods solve them (a pin joining several links becomes a two-link
    joint from its hub to each other link, see :class:`Pin`) and those pins."""
    if value is _ABSENT:
        return None, []
    if not isinstance(value, dict) or not value:
        ck.error(("joints",), "must be a mapping of joint names to joint definitions"
                              + ("" if isinstance(value, dict) else f", got {_show(value)}"))
        return None, []
    joints: list[Joint] = []
    pins: list[Pin] = []
    for jname, body in value.items():
        path = ("joints", jname)
        if not isinstance(body, dict):
            ck.error(path, f"must be a mapping like {{type: R, links: [a, b]}}, got {_show(body)}")
            continue
        jtype = ck.choice(body.get("type"), path + ("type",), JOINT_TYPES) if "type" in body \
            else None
        if "type" not in body:
            ck.error(path, "missing required key 'type' (R or T)")
        allowed = JOINT_KEYS.get(jtype or "T")
        ck.mapping(body, path, allowed, required=allowed[1:] if jtype else ("links",))
        if jtype is None or "links" not in body:
            continue
        names = _joint_links(jname, jtype, body["links"], path + ("links",), ck, links)
        if names is None:
            continue
        if jtype == "R":
            ok = True
            for i, lname in enumerate(names):
                if jname not in _link_points(lname, ground, links):
                    if lname == GROUND and jname in ck.invalid_points:
                        ok = False          # the ground point's own problem is reported
                        continue
                    where = "ground points" if lname == GROUND else f"link '{lname}' points"
                    ck.error(path + ("links", i),
                             f"R joint '{jname}' needs a point named '{jname}' in {where}")
                    ok = False
            if not ok:
                continue
            if len(names) == 2:
                joints.append(Joint(jname, "R", (names[0], names[1]), jname))
                continue
            pin = Pin(jname, tuple(names), names[0])
            pins.append(pin)
            joints += [Joint(pin.joint_name(x), "R", (pin.hub, x), jname) for x in pin.others]
        else:
            joint = _t_joint(jname, body, names, path, ck, ground, links, ls, unit)
            if joint is not None:
                joints.append(joint)
    for pin in pins:
        for x in pin.links:
            if pin.joint_name(x) in value:
                ck.error(("joints", pin.joint_name(x)), f"'{pin.joint_name(x)}' names the force "
                         f"of pin '{pin.name}' on '{x}'; give this joint another name")
    ck.invalid_joints.update(name for name in value
                             if name not in {j.name for j in joints} | {p.name for p in pins})
    return joints, pins


def _joint_links(jname: str, jtype: str, names: Any, path: tuple, ck: _Checker,
                 links: dict[str, Link]) -> list[str] | None:
    """The links a joint joins: two for a T joint, two or more for an R joint (a pin joining
    several links), each known and none twice (None after reporting what is wrong)."""
    if (not isinstance(names, list) or len(names) < 2 or (jtype == "T" and len(names) != 2)
            or not all(isinstance(x, str) for x in names)):
        quote = isinstance(names, list) and any(
            x is None or isinstance(x, (bool, int, float)) for x in names)
        ck.error(path, f"must be two link names [first, second], got {_show(names)}"
                 + (" (quote a name that looks like a number, true/false or null)" if quote
                    else " (a pin joining several links lists them all)" if jtype == "R"
                    else ""))
        return None
    ok = True
    for i, lname in enumerate(names):
        if lname != GROUND and lname not in links:
            if lname not in ck.invalid_links:
                known = ", ".join([GROUND, *sorted({*links, *ck.invalid_links})])
                ck.error(path + (i,), f"unknown link '{lname}' (links: {known})")
            ok = False
    if len(set(names)) < len(names):
        ck.error(path, "a joint needs two different links" if len(names) == 2 else
                 f"a pin joins each link once; '{jname}' lists "
                 f"{', '.join(sorted({x for x in names if names.count(x) > 1}))} twice")
        ok = False
    return names if ok else None


def _t_joint(jname: str, body: dict, pair: list, path: tuple, ck: _Checker,
             ground: dict[str, Vec], links: dict[str, Link], ls: float,
             unit: str) -> Joint | None:
    guide, slider = pair
    point = ck.name(body.get("point"), path + ("point",)) if "point" in body else None
    if point is not None and point not in _link_points(slider, ground, links):
        ck.error(path + ("point",), f"'{point}' is not a point of the slider '{slider}' "
                                    "(the second link of a T joint slides on the first)")
        point = None
    if "line" not in body:   # reported as a missing key
        return None
    line = ck.mapping(body["line"], path + ("line",), LINE_KEYS, required=LINE_REQUIRED)
    if line is None or any(k not in line for k in LINE_REQUIRED):
        return None
    through_raw, through_name = line["through"], None
    if isinstance(through_raw, str):
        pts = _link_points(guide, ground, links)
        if through_raw not in pts:
            if not (guide == GROUND and through_raw in ck.invalid_points):
                ck.error(path + ("line", "through"), f"'{through_raw}' is not a point of the "
                                                     f"guide '{guide}'")
            through = None
        else:
            through, through_name = pts[through_raw], through_raw
    else:
        through = ck.point(through_raw, path + ("line", "through"), "[x, y], a point name",
                           scale=ls, unit=unit)
    direction_raw = line["direction"]
    if isinstance(direction_raw, list):
        d = ck.vec2(direction_raw, path + ("line", "direction"), "[dx, dy] or an angle in degrees")
        if d is not None and math.hypot(*d) == 0:
            ck.error(path + ("line", "direction"), "must not be the zero vector")
            d = None
        direction = None if d is None else (d[0] / math.hypot(*d), d[1] / math.hypot(*d))
    else:
        angle = ck.number(direction_raw, path + ("line", "direction"))
        direction = None if angle is None else (math.cos(math.radians(angle)),
                                                math.sin(math.radians(angle)))
    if point is None or through is None or direction is None:
        return None
    return Joint(jname, "T", (guide, slider), point, Line(through, direction, through_name))


def _driver(value: Any, ck: _Checker, joints: list[Joint] | None,
            length_scale: float = 1.0, pins: list[Pin] = ()) -> Driver | None:
    """Any joint may drive: an R joint its relative angle (``rpm`` or ``omega``, ``alpha``), a
    T joint its stroke (``speed``, ``accel`` in the length unit per s and s^2)."""
    path = ("driver",)
    body = value if isinstance(value, dict) else {}
    if any(k not in body for k in DRIVER_REQUIRED):
        return None             # the models say what is wrong
    jname = None if ck.refused(path + ("joint",)) else body["joint"]
    numbers_refused = any(ck.refused(path + (k,))
                          for k in ("rpm", "omega", "alpha", "speed", "accel"))
    pin = next((p for p in pins if p.name == jname), None)
    if pin is not None:        # a pin joining several links drives its first two links
        jname = pin.joint_name(pin.links[1])
    joint = None if joints is None or jname is None else \
        next((j for j in joints if j.name == jname), None)
    if joint is None:
        if joints is not None and jname is not None and jname not in ck.invalid_joints:
            ck.error(path + ("joint",), f"unknown joint '{jname}' (joints: "
                                        f"{', '.join(j.name for j in joints)})")
        return None             # (its numbers are the models' to check)
    a, b = joint.links
    link = (b if a == GROUND else a) if GROUND in joint.links else b
    if joint.type == "T":
        wrong = [k for k in ("rpm", "omega", "alpha") if k in body]
        for k in wrong:
            ck.error(path + (k,), f"a T driver drives its stroke: give 'speed' (and 'accel') in "
                                  f"the length unit per second, not '{k}'")
        if "speed" not in body:
            if not wrong:
                ck.error(path, "a T driver needs 'speed' (length unit per second; 0 for a "
                               "static analysis)")
            return None
        if wrong or numbers_refused:
            return None
        speed = ck.si(body["speed"], path + ("speed",), scale=length_scale)
        accel = (ck.si(body["accel"], path + ("accel",), scale=length_scale)
                 if "accel" in body else 0.0)
        if speed is None or accel is None:
            return None
        return Driver(jname, link, speed, accel, None, "T", (a, b), length_scale)
    for k in ("speed", "accel"):
        if k in body:
            ck.error(path + (k,), f"an R driver turns: give 'rpm' or 'omega' (and 'alpha'), "
                                  f"not '{k}'")
    if ("rpm" in body) == ("omega" in body):
        ck.error(path, "give exactly one of 'rpm' or 'omega' (rad/s)")
        return None
    if numbers_refused:
        return None
    rpm = None
    key = "rpm" if "rpm" in body else "omega"
    speed = float(body[key])
    if key == "rpm":
        rpm = speed
        omega = None if speed is None else rpm_to_rad_s(speed)
        if omega is not None and not _in_range(omega):
            ck.error(path + (key,), f"{_show(speed)} rpm is {omega:g} rad/s; numbers must lie "
                                    f"{NUMBER_RANGE} in SI units too")
            omega = None
    else:
        omega = speed
    alpha = float(body["alpha"]) if "alpha" in body else 0.0
    if omega is None or "speed" in body or "accel" in body:
        return None
    return Driver(jname, link, omega, alpha, rpm, "R", (a, b))


def _default_gravity() -> Vec:
    """Gravity where a spec gives none, m/s² (the model's default)."""
    gx, gy = schema.SpecFile.model_fields["gravity"].default
    return (float(gx), float(gy))


def _cycle(top: dict, ck: _Checker) -> float:
    """``cycle``: the loads' period in crank degrees (the model's default where absent or
    refused)."""
    default = float(schema.SpecFile.model_fields["cycle"].default)
    if "cycle" not in top or ck.refused(("cycle",)):
        return default
    return float(top["cycle"])


def _default_sweep(cycle: float = 360.0) -> Sweep:
    """The sweep of a spec without ``sweep:`` (the model's defaults), degrees: one cycle
    (``stop`` defaults to ``cycle``)."""
    values = {key: float(field.default) for key, field in schema.Sweep.model_fields.items()}
    return Sweep(**{**values, "stop": cycle})


def _sweep(value: Any, ck: _Checker, cycle: float = 360.0) -> Sweep:
    """The crank angles analysed, degrees (the model's defaults where absent, ``stop``
    defaulting to one cycle; the defaults throughout when the model refused any of it)."""
    defaults = _default_sweep(cycle)
    if value is None or ck.refused(("sweep",)):
        return defaults
    vals = {key: float(value.get(key, getattr(defaults, key)))
            for key in ("start", "stop", "step")}
    if vals["stop"] <= vals["start"]:
        ck.error(("sweep", "stop"), f"must be greater than start ({vals['start']:g})")
        return defaults
    if (vals["stop"] - vals["start"]) / vals["step"] > MAX_SWEEP_ANGLES:
        ck.error(("sweep", "step"), f"gives more than {MAX_SWEEP_ANGLES} angles; use a larger "
                                    "step")
        return defaults
    sweep = Sweep(**vals)
    if len(sweep.angles()) == 0:   # stop - start below 1e-9 deg reads as "zero whole turns"
        ck.error(("sweep", "stop"), f"gives no crank angle: stop must exceed start "
                                    f"({vals['start']:g}) by more than 1e-9 degrees")
        return defaults
    return sweep


#: bidirectional controls: embeddings, overrides, isolates and marks (LRE ... RLO, LRI ... PDI,
#: LRM, RLM, ALM)
_BIDI_CONTROL = re.compile("[\u202a-\u202e\u2066-\u2069\u200e\u200f\u061c]")


def _key_names(node: Any, path: tuple, ck: _Checker) -> None:
    """Every mapping key of the document is a keyword or a name (of a link, point, joint,
    material, ...): none may hold a bidirectional control character."""
    if isinstance(node, dict):
        for key, value in node.items():
            if isinstance(key, str):
                ck.no_bidi_control(key, path + (key,))
            _key_names(value, path + (key,), ck)
    elif isinstance(node, list):
        for i, value in enumerate(node):
            _key_names(value, path + (i,), ck)


def _angle_list(value: Any, path: tuple, ck: _Checker) -> tuple[float, ...]:
    if not isinstance(value, list) or not value:
        ck.error(path, f"must be a list of crank angles in degrees, got {_show(value)}")
        return (0.0,)
    out = [ck.number(v, path + (i,)) for i, v in enumerate(value)]
    for i, v in enumerate(out):
        if v is not None and v in out[:i]:
            ck.error(path + (i,), f"{_show(value[i])} is given twice (also {path[-1]}"
                                  f"[{out.index(v)}]); give each reference angle once")
    return tuple(v for v in out if v is not None) or (0.0,)


def _assembly(value: Any, ck: _Checker, links: list[Link], ls: float,
              unit: str) -> dict[str, Vec]:
    if value is None:
        return {}
    if not isinstance(value, dict):
        ck.error(("assembly",), f"must map point names to rough [x, y], got {_show(value)}")
        return {}
    out = {}
    for pname, pv in value.items():
        v = ck.point(pv, ("assembly", pname), scale=ls, unit=unit)
        if not any(pname in l.points for l in links):
            if pname not in ck.invalid_points:
                ck.error(("assembly", pname), f"'{pname}' is not a point of any moving link")
        elif v is not None:
            out[pname] = v
    return out


def _profile(value: Any, path: tuple, ck: _Checker) -> tuple[tuple[float, float], ...] | None:
    if not isinstance(value, list) or not value:
        ck.error(path, "must be a list of [crank_angle_deg, magnitude] pairs")
        return None
    pairs = [ck.vec2(item, path + (i,), "[crank_angle_deg, magnitude]")
             for i, item in enumerate(value)]
    if any(p is None for p in pairs):
        return None
    angles = [p[0] for p in pairs]
    if any(a < 0 or a >= 360 for a in angles):
        ck.error(path, "angles must lie in [0, 360)")
        return None
    if any(b <= a for a, b in zip(angles, angles[1:])):
        ck.error(path, "angles must be strictly increasing")
        return None
    return tuple(pairs)


def _loads(value: Any, ck: _Checker, links: dict[str, Link], joints: list[Joint] | None = None,
           ground: dict[str, Vec] | None = None, ls: float = 1.0, pins=()) -> list[Load]:
    if value is None:
        return []
    if not isinstance(value, list):
        ck.error(("loads",), "must be a list of loads ({type: force|moment, link, ...})")
        return []
    loads = []
    names: dict[str, int] = {}    # load name -> its index
    for i, item in enumerate(value):
        path = ("loads", i)
        if not isinstance(item, dict):
            ck.error(path, f"must be a mapping like {{type: force, link, point, value}}, "
                           f"got {_show(item)}")
            continue
        kind = ck.choice(item.get("type"), path + ("type",), LOAD_TYPES)
        if kind is None:
            continue
        if kind in ("spring", "damper", "torsion_spring"):
            load = _element(kind, item, i, path, ck, links, joints, ground, names, ls, pins)
            if load is not None:
                names[load.label] = i
                loads.append(load)
            continue
        req = LOAD_REQUIRED[kind]
        if ck.mapping(item, path, LOAD_KEYS[kind], required=req) is None or \
                any(k not in item for k in req):
            continue
        lname = ck.name(item["link"], path + ("link",))
        if lname is None:
            continue
        if lname not in links:
            if lname not in ck.invalid_links:
                ck.error(path + ("link",), f"unknown link '{lname}' (loads act on moving links: "
                                           f"{', '.join(links)})")
            continue
        point = None
        if kind == "force":
            point = ck.name(item["point"], path + ("point",))
            if point is None:
                continue
            if point not in links[lname].points:
                ck.error(path + ("point",), f"'{point}' is not a point of link '{lname}'")
                continue
        has_value, has_profile = "value" in item, "profile" in item
        if has_value == has_profile:
            what = "'value', or 'direction' with 'profile'" if kind == "force" else \
                "'value' or 'profile'"
            ck.error(path, f"give exactly one of {what}")
            continue
        value_, direction, profile = None, None, None
        if kind == "force":
            if has_value:
                value_ = ck.vec2(item["value"], path + ("value",), "[Fx, Fy] in N")
                if "direction" in item:
                    ck.error(path + ("direction",), "goes with 'profile', not with 'value'")
            else:
                if "direction" not in item:
                    ck.error(path, "a force 'profile' needs a 'direction' [dx, dy]")
                    continue
                d = ck.vec2(item["direction"], path + ("direction",), "[dx, dy]")
                if d is not None and math.hypot(*d) == 0:
                    ck.error(path + ("direction",), "must not be the zero vector")
                    d = None
                direction = None if d is None else (d[0] / math.hypot(*d), d[1] / math.hypot(*d))
                profile = _profile(item["profile"], path + ("profile",), ck)
        else:
            if has_value:
                value_ = ck.number(item["value"], path + ("value",))
            else:
                profile = _profile(item["profile"], path + ("profile",), ck)
        oppose = None
        if "oppose" in item:
            oppose = ck.choice(item["oppose"], path + ("oppose",), OPPOSE[kind])
        if (has_value and value_ is None) or (has_profile and profile is None) or \
                ("oppose" in item and oppose is None):
            continue
        if kind == "force" and has_profile and direction is None:
            continue
        label = ck.name(item["name"], path + ("name",)) if "name" in item else f"load {i + 1}"
        if label is not None and label in names:
            ck.error(path + ("name",), f"'{label}' is the name of loads[{names[label]}] too: "
                                       "load names must differ (they label the torque "
                                       "breakdown)")
            label = None
        reacts = (ck.choice(item["reacts_on"], path + ("reacts_on",), REACTS_ON)
                  if "reacts_on" in item else None)
        if label is None or ("reacts_on" in item and reacts is None):
            continue
        names[label] = i
        loads.append(Load(kind, lname, i, point, value_, direction, profile, oppose,
                          item.get("name"), reacts))
    return loads


def _element(kind: str, item: dict, i: int, path: tuple, ck: _Checker, links: dict[str, Link],
             joints: list[Joint] | None, ground: dict[str, Vec] | None, names: dict[str, int],
             ls: float, pins=()) -> Load | None:
    """A spring, damper or torsion spring: machine elements whose force follows from the
    kinematics (docs/spec.md, section 8)."""
    required = LOAD_REQUIRED[kind]
    body = ck.mapping(item, path, LOAD_KEYS[kind], required=required)
    if body is None or any(k not in body for k in required):
        return None
    label = ck.name(item["name"], path + ("name",)) if "name" in item else f"load {i + 1}"
    if label is not None and label in names:
        ck.error(path + ("name",), f"'{label}' is the name of loads[{names[label]}] too: load "
                                   "names must differ (they label the torque breakdown)")
        return None
    if kind == "torsion_spring":
        jname = ck.name(body["joint"], path + ("joint",))
        joint = next((j for j in joints or () if j.name == jname), None)
        if jname is not None and joint is None and joints is not None:
            if jname not in ck.invalid_joints:
                ck.error(path + ("joint",), _pin_hint(jname, pins, "torsion spring")
                         or f"unknown joint '{jname}'")
            return None
        if joint is not None and joint.type != "R":
            ck.error(path + ("joint",), f"a torsion spring sits at an R joint; '{jname}' is a "
                                        "slider (T)")
            return None
        k = ck.number(body["stiffness"], path + ("stiffness",), positive=True)
        a0 = ck.number(body["free_angle"], path + ("free_angle",))
        if joint is None or k is None or a0 is None or label is None:
            return None
        moving = joint.links[1] if joint.links[1] != GROUND else joint.links[0]
        return Load(kind, moving, i, name=item.get("name"), joint=jname, stiffness=k,
                    free_angle=a0)
    ends = body["between"]
    where = path + ("between",)
    if not (isinstance(ends, list) and len(ends) == 2 and all(
            isinstance(e, list) and len(e) == 2 for e in ends)):
        ck.error(where, f"must be two ends [[link, point], [link, point]], got {_show(ends)}")
        return None
    pairs = []
    for e, (lname, pname) in enumerate(ends):
        lname = ck.name(lname, where + (e, 0))
        pname = ck.name(pname, where + (e, 1))
        if lname is None or pname is None:
            return None
        if lname != GROUND and lname not in links:
            if lname not in ck.invalid_links:
                ck.error(where + (e, 0), f"unknown link '{lname}' (ground or a moving link: "
                                         f"{', '.join(links)})")
            return None
        pts = (ground or {}) if lname == GROUND else links[lname].points
        if pname not in pts:
            ck.error(where + (e, 1), f"'{pname}' is not a point of "
                                     f"{'the ground' if lname == GROUND else repr(lname)}")
            return None
        pairs.append((lname, pname))
    if pairs[0][0] == pairs[1][0]:
        ck.error(where, f"both ends are on '{pairs[0][0]}': a {kind} between two points of one "
                        "link does nothing")
        return None
    moving = pairs[0][0] if pairs[0][0] != GROUND else pairs[1][0]
    if kind == "spring":
        k = ck.number(body["stiffness"], path + ("stiffness",), positive=True)
        free = ck.number(body["free_length"], path + ("free_length",), scale=ls)
        if k is None or free is None or free < 0 or label is None:
            if free is not None and free < 0:
                ck.error(path + ("free_length",), "must not be negative")
            return None
        return Load(kind, moving, i, name=item.get("name"), between=tuple(pairs), stiffness=k,
                    free_length=free)
    c = ck.number(body["damping"], path + ("damping",), positive=True)
    if c is None or label is None:
        return None
    return Load(kind, moving, i, name=item.get("name"), between=tuple(pairs), damping=c)


def _expect(value: Any, ck: _Checker, links: list[Link], joints: list[Joint] | None,
            src_lines: Source, driver: Driver | None = None, pins=()) -> list[Expectation]:
    """What the results must reproduce, SI; the entries' types and ranges are the models',
    the loader checks what needs the mechanism (the quantity, its unit, the angle's
    presence)."""
    if not isinstance(value, list):
        return []               # absent, or the models say what is wrong
    out = []
    joint_types = {j.name: j.type for j in (joints or [])}
    for i, item in enumerate(value):
        path = ("expect", i)
        body = item if isinstance(item, dict) else {}
        if any(k not in body for k in EXPECT_REQUIRED):
            continue
        quantity = body["quantity"]
        problem = _quantity_problem(quantity, links, joint_types, joints is not None, ck,
                                    driver, pins)
        if problem:
            ck.error(path + ("quantity",), problem)
            continue
        cycle = isinstance(quantity, str) and is_cycle(quantity)
        if cycle and "angle" in body:
            ck.error(path + ("angle",), f"'{body['quantity']}' is a cycle quantity (one value "
                                        "per turn): give it without an angle")
            continue
        if not cycle and "angle" not in body:
            ck.error(path, "missing required key 'angle' (only cycle quantities such as "
                           "cycle.torque.rms have none)")
            continue
        unit, scale = (_expect_unit(body["unit"], quantity, path + ("unit",), ck, joint_types)
                       if "unit" in body else (None, 1.0))
        if scale is None or any(ck.refused(path + (key,)) for key in ("angle", "value", "tol")):
            continue
        angle = float(body["angle"]) if not cycle else None
        target = ck.si(body["value"], path + ("value",), scale=scale, unit=unit or "")
        tol = (ck.si(body["tol"], path + ("tol",), scale=scale, unit=unit or "")
               if "tol" in body else None)
        if (angle is None and not cycle) or target is None or ("tol" in body and tol is None):
            continue
        if tol is None:       # 1e-4 of the value as written (at least 1e-4 in its unit)
            tol = 1e-4 * max(1.0, abs(target / scale)) * scale
        out.append(Expectation(angle, quantity, target, tol, src_lines.line(path), unit,
                               scale))
    return out


def _expect_unit(value: Any, quantity: str, path: tuple, ck: _Checker,
                 joint_types: dict[str, str] | None = None) -> tuple[str | None, float | None]:
    """The unit an ``expect`` entry is written in and its size in SI; (None, None) reported
    when it is not a unit of the quantity's kind."""
    parts = split_quantity(quantity)
    si = (joint_unit(parts[2], (joint_types or {}).get(parts[1], "R"))
          if parts and parts[0] == "joint" else unit_of(quantity))
    table = EXPECT_UNITS.get(si or "", {si: 1.0} if si else {})
    if not isinstance(value, str) or value not in table:
        shown = ", ".join(table) if table else "none"
        ck.error(path, f"must be a unit of {quantity} ({si or 'no unit'}): {shown}; got "
                       f"{_show(value)}")
        return None, None
    return value, float(table[value])


def _quantity_problem(q: Any, links: list[Link], joint_types: dict[str, str],
                      joints_known: bool, ck: _Checker,
                      driver: Driver | None = None, pins=()) -> str | None:
    """None if ``q`` names something, else a message saying what it should look like."""
    usage = ("expected driver.torque, joint.J.fx|fy|f|angle|moment|px|py|f_max|f_mean|"
             "f_equivalent|life_h, point.P.x|y|vx|vy|ax|ay|v|a, link.L.angle|omega|alpha, "
             "transmission_angle, or a cycle quantity (cycle.torque.rms, "
             "balance.counterweight.mr, ...; see docs/spec.md)")
    if not isinstance(q, str):
        return f"must be a quantity name ({usage}), got {_show(q)}"
    parts = split_quantity(q)
    if q in MECHANISM_UNITS:
        return None
    if q in ("driver.torque", "driver.force") or q in CYCLE_UNITS:
        if driver is not None and q.startswith("driver.") and q != driver.quantity:
            article = "an" if driver.kind == "R" else "a"
            return (f"'{q}': the driver joint '{driver.joint}' is {article} {driver.kind} "
                    f"joint, whose effort is {driver.quantity}")
        return None
    if q.startswith(("cycle.", "balance.")):
        near = difflib.get_close_matches(q, list(CYCLE_UNITS), n=1)
        hint = f"; did you mean '{near[0]}'?" if near else ""
        return f"'{q}' is not a cycle quantity{hint}"
    if parts is None:
        return f"'{q}' names nothing: {usage}"
    kind, name, attr = parts
    if kind == "member":
        return _member_quantity_problem(q, name, attr, links, ck)
    if kind == "joint":
        return _joint_quantity_problem(q, name, attr, joint_types, joints_known, ck, pins)
    if kind == "point":
        if not any(name in l.points for l in links):
            if name in ck.invalid_points:
                return None
            return f"'{q}': no moving link has a point named '{name}'"
        if attr not in POINT_QUANTITIES:
            return f"'{q}': a point has {', '.join(POINT_QUANTITIES)}"
        return None
    if kind == "link":
        if name not in {l.name for l in links}:
            if name in ck.invalid_links:
                return None
            return f"'{q}': no link named '{name}' (links: {', '.join(l.name for l in links)})"
        if attr not in LINK_QUANTITIES:
            return f"'{q}': a link has {', '.join(LINK_QUANTITIES)}"
        return None
    return f"'{q}' names nothing: {usage}"


def _member_quantity_problem(q: str, name: str, attr: str, links: list[Link],
                             ck: _Checker) -> str | None:
    """None if ``q`` (``member.<L>.<attr>`` or ``member.<L>.<P_Q>.<attr>``) names a
    member's quantity, else what is wrong."""
    lname, _, member = name.partition(".")
    link = next((l for l in links if l.name == lname), None)
    if link is None:
        if lname in ck.invalid_links:
            return None
        return f"'{q}': no link named '{lname}' (links: {', '.join(l.name for l in links)})"
    if link.strength is None:
        return f"'{q}': link '{lname}' has no 'section' (and 'material'): it has no members"
    names = [f"{p}_{x}" for p, x in link.strength.members]
    several = len(names) > 1
    if several and member not in names:
        return (f"'{q}': link '{lname}' has several members; name one: "
                + ", ".join(f"member.{lname}.{m}.{attr}" for m in names))
    if not several and member:
        return f"'{q}': link '{lname}' has one member: member.{lname}.{attr}"
    if attr not in MEMBER_UNITS:
        return f"'{q}': a member has {', '.join(MEMBER_UNITS)}"
    return None


def _joint_quantity_problem(q: str, name: str, attr: str, joint_types: dict[str, str],
                            joints_known: bool, ck: _Checker, pins) -> str | None:
    """None if ``q`` (``joint.<name>.<attr>``) names a joint's quantity, or what a pin's
    force on one link (``joint.J.on.<link>.fx``) names, else what is wrong."""
    if not joints_known:
        return None
    pin = next((p for p in pins if p.name == name), None)
    if pin is not None:
        names = ", ".join(f"joint.{name}.on.{x}.{attr}" for x in pin.links)
        return (f"'{q}': '{name}' is a pin joining {len(pin.links)} links; its force on each "
                f"is {names}")
    base, on, link = name.partition(".on.")
    pin = next((p for p in pins if p.name == base), None) if on else None
    if name in joint_types and not (pin is not None and link == pin.hub):
        allowed = (R_QUANTITIES if joint_types[name] == "R" else T_QUANTITIES) + \
            tuple(JOINT_CYCLE_UNITS)
        if attr not in allowed:
            return f"'{q}': a {joint_types[name]} joint has {', '.join(allowed)}"
        return None
    if pin is not None or (on and base in joint_types):
        links = pin.links if pin is not None else None
        if links is not None and link not in links:
            return f"'{q}': pin '{base}' joins {', '.join(links)}, not '{link}'"
        allowed = ON_QUANTITIES + (tuple(JOINT_CYCLE_UNITS) if pin is not None else ())
        if attr not in allowed:
            return f"'{q}': a pin's force on one link has {', '.join(allowed)}"
        return None
    if name in ck.invalid_joints or (on and base in ck.invalid_joints):
        return None
    return f"'{q}': no joint named '{name}' (joints: {', '.join(joint_types)})"


def _zero_length(ck: _Checker, links: list[Link], joints: list[Joint]) -> None:
    """A link whose pins (the points of its R joints) all coincide has zero length: it has no
    direction, so the dyad holding it has no solution, and a crank of zero length turns
    nothing. Pins may share a place as long as another pin of the link lies elsewhere (two
    joints at one place make a compound hinge)."""
    for link in links:
        pins = [j.point for j in joints if j.type == "R" and link.name in j.links]
        pins = list(dict.fromkeys(p for p in pins if p in link.points))
        if len(pins) < 2:
            continue
        first = link.points[pins[0]]
        if all(link.points[p] == first for p in pins[1:]):
            a, b = pins[0], pins[1]
            ck.error(("links", link.name, "points", b),
                     f"link '{link.name}' has zero length: its joint points '{a}' and '{b}' are "
                     "at the same place; a link's pins must be apart (did you mean another "
                     "coordinate?)")


def _structure(ck: _Checker, links: list[Link], joints: list[Joint]) -> None:
    """Mobility (Gruebler: M = 3 n - 2 j for one-freedom joints) and connectivity."""
    n, j = len(links), len(joints)
    mobility = 3 * n - 2 * j
    if mobility != 1:
        ck.error(("joints",), f"the mechanism has mobility {mobility} (Gruebler: 3 x {n} moving "
                              f"links - 2 x {j} joints); a single driver needs mobility 1")
    adjacency: dict[str, set[str]] = {GROUND: set(), **{l.name: set() for l in links}}
    for joint in joints:
        a, b = joint.links
        adjacency[a].add(b)
        adjacency[b].add(a)
    seen, todo = {GROUND}, [GROUND]
    while todo:
        for nxt in adjacency[todo.pop()]:
            if nxt not in seen:
                seen.add(nxt)
                todo.append(nxt)
    loose = [l.name for l in links if l.name not in seen]
    if loose:
        ck.error(("links", loose[0]), f"not connected to the rest of the mechanism: "
                                      f"{', '.join(loose)}")


def _report(value: Any, ck: _Checker, units: dict[str, str],
            whole_turn: bool) -> ReportSettings:
    """The ``report`` section: display units (lengths default to the spec's ``units.length``,
    the rest to SI), first-page metadata, ``animation`` (default: ``whole_turn``, the sweep is
    one whole turn of a crank) and ``dxf`` (docs/spec.md, section 16). Types and lengths are
    the models'; a key they refuse takes its default."""
    path = ("report",)
    body = value if isinstance(value, dict) else {}

    def given(key: tuple, default: Any) -> Any:
        where, node = path, body
        for part in key:
            where += (part,)
            node = node.get(part) if isinstance(node, dict) else None
        return default if node is None or ck.refused(where) else node

    shown = {"length": units.get("length", "m"), "force": "N", "moment": "N*m", "mass": "kg"}
    shown = {key: given(("units", key), default) for key, default in shown.items()}
    meta = {key: " ".join(str(given((key,), "")).split()) for key in REPORT_TEXT_KEYS}
    return ReportSettings(units=shown, **meta, animation=given(("animation",), whole_turn),
                          dxf=given(("dxf",), schema.Report.model_fields["dxf"].default))
