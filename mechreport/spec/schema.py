"""The spec format's shape, declared once: pydantic models of a spec as written in YAML.

These models are the single source of the format's keys, their types, which of them are
required, their enumerations (joint and load types, unit names, ...) and the ranges a number
may take, as written in the spec (lengths in its ``units.length``, before any conversion).
From them come

- the key tables of the loader (``TOP_KEYS = keys_of(SpecFile)``, ...), so that a key is
  added to the format by one edit here;
- the validation of every file the loader reads (:func:`shape_errors`): the loader maps
  each pydantic error to ``file:line: key.path: message`` in the house wording (markers
  :class:`Wording`, :class:`Refusal`; errors of type :data:`WORDED` carry their message);
- the JSON Schema (:func:`json_schema`, ``mechreport schema``, ``docs/spec.schema.json``)
  with which an editor's YAML language server checks and completes a spec as it is typed;
  the field descriptions below are its hover texts (from docs/spec.md).

What one mapping's values say together is checked here too (a load's value or profile, a
profile's increasing angles, a grid's range count). What needs the mechanism (a joint naming a
link that exists, points present on both links, mobility, which cycle quantities are
defined, units converted to SI) is the loader's pass over the validated data. Every model forbids unknown keys.
Nothing here is built until it is used: the validator is built on the first validation, the
JSON Schema on request.
"""
import functools
import json
import re
import typing
import unicodedata
from dataclasses import dataclass
from typing import Annotated, Any, Literal, Optional, Union

from pydantic import (AfterValidator, BaseModel, BeforeValidator, ConfigDict, Discriminator,
                      Field, Tag, model_validator,
                      ValidationError)
from pydantic.fields import FieldInfo
from pydantic.json_schema import GenerateJsonSchema
from pydantic_core import InitErrorDetails, PydanticCustomError

from ..quantities import CYCLE_UNITS, JOINT_CYCLE_UNITS, MEMBER_UNITS
from ..units import EXPECT_UNITS, PRESSURE_UNITS, SPEC_UNITS, UNIT_TABLES
from .types import GROUND

__all__ = ["SpecFile", "LOAD_MODELS", "NUMBER_MAX", "NUMBER_MIN", "MAX_STUDY_VARIANTS",
           "MAX_SEED", "REPORT_TEXT_MAX", "SCHEMA_ID", "keys_of", "required_of", "choices_of",
           "literal_values", "shape_errors", "locate", "Located", "Wording", "Refusal", "ByKey",
           "ZeroOrPositive", "InUnit", "unit_kind",
           "json_schema"]

# Every number in a spec is finite and, unless exactly zero, has a magnitude between
# NUMBER_MIN and NUMBER_MAX, as written and in SI: squares, products and sums of such numbers
# (kinematics, forces, power, condition numbers) stay far from float overflow and underflow.
NUMBER_MAX = 1e20
NUMBER_MIN = 1e-20
MAX_STUDY_VARIANTS = 1_000_000
MAX_SEED = 2**63 - 1

SCHEMA_ID = "urn:mechreport:spec-schema:1.1"
SCHEMA_DIALECT = "https://json-schema.org/draft/2020-12/schema"


# -------------------------------------------------------------------------------- markers

@dataclass(frozen=True)
class Wording:
    """What a value must be, in the loader's words ("a pair [x, y]"): how a type error on it
    is reported (``must be <text>, got ...``). Metadata only: it changes no validation."""

    text: str


@dataclass(frozen=True)
class Refusal:
    """The whole message a wrong value of a key gets, ``{value}`` standing for the value as
    written (the format version's: "format version must be 1, got 2"), for the pydantic
    error types ``kinds`` (every type if none is given). Metadata only."""

    text: str
    kinds: tuple[str, ...] = ()

    def says(self, kind: str) -> bool:
        """Whether this message is the one for an error of type ``kind``."""
        return not self.kinds or kind in self.kinds


@dataclass(frozen=True)
class InUnit:
    """The number is written in the spec's unit of ``kind`` (``units.force``,
    ``units.moment``): the loader converts it to SI. Metadata only."""

    kind: str


def unit_kind(model: type[BaseModel], key: str) -> str | None:
    """The kind of the spec's unit a key of ``model`` is written in (:class:`InUnit`), None
    when it is always SI (or the loader converts it itself)."""
    field = next(f for n, f in model.model_fields.items() if (f.alias or n) == key)
    return next((m.kind for m in field.metadata if isinstance(m, InUnit)), None)


@dataclass(frozen=True)
class ZeroOrPositive:
    """A number whose 0 means something of its own (a massless link, a point mass): any other
    value is refused as "must be a positive number". Metadata only."""


@dataclass(frozen=True)
class DocRequired:
    """What docs/spec.md's key table says in its "required" column for a key that is neither
    plainly required nor plainly optional ("for random and lhs"). Metadata only."""

    text: str


@dataclass(frozen=True, eq=False)
class _JsonExtra:
    """Keywords added to a type's JSON Schema (where pydantic has no constraint for them);
    compared and hashed by identity (typing hashes Annotated metadata)."""

    extra: tuple

    def __get_pydantic_json_schema__(self, core_schema, handler):
        schema = handler(core_schema)
        schema.update(dict(self.extra))
        return schema


_SHARED = "x-mechreport-shared"     # a temporary keyword, replaced by a $ref


def _shared(name: str, description: str) -> _JsonExtra:
    """Marks a type whose JSON Schema is written once, under ``$defs/<name>``, and referred
    to wherever the type is used (see :meth:`_SpecSchema.generate`)."""
    return _JsonExtra(((_SHARED, (name, description)),))


class ByKey:
    """A discriminator: the tag of a mapping is the text of its ``key`` (a load's ``type``),
    None when it has none. ``tags`` lists the tags in the spec's order."""

    def __init__(self, key: str, tags: tuple[str, ...]):
        self.key, self.tags = key, tags
        self.__name__ = f"by_{key}"       # pydantic names a discriminator by it

    def __call__(self, value: Any) -> str | None:
        tag = value.get(self.key) if isinstance(value, dict) else None
        return tag if isinstance(tag, str) else None


def _point_tag(value: Any) -> str:
    """A point is polar when it is a mapping with ``r`` or ``angle`` (as the loader reads it),
    else a pair."""
    return "polar" if isinstance(value, dict) and ({"r", "angle"} & set(value)) else "pair"


def _shape_tag(value: Any) -> str | None:
    """``{bar: ...}`` or ``{block: ...}``: a mapping of exactly one of the two."""
    if isinstance(value, dict) and len(value) == 1 and next(iter(value)) in ("bar", "block"):
        return next(iter(value))
    return None


def _section_tag(value: Any) -> str | None:
    """``{rect: ...}``, ``{round: ...}``, ``{tube: ...}`` (a mapping of exactly one of them),
    or ``{area, inertia, c}`` (a mapping with any of those keys)."""
    if isinstance(value, dict) and len(value) == 1 and next(iter(value)) in SECTION_KINDS:
        return next(iter(value))
    if isinstance(value, dict) and {"area", "inertia", "c"} & set(value):
        return "area"
    return None


def _material_tag(value: Any) -> str:
    """A link's ``material``: a name from ``materials:`` (text), or inline properties."""
    return "name" if isinstance(value, str) else "inline"


def _through_tag(value: Any) -> str:
    """A T joint's ``line.through``: a point's name (text), or a point."""
    return "name" if isinstance(value, str) else "point"


def _direction_tag(value: Any) -> str:
    """A T joint's ``line.direction``: a vector (a list), or an angle."""
    return "vector" if isinstance(value, list) else "angle"


def _text_tag(value: Any) -> str:
    """Report metadata: text, or a whole number read as its text (``revision: 2``)."""
    return "number" if _is_whole(value) else "text"


def _is_whole(value: Any) -> bool:
    """An int, or a float with a whole value: ``3.0`` is the number 3 in JSON, as a YAML
    language server checks a spec (never true/false)."""
    return type(value) is int or type(value) is float and value.is_integer()


def _whole_value(value: Any) -> Any:
    """A whole float as its int (``3.0`` -> 3); any other value as it is."""
    return int(value) if type(value) is float and value.is_integer() else value


def _not_true_or_false(value: Any) -> Any:
    """``value``, unless it is true or false (which pydantic reads as 1 and 0)."""
    if isinstance(value, bool):
        raise PydanticCustomError("bool_refused", "must not be true or false")
    return value


def _until_tag(value: Any) -> str:
    """``dynamics.until``: text is ``steady`` (or wrong), anything else a time."""
    return "steady" if isinstance(value, str) else "time"


#: the type of the errors whose message is written here, in the house wording (``msg``)
WORDED = "spec_worded"


def _flywheel_tag(value: Any) -> str:
    """``dynamics.flywheel``: a mapping is a geared flywheel, anything else a number."""
    return "geared" if isinstance(value, dict) else "number"


def _motor_tag(value: Any) -> str | None:
    """``dynamics.motor``: the one kind (torque, curve, linear) a mapping gives; None when it
    gives none or several."""
    if not isinstance(value, dict):
        return None
    given = [kind for kind in DYNAMICS_MOTOR_KINDS if kind in value]
    return given[0] if len(given) == 1 else None


def _friction_tag(value: Any) -> str:
    """A friction entry with a journal ``radius`` is an R joint's, else a T joint's (which
    one it must be is the loader's to say: it knows the joint)."""
    return "R" if isinstance(value, dict) and "radius" in value else "T"


# -------------------------------------------------------------------------------- numbers

def _magnitude(x: float) -> float:
    """Zero, or a magnitude of at least NUMBER_MIN (what ``ge``/``le`` cannot say)."""
    if x != 0 and abs(x) < NUMBER_MIN:
        raise PydanticCustomError("number_range", "nonzero magnitudes must be at least "
                                                  "{minimum}", {"minimum": NUMBER_MIN})
    return x


# in JSON Schema: not (a nonzero number of magnitude below NUMBER_MIN); "type" inside, so
# that a value of another type (text) is refused by its type alone, not a second time here
_NOT_TINY = _JsonExtra((("not", {"type": "number", "exclusiveMinimum": -NUMBER_MIN,
                                 "exclusiveMaximum": NUMBER_MIN, "not": {"const": 0}}),))
_RANGE = (f"between {-NUMBER_MAX:g} and {NUMBER_MAX:g}, zero or at least {NUMBER_MIN:g} in "
          "magnitude")

