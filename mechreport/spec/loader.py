"""Load and validate a spec file (format version 1, documented in docs/spec.md).

Every problem of a file is collected and raised together as one ``SpecError``; each names the
file, line, key path and what was expected. Whatever the input, loading ends in a ``Spec`` or a
``SpecError``, quickly and in little memory: the reader (``yaml_source``) caps the file size
and the nesting depth and refuses aliases, tags and non-UTF-8 text.

The format (its keys, which are required, their types, enumerations and number ranges, and
what one mapping's values say together) is declared once, by the pydantic models of
:mod:`.schema`; they validate every file, and :func:`_shape_problem` turns each of their errors
into ``file:line: key.path: message`` in the house wording. What is left here is one pass over
the validated data (a part the models refused is left out of it, so that nothing is reported
twice): the references between names (a joint's links, a load's point), mobility, which cycle
quantities are defined, and the conversion to SI (:mod:`.types`).
"""
from __future__ import annotations

import difflib
import math
import os
import re
from dataclasses import replace
from pathlib import Path as FsPath
from typing import Any

from ..errors import Problem, SpecError
from ..quantities import (CYCLE_UNITS, DYNAMICS_INSTANT, JOINT_CYCLE_UNITS, MECHANISM_UNITS,
                          MEMBER_UNITS, is_cycle, is_member, joint_unit, unit_of,
                          split as split_quantity)
from ..units import EXPECT_UNITS, PRESSURE_UNITS, SPEC_UNITS, UNIT_TABLES, rpm_to_rad_s
import mechreport.spec.schema as schema   # the models (not `from . import`: spec/__init__)
from .schema import (MAX_STUDY_VARIANTS, NUMBER_MAX, NUMBER_MIN, _is_whole, keys_of,
                     required_of)
from .strength import strength_links
from .sheet_section import sheet_section
from .types import ReportSettings
from .types import (GROUND, BearingSpec, Design, Driver, Dynamics, Expectation, Friction, Joint,
                    Line, Link, Load, MotorCurve, Pin, Pressure, Shape, Spec, Study, Sweep,
                    Vary, Vec)
from .types import Bound, Optimize, TolVary, Tolerances
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

# What the post-validation pass reads of the models (the one place a key is declared).
SHAPE_KEYS = {"bar": keys_of(schema.Bar), "block": keys_of(schema.Block)}
DRIVER_REQUIRED = required_of(schema.Driver)
FRICTION_KEYS = {"R": keys_of(schema.RFriction), "T": keys_of(schema.TFriction)}
FRICTION_REQUIRED = {"R": required_of(schema.RFriction), "T": required_of(schema.TFriction)}
DYN_MOTOR_KEYS = schema.DYNAMICS_MOTOR_KINDS
EXPECT_REQUIRED = required_of(schema.Expectation)
REPORT_TEXT_KEYS = tuple(k for k in keys_of(schema.Report) if k not in ("units", "animation",
                                                                      "dxf", "html"))
STUDY_REQUIRED = required_of(schema.Study)
VARY_REQUIRED = required_of(schema.Vary)
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


def polar_point(r: float, angle: float) -> Vec:
    """The point at distance ``r`` and ``angle`` degrees from the x-axis (CCW). At a multiple
    of 90 degrees the zero coordinate is exactly 0 (cos 90 deg is 6e-17 in floating point)."""
    quarter = angle / 90.0
    if quarter == round(quarter):        # exact on the axes
        c, s = ((1.0, 0.0), (0.0, 1.0), (-1.0, 0.0), (0.0, -1.0))[int(round(quarter)) % 4]
    else:
        c, s = math.cos(math.radians(angle)), math.sin(math.radians(angle))
    return (r * c + 0.0, r * s + 0.0)


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
        self.shape = schema.shape_errors(data) if data is not None else []
        self.refused_paths = [schema.locate(tuple(e["loc"])).path for e in self.shape]

    def refused_here(self, path: tuple) -> bool:
        """Whether the models refused the value at ``path`` itself (or what holds it)."""
        return any(tuple(path[:len(p)]) == tuple(p) for p in self.refused_paths)

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

    def to_point(self, value: Any, path: tuple, scale: float, unit: str) -> Vec | None:
        """A point the models validated (``[x, y]`` or ``{r, angle}``, in the length unit) in
        SI; None (reported) when it leaves the range of numbers in SI units."""
        if isinstance(value, dict):
            r = self.si(value["r"], path + ("r",), scale=scale, unit=unit)
            return None if r is None else polar_point(r, float(value["angle"]))
        x = self.si(value[0], path + (0,), scale=scale, unit=unit)
        y = self.si(value[1], path + (1,), scale=scale, unit=unit)
        return None if x is None or y is None else (x, y)

    def no_bidi_control(self, name: str, path: tuple) -> None:
        """A mapping's key at ``path`` (a name of a link, point, joint ...) must not hold a
        bidirectional control character (:func:`.schema.bidi_problem`)."""
        problem = schema.bidi_problem(name)
        if problem is not None:
            self.error(path, problem)

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
    """Report every problem the models of :mod:`.schema` find in ``data`` at the line of its
    key path (each once), in the wording of :func:`_shape_problem`."""
    if data is None:
        return              # an empty file is reported as such
    if ck.shape is None:
        ck.validate(data)
    added: set[tuple[tuple, str]] = set()
    for error in ck.shape:
        found = _shape_problem(error)
        if found not in added:
            added.add(found)
            ck.error(*found)


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
    refusal = where.refusal(kind)
    if refusal is not None:
        return where.path, refusal.text.format(value=_show(value))
    if kind in ("union_tag_invalid", "union_tag_not_found"):
        return _tag_problem(where, value)
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
    items = value if isinstance(value, list) else [value]
    quote = (" (quote a name that looks like a number, true/false or null)"
             if "name" in what and any(x is None or isinstance(x, (bool, int, float))
                                       for x in items) else "")
    return f"must be {what}, got {_show(value)}{quote}"


