"""The spec schema (mechreport/spec/schema.py): pydantic models of a spec as written, the one
place the format's keys, types, enumerations and number ranges are declared.

- docs/spec.schema.json is what the models give (``mechreport schema``);
- the JSON Schema accepts every shipped spec and rejects the specs the loader rejects for
  their shape, pointing at the same place;
- the loader's key tables come from the models, and the models' own verdict reaches the user
  as ``file:line: key.path: message``, in the loader's wording, once per problem.

Specs are read with the loader's YAML reader (YAML 1.2, as a YAML language server reads
them): PyYAML's YAML 1.1 would read ``1e-3`` as text.
"""
from __future__ import annotations

import json
from pathlib import Path

import pytest

from mechreport.errors import SpecError
from mechreport.spec import loader, parse_spec
from mechreport.spec.schema import (SpecFile, json_schema, keys_of, required_of,
                                    shape_errors)
from mechreport.spec.yaml_source import Source, format_path

jsonschema = pytest.importorskip("jsonschema")

ROOT = Path(__file__).resolve().parents[2]
PUBLISHED = ROOT / "docs" / "spec.schema.json"
FILE = "specs/x.yaml"
SHIPPED = sorted([*(ROOT / "specs").glob("*.yaml"), *(ROOT / "tests" / "data").glob("*.yaml"),
                  *(ROOT / "tests" / "data" / "edge").glob("*.yaml")])

BASE = """\
mechreport: 1
name: slider-crank
units: {length: m, mass: kg}
gravity: [0, -10]
ground:
  A: [0, 0]
  O: [0, 0]
links:
  crank:
    points: {A: [0, 0], B: [1, 0]}
    mass: 1
    shape: {bar: {length: 1, height: 0.01, depth: 0.001}}
  rod:
    points: {B: [0, 0], C: [1, 0]}
    mass: 2
    shape: {bar: {length: 1, height: 0.01, depth: 0.001}}
  slider:
    points: {C: [0, 0]}
    mass: 3
    shape: {block: {width: 0.01, height: 0.01, depth: 0.001}}
joints:
  A: {type: R, links: [ground, crank]}
  B: {type: R, links: [crank, rod]}
  C: {type: R, links: [rod, slider]}
  C_T: {type: T, links: [ground, slider], point: C, line: {through: O, direction: 0}}
driver: {joint: A, rpm: 60}
sweep: {start: 0, stop: 360, step: 1}
at: [45]
assembly: {C: [1.4, 0]}
loads:
  - {type: force, link: slider, point: C, value: [100, 0], oppose: velocity}
expect:
  - {angle: 45, quantity: point.C.x, value: 1.4142136}
  - {angle: 45, quantity: link.rod.omega, value: -1}
"""

# Every section and every format 1.1 form at once: polar points, a three-link pin, a massless
# link, a point mass, friction, expectations with units, design, report and study.
EVERYTHING = BASE.replace("mechreport: 1\n", "mechreport: 1.1\n").replace(
    "  O: [0, 0]\n", "  O: {r: 0, angle: 90}\n").replace(
    "    mass: 3\n    shape: {block: {width: 0.01, height: 0.01, depth: 0.001}}\n",
    "    mass: 3\n    com: {r: 0, angle: 0}\n    inertia: 0\n").replace(
    "value: -1}", "value: -9.5493, unit: rpm, tol: 1e-3}") + """\
  - {quantity: cycle.torque.rms, value: 1, tol: 100}
friction:
  A: {mu: 0.05, radius: 0.01}
  C_T: {mu: 0.1, length: 0.02, friction_sense: 1}
sheet: false
description: |
  Every section of the format.
design:
  speed_fluctuation: 0.05
  motor: {rated_torque: 300, peak_torque: 600, rated_power: 5000}
  bearings:
    A: {rating: 40000, life_h: 20}
  limits: {joint_force: 1e6, transmission_angle: 10, shaking_force: 1e6, efficiency: 0.1}
report:
  units: {length: mm, force: kN, moment: N*m, mass: g}
  title: "Everything"
  project: P-1
  author: ~
  revision: 2
study:
  vary:
    - {key: links.rod.mass, from: 1, to: 3, count: 3}
    - {key: driver.rpm, values: [30, 60]}
  sample: grid
  seed: 1
  keep: [cycle.torque.rms, joint.B.f_max]
"""