#: a finite number in range (an int or a float, never true/false or quoted text)
Number = Annotated[float, Field(strict=True, ge=-NUMBER_MAX, le=NUMBER_MAX,
                                allow_inf_nan=False),
                   AfterValidator(_magnitude), _NOT_TINY, Wording("a number"),
                   _shared("number", f"A finite number {_RANGE}.")]
#: a number greater than zero, in range
Positive = Annotated[float, Field(strict=True, ge=NUMBER_MIN, le=NUMBER_MAX,
                                  allow_inf_nan=False), Wording("a positive number"),
                     _shared("positive", f"A positive number, between {NUMBER_MIN:g} and "
                                         f"{NUMBER_MAX:g}.")]
#: zero or a positive number in range
NonNegative = Annotated[float, Field(strict=True, ge=0, le=NUMBER_MAX, allow_inf_nan=False),
                        AfterValidator(_magnitude), _NOT_TINY,
                        Wording("a number, 0 or more"),
                        _shared("non_negative", f"0, or a positive number between "
                                                f"{NUMBER_MIN:g} and {NUMBER_MAX:g}.")]
#: a name (of a point, link, joint or load): non-empty text
Name = Annotated[str, Field(strict=True, min_length=1), Wording("a name"),
                 _shared("name", "A name (case-sensitive); quote one that reads as a number, "
                                 "true/false or null.")]
Text = Annotated[str, Field(strict=True), Wording("text")]

#: bidirectional controls: embeddings, overrides, isolates and marks (LRE ... RLO, LRI ... PDI,
#: LRM, RLM, ALM)
BIDI_CONTROL = re.compile("[\u202a-\u202e\u2066-\u2069\u200e\u200f\u061c]")


def bidi_problem(name: str) -> str | None:
    """Why ``name`` may not be a name (it holds a bidirectional control character, which
    shows it in a report as other than it is: the "Trojan Source" trick), or None."""
    bad = BIDI_CONTROL.search(name)
    if bad is None:
        return None
    char = bad.group()
    return (f"must not hold U+{ord(char):04X} "
            f"({unicodedata.name(char, 'a bidirectional control')}), a bidirectional control "
            "character that makes a name display as other than it is; remove it")


def _no_bidi_control(name: str) -> str:
    problem = bidi_problem(name)
    if problem is not None:
        raise PydanticCustomError(WORDED, problem)
    return name


#: a name that labels something in the reports (the mechanism's, a load's)
Label = Annotated[Name, AfterValidator(_no_bidi_control)]


def _whole(low: int, high: int) -> Any:
    """A whole number (3, or 3.0: the same number in JSON) from ``low`` to ``high``."""
    return Annotated[int, Field(strict=True, ge=low, le=high), BeforeValidator(_whole_value),
                     Wording(f"a whole number from {low} to {high}")]


Pair = Annotated[tuple[Number, Number], Wording("a pair [x, y]"),
                 _shared("pair", "[x, y]: two numbers.")]


def _not_zero_vector(value: tuple) -> tuple:
    if value[0] == 0 and value[1] == 0:
        raise PydanticCustomError(WORDED, "must not be the zero vector")
    return value


#: a direction [dx, dy]: two numbers, not both zero (its length does not matter)
Direction = Annotated[Pair, AfterValidator(_not_zero_vector),
                      _JsonExtra((("not", {"const": [0, 0]}),))]


# ---------------------------------------------------------------------------------- models

class _Model(BaseModel):
    """Unknown keys are errors at every level; validators are built on first use."""

    model_config = ConfigDict(extra="forbid", defer_build=True)


class Polar(_Model):
    """A point in polar form: ``{r: R, angle: A}``."""

    model_config = ConfigDict(title="polar point")
    r: Annotated[NonNegative, Refusal("must be a distance (not negative), got {value}",
                                      ("greater_than_equal",))] = Field(description="Distance from the frame's origin, in the length unit "
                                       "(not negative).")
    angle: Number = Field(description="Degrees from the frame's x-axis, counter-clockwise.")


Point = Annotated[Union[Annotated[Pair, Tag("pair")], Annotated[Polar, Tag("polar")]],
                  Discriminator(_point_tag), Wording("a pair [x, y] or {r: R, angle: A}"),
                  _shared("point", "A point: [x, y], or {r: R, angle: A} (R in the length "
                                   "unit, A in degrees from the frame's x-axis, "
                                   "counter-clockwise).")]


class Units(_Model):
    """The units the spec's numbers are written in (each defaults to SI)."""

    length: Literal[SPEC_UNITS["length"]] = Field(
        "m", description="Unit of every length and coordinate in the spec: ground and link "
                         "points, com, shape sizes, line.through, assembly hints (m, cm, mm, "
                         "in, ft).")
    mass: Literal[SPEC_UNITS["mass"]] = Field("kg", description="Unit of `mass` (kg, g, lb).")
    force: Literal[SPEC_UNITS["force"]] = Field(
        "N", description="Unit of every force the spec writes: force loads' values and "
                         "profiles, spring and damper rates (per length unit), bearing "
                         "ratings and force limits (N, lbf, kip; format 1.2).")
    moment: Literal[SPEC_UNITS["moment"]] = Field(
        "N*m", description="Unit of every moment and torque: moment loads, torsion spring "
                           "rates (per rad), motor torques, design.motor torques (N*m, N*mm, "
                           "lbf*in, lbf*ft; format 1.2).")
    inertia: Literal[SPEC_UNITS["inertia"]] = Field(
        "kg*m^2", description="Unit of link and flywheel inertias (kg*m^2, g*mm^2, lb*in^2, "
                              "lb*ft^2; format 1.2).")


class Bar(_Model):
    """A plate along the link's x-axis from x = 0 to x = length, centred on y = 0."""

    length: Positive = Field(description="Along the link's x-axis, in the length unit.")
    height: Positive = Field(description="Across the link, in the length unit.")
    depth: Positive = Field(description="Thickness normal to the plane, in the length unit.")


class Block(_Model):
    """A rectangle centred on the link's origin, `width` along its x-axis."""

    width: Positive = Field(description="Along the link's x-axis, in the length unit.")
    height: Positive = Field(description="Across the link, in the length unit.")
    depth: Positive = Field(description="Thickness normal to the plane, in the length unit.")


class BarShape(_Model):
    """``{bar: {length, height, depth}}``."""

    model_config = ConfigDict(title="bar shape")
    bar: Bar = Field(description="A bar: centroid (length/2, 0); I = m (length² + height²) "
                                 "/ 12.")


class BlockShape(_Model):
    """``{block: {width, height, depth}}``."""

    model_config = ConfigDict(title="block shape")
    block: Block = Field(description="A block: centroid (0, 0); I = m (width² + height²) / 12.")


Shape = Annotated[Union[Annotated[BarShape, Tag("bar")], Annotated[BlockShape, Tag("block")]],
                  Discriminator(_shape_tag),
                  Wording("{bar: {length, height, depth}} or {block: {width, height, depth}}")]


SECTION_KINDS = ("rect", "round", "tube")


class Rect(_Model):
    """A solid rectangle."""

    width: Positive = Field(description="Normal to the plane of motion, in the length unit.")
    height: Positive = Field(description="In the plane of motion (the depth that resists "
                                         "in-plane bending), in the length unit.")


class Round(_Model):
    """A solid round bar."""

    d: Positive = Field(description="Diameter, in the length unit.")


class Tube(_Model):
    """A round tube."""

    d: Positive = Field(description="Outer diameter, in the length unit.")
    t: Positive = Field(description="Wall thickness, in the length unit (at most d/2).")


class RectSection(_Model):
    """``{rect: {width, height}}``."""

    model_config = ConfigDict(title="rect section")
    rect: Rect = Field(description="I = width height³ / 12, c = height / 2.")


class RoundSection(_Model):
    """``{round: {d}}``."""

    model_config = ConfigDict(title="round section")
    round: Round = Field(description="I = pi d⁴ / 64, c = d / 2.")


class TubeSection(_Model):
    """``{tube: {d, t}}``."""

    model_config = ConfigDict(title="tube section")
    tube: Tube = Field(description="I = pi (d⁴ - (d - 2t)⁴) / 64, c = d / 2.")


class GivenSection(_Model):
    """``{area, inertia, c}``: any section by its properties."""

    model_config = ConfigDict(title="section properties")
    area: Positive = Field(description="Area, length unit².")
    inertia: Positive = Field(description="Second moment for in-plane bending, length "
                                          "unit⁴.")
    c: Positive = Field(description="Neutral axis to the outer fibre, in the length unit.")
    inertia_out: Positive = Field(
        None, description="Second moment for out-of-plane bending and buckling, length unit⁴ "
                          "(default: `inertia`; format 1.2).")


Section = Annotated[Union[Annotated[RectSection, Tag("rect")],
                          Annotated[RoundSection, Tag("round")],
                          Annotated[TubeSection, Tag("tube")],
                          Annotated[GivenSection, Tag("area")]],
                    Discriminator(_section_tag),
                    Wording("{rect: {width, height}}, {round: {d}}, {tube: {d, t}} or "
                            "{area, inertia, c}")]


class Material(_Model):
    """A material's strengths, Pa (always SI)."""

    E: Positive = Field(description="Young's modulus, Pa.")
    yield_: Positive = Field(alias="yield", description="Yield strength, Pa.")
    endurance: Positive = Field(description="Endurance limit (fully corrected), Pa.")
    ultimate: Positive = Field(description="Ultimate tensile strength, Pa.")


MaterialRef = Annotated[Union[Annotated[Name, Tag("name")], Annotated[Material, Tag("inline")]],
                        Discriminator(_material_tag),
                        Wording("a name from 'materials:' or {E, yield, endurance, "
                                "ultimate}")]


def _names_only(value: Any) -> Any:
    """A list of link names holds names only (said of the list, as "two link names")."""
    if isinstance(value, list) and not all(isinstance(x, str) and x for x in value):
        raise PydanticCustomError("names_only", "must be a list of names")
    return value


class Rankine(_Model):
    """Rankine's column formula: P = crushing A / (1 + a (kL / r)^2)."""

    crushing: Positive = Field(description="The crushing stress, Pa.")
    a: Positive = Field(description="Rankine's constant (dimensionless; 1/7500 for mild "
                                    "steel, pinned ends).")


BUCKLING_FORMULAS = ("euler-johnson", "rankine")