def _range_problem(where: schema.Located, value: Any) -> str | None:
    """A number's problem: not a number, out of the range every number keeps, or out of the
    range of its key (greater than zero, 0 or more, at most some limit)."""
    low, high = where.constraint("ge"), where.constraint("le")
    positive = low is not None and low > 0 or where.marker(schema.ZeroOrPositive) is not None
    problem = _number_problem(value, positive=positive)
    if problem is not None:
        return problem
    if low == 0 and value < 0:
        return (f"must be a positive number, got {_show(value)}" if positive else
                f"must be 0 or more, got {_show(value)}")
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
    if not isinstance(data, dict):
        return None             # the models say what it must be
    top = data
    _key_names(top, (), ck)

    name = None if "name" not in top or ck.refused(("name",)) else top["name"]
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
                   length_scale, pins, units)
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
    dynamics = (_dynamics(top["dynamics"], ck, driver, sweep, units)
                if "dynamics" in top else None)
    expect = _expect(top.get("expect"), ck, links, joints, src_lines=ck.src, driver=driver,
                     pins=pins)
    design = (_design(top.get("design"), ck, joints, pins, units) if "design" in top
              else Design())
    report = (_report(top.get("report"), ck, units, sweep.whole_turn) if "report" in top
              else ReportSettings(animation=sweep.whole_turn))
    study = _study(top["study"], ck, top) if "study" in top else None
    tolerances = _tolerances(top["tolerances"], ck, top) if "tolerances" in top else None
    sheet, sheet_settings = sheet_section(top.get("sheet"), ck.refused(("sheet",)),
                                          lambda key, where: _key_path(key, where, ck, top),
                                          ck.src.line)

    if links and joints:
        _zero_length(ck, links, joints)
    if links and joints is not None and link_names and not (ck.invalid_links or
                                                            ck.invalid_joints):
        _structure(ck, links, joints)

    if ck.problems or ck.shape or name is None or driver is None or joints is None:
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
                expect=tuple(expect), sheet=sheet, units=_written_units(units), design=design,
                report=report, study=study, pins=tuple(pins), friction=friction,
                dynamics=dynamics, tolerances=tolerances,
                sheet_settings=sheet_settings)
    _cycle_requests(spec, ck)
    if study is not None:
        _study_requests(spec, ck)
    if tolerances is not None:
        _study_requests(spec, ck, "tolerances", tolerances.keep)
    if "optimize" in top:
        spec = replace(spec, optimize=_optimize(top["optimize"], ck, top, spec))
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
        if ck.refused(where):
            continue            # the models say what is wrong
        entry = body            # an R joint's keys, or a T joint's: its type decides
        for key in entry:
            if key not in FRICTION_KEYS[jtype]:
                ck.error(where + (key,), _unknown_key(key, FRICTION_KEYS[jtype]))
        missing = [k for k in FRICTION_REQUIRED[jtype] if k not in entry]
        for key in missing:
            ck.error(where, f"missing required key '{key}'")
        if missing or any(k not in FRICTION_KEYS[jtype] for k in entry):
            continue
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