def data_of(text: str):
    """The data tree of a spec text, read as the loader reads it."""
    return Source(FILE, text).data


@pytest.fixture(scope="module")
def validator():
    schema = json.loads(PUBLISHED.read_text(encoding="utf-8"))
    return jsonschema.Draft202012Validator(schema)


def edit(text: str, old: str, new: str) -> str:
    assert text.count(old) == 1, f"{old!r} occurs {text.count(old)} times"
    return text.replace(old, new)


def line_of(text: str, needle: str) -> int:
    """The number of the first line that starts with ``needle`` (after its indent) or, if
    none does, holds it."""
    lines = text.splitlines()
    return next((k for k, line in enumerate(lines, start=1) if line.lstrip().startswith(needle)),
                None) or next(k for k, line in enumerate(lines, start=1) if needle in line)


# -- the published schema ------------------------------------------------------------------

def test_docs_spec_schema_json_is_what_the_models_give():
    from mechreport.app.schema import schema_text
    assert PUBLISHED.read_text(encoding="utf-8") == schema_text(), (
        "docs/spec.schema.json is out of date: run "
        "`mechreport schema --output docs/spec.schema.json`")


def test_the_schema_is_draft_2020_12_with_an_id_and_a_title():
    schema = json_schema()
    jsonschema.Draft202012Validator.check_schema(schema)
    assert schema["$schema"] == "https://json-schema.org/draft/2020-12/schema"
    assert schema["$id"] and schema["title"]
    assert schema["additionalProperties"] is False
    assert schema["required"] == ["mechreport", "name", "links", "joints", "driver"]


def test_every_key_has_a_description_for_the_editor():
    """The descriptions are what an editor shows on hover."""
    schema = json_schema()
    missing = [f"{owner}.{key}" for owner, body in [("", schema), *schema["$defs"].items()]
               for key, prop in body.get("properties", {}).items()
               if not prop.get("description")]
    assert missing == []


def test_every_key_of_format_1_1_is_in_the_schema():
    """The version 1.1 additions, each where the format puts it."""
    schema = json_schema()
    props, defs = schema["properties"], schema["$defs"]
    assert {"friction", "dynamics", "materials"} <= set(props)
    assert {"section", "material", "members"} <= set(defs["Link"]["properties"])
    assert {"animation", "dxf", "html"} <= set(defs["Report"]["properties"])
    assert {"motor", "flywheel", "start", "until", "output_step"} <= set(
        defs["Dynamics"]["properties"])


def test_the_dynamics_keys_of_format_1_2_are_in_the_schema():
    """``mean_rpm`` beside ``motor``; a motor's ``ratio`` and ``efficiency``."""
    defs = json_schema()["$defs"]
    assert "mean_rpm" in defs["Dynamics"]["properties"]
    motors = [d for d in defs.values() if {"ratio", "efficiency"} <= set(d.get("properties", {}))]
    assert len(motors) == 3


# -- it accepts every spec the loader accepts ----------------------------------------------

@pytest.mark.parametrize("path", SHIPPED, ids=[p.stem for p in SHIPPED])
def test_the_json_schema_accepts_every_shipped_spec(path, validator):
    text = path.read_text(encoding="utf-8")
    parse_spec(text, str(path))                       # a valid spec ...
    errors = [f"{format_path(e.absolute_path)}: {e.message}"
              for e in validator.iter_errors(data_of(text))]
    assert errors == []                               # ... is valid for an editor too