class Buckling(_Model):
    """How a member buckles (format 1.2): effective lengths in and out of the plane, and the
    formula."""

    k: Positive = Field(1, description="Effective-length factor in the plane of motion "
                                       "(default 1: pinned-pinned; 0.5 fixed-fixed, 0.7 "
                                       "fixed-pinned, 2 a free end).")
    k_out: Positive = Field(None, description="Effective-length factor out of the plane "
                                              "(default `k`).")
    formula: Literal[BUCKLING_FORMULAS] = Field(
        "euler-johnson", description="`euler-johnson` (default: Euler above the transition "
                                     "slenderness, Johnson below, taken with kL) or "
                                     "`rankine`.")
    rankine: Rankine = Field(None, description="{crushing, a}: Rankine's constants (with "
                                               "`formula: rankine`).")

    @model_validator(mode="after")
    def _rankine_constants(self):
        """Rankine's formula needs its constants; the constants need the formula."""
        if self.formula == "rankine" and self.rankine is None:
            raise PydanticCustomError(WORDED, "formula: rankine needs 'rankine: {crushing, a}'"
                                              " (the crushing stress in Pa and the constant a)")
        if self.formula != "rankine" and self.rankine is not None:
            raise PydanticCustomError(WORDED, "goes with 'formula: rankine'", {"key": "rankine"})
        return self


MemberPair = Annotated[list[Name], BeforeValidator(_names_only),
                       Field(min_length=2, max_length=2), Wording("a pair of point names [P, Q]")]


class MemberEntry(_Model):
    """A member with its own buckling data (format 1.2): ``{points: [P, Q], buckling}``."""

    model_config = ConfigDict(title="member")
    points: MemberPair = Field(description="[P, Q]: two points of the link.")
    buckling: Buckling = Field(None, description="How this member buckles (default: the "
                                                 "link's `buckling`).")


def _member_tag(value: Any) -> str:
    """A member: ``[P, Q]``, or ``{points: [P, Q], buckling}``."""
    return "entry" if isinstance(value, dict) else "pair"


Member = Annotated[Union[Annotated[MemberPair, Tag("pair")],
                         Annotated[MemberEntry, Tag("entry")]],
                   Discriminator(_member_tag),
                   Wording("a pair of point names [P, Q] or {points: [P, Q], buckling}")]


class Link(_Model):
    """A moving link: its named points in its own frame and its mass properties."""

    points: Annotated[dict[str, Point],
                      Refusal("must map at least one point name to [x, y], got {value}",
                              ("dict_type",)),
                      Refusal("must map at least one point name to [x, y]",
                              ("too_short",))] = Field(
        min_length=1, description="required, at least one: `NAME: [x, y]` in the link's own frame")
    mass: Annotated[NonNegative, ZeroOrPositive()] = Field(
        None, description=(
            "kg (or g with `units.mass: g`). Or give `density` and a `shape`: mass = density x "
            "shape volume. `mass: 0` alone (no `density`, `shape`, `com` or `inertia`) is a "
            "massless link: no weight, no inertia (a two-force member when it carries no load)"))
    density: Positive = Field(
        None, description="kg/m³, used with `shape` when `mass` is absent")
    com: Point = Field(
        None, description=(
            "centre of mass `[x, y]` in the link frame. Default: the shape's centroid"))
    inertia: Annotated[NonNegative, ZeroOrPositive()] = Field(
        None, description=(
            "kg·m² (or `units.inertia`) about the centre of mass, axis normal to the plane. "
            "Default: from the shape. "
            "`inertia: 0` with a `mass` is a point mass"))
    shape: Shape = Field(
        None, description=(
            "`{bar: {length, height, depth}}` or `{block: {width, height, depth}}`, see below"))
    section: Section = Field(
        None, description=(
            "`{rect: {width, height}}`: `height` in the plane of motion (it resists in-plane "
            "bending), `width` normal to it; A = width height, I = width height³ / 12, c = height"
            " / 2. `{round: {d}}`: I = π d⁴ / 64, c = d / 2. `{tube: {d, t}}`: outer diameter and"
            " wall (t at most d / 2). `{area, inertia, c}`: any section, area in length unit², "
            "inertia (in-plane bending) in length unit⁴, c the distance from the neutral axis to "
            "the outer fibre. Sizes are in the spec's length unit; all must be positive"))
    material: MaterialRef = Field(
        None, description=(
            "a name from the top-level `materials:`, or inline `{E, yield, endurance, ultimate}`,"
            " all in Pa (SI whatever `units` says). `endurance` is the fully corrected endurance "
            "limit S_e (surface, size, load, reliability already applied). `yield` and "
            "`endurance` may not exceed `ultimate`"))
    members: Annotated[list[Member], Wording("a list of point pairs [[P, Q], ...]")] = Field(
        None, min_length=1, description=(
            "`[[P, Q], ...]`, points of the link: the straight beams it is made of. Default: the "
            "segment between the link's two joint points (the points of its R joints, and of T "
            "joints where it is the slider); a link with more or fewer joint points must list "
            "them. The members must join into one piece without a closed loop (a closed frame is "
            "statically indeterminate); a member of zero length is an error. A member may be "
            "written `{points: [P, Q], buckling: {...}}` to give it its own buckling data "
            "(format 1.2)"))
    buckling: Buckling = Field(
        None, description=(
            "`{k, k_out, formula, rankine: {crushing, a}}` (format 1.2): the effective-length "
            "factor `k` in the plane of motion (default 1, pinned-pinned) and `k_out` out of it "
            "(default `k`), each with the section's second moment about that axis (a rect's "
            "out-of-plane I is height width³ / 12); `formula` `euler-johnson` (default) or "
            "`rankine` (P = crushing A / (1 + a (kL/r)²), `crushing` in Pa, `a` "
            "dimensionless). member.L.buckling_safety is the smaller of the two planes; "
            "member.L.buckling_plane is 1 when the plane of motion governs, 2 when out of the "
            "plane does"))


class Line(_Model):
    """The line a T joint's slider moves along, in the guide's frame."""

    through: Annotated[Union[Annotated[Name, Tag("name")], Annotated[Point, Tag("point")]],
                       Discriminator(_through_tag),
                       Wording("a pair [x, y], a point name or {r: R, angle: A}")] = Field(
        description="A point of the guide (its name), or [x, y] in the guide's frame.")
    direction: Annotated[Union[Annotated[Number, Tag("angle")],
                               Annotated[Direction, Tag("vector")]],
                         Discriminator(_direction_tag),
                         Wording("a pair [dx, dy] or an angle in degrees")] = Field(
        description="An angle in degrees, or a vector [dx, dy], in the guide's frame.")


class RJoint(_Model):
    """A revolute joint (pin): joins the point named like the joint on each of its links."""

    model_config = ConfigDict(title="R joint")
    type: Literal["R"] = Field(description="R: revolute (pin).")
    links: Annotated[list[Name], BeforeValidator(_names_only),
                     Wording("two link names [first, second]"),
                     Refusal("must be two link names [first, second], got {value} (a pin "
                             "joining several links lists them all)", ("too_short",))] = Field(
        min_length=2, description="[first, second]: the reaction reported is the force of the "
                                  "first on the second. Three or more: one pin joining them "
                                  "all (format 1.1).")


class TJoint(_Model):
    """A prismatic joint (slider): the second link slides on the first."""

    model_config = ConfigDict(title="T joint")
    type: Literal["T"] = Field(description="T: prismatic (slider).")
    links: Annotated[list[Name], BeforeValidator(_names_only),
                     Wording("two link names [first, second]")] = Field(
        min_length=2, max_length=2, description="[guide, slider]: the second link slides on "
                                                "the first.")
    point: Name = Field(description="A point of the slider that stays on the guide's line.")
    line: Line = Field(description="The guide's line: {through, direction}.")


JOINT_TYPES = ("R", "T")
Joint = Annotated[Union[Annotated[RJoint, Tag("R")], Annotated[TJoint, Tag("T")]],
                  Discriminator(ByKey("type", JOINT_TYPES)),
                  Wording("a mapping like {type: R, links: [a, b]}")]


class Driver(_Model):
    """The driving joint and its speed (R: rpm or omega; T: speed)."""

    joint: Name = Field(description="The driving joint. An R joint turns (rpm or omega); a T "
                                    "joint drives its stroke (speed).")
    rpm: Number = Field(None, description="R driver: speed in rpm (negative: clockwise; 0: "
                                          "at rest).")
    omega: Number = Field(None, description="R driver: speed in rad/s (instead of rpm).")
    alpha: Number = Field(None, description="R driver: angular acceleration, rad/s² (default "
                                            "0).")
    speed: Number = Field(None, description="T driver: stroke speed, length unit per second "
                                            "(0: at rest).")
    accel: Number = Field(None, description="T driver: stroke acceleration, length unit per "
                                            "s² (default 0).")


class Sweep(_Model):
    """The crank angles analysed: start, start + step, ... up to stop (degrees)."""

    start: Number = Field(0, description="First angle, degrees (stroke for a T driver).")
    stop: Number = Field(360, description="Last angle, degrees; greater than start (default "
                                          "`cycle`: one cycle).")
    step: Positive = Field(1, description="Step, degrees (positive).")


#: the largest ``cycle``, crank degrees (a hundred turns)
CYCLE_MAX = 36000
#: ``cycle``: the loads' period in crank degrees, a positive whole multiple of 360
Cycle = Annotated[int, Field(strict=True, ge=360, le=CYCLE_MAX, multiple_of=360),
                  BeforeValidator(_not_true_or_false), BeforeValidator(_whole_value),
                  Refusal("must be a whole multiple of 360 crank degrees (360, 720, ...) up to "
                          f"{CYCLE_MAX}, got {{value}}")]


#: a profile's crank angle, degrees: in [0, cycle] (the spec's ``cycle``, checked by
#: :meth:`SpecFile._profiles_within_cycle`)
ProfileAngle = Annotated[float, Field(strict=True, ge=0, le=CYCLE_MAX, allow_inf_nan=False),
                         AfterValidator(_magnitude), _NOT_TINY,
                         Wording("an angle in [0, cycle]")]


def _increasing(profile: list) -> list:
    """A profile's angles strictly increase."""
    if any(b[0] <= a[0] for a, b in zip(profile, profile[1:])):
        raise PydanticCustomError(WORDED, "angles must be strictly increasing")
    return profile


Profile = Annotated[list[Annotated[tuple[ProfileAngle, Number],
                                   Wording("a pair [crank_angle_deg, magnitude]")]],
                    Field(min_length=1), AfterValidator(_increasing),
                    Wording("a list of [crank_angle_deg, magnitude] pairs")]
End = Annotated[tuple[Name, Name], Wording("an end [link, point]"),
                _shared("end", "[link, point]: a point of a link (or of ground).")]