def _dynamics(value: Any, ck: _Checker, driver: Driver | None, sweep: Sweep,
              units: dict[str, str]) -> Dynamics | None:
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
    motor = (_dynamics_motor(body["motor"], path + ("motor",), ck, _si(units, "moment"))
             if "motor" in body else None)
    if not ok or (motor is None and "motor" in body) or ck.refused(path):
        return None
    start = body.get("start") or {}
    until = body.get("until")
    fly = body.get("flywheel", 0.0)
    geared = (float(fly["inertia"]), float(fly["ratio"])) if isinstance(fly, dict) else None
    flywheel = ck.si(geared[1] ** 2 * geared[0] if geared else fly, path + ("flywheel",),
                     scale=_si(units, "inertia"), unit=units["inertia"])
    if flywheel is None:
        return None
    return Dynamics(motor, flywheel,
                    float(start.get("angle", sweep.start)), float(start.get("rpm", 0.0)),
                    None if until in (None, "steady") else float(until),
                    None if body.get("output_step") is None else float(body["output_step"]),
                    None if body.get("mean_rpm") is None else float(body["mean_rpm"]),
                    geared)


def _dynamics_motor(value: Any, path: tuple, ck: _Checker,
                    ms: float = 1.0) -> MotorCurve | None:
    """The motor of ``dynamics:``: exactly one of ``torque``, ``curve``, ``linear`` (torques
    in the spec's moment unit, ``ms`` N·m each), with its gearing (``ratio``,
    ``efficiency``)."""
    if ck.refused(path):
        return None             # the models say what is wrong
    body = value
    kind = next(k for k in DYN_MOTOR_KEYS if k in body)
    gear = {k: float(body[k]) for k in ("ratio", "efficiency") if k in body}
    if kind == "torque":
        return MotorCurve(constant=float(body["torque"]) * ms, **gear)
    if kind == "linear":
        return MotorCurve(stall_torque=float(body["linear"]["stall_torque"]) * ms,
                          no_load_rpm=float(body["linear"]["no_load_rpm"]), **gear)
    points = [(float(a), float(b) * ms) for a, b in body["curve"]]
    for i in range(1, len(points)):
        if not points[i][0] > points[i - 1][0]:
            ck.error(path + ("curve", i, 0), f"the speeds must increase: {points[i][0]:g} rpm "
                                             f"follows {points[i - 1][0]:g} rpm")
            return None
    return MotorCurve(curve=tuple(points), **gear)