def test_a_spec_with_every_section_is_valid_for_the_loader_and_the_schema(validator):
    spec = parse_spec(EVERYTHING, FILE)
    assert spec.study is not None and spec.design.bearings and spec.friction
    assert spec.report.units["force"] == "kN" and spec.link("slider").inertia == 0.0
    assert list(validator.iter_errors(data_of(EVERYTHING))) == []
    assert shape_errors(data_of(EVERYTHING)) == []


# -- it rejects what the loader rejects for its shape, at the same place --------------------

SHAPE_MISTAKES = [
    # unknown keys, at several levels
    ("gravity: [0, -10]", "gravty: [0, -10]", "gravty", "gravty"),
    ("    mass: 2\n", "    mass: 2\n    intertia: 0.1\n", "links.rod.intertia", "intertia"),
    ("{type: R, links: [crank, rod]}", "{type: R, links: [crank, rod], point: B}",
     "joints.B.point", "B: {type: R"),
    ("direction: 0}", "direction: 0, angle: 3}", "joints.C_T.line.angle", "C_T:"),
    ("{type: force, link", "{type: force, lnk: slider, link", "loads[0].lnk", "lnk"),
    ("value: -1}", "value: -1, tl: 0.1}", "expect[1].tl", "tl: 0.1"),
    ("rpm: 60}", "rpm: 60, torque: 2}", "driver.torque", "driver:"),
    ("step: 1}", "steps: 1}", "sweep.steps", "sweep:"),
    ("depth: 0.001}}\n  slider:", "depth: 0.001, width: 1}}\n  slider:",
     "links.rod.shape.bar.width", "width: 1}}"),
    ("B: [1, 0]}", "B: {r: 1, angle: 0, radius: 1}}", "links.crank.points.B.radius",
     "radius: 1"),
    ("at: [45]", "at: [45]\ndynamics: {}", "dynamics", "dynamics"),
    ("at: [45]", "at: [45]\nreport: {animaton: true}", "report.animaton", "animaton"),
    ("at: [45]", "at: [45]\ndesign: {motor: {rated_torqe: 3}}", "design.motor.rated_torqe",
     "design:"),
    ("at: [45]", "at: [45]\nstudy: {vary: [{key: driver.rpm, value: [1]}], "
                 "keep: [cycle.torque.rms]}", "study.vary[0].value", "study:"),
    # wrong types
    ("    mass: 2\n", "    mass: heavy\n", "links.rod.mass", "mass: heavy"),
    ("    mass: 2\n", "    mass: '2'\n", "links.rod.mass", "mass: '2'"),
    ("gravity: [0, -10]", "gravity: down", "gravity", "gravity:"),
    ("at: [45]", "at: 45", "at", "at:"),
    ("name: slider-crank", "name: 2024", "name", "name:"),
    ("at: [45]", "at: [45]\nsheet: yes", "sheet", "sheet:"),
    ("at: [45]", "at: [45]\nreport: {animation: yes}", "report.animation", "animation"),
    ("at: [45]", "at: [45]\nreport: {dxf: 1}", "report.dxf", "dxf"),
    ("at: [45]", "at: [45]\nreport: {html: 'no'}", "report.html", "html"),
    ("links: [crank, rod]", "links: [crank, 5]", "joints.B.links", "links: [crank, 5]"),
    ("points: {C: [0, 0]}", "points: [C]", "links.slider.points", "points: [C]"),
    ("B: [1, 0]}", "B: [1, 0, 0]}", "links.crank.points.B", "[1, 0, 0]"),
    # missing required keys
    ("name: slider-crank\n", "", "", None),
    ("driver: {joint: A, rpm: 60}\n", "", "", None),
    ("    points: {C: [0, 0]}\n", "", "links.slider", "  slider:"),
    (", line: {through: O, direction: 0}}", "}", "joints.C_T", "C_T:"),
    ("B: {type: R, links: [crank, rod]}", "B: {links: [crank, rod]}", "joints.B", "B: {links"),
    ("B: [1, 0]}", "B: {r: 1}}", "links.crank.points.B", "B: {r: 1}"),
    # enumerations
    ("B: {type: R,", "B: {type: Q,", "joints.B.type", "B: {type: Q"),
    ("{type: force, link", "{type: forse, link", "loads[0].type", "forse"),
    ("length: m,", "length: inch,", "units.length", "units:"),
    ("oppose: velocity", "oppose: always", "loads[0].oppose", "always"),
    ("mechreport: 1\n", "mechreport: 2\n", "mechreport", "mechreport:"),
    ("value: -1}", "value: -1, unit: furlong}", "expect[1].unit", "furlong"),
    ("at: [45]", "at: [45]\nreport: {units: {force: ton}}", "report.units.force", "report:"),
    # list lengths
    ("links: [ground, slider], point: C", "links: [ground, slider, rod], point: C",
     "joints.C_T.links", "C_T:"),
    ("links: [crank, rod]", "links: [crank]", "joints.B.links", "links: [crank]"),
    ("at: [45]", "at: []", "at", "at:"),
    # number ranges
    ("    mass: 2\n", "    mass: -2\n", "links.rod.mass", "mass: -2"),
    ("    mass: 2\n", "    density: -7850\n", "links.rod.density", "density:"),
    ("step: 1}", "step: 0}", "sweep.step", "sweep:"),
    ("{block: {width: 0.01,", "{block: {width: 0,", "links.slider.shape.block.width",
     "width: 0,"),
    ("rpm: 60}", "rpm: 1e160}", "driver.rpm", "driver:"),
    ("rpm: 60}", "rpm: .inf}", "driver.rpm", "driver:"),
    ("B: [1, 0]}", "B: {r: -1, angle: 0}}", "links.crank.points.B.r", "B: {r: -1"),
    ("at: [45]", "at: [45]\ndesign: {limits: {efficiency: 85}}", "design.limits.efficiency",
     "design:"),
]