Ends = Annotated[tuple[End, End], Wording("two ends [[link, point], [link, point]]")]
LOAD_NAME = ("Labels the load in the torque breakdown, the plots and summary.json (names "
             "must differ).")
SHIFT = ("Degrees, with `profile`: the value at crank angle phi is profile(phi - shift) "
         "(format 1.2; default 0).")


class ForceLoad(_Model):
    """A force at a point of a moving link."""

    model_config = ConfigDict(title="force", json_schema_extra={
        "oneOf": [{"required": ["value"]}, {"required": ["profile"]}],
        "dependentRequired": {"profile": ["direction"]},
        "dependentSchemas": {"value": {"not": {"required": ["direction"]}}}})
    type: Literal["force"] = Field(description="A force at a point of a link.")
    link: Name = Field(description="The moving link it acts on.")
    point: Name = Field(description="The point of the link where it acts.")
    value: Pair = Field(None, description="[Fx, Fy] in N (or `units.force`), global.")
    direction: Direction = Field(None, description="[dx, dy], with `profile`.")
    profile: Profile = Field(
        None, description="[[crank_angle_deg, magnitude_N], ...], angles strictly increasing "
                          "within [0, cycle] (a point at `cycle` repeats the one at 0).")
    shift: Number = Field(None, description=SHIFT)
    oppose: Literal["velocity"] = Field(
        None, description="velocity: the force opposes the motion of its point.")
    name: Label = Field(None, description=LOAD_NAME)
    reacts_on: Literal[GROUND] = Field(
        None, description="ground: the load's reaction acts on the frame.")

    @model_validator(mode="after")
    def _value_or_profile(self):
        """A force is a ``value`` [Fx, Fy], or a ``profile`` of magnitudes along a
        ``direction``."""
        _value_or_profile(self, "'value', or 'direction' with 'profile'")
        if self.value is not None and self.direction is not None:
            raise PydanticCustomError(WORDED, "goes with 'profile', not with 'value'",
                                      {"key": "direction"})
        if self.profile is not None and self.direction is None:
            raise PydanticCustomError(WORDED, "a force 'profile' needs a 'direction' [dx, dy]")
        return self


def _value_or_profile(load: "_Model", what: str) -> None:
    """A load gives exactly one of its ``value`` and its ``profile``."""
    if (load.value is None) == (load.profile is None):
        raise PydanticCustomError(WORDED, "give exactly one of {what}", {"what": what})


class MomentLoad(_Model):
    """A moment on a moving link."""

    model_config = ConfigDict(title="moment", json_schema_extra={
        "oneOf": [{"required": ["value"]}, {"required": ["profile"]}]})
    type: Literal["moment"] = Field(description="A moment on a link.")
    link: Name = Field(description="The moving link it acts on.")
    value: Number = Field(None, description="M in N·m (or `units.moment`), counter-clockwise "
                                            "positive.")
    profile: Profile = Field(
        None, description="[[crank_angle_deg, M], ...], angles strictly increasing within "
                          "[0, cycle] (a point at `cycle` repeats the one at 0).")
    shift: Number = Field(None, description=SHIFT)
    oppose: Literal["rotation"] = Field(
        None, description="rotation: M = -sign(omega) |M0|.")
    name: Label = Field(None, description=LOAD_NAME)
    reacts_on: Literal[GROUND] = Field(
        None, description="ground: the load's reaction acts on the frame.")

    @model_validator(mode="after")
    def _value_or_profile(self):
        """A moment is a ``value`` or a ``profile``."""
        _value_or_profile(self, "'value' or 'profile'")
        return self


def _not_zero(pair: tuple) -> tuple:
    """A direction: not the zero vector."""
    if pair[0] == 0 and pair[1] == 0:
        raise PydanticCustomError("zero_direction", "must not be the zero vector")
    return pair


_BORE_OR_AREA = Refusal("give exactly one of 'bore' (the cylinder's diameter) or 'area' (the "
                        "piston's)", ("bore_or_area",))


class PressureLoad(_Model):
    """A gas pressure on a piston (format 1.2): (p - ambient) times the area, along
    ``direction``; its reaction acts on the cylinder head (the frame)."""

    model_config = ConfigDict(title="pressure")
    type: Literal["pressure"] = Field(description="A pressure on a piston's crown.")
    link: Name = Field(description="The moving link it acts on (the piston).")
    point: Name = Field(description="The point of the link where the force acts.")
    bore: Annotated[Positive, _BORE_OR_AREA] = Field(
        None, description="Cylinder diameter, in the length unit (or `area`).")
    area: Annotated[Positive, _BORE_OR_AREA] = Field(
        None, description="Piston area, in the length unit squared (or `bore`).")
    direction: Annotated[Pair, AfterValidator(_not_zero),
                         Wording("a direction [dx, dy], not zero")] = Field(
        description="[dx, dy]: the way the gas pushes the piston (need not be a unit vector; "
                    "not zero).")
    unit: Literal[tuple(PRESSURE_UNITS)] = Field(
        "Pa", description="The profile's and ambient's pressure unit (default Pa).")
    ambient: Number = Field(0, description="The pressure on the other side, in `unit` "
                                           "(default 0).")
    profile: Profile = Field(
        description="[[crank_angle_deg, p], ...] over one cycle, p in `unit`; angles strictly "
                    "increasing within [0, cycle] (a point at `cycle` repeats the one at 0).")
    shift: Number = Field(None, description=SHIFT)
    name: Label = Field(None, description=LOAD_NAME)
    reacts_on: Literal[GROUND] = Field(
        None, description="ground (the default for a pressure load): the reaction acts on the "
                          "cylinder head, part of the frame.")

    @model_validator(mode="after")
    def _bore_or_area(self):
        """Exactly one of ``bore`` and ``area`` (the problem is put on ``area`` when both
        are given, else on the missing ``bore``)."""
        if (self.bore is None) == (self.area is None):
            key = "area" if self.area is not None else "bore"
            raise ValidationError.from_exception_data("PressureLoad", [InitErrorDetails(
                type=PydanticCustomError("bore_or_area", "give exactly one of bore or area"),
                loc=(key,), input=getattr(self, key))])
        return self


class SpringLoad(_Model):
    """A linear spring between two points; its tension k (L - L0) pulls them together."""

    model_config = ConfigDict(title="spring")
    type: Literal["spring"] = Field(description="A linear spring between two points.")
    between: Ends = Field(description="[[link, point], [link, point]]; either link may be "
                                      "ground.")
    stiffness: Positive = Field(description="N/m (or `units.force` per length unit).")
    name: Label = Field(None, description=LOAD_NAME)
    free_length: NonNegative = Field(description="In the length unit.")


class DamperLoad(_Model):
    """A damper between two points: a force c dL/dt along the line, resisting extension."""

    model_config = ConfigDict(title="damper")
    type: Literal["damper"] = Field(description="A linear damper between two points.")
    between: Ends = Field(description="[[link, point], [link, point]]; either link may be "
                                      "ground.")
    damping: Positive = Field(description="N·s/m (or `units.force` s per length unit).")
    name: Label = Field(None, description=LOAD_NAME)


class TorsionSpringLoad(_Model):
    """A torsion spring at an R joint: a couple k (relative angle - free angle)."""

    model_config = ConfigDict(title="torsion spring")
    type: Literal["torsion_spring"] = Field(description="A torsion spring at an R joint.")
    joint: Name = Field(description="The R joint it sits at.")
    stiffness: Positive = Field(description="N·m/rad (or `units.moment` per rad).")
    free_angle: Number = Field(description="Degrees.")
    name: Label = Field(None, description=LOAD_NAME)


#: the load models by their ``type``, in the spec's order
LOAD_MODELS = {"force": ForceLoad, "moment": MomentLoad, "spring": SpringLoad,
               "damper": DamperLoad, "torsion_spring": TorsionSpringLoad,
               "pressure": PressureLoad}
Load = Annotated[Union[tuple(Annotated[m, Tag(t)] for t, m in LOAD_MODELS.items())],
                 Discriminator(ByKey("type", tuple(LOAD_MODELS))),
                 Wording("a mapping like {type: force, link, point, value}")]


FrictionSense = Annotated[Literal[1, -1], BeforeValidator(_not_true_or_false), Refusal(
    "must be +1 or -1 (the way the joint is about to move in a static analysis), got {value}"),
    Field(description="At rest: the sign of the relative motion the joint is about to have.")]


class RFriction(_Model):
    """Coulomb friction in an R joint: a couple mu radius |F|."""

    model_config = ConfigDict(title="R joint friction")
    mu: NonNegative = Field(description="Coefficient of friction (0 or more; 0 adds nothing).")
    radius: Positive = Field(description="Journal radius, in the length unit.")
    friction_sense: FrictionSense = None
    model: Literal["couple", "circle"] = Field(
        None, description="`couple` (default): a couple mu r |F|; `circle`: the "
                          "friction circle's r sin(atan mu) |F| (format 1.2).")


class TFriction(_Model):
    """Coulomb friction in a T joint: a force mu |N| along the line."""

    model_config = ConfigDict(title="T joint friction")
    mu: NonNegative = Field(description="Coefficient of friction (0 or more; 0 adds nothing).")
    length: Positive = Field(None, description="Slider length, in the length unit (its two "
                                               "ends carry the normal force and couple).")
    friction_sense: FrictionSense = None


Friction = Annotated[Union[Annotated[RFriction, Tag("R")], Annotated[TFriction, Tag("T")]],
                     Discriminator(_friction_tag),
                     Wording("{mu, radius} (an R joint) or {mu, length} (a T joint)")]

EXPECT_UNIT_NAMES = tuple(dict.fromkeys(u for table in EXPECT_UNITS.values() for u in table))


class Expectation(_Model):
    """A value the results must reproduce (`mechreport check`)."""

    angle: Number = Field(None, description="Crank angle, degrees. Cycle quantities have "
                                            "none.")
    quantity: Name = Field(description="driver.torque, joint.J.fx|fy|f|..., point.P.x|y|..., "
                                       "link.L.angle|omega|alpha, transmission_angle, or a "
                                       "cycle quantity (cycle.torque.rms, ...).")
    value: Number = Field(description="SI, or in `unit`.")
    tol: Positive = Field(None, description="Absolute tolerance; default 1e-4 x max(1, "
                                            "|value|).")
    unit: Literal[EXPECT_UNIT_NAMES] = Field(
        None, description="The unit value and tol are written in (one of the quantity's "
                          "kind).")