def _design(value: Any, ck: _Checker, joints: list[Joint] | None, pins=(),
            units: dict[str, str] | None = None) -> Design:
    """The design review's inputs in SI (forces and torques written in the spec's units; their
    types and ranges are the models'; a part they refuse is left out); a bearing must name a
    joint."""
    path = ("design",)
    body = value if isinstance(value, dict) else {}
    units = units or {key: f.default for key, f in schema.Units.model_fields.items()}

    def si(model, key: str, x: Any) -> float:
        kind = schema.unit_kind(model, key)
        return float(x) * (_si(units, kind) if kind else 1.0)

    def numbers(key: str, model) -> dict[str, float]:
        raw = body.get(key)
        if not isinstance(raw, dict) or ck.refused(path + (key,)):
            return {}
        return {k: si(model, k, raw[k]) for k in keys_of(model) if k in raw}

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
            bearings[jname] = BearingSpec(si(schema.Bearing, "rating", item["rating"]),
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
NOT_VARIED = ("mechreport", "study", "expect", "report", "tolerances", "optimize")


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
            ck.error(where + ("key",), f"'{body['key']}' is varied by {format_path(path)}[{seen[leaf]}] "
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


def _study_requests(spec: Spec, ck: _Checker, section: str = "study",
                    keep: tuple[str, ...] | None = None) -> None:
    """A study (or the ``section`` keeping ``keep``: ``tolerances``) tabulates cycle
    quantities: :func:`_kept_requests` of its ``keep``."""
    keep = spec.study.keep if keep is None else keep
    what = "a study tabulates" if section == "study" else f"{section} keeps"
    _kept_requests(spec, ck, [((section, "keep", i), q) for i, q in enumerate(keep)],
                   (section,), what)


# ---------------------------------------------------------------------------- tolerances

def _tolerances(value: Any, ck: _Checker, top: dict) -> Tolerances | None:
    """The ``tolerances`` section (docs/spec.md, section 21): the models check its shape;
    each key path must lead to a number of this spec (as a study's), each once; values stay
    in the spec's own units, each leaf's distribution resolved about the spec's value."""
    path = ("tolerances",)
    body = value if isinstance(value, dict) else {}
    if not isinstance(body.get("vary"), list):
        return None             # the models say what is wrong
    model = schema.Tolerances.model_fields
    out, seen = [], {}
    for i, item in enumerate(body["vary"]):
        where = path + ("vary", i)
        if not isinstance(item, dict) or not isinstance(item.get("key"), str) \
                or ck.refused(where + ("key",)):
            continue            # the models say what is wrong
        leaf = _key_path(item["key"], where + ("key",), ck, top)
        if leaf is None:
            continue
        if leaf in seen:
            ck.error(where + ("key",), f"'{item['key']}' is varied by tolerances.vary"
                                       f"[{seen[leaf]}] too: give each key once")
            continue
        seen[leaf] = i
        if not ck.refused(where):
            out.append(_tol_vary(item, leaf, _leaf_value(top, leaf), ck.src.line(where)))
    keep = None if ck.refused(path + ("keep",)) or "keep" not in body else _keep(
        body["keep"], path + ("keep",), ck)
    if ck.refused(path) or len(out) < len(body["vary"]) or keep is None:
        return None
    return Tolerances(tuple(out), keep, int(body.get("count", model["count"].default)),
                      body.get("sample", model["sample"].default),
                      int(body.get("seed", model["seed"].default)), ck.src.line(path))


def _leaf_value(top: dict, leaf: tuple) -> float:
    node: Any = top
    for part in leaf:
        node = node[part]
    return float(node)


def _tol_vary(item: dict, leaf: tuple, nominal: float, line: int | None) -> TolVary:
    """One ``tolerances.vary`` entry (its shape checked by the models) as a TolVary."""
    if "sigma" in item:
        s = float(item["sigma"])
        return TolVary(item["key"], leaf, nominal, "normal", nominal - 3 * s, nominal + 3 * s,
                       nominal, s, "sigma", line)
    if "tol" in item:
        low, high, given = nominal - float(item["tol"]), nominal + float(item["tol"]), "tol"
    else:
        a, b = float(item["from"]), float(item["to"])
        low, high, given = min(a, b), max(a, b), "range"
    dist = item.get("dist", "uniform")
    return TolVary(item["key"], leaf, nominal, dist, low, high, (low + high) / 2,
                   (high - low) / 6 if dist == "normal" else 0.0, given, line)


def _optimize(value: Any, ck: _Checker, top: dict, spec: Spec) -> Optimize | None:
    """The ``optimize`` section (format 1.2): its key paths checked as ``study.vary``'s, its
    quantities as ``study.keep``'s, its bounds converted to SI (``unit``); values of ``vary``
    kept as written (the spec's own units). None (reported) when it is not valid."""
    path = ("optimize",)
    if not isinstance(value, dict) or ck.refused(path) or "vary" not in value:
        return None             # the models say what is wrong
    vary = _vary(value["vary"], path + ("vary",), ck, top, "random")
    for i, v in enumerate(vary or ()):
        if v.path[0] == "design":      # the verdicts are the constraints: never relaxed
            ck.error(path + ("vary", i, "key"), f"'{v.key}': an optimisation varies the "
                                                "mechanism, not the limits it is judged by")
            vary = None
        elif v.path[0] in ("sweep", "cycle"):   # the angles judged: a design never passes
            ck.error(path + ("vary", i, "key"), f"'{v.key}': an optimisation varies the "
                                                "mechanism, not the angles it is judged at "
                                                "(sweep and cycle stay as written)")
            vary = None
    objective = value.get("minimize", value.get("maximize"))
    bounds = []
    for i, body in enumerate(value.get("subject_to") or ()):
        where = path + ("subject_to", i)
        unit, scale = (_expect_unit(body["unit"], body["quantity"], where + ("unit",), ck)
                       if "unit" in body else (None, 1.0))
        if scale is None:
            continue
        low, high = ((None if body.get(k) is None else
                      ck.si(body[k], where + (k,), scale=scale, unit=unit or ""))
                     for k in ("min", "max"))
        bounds.append(Bound(body["quantity"], low, high, unit, ck.src.line(where)))
    if vary is None or not isinstance(objective, str) or ck.problems:
        return None
    where = {"minimize" if "minimize" in value else "maximize": objective}
    for i, b in enumerate(bounds):
        where[("subject_to", i, "quantity")] = b.quantity
    _kept_requests(spec, ck, [(path + ((k,) if isinstance(k, str) else k), q)
                              for k, q in where.items()], path, "an optimisation reads")
    if ck.problems:
        return None
    default = schema.Optimize.model_fields
    return Optimize(vary, objective, "maximize" in value, tuple(bounds),
                    int(value.get("budget", default["budget"].default)),
                    int(value.get("seed", default["seed"].default)), ck.src.line(path))


def _kept_requests(spec: Spec, ck: _Checker, quantities: list[tuple[tuple, str]],
                   section: tuple, what: str) -> None:
    """Cycle quantities (each with its key path) that a ``section`` reads ("``what``
    cycle quantities": "a study tabulates") must be defined for the spec, name a joint of
    the mechanism and have the design inputs they need."""
    why = spec.cycle_problem()
    if why is not None and not (all(is_member(q) for _, q in quantities)
                                and cycle_design(spec.design).empty):
        ck.error(section, f"{what} cycle quantities, which are undefined here: {why}")
        return
    joints = set(spec.reported_reactions())
    for where, q in quantities:
        kind, name, attr = split_quantity(q) or ("", "", "")
        if kind == "member":
            problem = _member_quantity_problem(q, name, attr, list(spec.links), ck)
            if problem:
                ck.error(where, problem)
            continue
        if kind == "joint" and name not in joints:
            ck.error(where, f"'{q}': no joint named '{name}' (joints: "
                            f"{', '.join(sorted(joints))})")
            continue
        need = _cycle_need(spec, q)
        if need:
            ck.error(where, need)


def _units(value: Any, ck: _Checker) -> tuple[float, float, dict[str, str]]:
    """The factors of the spec's length and mass units to m and kg, and the names of all its
    units (length, mass, force, moment, inertia: the model's defaults where absent or
    refused)."""
    given = value if isinstance(value, dict) else {}
    names = {key: (given[key] if key in given and not ck.refused(("units", key))
                   else field.default)
             for key, field in schema.Units.model_fields.items()}
    return LENGTH_UNITS[names["length"]], MASS_UNITS[names["mass"]], names


def _si(units: dict[str, str], kind: str) -> float:
    """The size in SI of the spec's unit of ``kind`` (force, moment, inertia, ...)."""
    return UNIT_TABLES[kind][units[kind]]


#: the units every spec has in Spec.units; the others only where they are not SI
_ALWAYS_SHOWN = ("length", "mass")


def _written_units(units: dict[str, str]) -> dict[str, str]:
    """``Spec.units``: the length and mass units, and the force, moment and inertia units
    where the spec writes them in other than SI."""
    return {key: name for key, name in units.items()
            if key in _ALWAYS_SHOWN or name != schema.Units.model_fields[key].default}


def _ground(value: Any, ck: _Checker, s: float, unit: str) -> dict[str, Vec]:
    """The ground points, SI (their shape is the models'; a refused point is left out, and
    later checks do not report it again as missing)."""
    if not isinstance(value, dict):
        return {}
    out = {}
    for pname, pvalue in value.items():
        v = None if ck.refused(("ground", pname)) else ck.to_point(pvalue, ("ground", pname),
                                                                     s, unit)
        if v is not None:
            out[pname] = v
        else:
            ck.invalid_points.add(pname)
    return out


def _links(value: Any, ck: _Checker, ls: float, ms: float, units: dict[str, str]) -> list[Link]:
    """The moving links, SI (their shape is the models'); a link whose points or mass
    properties the models refused is left out, and its name and points are not reported
    again where they are used."""
    if not isinstance(value, dict):
        return []
    links = []
    for number, (lname, body) in enumerate(value.items(), start=1):
        path = ("links", lname)
        if lname == GROUND:
            ck.error(path, "'ground' is the reserved name of the frame; name moving links otherwise")
            continue
        link = (_link(lname, number, body, path, ck, ls, ms, units)
                if isinstance(body, dict) and not any(ck.refused(path + (key,))
                                                      for key in LINK_MASS_KEYS) else None)
        if link is not None:
            links.append(link)
        else:
            ck.invalid_links.add(lname)
            raw = body.get("points") if isinstance(body, dict) else None
            ck.invalid_points.update(raw if isinstance(raw, dict) else ())
    return links


#: the keys of a link that make its kinematic and mass model (the rest: its strength)
LINK_MASS_KEYS = ("points", "mass", "density", "com", "inertia", "shape")


def _link(lname: str, number: int, body: dict, path: tuple, ck: _Checker,
          ls: float, ms: float, units: dict[str, str]) -> Link | None:
    """A link the models validated, SI: its mass, centre of mass and inertia as given, or
    from its ``density`` and ``shape``."""
    lu, mu = units["length"], units["mass"]
    points: dict[str, Vec] = {}
    points_ok = True
    for pname, pv in body["points"].items():
        v = ck.to_point(pv, path + ("points", pname), ls, lu)
        if v is not None:
            points[pname] = v
        else:
            points_ok = False
    shape = _shape(body["shape"], path + ("shape",), ck, ls, lu) if "shape" in body else None
    massless = "mass" in body and body["mass"] == 0
    mass = (ck.si(body["mass"], path + ("mass",), scale=ms, unit=mu)
            if "mass" in body and not massless else 0.0 if massless else None)
    density = float(body["density"]) if "density" in body else None
    com = ck.to_point(body["com"], path + ("com",), ls, lu) if "com" in body else None
    point_mass = "inertia" in body and body["inertia"] == 0
    inertia = (0.0 if point_mass else
               ck.si(body["inertia"], path + ("inertia",), scale=_si(units, "inertia"),
                     unit=units["inertia"]) if "inertia" in body else None)
    bad = any(k in body and v is None for k, v in
              (("shape", shape), ("mass", mass), ("com", com), ("inertia", inertia))) \
        or not points_ok
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


def _shape(value: dict, path: tuple, ck: _Checker, ls: float, unit: str) -> Shape | None:
    """A shape the models validated (``{bar: ...}`` or ``{block: ...}``), sizes in SI."""
    kind, dims = next(iter(value.items()))
    keys = SHAPE_KEYS[kind]
    sizes = [ck.si(dims[k], path + (kind, k), scale=ls, unit=unit) for k in keys]
    if any(v is None for v in sizes):
        return None
    return Shape(kind, sizes[0], sizes[1], sizes[2])


def _link_points(lname: str, ground: dict[str, Vec], links: dict[str, Link]) -> dict[str, Vec]:
    return ground if lname == GROUND else links[lname].points


def _joints(value: Any, ck: _Checker, ground: dict[str, Vec], links: dict[str, Link],
            ls: float, unit: str) -> tuple[list[Joint] | None, list[Pin]]:
    """The joints as the methods solve them (a pin joining several links becomes a two-link
    joint from its hub to each other link, see :class:`Pin`) and those pins. Their shape is
    the models'; here: the links and points they name exist."""
    if value is _ABSENT:
        return None, []
    if not isinstance(value, dict) or ck.refused(("joints",)) and not value:
        return None, []
    joints: list[Joint] = []
    pins: list[Pin] = []
    for jname, body in value.items():
        path = ("joints", jname)
        if not isinstance(body, dict) or ck.refused_here(path) or any(
                ck.refused(path + (key,)) for key in ("type", "links", "point", "line")):
            continue            # the models say what is wrong
        jtype = body["type"]
        names = _joint_links(jname, body["links"], path + ("links",), ck, links)
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


def _joint_links(jname: str, names: list[str], path: tuple, ck: _Checker,
                 links: dict[str, Link]) -> list[str] | None:
    """The links a joint joins (two for a T joint, two or more for an R joint: the models'),
    each known and none twice (None after reporting what is wrong)."""
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
    """A T joint the models validated, SI: its point is the slider's, a line through a named
    point passes through one of the guide's."""
    guide, slider = pair
    point = body["point"]
    if point not in _link_points(slider, ground, links):
        ck.error(path + ("point",), f"'{point}' is not a point of the slider '{slider}' "
                                    "(the second link of a T joint slides on the first)")
        point = None
    line = body["line"]
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
        through = ck.to_point(through_raw, path + ("line", "through"), ls, unit)
    direction = _direction(line["direction"])
    if point is None or through is None:
        return None
    return Joint(jname, "T", (guide, slider), point, Line(through, direction, through_name))


def _direction(value: Any) -> Vec:
    """A direction the models validated (an angle in degrees, or a vector that is not zero)
    as a unit vector."""
    if isinstance(value, list):
        norm = math.hypot(*value)
        return (value[0] / norm, value[1] / norm)
    return (math.cos(math.radians(value)), math.sin(math.radians(value)))


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
    return Sweep(**{**values, "stop": cycle}, cycle=cycle)


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
    sweep = Sweep(**vals, cycle=cycle)
    if len(sweep.angles()) == 0:   # stop - start below 1e-9 deg reads as "zero whole turns"
        ck.error(("sweep", "stop"), f"gives no crank angle: stop must exceed start "
                                    f"({vals['start']:g}) by more than 1e-9 degrees")
        return defaults
    return sweep


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
    """The reference angles, degrees (their types are the models'); each given once."""
    if not isinstance(value, list) or not value or ck.refused(path):
        return (0.0,)
    out = [float(v) for v in value]
    for i, v in enumerate(out):
        if v in out[:i]:
            ck.error(path + (i,), f"{_show(value[i])} is given twice (also {path[-1]}"
                                  f"[{out.index(v)}]); give each reference angle once")
    return tuple(out)


def _assembly(value: Any, ck: _Checker, links: list[Link], ls: float,
              unit: str) -> dict[str, Vec]:
    """The assembly hints, SI: each names a point of a moving link."""
    if not isinstance(value, dict):
        return {}
    out = {}
    for pname, pv in value.items():
        v = None if ck.refused(("assembly", pname)) else ck.to_point(pv, ("assembly", pname),
                                                                       ls, unit)
        if not any(pname in l.points for l in links):
            if pname not in ck.invalid_points:
                ck.error(("assembly", pname), f"'{pname}' is not a point of any moving link")
        elif v is not None:
            out[pname] = v
    return out


def _loads(value: Any, ck: _Checker, links: dict[str, Link], joints: list[Joint] | None = None,
           ground: dict[str, Vec] | None = None, ls: float = 1.0, pins=(),
           units: dict[str, str] | None = None) -> list[Load]:
    """The loads, SI (their shape is the models'; forces in ``units.force``, moments in
    ``units.moment``); here: the links, points and joints they name exist, and their names
    differ."""
    units = units or {key: f.default for key, f in schema.Units.model_fields.items()}
    if not isinstance(value, list):
        return []
    loads = []
    names: dict[str, int] = {}    # load name -> its index
    for i, item in enumerate(value):
        path = ("loads", i)
        if not isinstance(item, dict) or ck.refused_here(path) or ck.refused(path + ("type",)):
            continue            # the models say what is wrong
        label = _load_label(item, i, path, ck, names)
        kind = item["type"]
        if kind == "pressure":
            load = _pressure(item, i, path, ck, links, ls)
        elif kind in ("spring", "damper", "torsion_spring"):
            load = _element(kind, item, i, path, ck, links, joints, ground, ls, pins, units)
        else:
            load = _load(kind, item, i, path, ck, links, units)
        if label is not None:
            names[label] = i
        if load is not None and label is not None and not ck.refused(path):
            loads.append(load)
    return loads


def _load_label(item: dict, i: int, path: tuple, ck: _Checker,
                names: dict[str, int]) -> str | None:
    """The label of a load (its ``name``, or "load N"); None (reported) when an earlier load
    has it."""
    if ck.refused(path + ("name",)):
        return None
    label = item["name"] if "name" in item else f"load {i + 1}"
    if label in names:
        ck.error(path + ("name",), f"'{label}' is the name of loads[{names[label]}] too: "
                                   "load names must differ (they label the torque breakdown)")
        return None
    return label


def _moving_link(lname: str, path: tuple, ck: _Checker, links: dict[str, Link]) -> bool:
    """Whether the load at ``path`` names a moving link (else said, unless the link itself
    was refused)."""
    if lname in links:
        return True
    if lname not in ck.invalid_links:
        ck.error(path + ("link",), f"unknown link '{lname}' (loads act on moving links: "
                                   f"{', '.join(links)})")
    return False


def _point_of(point: str, lname: str, path: tuple, ck: _Checker,
              links: dict[str, Link]) -> bool:
    """Whether the load at ``path`` acts at a point of its link (else said)."""
    if point in links[lname].points:
        return True
    ck.error(path + ("point",), f"'{point}' is not a point of link '{lname}'")
    return False


def _load(kind: str, item: dict, i: int, path: tuple, ck: _Checker,
          links: dict[str, Link], units: dict[str, str]) -> Load | None:
    """A force or a moment the models validated, on a moving link (at one of its points)."""
    if ck.refused(path + ("link",)) or not _moving_link(item["link"], path, ck, links):
        return None
    lname = item["link"]
    point = None
    if kind == "force":
        if ck.refused(path + ("point",)) or "point" not in item:
            return None                 # the models say what is missing or wrong
        point = item["point"]
        if not _point_of(point, lname, path, ck, links):
            return None
    if ck.refused(path):
        return None
    unit = units[kind]                  # a force's, or a moment's
    scale = _si(units, kind)
    value_ = item.get("value")
    if kind == "force" and value_ is not None:
        value_ = tuple(ck.si(x, path + ("value", k), scale=scale, unit=unit)
                       for k, x in enumerate(value_))
    elif value_ is not None:
        value_ = ck.si(value_, path + ("value",), scale=scale, unit=unit)
    direction = _direction(item["direction"]) if "direction" in item else None
    profile = (tuple((float(a), ck.si(b, path + ("profile", k, 1), scale=scale, unit=unit))
                     for k, (a, b) in enumerate(item["profile"])) if "profile" in item
               else None)
    values = ([] if value_ is None else list(value_) if isinstance(value_, tuple) else [value_])
    values += [b for _, b in profile or ()]
    if not values or any(x is None for x in values):
        return None             # (reported: out of range in SI)
    return Load(kind, lname, i, point, value_, direction, profile, item.get("oppose"),
                item.get("name"), item.get("reacts_on"), shift=float(item.get("shift", 0.0)))


def _pressure(item: dict, i: int, path: tuple, ck: _Checker, links: dict[str, Link],
              ls: float) -> Load | None:
    """A ``type: pressure`` load (format 1.2) as the force it is: the profile (p - ambient)
    x area [N] along the unit ``direction``, at ``point`` of ``link``, reacting on the frame
    (the cylinder head). The models checked its keys; here only what needs the rest of the
    spec (the link and its point) and the conversion to SI."""
    if ck.refused(path) or ck.refused(path + ("link",)) or ck.refused(path + ("point",)):
        return None
    lname, point = item["link"], item["point"]
    if not _moving_link(lname, path, ck, links) or not _point_of(point, lname, path, ck, links):
        return None
    model = schema.PressureLoad.model_fields
    unit = item.get("unit", model["unit"].default)
    ambient = float(item.get("ambient", model["ambient"].default))
    bore = ck.si(item["bore"], path + ("bore",), scale=ls) if "bore" in item else None
    area = (math.pi * bore ** 2 / 4.0 if bore is not None
            else ck.si(item["area"], path + ("area",), scale=ls * ls))
    if area is None or ("bore" in item and bore is None):
        return None
    pressure = Pressure(area, unit, PRESSURE_UNITS[unit], ambient,
                        tuple((float(a), float(p)) for a, p in item["profile"]), bore)
    force = tuple((a, pressure.pressure_pa(p) * area) for a, p in pressure.profile)
    if not all(_in_range(f) for _, f in force):
        ck.error(path + ("profile",), "gives forces (p - ambient) x area beyond the range of "
                                      f"numbers ({NUMBER_RANGE}) in SI units")
        return None
    return Load("force", lname, i, point, None, _direction(item["direction"]), force, None,
                item.get("name"), item.get("reacts_on", GROUND),
                shift=float(item.get("shift", 0.0)), pressure=pressure)


def _rate_unit(units: dict[str, str], ls: float) -> tuple[float, str]:
    """The size in SI (N/m) of the unit a spring's or damper's rate is written in, and its
    name: ``units.force`` per length unit (lbf/in, kip/in) when the spec's forces are not in
    newtons, else N/m whatever the length unit (as in format 1.1)."""
    if units["force"] == "N":
        return 1.0, "N/m"
    return _si(units, "force") / ls, f"{units['force']}/{units['length']}"


def _element(kind: str, item: dict, i: int, path: tuple, ck: _Checker, links: dict[str, Link],
             joints: list[Joint] | None, ground: dict[str, Vec] | None, ls: float,
             pins=(), units: dict[str, str] | None = None) -> Load | None:
    """A spring, damper or torsion spring the models validated: machine elements whose force
    follows from the kinematics (docs/spec.md, section 8); the joint or the points they join
    exist."""
    if kind == "torsion_spring":
        if ck.refused(path + ("joint",)):
            return None
        jname = item["joint"]
        joint = next((j for j in joints or () if j.name == jname), None)
        if joint is None and joints is not None:
            if jname not in ck.invalid_joints:
                ck.error(path + ("joint",), _pin_hint(jname, pins, "torsion spring")
                         or f"unknown joint '{jname}'")
            return None
        if joint is not None and joint.type != "R":
            ck.error(path + ("joint",), f"a torsion spring sits at an R joint; '{jname}' is a "
                                        "slider (T)")
            return None
        if joint is None or ck.refused(path):
            return None
        moving = joint.links[1] if joint.links[1] != GROUND else joint.links[0]
        k = ck.si(item["stiffness"], path + ("stiffness",), scale=_si(units, "moment"),
                  unit=units["moment"] + "/rad")
        if k is None:
            return None
        return Load(kind, moving, i, name=item.get("name"), joint=jname, stiffness=k,
                    free_angle=float(item["free_angle"]))
    where = path + ("between",)
    if ck.refused(where):
        return None
    pairs = []
    for e, (lname, pname) in enumerate(item["between"]):
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
    if ck.refused(path):
        return None
    moving = pairs[0][0] if pairs[0][0] != GROUND else pairs[1][0]
    rate, per = _rate_unit(units, ls)
    if kind == "spring":
        free = ck.si(item["free_length"], path + ("free_length",), scale=ls)
        k = ck.si(item["stiffness"], path + ("stiffness",), scale=rate, unit=per)
        if free is None or k is None:
            return None
        return Load(kind, moving, i, name=item.get("name"), between=tuple(pairs),
                    stiffness=k, free_length=free)
    c = ck.si(item["damping"], path + ("damping",), scale=rate, unit=per + "*s")
    if c is None:
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
    """The ``report`` section: display units (lengths, forces and moments default to the spec's
    own units, masses to kg, stresses to MPa: ``stress`` is there only when given), first-page metadata, ``animation`` (default: ``whole_turn``, the sweep is
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

    shown = {"length": units.get("length", "m"), "force": units.get("force", "N"),
             "moment": units.get("moment", "N*m"), "mass": "kg"}
    shown = {key: given(("units", key), default) for key, default in shown.items()}
    shown.update({key: given(("units", key), None) for key in ("stress", "pressure")
                  if given(("units", key), None) is not None})
    meta = {key: " ".join(str(given((key,), "")).split()) for key in REPORT_TEXT_KEYS}
    return ReportSettings(units=shown, **meta, animation=given(("animation",), whole_turn),
                          dxf=given(("dxf",), schema.Report.model_fields["dxf"].default),
                          html=given(("html",), schema.Report.model_fields["html"].default))