@pytest.mark.parametrize("old, new, path, needle", SHAPE_MISTAKES,
                         ids=[f"{k}-{m[2] or 'top'}" for k, m in enumerate(SHAPE_MISTAKES)])
def test_a_shape_mistake_is_refused_by_the_loader_and_the_schema_at_its_key(
        old, new, path, needle, validator):
    text = edit(BASE, old, new)
    with pytest.raises(SpecError) as info:
        parse_spec(text, FILE)
    line = line_of(text, needle) if needle else 1
    assert any(p.path == path and p.line == line for p in info.value.problems), \
        "\n".join(map(str, info.value.problems))
    # an editor marks the key, or the mapping that holds it (unknown and missing keys)
    marked = [format_path(e.absolute_path) for e in validator.iter_errors(data_of(text))]
    assert marked, "the JSON Schema accepts it"
    assert any(path == m or path.startswith(m + ".") or path.startswith(m + "[") or m == ""
               for m in marked), marked
    # and the models, mapped to key paths, say so at the same key, around it or inside it
    shape = [format_path(loader._shape_problem(e)[0]) for e in shape_errors(data_of(text))]
    assert any(_related(path, s) for s in shape), shape


def _related(a: str, b: str) -> bool:
    """Whether key paths ``a`` and ``b`` are the same, or one holds the other."""
    def below(x, y):
        return y == "" or x.startswith(y + ".") or x.startswith(y + "[")
    return a == b or below(a, b) or below(b, a)


# -- the loader's key tables come from the models ------------------------------------------

def test_the_key_tables_are_the_models():
    """The loader holds no key table of its own: every key is declared by the models."""
    from mechreport.spec import schema
    assert not hasattr(loader, "TOP_KEYS") and not hasattr(loader, "LOAD_KEYS")
    assert required_of(SpecFile) == ("mechreport", "name", "links", "joints", "driver")
    assert keys_of(schema.Link) == ("points", "mass", "density", "com", "inertia", "shape",
                                    "section", "material", "members", "buckling")
    assert {t: keys_of(m) for t, m in (("R", schema.RJoint), ("T", schema.TJoint))} == {
        "R": ("type", "links"), "T": ("type", "links", "point", "line")}
    assert required_of(schema.SpringLoad) == ("type", "between", "stiffness", "free_length")
    assert keys_of(schema.Vary) == ("key", "from", "to", "count", "values")
    assert schema.choices_of(schema.Study, "sample") == ("grid", "random", "lhs")