class Motor(_Model):
    """The motor's ratings, checked against the cycle."""

    rated_torque: Annotated[Positive, InUnit("moment")] = Field(
        None, description="N·m (or `units.moment`), against cycle.torque.rms.")
    peak_torque: Annotated[Positive, InUnit("moment")] = Field(
        None, description="N·m (or `units.moment`), against the largest |driver torque|.")
    rated_power: Positive = Field(None, description="W, against cycle.power.max.")


class Bearing(_Model):
    """A joint's bearing: its dynamic load rating and required life."""

    rating: Annotated[Positive, InUnit("force")] = Field(
        description="Dynamic load rating C, N (or `units.force`).")
    life_h: Positive = Field(None, description="Required L10 life, hours.")


class Limits(_Model):
    """Limits the cycle must keep."""

    joint_force: Annotated[Positive, InUnit("force")] = Field(
        None, description="N (or `units.force`), every joint over the cycle.")
    transmission_angle: Annotated[Positive, Field(le=90), Refusal(
        "must be at most 90 degrees (the transmission angle is folded into [0, 90])",
        ("less_than_equal",))] = Field(
        None, description="Degrees, the smallest allowed (at most 90).")
    shaking_force: Annotated[Positive, InUnit("force")] = Field(
        None, description="N (or `units.force`), the largest allowed.")
    efficiency: Annotated[Positive, Field(le=1), Refusal(
        "must be at most 1 (an efficiency is a fraction: 0.85, not 85)",
        ("less_than_equal",))] = Field(
        None, description="The smallest cycle.efficiency allowed (at most 1; needs friction).")
    speed_fluctuation: Positive = Field(
        None, description="The largest dynamics.speed_fluctuation allowed (needs dynamics).")

    static_safety: Positive = Field(None, description="The smallest member.*.static_safety "
                                                      "allowed.")
    fatigue_safety: Positive = Field(None, description="The smallest member.*.fatigue_safety "
                                                       "allowed.")
    buckling_safety: Positive = Field(None, description="The smallest "
                                                        "member.*.buckling_safety allowed.")


#: a gearing's efficiency: a fraction in (0, 1]
GearEfficiency = Annotated[Positive, Field(le=1), Refusal(
    "must be at most 1 (an efficiency is a fraction: 0.92, not 92)", ("less_than_equal",))]


MOTOR_RATIO = ("Motor speed over crank speed (default 1); the motor's curve stays in motor "
               "rpm and N·m.")
MOTOR_EFFICIENCY = ("Of the gearing, (0, 1], default 1: the crank receives ratio × efficiency "
                    "× the motor's torque while the motor drives, ratio × torque / efficiency "
                    "when the crank drives it back.")


class LinearMotor(_Model):
    """A motor whose torque falls linearly from its stall torque at rest to 0 at its
    no-load speed."""

    stall_torque: Positive = Field(description="N·m, at rest.")
    no_load_rpm: Positive = Field(description="rpm, where the torque is 0.")


CurvePoint = Annotated[tuple[Number, Number], Wording("a pair [rpm, N·m]")]


class TorqueMotor(_Model):
    """A motor of constant torque."""

    model_config = ConfigDict(title="constant torque motor")
    torque: Number = Field(description="A constant torque, N·m.")
    ratio: Positive = Field(None, description=MOTOR_RATIO)
    efficiency: GearEfficiency = Field(None, description=MOTOR_EFFICIENCY)


class CurveMotor(_Model):
    """A motor whose torque follows a curve over speed."""

    model_config = ConfigDict(title="torque curve motor")
    curve: Annotated[list[CurvePoint], Wording("a list of [rpm, torque] pairs"),
                     Refusal("must be a list of at least two [rpm, N·m] points, got {value}",
                             ("list_type", "too_short"))] = Field(
        min_length=2, description="[[rpm, N·m], ...], speeds increasing; linear between "
                                  "the points and along the end segments beyond them.")
    ratio: Positive = Field(None, description=MOTOR_RATIO)
    efficiency: GearEfficiency = Field(None, description=MOTOR_EFFICIENCY)


class LinearCurveMotor(_Model):
    """A motor whose torque falls linearly with speed."""

    model_config = ConfigDict(title="linear motor")
    linear: LinearMotor = Field(description="{stall_torque, no_load_rpm}.")
    ratio: Positive = Field(None, description=MOTOR_RATIO)
    efficiency: GearEfficiency = Field(None, description=MOTOR_EFFICIENCY)


#: the kinds of dynamics.motor, one key each (a motor gives exactly one)
DYNAMICS_MOTOR_KINDS = ("torque", "curve", "linear")
DynamicsMotor = Annotated[Union[Annotated[TorqueMotor, Tag("torque")],
                                Annotated[CurveMotor, Tag("curve")],
                                Annotated[LinearCurveMotor, Tag("linear")]],
                          Discriminator(_motor_tag),
                          Wording("exactly one of {torque}, {curve} or {linear}"),
                          Refusal("give exactly one of torque (N·m), curve ([[rpm, N·m], ...])"
                                  " or linear ({{stall_torque, no_load_rpm}}), got {value}",
                                  ("union_tag_not_found",))]


class DynamicsStart(_Model):
    """The initial state of the crank."""

    angle: Number = Field(None, description="Crank angle, degrees (default sweep.start).")
    rpm: Annotated[NonNegative, Refusal(
        "must be 0 or more: the crank starts at rest or turning the way the motor drives it",
        ("greater_than_equal",))] = Field(
        None, description="Crank speed, rpm (default 0: from rest).")


class GearedFlywheel(_Model):
    """A flywheel on a shaft geared to the crank."""

    model_config = ConfigDict(title="geared flywheel")
    inertia: Annotated[NonNegative, Refusal("must be 0 or more (kg·m²), got {value}",
                                            ("greater_than_equal",))] = Field(
        description="The flywheel's own inertia, kg·m² (or `units.inertia`).")
    ratio: Positive = Field(description="Its speed over the crank's (it counts ratio² times "
                                        "on the crank).")


#: exactly one of motor and mean_rpm; mean_rpm without start or until
_MOTOR_OR_MEAN_SPEED = {"oneOf": [
    {"required": ["motor"]},
    {"required": ["mean_rpm"], "not": {"anyOf": [{"required": ["start"]},
                                                 {"required": ["until"]}]}}]}


class Dynamics(_Model):
    """Machine dynamics: the motion a motor and a flywheel give (format 1.1), or the steady
    state at a mean speed (format 1.2)."""

    model_config = ConfigDict(json_schema_extra=_MOTOR_OR_MEAN_SPEED)

    motor: DynamicsMotor = Field(None, description="One of {torque}, {curve}, {linear}, with "
                                                   "optional ratio and efficiency (exclusive "
                                                   "with mean_rpm).")
    mean_rpm: Positive = Field(None, description="Instead of a motor: the periodic state at "
                                                 "this time-mean crank speed, rpm, under a "
                                                 "constant driving torque (the cycle mean).")
    flywheel: Annotated[Union[Annotated[NonNegative, Tag("number"),
                                        Refusal("must be 0 or more (kg·m²), got {value}",
                                                ("greater_than_equal",))],
                              Annotated[GearedFlywheel, Tag("geared")]],
                        Discriminator(_flywheel_tag),
                        Wording("a number (kg·m²) or {inertia, ratio}")] = Field(
        None, description="Extra inertia on the crank shaft, kg·m² (or `units.inertia`; default 0), or {inertia, "
                          "ratio}: a flywheel turning ratio times as fast as the crank.")
    start: DynamicsStart = Field(None, description="{angle, rpm}, default sweep.start at rest.")
    until: Annotated[Union[Annotated[Literal["steady"], Tag("steady")],
                           Annotated[Positive, Tag("time")]],
                     Discriminator(_until_tag),
                     Refusal("must be steady or a time in s, got {value}",
                             ("literal_error",))] = Field(
        None, description="steady (default: until two cycles agree), or a time in s.")
    output_step: Positive = Field(None, description="s, the sampling of the time histories "
                                                    "(default 200 per steady cycle).")

    @model_validator(mode="after")
    def _motor_or_mean_speed(self):
        """Exactly one of ``motor`` and ``mean_rpm``; ``mean_rpm`` is the steady state
        itself (no start, no end time)."""
        if (self.motor is None) == (self.mean_rpm is None):
            raise PydanticCustomError(
                WORDED, "give exactly one of motor (the motion it gives) or "
                "mean_rpm (the steady state at that mean speed){extra}",
                {"extra": "" if self.motor is None else ", not both"})
        if self.mean_rpm is not None and (self.start is not None or self.until is not None):
            raise PydanticCustomError(
                WORDED, "with mean_rpm the steady state is found directly: start "
                "and until are not used (leave them out)")
        return self


class Design(_Model):
    """The design review's inputs."""

    speed_fluctuation: Positive = Field(None, description="Cs: enables "
                                                          "cycle.flywheel_inertia.")
    motor: Motor = Field(None, description="{rated_torque, peak_torque, rated_power}.")
    bearings: Annotated[dict[str, Bearing],
                        Refusal("must map joint names to {{rating, life_h}}",
                                ("dict_type",))] = Field(
        None, description="Joint name -> {rating, life_h}.")
    limits: Limits = Field(None, description="{joint_force, transmission_angle, "
                                             "shaking_force, efficiency}.")


class ReportUnits(_Model):
    """How reports show values (results.csv and summary.json stay SI)."""

    model_config = ConfigDict(title="report units")
    length: Literal[tuple(UNIT_TABLES["length"])] = Field(
        None, description="Default: the spec's units.length.")
    force: Literal[tuple(UNIT_TABLES["force"])] = Field(
        None, description="Default: the spec's units.force (N).")
    moment: Literal[tuple(UNIT_TABLES["moment"])] = Field(
        None, description="Default: the spec's units.moment (N*m).")
    mass: Literal[tuple(UNIT_TABLES["mass"])] = Field(None, description="Default kg.")
    stress: Literal[tuple(UNIT_TABLES["stress"])] = Field(
        None, description="Default MPa (format 1.2: also psi, ksi).")
    pressure: Literal[tuple(UNIT_TABLES["pressure"])] = Field(
        None, description="Pressures (format 1.2: Pa, kPa, bar, MPa, psi); default: as a "
                          "pressure load writes them.")


REPORT_TEXT_MAX = 200
#: one line of at most REPORT_TEXT_MAX characters (a number is read as its text), or nothing
ReportText = Optional[Annotated[
    Union[Annotated[str, Field(strict=True, max_length=REPORT_TEXT_MAX,
                               pattern=r"^\s*[^\n]*\s*$"), Tag("text")],
          Annotated[int, Field(strict=True), BeforeValidator(_whole_value), Tag("number")]],
    Discriminator(_text_tag), Wording("text"),
    Refusal("must be text, got {value} (quote it: '...')", ("string_type",))]]


class Report(_Model):
    """Display units, first-page metadata, animation and DXF export of the reports."""

    units: ReportUnits = Field(None, description="{length, force, moment, mass}.")
    title: ReportText = Field(None, description="First page and page header; default: the "
                                                "spec's name. One line, at most 200 "
                                                "characters.")
    project: ReportText = Field(None, description="First page and page header; one line.")
    author: ReportText = Field(None, description="First page and page header; one line.")
    revision: ReportText = Field(None, description="First page and page header; one line (a "
                                                   "number is read as its text).")
    animation: bool = Field(None, strict=True, description="animation.gif: the mechanism "
                                                          "moving over the sweep with its "
                                                          "joint reactions; default true for a "
                                                          "whole-turn sweep, else false.")
    dxf: bool = Field(False, strict=True, description="true writes mechanism.dxf: the "
                                                      "mechanism at each reference angle on "
                                                      "its own layer, in the spec's length "
                                                      "unit.")
    html: bool = Field(True, strict=True, description="report.html beside report.md (and "
                                                      "index.html beside index.md): the "
                                                      "report in a browser, offline, with "
                                                      "an angle slider moving the mechanism "
                                                      "and its forces.")


class Vary(_Model):
    """A varied leaf of the spec: {key, from, to, count} or {key, values}."""

    key: Name = Field(description="A key path into this spec, dots between keys, a list index "
                                  "as a number (links.rod.points.C.0).")
    from_: Number = Field(None, alias="from", description="One end of the range.")
    to: Number = Field(None, description="The other end of the range.")
    count: _whole(1, MAX_STUDY_VARIANTS) = Field(
        None, description="Grid values from `from` to `to`, both included (at least 2).")
    values: Annotated[list[Number],
                      Wording(f"a list of 1 to {MAX_STUDY_VARIANTS} numbers")] = Field(
        None, min_length=1, max_length=MAX_STUDY_VARIANTS,
        description="The values the key takes, instead of a range.")


def _cycle_pattern() -> str:
    """What :func:`mechreport.quantities.is_cycle` accepts, as a regular expression."""
    named = "|".join(re.escape(q) for q in CYCLE_UNITS)
    joint = "|".join(map(re.escape, JOINT_CYCLE_UNITS))
    member = "|".join(map(re.escape, MEMBER_UNITS))
    return (f"^(?:{named}|joint\\.[\\s\\S]+\\.(?:{joint})"
            f"|member\\.[\\s\\S]+\\.(?:{member}))$")


#: a quantity with one value per sweep (cycle.*, balance.*, joint.J.f_max, member.L.*)
CycleQuantity = Annotated[str, Field(strict=True, pattern=_cycle_pattern()),
                          Wording("a cycle quantity")]

#: in JSON Schema, what :meth:`Study._grid_ranges` checks
_GRID_RANGES = {
    "if": {"properties": {"sample": {"enum": ["random", "lhs"]}}, "required": ["sample"]},
    "else": {"properties": {"vary": {"items": {
        "if": {"anyOf": [{"required": ["from"]}, {"required": ["to"]}]},
        "then": {"properties": {"count": {"minimum": 2}}}}}}}}


class Study(_Model):
    """The variants `mechreport study` runs."""

    model_config = ConfigDict(json_schema_extra=_GRID_RANGES)

    vary: Annotated[list[Vary], Wording("a list of {key, from, to, count} or {key, "
                                        "values}")] = Field(
        min_length=1, description=(
            "a list of varied leaves, each `{key, from, to, count}` or `{key, values}`"))
    sample: Literal["grid", "random", "lhs"] = Field(
        "grid", description="`grid` (default), `random` or `lhs` (Latin hypercube)")
    count: Annotated[_whole(1, MAX_STUDY_VARIANTS), DocRequired("for `random` and `lhs`")] = Field(
        None, description=(
            "how many variants they draw, 1 to 1 000 000; `grid` does not use it (it may stay in "
            "the file when you switch to `grid`: the study says it is not used)"))
    seed: _whole(0, MAX_SEED) = Field(0, description=(
            "a whole number from 0 to 2^63 - 1, default 0: the same spec and seed always give the"
            " same variants"))
    keep: Annotated[list[CycleQuantity], Wording("a list of cycle quantities")] = Field(
        min_length=1, description="the cycle quantities to tabulate (below)")

    @model_validator(mode="after")
    def _grid_ranges(self):
        """A grid takes ``count`` values of a range, both ends included: at least 2."""
        if self.sample == "grid":
            for i, vary in enumerate(self.vary):
                if (vary.from_ is not None or vary.to is not None) and vary.count == 1:
                    raise PydanticCustomError(
                        "grid_range_count", "vary[{i}].count must be at least 2 for a range",
                        {"i": i})
        return self


#: in JSON Schema, what :meth:`TolVary._one_spread` checks
_ONE_SPREAD = {
    "oneOf": [{"required": ["tol"], "not": {"anyOf": [{"required": [k]}
                                                      for k in ("sigma", "from", "to")]}},
              {"required": ["sigma"], "not": {"anyOf": [{"required": [k]}
                                                        for k in ("tol", "from", "to")]},
               "properties": {"dist": {"const": "normal"}}},
              {"required": ["from", "to"], "not": {"anyOf": [{"required": [k]}
                                                             for k in ("tol", "sigma")]}}]}


class TolVary(_Model):
    """One uncertain leaf of the spec: {key, tol}, {key, sigma} or {key, from, to}, with
    `dist`."""

    model_config = ConfigDict(json_schema_extra=_ONE_SPREAD)

    key: Name = Field(description="A key path into this spec, as in `study.vary` "
                                  "(links.coupler.points.C.0).")
    tol: Positive = Field(None, description=(
        "Plus or minus this much about the spec's value, in the spec's unit of the key."))
    sigma: Positive = Field(None, description=(
        "The standard deviation of a normal distribution about the spec's value, in the "
        "spec's unit of the key."))
    from_: Number = Field(None, alias="from", description="One end of a range of values.")
    to: Number = Field(None, description="The other end of the range.")
    dist: Literal["uniform", "normal"] = Field(None, description=(
        "`uniform` (the default for `tol` and `from`/`to`) or `normal` (the default for "
        "`sigma`); a normal `tol` or range spans plus or minus 3 standard deviations about "
        "its middle."))

    @model_validator(mode="after")
    def _one_spread(self):
        """Exactly one of ``tol``, ``sigma`` and a ``from``/``to`` range; ``sigma`` is
        normal."""
        given = [k for k, v in (("tol", self.tol), ("sigma", self.sigma)) if v is not None]
        if self.from_ is not None or self.to is not None:
            given.append("from/to")
        if len(given) != 1:
            raise PydanticCustomError(
                WORDED, "give one of 'tol', 'sigma' or 'from' and 'to', got {got}",
                {"got": " and ".join(given) if given else "none"})
        if given == ["from/to"] and (self.from_ is None or self.to is None
                                     or self.from_ == self.to):
            raise PydanticCustomError(
                WORDED, "a range needs 'from' and 'to', two different numbers")
        if self.sigma is not None and self.dist == "uniform":
            raise PydanticCustomError(
                WORDED, "'sigma' is the standard deviation of a normal "
                "distribution; for a uniform one give 'tol' or 'from' and 'to'")
        return self


MAX_TOLERANCE_SAMPLES = 1_000_000


class Tolerances(_Model):
    """The samples `mechreport tolerance` draws."""

    vary: Annotated[list[TolVary], Wording("a list of {key, tol}, {key, sigma, dist: normal} "
                                           "or {key, from, to}")] = Field(
        min_length=1, description=(
            "the uncertain leaves, each `{key, tol}` (uniform, plus or minus `tol`), `{key, "
            "sigma, dist: normal}` or `{key, from, to}` (uniform over the range)"))
    count: _whole(2, MAX_TOLERANCE_SAMPLES) = Field(1000, description=(
        "how many samples, 2 to 1 000 000, default 1000"))
    sample: Literal["lhs", "random"] = Field(
        "lhs", description="`lhs` (Latin hypercube, the default) or `random`")
    seed: _whole(0, MAX_SEED) = Field(0, description=(
        "a whole number from 0 to 2^63 - 1, default 0: the same spec and seed always give the "
        "same samples"))
    keep: Annotated[list[CycleQuantity], Wording("a list of cycle quantities")] = Field(
        min_length=1, description="the cycle quantities to report (as `study.keep`)")
class OptimizeVary(_Model):
    """A varied leaf of an optimisation: {key, from, to} (format 1.2)."""

    model_config = ConfigDict(title="optimize vary")
    key: Name = Field(description="A key path into this spec, as in study.vary "
                                  "(links.coupler.points.C.0).")
    from_: Number = Field(alias="from", description="One end of the range, in the spec's "
                                                    "units.")
    to: Number = Field(description="The other end of the range.")


class OptimizeBound(_Model):
    """A bound on a cycle quantity that the optimum must keep (format 1.2)."""

    model_config = ConfigDict(title="optimize bound")
    quantity: CycleQuantity = Field(description="Any study.keep quantity (cycle.*, "
                                                "joint.J.*, member.L.*).")
    min: Number = Field(None, description="The smallest allowed value (SI, or in `unit`).")
    max: Number = Field(None, description="The largest allowed value (SI, or in `unit`).")
    unit: Literal[EXPECT_UNIT_NAMES] = Field(
        None, description="The unit min and max are written in (one of the quantity's kind).")

    @model_validator(mode="after")
    def _one_bound(self):
        if self.min is None and self.max is None:
            raise PydanticCustomError("bound_missing", "give 'min', 'max' or both")
        if self.min is not None and self.max is not None and self.min > self.max:
            raise PydanticCustomError("bound_order", "'min' must not exceed 'max'")
        return self