# -- the models' verdict, in the loader's words --------------------------------------------

def test_a_nested_unknown_key_maps_to_file_line_and_key_path():
    """The models' own error (pydantic's loc, type and input), without the loader's hand
    checks, as the problem a user reads."""
    text = BASE + "design:\n  bearings:\n    A:\n      ratng: 4000\n"
    src = Source(FILE, text)
    ck = loader._Checker(src)
    loader._shape_check(src.data, ck)
    assert sorted(map(str, ck.problems)) == [
        f"{FILE}:{line_of(text, '    A:')}: design.bearings.A: missing required key 'rating'",
        f"{FILE}:{line_of(text, 'ratng')}: design.bearings.A.ratng: unknown key; did you mean "
        "'rating'?",
    ]


@pytest.mark.parametrize("old, new, path, message", [
    ("    mass: 2\n", "    density: '2'\n", "links.rod.density",
     "must be a positive number, got '2' (a quoted number is text: remove the quotes)"),
    ("name: slider-crank", "name: 2024", "name",
     "must be a name, got 2024 (quote a name that looks like a number, true/false or null)"),
    ("at: [45]", "at: [45]\nsheet: yes", "sheet",
     "must be true or false, got 'yes' (YAML 1.1 read yes/no/on/off as true/false; a spec "
     "does not: write true or false)"),
    ("B: {type: R,", "B: {type: Q,", "joints.B.type", "must be one of R, T, got 'Q'"),
    ("B: {type: R, links: [crank, rod]}", "B: {links: [crank, rod]}", "joints.B",
     "missing required key 'type' (R or T)"),
    ("length: m,", "length: inch,", "units.length", "must be one of m, cm, mm, in, ft, got 'inch'"),
    ("B: [1, 0]}", "B: [1, 0, 0]}", "links.crank.points.B",
     "must be a pair [x, y] or {r: R, angle: A}, got [1, 0, 0]"),
    ("{block: {width: 0.01,", "{block: {width: 0,", "links.slider.shape.block.width",
     "must be a positive number, got 0"),
    ("rpm: 60}", "rpm: 1e160}", "driver.rpm",
     "must be a number between -1e+20 and 1e+20 (nonzero magnitudes at least 1e-20), got "
     "1e+160"),
])
def test_the_models_errors_read_like_the_loaders(old, new, path, message):
    """Where the loader's checks and the models both see a problem, they say the same."""
    text = edit(BASE, old, new)
    mapped = {loader._shape_problem(e) for e in shape_errors(data_of(text))}
    keyed = {(format_path(p), m) for p, m in mapped}
    assert (path, message) in keyed, keyed
    with pytest.raises(SpecError) as info:
        parse_spec(text, FILE)
    assert [(p.path, p.message) for p in info.value.problems] == [(path, message)]


def test_what_the_checks_skip_the_models_still_report():
    """An expectation whose quantity names nothing is not looked at further by the loader;
    its other mistakes are reported too, all problems of the file at once."""
    text = edit(BASE, "quantity: link.rod.omega, value: -1}",
                "quantity: link.rod.speed, value: fast, tol: -1}")
    with pytest.raises(SpecError) as info:
        parse_spec(text, FILE)
    line = line_of(text, "link.rod.speed")
    assert [(p.line, p.path, p.message.split(",")[0]) for p in info.value.problems] == [
        (line, "expect[1].quantity", "'link.rod.speed': a link has angle"),
        (line, "expect[1].value", "must be a number"),
        (line, "expect[1].tol", "must be a positive number"),
    ]