class Optimize(_Model):
    """The search `mechreport optimize` runs (format 1.2)."""

    vary: Annotated[list[OptimizeVary], Wording("a list of {key, from, to}")] = Field(
        min_length=1, description="the varied leaves, each `{key, from, to}` (key paths as in "
                                  "`study.vary`)")
    minimize: CycleQuantity = Field(None, description=(
        "the cycle quantity to make smallest (any `study.keep` quantity); or `maximize`"))
    maximize: CycleQuantity = Field(None, description=(
        "the cycle quantity to make largest; give exactly one of `minimize` and `maximize`"))
    subject_to: Annotated[list[Annotated[OptimizeBound, Refusal(
        "needs 'min', 'max' or both (min not above max), got {value}",
        ("bound_missing", "bound_order"))]],
                          Wording("a list of {quantity, min, max, unit}")] = Field(
        None, description=("bounds `{quantity, min, max, unit}` the optimum must keep, besides "
                           "every verdict of `design:`"))
    budget: _whole(10, MAX_STUDY_VARIANTS) = Field(1000, description=(
        "evaluations at most, 10 to 1 000 000 (default 1000)"))
    seed: _whole(0, MAX_SEED) = Field(0, description=(
        "a whole number from 0 to 2^63 - 1, default 0: the same spec and seed give the same "
        "search and the same optimum"))

    @model_validator(mode="after")
    def _one_objective(self):
        if (self.minimize is None) == (self.maximize is None):
            raise PydanticCustomError("objective", "give exactly one of 'minimize' and "
                                                   "'maximize'")
        return self
# ------------------------------------------------------------------- sheets (format 1.2)

MAX_SHEET_VARIANTS = 500


class SheetVary(_Model):
    """A varied datum of a problem's variants: {key, from, to, step} or {key, values}."""

    key: Name = Field(description="A key path into this spec, as in `study.vary` "
                                  "(links.crank.points.B.0).")
    from_: Number = Field(None, alias="from", description="One end of the range (spec units).")
    to: Number = Field(None, description="The other end of the range.")
    step: Positive = Field(None, description="The range's values are from, from + step, ... up "
                                             "to `to`; without it any value of the range.")
    values: Annotated[list[Number], Wording("a list of numbers")] = Field(
        None, min_length=1, max_length=MAX_STUDY_VARIANTS,
        description="The values the key takes, instead of a range.")

    @model_validator(mode="after")
    def _range_or_values(self):
        ranged = self.from_ is not None or self.to is not None or self.step is not None
        if (self.values is not None) == ranged:
            raise PydanticCustomError("vary_form", "give either 'values: [...]' or 'from', "
                                                   "'to' (and 'step'), not both or neither")
        if ranged and (self.from_ is None or self.to is None):
            raise PydanticCustomError("vary_range", "a range needs 'from' and 'to'")
        if ranged and self.from_ == self.to:
            raise PydanticCustomError("vary_range", "'to' equals 'from': for one value write "
                                                    "values: [x]")
        if self.key == "at" or self.key.startswith("at."):
            # the answers are taken at the sheet's angles, the spec's `at` as written: a
            # varied `at` printed one angle on the problem and keyed the answers at another
            raise PydanticCustomError(WORDED, "the sheet's angles (at) are not varied: every "
                                              "variant is asked at the spec's 'at'; vary the "
                                              "data", {"key": "key"})
        return self


class SheetRequire(_Model):
    """What every variant must meet at the sheet's angles (else it is redrawn)."""

    transmission_angle_min: Annotated[float, Field(strict=True, ge=0, le=90,
                                                   allow_inf_nan=False)] = Field(
        None, description="the smallest transmission angle allowed at the sheet's angles, "
                          "degrees (0 to 90)")


class SheetVariants(_Model):
    """One problem per student: the data varied, drawn from a seed."""

    vary: Annotated[list[Annotated[SheetVary, Refusal(
        "must be {{key, values: [...]}} or {{key, from, to}} (with 'step' or not), 'from' and "
        "'to' different, got {value}", ("vary_form", "vary_range"))]],
                    Wording("a list of {key, from, to, step} or {key, values}")] = Field(
        min_length=1, description="the varied data, each `{key, from, to, step}` or "
                                  "`{key, values}` (spec units)")
    count: _whole(1, MAX_SHEET_VARIANTS) = Field(30, description=(
        f"how many variants (1 to {MAX_SHEET_VARIANTS}, default 30); `mechreport build "
        "--variants N` overrides it"))
    seed: _whole(0, MAX_SEED) = Field(0, description=(
        "a whole number, default 0: the same spec and seed give the same variants "
        "(`--seed` overrides it)"))
    digits: _whole(2, 6) = Field(3, description=(
        "significant digits the varied data are printed with (2 to 6, default 3); the "
        "answers are computed from the printed data"))
    require: SheetRequire = Field(None, description=(
        "conditions every variant meets at the sheet's angles: `{transmission_angle_min: "
        "deg}`; a variant that fails is redrawn"))


class SheetSection(_Model):
    """The problem and solution sheets: on/off, the problem's own statement, variants."""

    enabled: bool = Field(True, strict=True, description=(
        "`false` keeps the sheets off unless `build --sheet` asks for them (default `true`: a "
        "`sheet:` mapping turns them on)"))
    statement: Annotated[str, Field(strict=True, min_length=1, max_length=20000),
                         Wording("text (Markdown)")] = Field(None, description=(
        "the problem sheet's own wording of the task (Markdown); default: a statement "
        "written from the data (the spec's `description` is never copied into a problem)"))
    variants: SheetVariants = Field(None, description=(
        "one problem per student: `{vary, count, seed, digits, require}`"))


def _sheet_tag(value: Any) -> str:
    """``sheet``: a mapping is the section, anything else the flag (true/false)."""
    return "mapping" if isinstance(value, dict) else "flag"


#: ``sheet: true`` / ``false`` or ``sheet: {enabled, statement, variants}``
SheetValue = Annotated[Union[Annotated[bool, Field(strict=True), Tag("flag")],
                             Annotated[SheetSection, Tag("mapping")]],
                       Discriminator(_sheet_tag), Wording("true, false or a mapping")]


class SpecFile(_Model):
    """A mechreport spec: one planar linkage (docs/spec.md)."""

    model_config = ConfigDict(title="mechreport spec")
    mechreport: Annotated[Literal[1, 1.1, 1.2], BeforeValidator(_not_true_or_false),
                          Refusal("format version must be 1, got {value} (or 1.1 or 1.2: the "
                                  "same format with its version 1.1 or 1.2 keys)")] = Field(
        description=(
            "format version: `1`, or `1.1` or `1.2` (the same format; a file using the version "
            "1.1 or 1.2 keys may say so)"))
    name: Label = Field(description="the mechanism's name, used in report titles")
    description: Annotated[Optional[Text],
                           Refusal("must be text (Markdown), got {value}")] = Field(None, description=(
            "Markdown text shown at the top of the report"))
    units: Optional[Units] = Field(None, description=(
            "`{length: m|cm|mm|in|ft, mass: kg|g|lb, force: N|lbf|kip, moment: N*m|N*mm|lbf*in|lbf*ft, "
            "inertia: kg*m^2|g*mm^2|lb*in^2|lb*ft^2}`, each defaulting to SI (m, kg, N, N*m, "
            "kg*m^2); any key may be left out"))
    gravity: Annotated[Pair, Wording("a pair [gx, gy] in m/s^2")] = Field(
        (0.0, -9.80665), description=(
            "`[gx, gy]` in m/s², default `[0, -9.80665]`; acts on every moving link at its centre"
            " of mass"))
    ground: Annotated[Optional[dict[str, Point]], DocRequired("no*"),
                      Wording("a mapping of point names to [x, y]")] = Field(
        None, description=(
            "named points of the frame, global coordinates (*needed for every joint with "
            "`ground`)"))
    links: Annotated[dict[str, Link],
                     Refusal("must be a mapping of link names to link definitions, got "
                             "{value}", ("dict_type",)),
                     Refusal("must be a mapping of link names to link definitions",
                             ("too_short",))] = Field(
        min_length=1, description="the moving links (section 4)")
    joints: Annotated[dict[str, Joint],
                      Refusal("must be a mapping of joint names to joint definitions, got "
                              "{value}", ("dict_type",)),
                      Refusal("must be a mapping of joint names to joint definitions",
                              ("too_short",))] = Field(
        min_length=1, description="the joints (section 5)")
    driver: Driver = Field(description="the driving crank and its speed (section 6)")
    cycle: Cycle = Field(360, description=(
            "crank degrees after which the loads repeat, a whole multiple of 360 (`720`: a "
            "four-stroke engine); default 360 (format 1.2)"))
    sweep: Optional[Sweep] = Field(None, description=(
            "crank angles to analyse, default one cycle: 0 to `cycle` by 1 degree"))
    at: Annotated[list[Number], Wording("a list of crank angles in degrees")] = Field(
        None, min_length=1, description="reference angles, default `[sweep.start]`")
    assembly: Annotated[Optional[dict[str, Point]],
                        Refusal("must map point names to rough [x, y], got {value}",
                                ("dict_type",))] = Field(
        None, description="hints that choose the assembly branch (section 7)")
    loads: Optional[Annotated[list[Load], Wording("a list of loads"),
                              Refusal("must be a list of loads ({{type: force|moment, link, "
                                      "...}}), got {value}", ("list_type",))]] = Field(
        None, description="external forces and moments (section 8)")
    materials: Annotated[dict[str, Material],
                         Refusal("must map material names to {{E, yield, endurance, "
                                 "ultimate}} (Pa)", ("dict_type", "too_short"))] = Field(
        None, min_length=1, description=(
            "named materials for the links' `material` (section 19, format 1.1)"))
    friction: dict[str, Friction] = Field(
        None, min_length=1, description=(
            "Coulomb friction in the joints, by joint name (section 8, format 1.1)"))
    dynamics: Dynamics = Field(None, description=(
            "the motion a motor and a flywheel give: motor, flywheel, start, until (section 18, "
            "format 1.1)"))
    expect: Optional[Annotated[list[Expectation], Wording("a list of {angle, quantity, value, "
                                                          "tol}")]] = Field(
        None, description="values the results must reproduce (section 9)")
    sheet: SheetValue = Field(False, description=(
            "`true` adds worked solution sheets to `mechreport build` (section 14); default "
            "`false`; or a mapping `{enabled, statement, variants}` (format 1.2, section 14)"))
    design: Design = Field(None, description="the design review's inputs (section 15)")
    report: Optional[Report] = Field(None, description=(
            "display units and first-page metadata of the reports (section 16)"))
    study: Study = Field(None, description=(
            "the variants `mechreport study` runs (section 17); every other command validates it "
            "and otherwise ignores it"))
    tolerances: Tolerances = Field(None, description=(
            "the manufacturing and parameter uncertainty `mechreport tolerance` samples "
            "(section 21, format 1.2); every other command validates it and otherwise ignores "
            "it"))

    @model_validator(mode="after")
    def _profiles_within_cycle(self):
        """A load's profile is given over one cycle: its angles lie in [0, cycle], and a
        point at exactly ``cycle`` closes the diagram, repeating the point at 0."""
        errors = []
        for i, load in enumerate(self.loads or ()):
            for j, (angle, value) in enumerate(getattr(load, "profile", None) or ()):
                loc = ("loads", i, "profile", j, 0)
                first = load.profile[0]
                if angle > self.cycle:
                    errors.append(InitErrorDetails(type=PydanticCustomError(
                        "profile_beyond_cycle", "lies beyond the cycle, {cycle} crank degrees "
                        "(a profile is given over one cycle and repeats every cycle)",
                        {"cycle": self.cycle}),
                        loc=loc, input=angle))
                elif angle == self.cycle and j > 0 and (first[0] != 0 or first[1] != value):
                    errors.append(InitErrorDetails(type=PydanticCustomError(
                        "profile_not_closed", f"a point at the cycle's end ({self.cycle} deg) "
                        "closes the profile: it must repeat the point at 0 (the first point "
                        f"is [{first[0]:g}, {first[1]:g}])"), loc=loc[:-1], input=[angle, value]))
        if errors:
            raise ValidationError.from_exception_data("SpecFile", errors)
        return self
    optimize: Annotated[Optimize, Refusal("needs exactly one of 'minimize' and 'maximize', "
                                          "got {value}", ("objective",))] = Field(None, description=(
            "the search `mechreport optimize` runs (format 1.2); every other command validates "
            "it and otherwise ignores it"))