def test_a_study_without_vary_still_has_its_other_keys_checked():
    text = BASE + "study: {sample: rand, keep: [cycle.torque.rms]}\n"
    with pytest.raises(SpecError) as info:
        parse_spec(text, FILE)
    assert [(p.path, p.message) for p in info.value.problems] == [
        ("study", "missing required key 'vary'"),
        ("study.sample", "must be one of grid, random, lhs, got 'rand'"),
    ]


def test_one_problem_is_reported_once():
    """The loader's checks and the models see the same mistakes: each is listed once, in the
    loader's wording (the models' problem at the same key path, or inside or around it, is
    left out)."""
    text = edit(BASE, "    mass: 2\n", "    mass: heavy\n    colour: red\n")
    text = edit(text, "links: [ground, slider], point: C", "links: [ground, slider, rod], "
                                                           "point: C")
    with pytest.raises(SpecError) as info:
        parse_spec(text, FILE)
    paths = [p.path for p in info.value.problems]
    assert paths == ["links.rod.mass", "links.rod.colour", "joints.C_T.links"]
    assert info.value.problems[0].message == "must be a positive number, got 'heavy'"


def test_a_spring_without_its_free_length_is_one_problem_not_an_internal_error():
    text = edit(BASE, "{type: force, link: slider, point: C, value: [100, 0], oppose: velocity}",
                "{type: spring, between: [[ground, O], [slider, C]], stiffness: 10}")
    with pytest.raises(SpecError) as info:
        parse_spec(text, FILE)
    assert [str(p) for p in info.value.problems] == [
        f"{FILE}:{line_of(text, 'type: spring')}: loads[0]: missing required key "
        "'free_length'"]


# -- the models are never stricter than the loader's checks, nor the JSON Schema -----------

@pytest.mark.slow
def test_the_models_and_the_json_schema_agree_with_the_loader_on_mutated_specs(validator):
    """Mutated shipped specs (tests/spec/test_fuzz_loader.py's mutations): what the loader's
    checks accept, the models and the JSON Schema accept; what the JSON Schema refuses, the
    loader refuses. (The JSON Schema may accept what the loader refuses for a reason that
    needs more than one value, such as a reference to a link that does not exist.)"""
    from hypothesis import HealthCheck, given, settings
    from hypothesis import strategies as st
    fuzz = pytest.importorskip("test_fuzz_loader")

    @settings(max_examples=300, deadline=None, derandomize=True,
              suppress_health_check=list(HealthCheck))
    @given(st.one_of(fuzz.mutated_specs(), fuzz.tweaked_specs()))
    def agree(case):
        name, done, text = case
        try:
            src = Source(FILE, text)
        except SpecError:                 # not even read (a character YAML forbids ...)
            return
        try:
            parse_spec(text, FILE)
            accepted = True
        except SpecError:
            accepted = False
        if accepted:
            assert shape_errors(src.data) == [], (name, done)
            assert list(validator.iter_errors(src.data)) == [], (name, done)
        if next(validator.iter_errors(src.data), None) is not None:
            with pytest.raises(SpecError):
                parse_spec(text, FILE)

    agree()


def test_a_value_of_the_wrong_type_gets_one_message_not_two():
    """'heavy' for a mass was refused twice: by its type, and by the range check's `not`
    ("'heavy' should not be valid under {'exclusiveMaximum': 1e-20, ...}")."""
    import jsonschema
    from mechreport.spec.yaml_source import Source
    schema = json.loads(PUBLISHED.read_text(encoding="utf-8"))
    text = (ROOT / "specs" / "four_bar.yaml").read_text(encoding="utf-8")
    text = text.replace("mass: 220", "mass: heavy", 1)
    assert "mass: heavy" in text
    errors = list(jsonschema.Draft202012Validator(schema).iter_errors(Source("x", text).data))
    assert [e.message for e in errors] == ["'heavy' is not of type 'number'"]