# ------------------------------------------------------------------------- the key tables

def _key_of(name: str, field: FieldInfo) -> str:
    """The key a field is written as in a spec (``from`` for ``from_``)."""
    return field.alias or name


def keys_of(model: type[BaseModel]) -> tuple[str, ...]:
    """The keys a mapping of ``model`` may have, in the order they are declared."""
    return tuple(_key_of(n, f) for n, f in model.model_fields.items())


def required_of(model: type[BaseModel]) -> tuple[str, ...]:
    """The keys a mapping of ``model`` must have, in the order they are declared."""
    return tuple(_key_of(n, f) for n, f in model.model_fields.items() if f.is_required())


def choices_of(model: type[BaseModel], key: str) -> tuple:
    """The values an enumerated key of ``model`` may take (its Literal's, in order)."""
    field = next(f for n, f in model.model_fields.items() if _key_of(n, f) == key)
    return _literal_args(field.annotation)


def literal_values(annotation: Any) -> tuple:
    """The values of ``annotation`` if it is a Literal (an enumeration), else ()."""
    return typing.get_args(annotation) if typing.get_origin(annotation) is Literal else ()


def _literal_args(annotation: Any) -> tuple:
    """The values of the Literal in ``annotation`` (inside Optional or Annotated too)."""
    while True:
        origin = typing.get_origin(annotation)
        if origin is Literal:
            return typing.get_args(annotation)
        if origin is Annotated:
            annotation = typing.get_args(annotation)[0]
        elif origin is Union:
            annotation = next(a for a in typing.get_args(annotation) if a is not type(None))
        else:
            raise TypeError(f"{annotation!r} is not an enumeration")


# ----------------------------------------------------------------------------- validation

def shape_errors(data: Any) -> list[dict]:
    """pydantic's errors for a spec's data tree (``loc``, ``type``, ``input``, ``ctx``; none
    when its shape is right). The validator is built on the first call."""
    try:
        SpecFile.model_validate(data)
    except ValidationError as exc:
        return exc.errors(include_url=False)
    return []


@dataclass(frozen=True)
class Located:
    """Where a pydantic error ``loc`` points in the spec: the key ``path`` in the data (union
    tags left out), the model whose keys hold its last key (``owner``), and the type there
    (``annotation``, unwrapped) with its constraints and markers (``metadata``, those of the
    outermost declaration first: a point's wording before a pair's)."""

    path: tuple
    owner: type[BaseModel] | None
    annotation: Any
    metadata: tuple

    def marker(self, kind: type) -> Any:
        """The first metadata item of type ``kind`` (a Wording, a Discriminator ...)."""
        return next((m for m in self.metadata if isinstance(m, kind)), None)

    def refusal(self, kind: str) -> "Refusal | None":
        """The first :class:`Refusal` here whose message is the one for an error of type
        ``kind``."""
        return next((m for m in self.metadata if isinstance(m, Refusal) and m.says(kind)), None)

    def picker(self) -> Any:
        """The discriminator of the tagged union at this place (a :class:`ByKey`, a
        function), None if there is none."""
        found = self.marker(Discriminator)
        return found.discriminator if found is not None else None

    def is_model(self) -> bool:
        """Whether the value here is one of the models (a mapping of known keys)."""
        return isinstance(self.annotation, type) and issubclass(self.annotation, BaseModel)

    def constraint(self, name: str) -> Any:
        """A constraint's value (``ge``, ``le``, ``min_length`` ...), the tightest where
        several apply (a limit of 90 on a positive number); None when absent."""
        values = [getattr(m, name) for m in self.metadata if hasattr(m, name)]
        if not values:
            return None
        return max(values) if name in ("ge", "gt", "min_length") else min(values)


def _unwrap(annotation: Any, metadata: list) -> Any:
    """Strip Annotated and Optional, adding the metadata to ``metadata`` outermost first
    (typing flattens nested Annotated innermost first: they are taken in reverse)."""
    while True:
        origin = typing.get_origin(annotation)
        if origin is Annotated:
            args = typing.get_args(annotation)
            metadata.extend(reversed(_flat(args[1:])))
            annotation = args[0]
        elif origin is Union and type(None) in typing.get_args(annotation):
            members = [a for a in typing.get_args(annotation) if a is not type(None)]
            annotation = members[0] if len(members) == 1 else Union[tuple(members)]
        else:
            return annotation


def _flat(items) -> list:
    """Annotated metadata with FieldInfo objects opened into their constraints."""
    out = []
    for item in items:
        if isinstance(item, FieldInfo):
            out.extend(item.metadata)
        else:
            out.append(item)
    return out


def _member(annotation: Any, tag: Any) -> Any:
    """The member of a tagged union whose Tag is ``tag`` (None if none is)."""
    for member in typing.get_args(annotation):
        if typing.get_origin(member) is Annotated and any(
                isinstance(m, Tag) and m.tag == tag for m in typing.get_args(member)[1:]):
            return member
    return None


def locate(loc: tuple) -> Located:
    """Follow a pydantic error's ``loc`` through the models (see :class:`Located`)."""
    annotation: Any = SpecFile
    metadata: list = []
    path: list = []
    owner = None
    for part in loc:
        annotation = _unwrap(annotation, metadata)
        origin = typing.get_origin(annotation)
        if isinstance(annotation, type) and issubclass(annotation, BaseModel):
            owner = annotation
            path.append(part)
            field = next((f for n, f in annotation.model_fields.items()
                          if _key_of(n, f) == part), None)
            annotation = field.annotation if field is not None else None
            metadata = list(reversed(field.metadata)) if field is not None else []
            continue
        if origin is Union:
            member = _member(annotation, part)
            if member is not None:          # a union's tag: not a key of the data
                annotation = member
                continue
        path.append(part)
        args = typing.get_args(annotation)
        metadata = []
        if origin is dict:
            annotation = args[1]
        elif origin is list:
            annotation = args[0]
        elif origin is tuple and isinstance(part, int) and part < len(args):
            annotation = args[part]
        else:
            annotation = None               # beyond what the models describe
    metadata_list = list(metadata)
    annotation = _unwrap(annotation, metadata_list)
    return Located(tuple(path), owner, annotation, tuple(metadata_list))


# ---------------------------------------------------------------------------- JSON Schema

class _SpecSchema(GenerateJsonSchema):
    """Draft 2020-12 with ``$schema`` and ``$id``; no ``"default": null`` on keys that may
    not be null (an absent key is not a null one), and no titles made up from key names (an
    editor shows the key and its description)."""

    def field_title_should_be_set(self, schema) -> bool:
        return False

    def generate(self, schema, mode="validation"):
        out = super().generate(schema, mode=mode)
        shared: dict[str, dict] = {}
        out = _hoisted(out, shared)
        defs = dict(sorted({**out.pop("$defs", {}), **shared}.items()))
        head = {key: out.pop(key) for key in ("title", "description", "type") if key in out}
        return {"$schema": SCHEMA_DIALECT, "$id": SCHEMA_ID, **head, **out, "$defs": defs}

    def default_schema(self, schema):
        out = super().default_schema(schema)
        if out.get("default", 0) is None and not _nullable(out):
            del out["default"]
        return out


#: what stays where a shared type is used: what the key means, not what its value is
_USE_KEYWORDS = ("description", "default", "title", "examples")


def _hoisted(node: Any, shared: dict[str, dict]) -> Any:
    """``node`` with every schema marked by :func:`_shared` replaced by a ``$ref`` to its one
    copy in ``shared`` (inner ones first, so that a pair refers to the number)."""
    if isinstance(node, list):
        return [_hoisted(item, shared) for item in node]
    if not isinstance(node, dict):
        return node
    node = {key: _hoisted(value, shared) for key, value in node.items()}
    items = node.get("prefixItems")
    if items and "items" not in node and all(item == items[0] for item in items):
        # [x, y], [link, point]: two of one kind. ``items`` says so to tools that read only
        # draft-07 (YAML language servers); in 2020-12 it adds nothing (maxItems is 2).
        node["items"] = items[0]
    if _SHARED not in node:
        return node
    name, description = node.pop(_SHARED)
    body = {k: v for k, v in node.items() if k not in _USE_KEYWORDS}
    if shared.setdefault(name, {"description": description, **body}) != {
            "description": description, **body}:
        return node                  # constrained further where it is used: written out
    return {"$ref": f"#/$defs/{name}", **{k: v for k, v in node.items() if k in _USE_KEYWORDS}}


def _nullable(schema: dict) -> bool:
    return schema.get("type") == "null" or any(s.get("type") == "null"
                                               for s in schema.get("anyOf", ()))


@functools.cache
def _schema_text() -> str:
    """The JSON Schema as JSON text (built once; text, so that the cached value cannot be
    changed by a caller)."""
    return json.dumps(SpecFile.model_json_schema(schema_generator=_SpecSchema))


def json_schema() -> dict:
    """The JSON Schema of a spec file (a new dict each call)."""
    return json.loads(_schema_text())
