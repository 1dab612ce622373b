"""The spec loader cannot be knocked over (issue 9).

Whatever the input, ``parse_spec`` / ``load_spec`` end in a ``Spec`` or in ``SpecError`` whose
every problem names the file: never a traceback, within a second and a few megabytes. Each
test is named after the hostile input it guards against; most edit one thing in ``BASE``
(the textbook 4.6 slider-crank, as in test_spec_errors.py).
"""
from __future__ import annotations

import os
import subprocess
import sys
import tracemalloc
from pathlib import Path

import pytest

from mechreport.errors import SpecError
from mechreport.spec import load_spec, parse_spec
from mechreport.spec import loader, yaml_source
from mechreport.spec.loader import MAX_DEPTH, MAX_FILE_BYTES, MAX_PROBLEMS, NUMBER_MAX, NUMBER_MIN
from mechreport.spec.yaml_source import Source

FILE = "specs/x.yaml"
ROOT = Path(__file__).resolve().parents[2]
SPECS = sorted((ROOT / "specs").glob("*.yaml")) + sorted((ROOT / "tests" / "data").glob("*.yaml"))

RANGE = "between -1e+20 and 1e+20 (nonzero magnitudes at least 1e-20)"
POSITIVE_RANGE = "between 1e-20 and 1e+20"

from test_spec_errors import BASE  # noqa: E402 - the textbook 4.6 spec, written out once

# "Billion laughs": 1.3 KB of YAML whose aliases expand to 9^9 strings (gigabytes).
ALIAS_BOMB = ('a: &a ["lol","lol","lol","lol","lol","lol","lol","lol","lol"]\n' + "".join(
    f"{b}: &{b} [{', '.join(['*' + a] * 9)}]\n" for a, b in zip("abcdefgh", "bcdefghi")))


# -- helpers -------------------------------------------------------------------------------

def edit(text: str, old: str, new: str) -> str:
    assert text.count(old) == 1, f"{old!r} occurs {text.count(old)} times"
    return text.replace(old, new)


def line_of(text: str, needle: str) -> int:
    hits = [k for k, line in enumerate(text.splitlines(), start=1) if needle in line]
    assert hits, f"{needle!r} not found"
    return hits[0]


def refused(text, filename: str = FILE) -> list:
    """The problems of ``text``; fails on any other exception or if it loads."""
    with pytest.raises(SpecError) as info:
        parse_spec(text, filename)
    found = info.value.problems
    assert found, "SpecError without problems"
    for p in found:
        assert p.file == filename, str(p)
        assert "internal error" not in p.message, str(p)
    return found


def only(text, filename: str = FILE):
    found = refused(text, filename)
    assert len(found) == 1, "expected one problem, got:\n" + "\n".join(map(str, found))
    return found[0]


def check(problem, line, path: str, *parts: str) -> None:
    assert problem.file == FILE
    assert problem.line == line, str(problem)
    assert problem.path == path, str(problem)
    for part in parts:
        assert part in problem.message, f"{part!r} not in {str(problem)!r}"


@pytest.fixture
def events(monkeypatch):
    """How many YAML events each reader took from its parser (one entry per Source): the
    work a hostile input costs, counted (timings are bench/bench_loader.py's)."""
    counts: list[int] = []
    base = yaml_source._CParser or yaml_source._PyParser

    class Counting:
        def __init__(self, text):
            self.parser = base(text)
            counts.append(0)

        def get_event(self):
            counts[-1] += 1
            return self.parser.get_event()

        def dispose(self):
            dispose = getattr(self.parser, "dispose", None)
            if dispose is not None:
                dispose()
    monkeypatch.setattr(yaml_source, "_CParser", Counting)
    return counts


def refused_within(text, events: list[int], at_most: int):
    """``text`` refused after reading at most ``at_most`` YAML events."""
    found = refused(text)
    assert events and events[-1] <= at_most, f"read {events[-1]} events"
    return found


def peak_memory_mb(fn) -> float:
    tracemalloc.start()
    try:
        fn()
    except SpecError:
        pass
    finally:
        peak = tracemalloc.get_traced_memory()[1]
        tracemalloc.stop()
    return peak / 2**20


def test_base_is_valid():
    parse_spec(BASE, FILE)


# -- size ----------------------------------------------------------------------------------

def test_huge_file_is_refused_before_reading(tmp_path, monkeypatch):
    # 48 MB took over 300 s; the size is checked (sparse file: nothing is written) first
    path = tmp_path / "huge.yaml"
    with open(path, "wb") as fh:
        fh.truncate(48 * 2**20)
    read = []
    real_open = open

    def counting_open(*args, **kwargs):
        fh = real_open(*args, **kwargs)
        real_read = fh.read

        def read_counted(size=-1):
            data = real_read(size)
            read.append(len(data))
            return data
        fh.read = read_counted
        return fh
    monkeypatch.setattr(loader, "open", counting_open, raising=False)
    with pytest.raises(SpecError) as info:
        load_spec(path)
    assert sum(read) == 0                                  # refused by its size alone
    (p,) = info.value.problems
    assert p.file == str(path) and p.line is None
    assert p.message == (f"the file is {48 * 2**20} bytes; a spec file may be at most "
                         f"{MAX_FILE_BYTES} bytes (128 KiB)")


def test_text_over_the_size_cap_is_refused():
    text = BASE + "#" * MAX_FILE_BYTES + "\n"
    p = only(text)
    assert p.line is None and f"a spec file may be at most {MAX_FILE_BYTES} bytes" in p.message
    p = only(text.encode("utf-8"))
    assert "a spec file may be at most" in p.message


def test_size_cap_counts_utf8_bytes():
    # fewer characters than the cap, more bytes: 3 bytes per character
    text = BASE + "# " + "\u20ac" * (MAX_FILE_BYTES // 3) + "\n"
    assert len(text) < MAX_FILE_BYTES < len(text.encode("utf-8"))
    assert "a spec file may be at most" in only(text).message


def test_spec_just_under_the_size_cap_loads():
    text = BASE + "#" * (MAX_FILE_BYTES - len(BASE) - 1) + "\n"
    assert len(text.encode("utf-8")) == MAX_FILE_BYTES
    assert parse_spec(text, FILE).name == "slider-crank"


@pytest.mark.skipif(not os.path.exists("/dev/zero"), reason="needs /dev/zero")
def test_endless_device_is_refused():
    # st_size is 0, but at most MAX_FILE_BYTES + 1 bytes are ever read
    with pytest.raises(SpecError) as info:
        load_spec("/dev/zero")
    (p,) = info.value.problems
    assert p.file == "/dev/zero" and "a spec file may be at most" in p.message


def test_directory_is_reported_not_raised(tmp_path):
    with pytest.raises(SpecError) as info:
        load_spec(tmp_path)
    (p,) = info.value.problems
    assert p.file == str(tmp_path) and p.message.startswith("cannot read file")


# -- aliases and anchors -------------------------------------------------------------------

def test_alias_bomb_is_refused_at_once_and_small(events):
    assert len(ALIAS_BOMB) < 1400
    p = refused_within(ALIAS_BOMB, events, 10)[0]           # at its first anchor
    assert (p.line, p.path) == (1, "a")
    assert "anchors and aliases (&name, *name) are not allowed" in p.message
    assert peak_memory_mb(lambda: parse_spec(ALIAS_BOMB, FILE)) < 5


@pytest.mark.parametrize("old, new, needle, path", [
    ("  O: [0, 0]\n", "  O: &origin [0, 0]\n", "&origin", "ground.O"),
    ("    points: {B: [0, 0], C: [1, 0]}\n", "    points: {B: [0, 0], C: [1, 0]}\n    com: *x\n",
     "*x", "links.rod.com"),
    ("  O: [0, 0]\n", "  O: [0, 0]\n  &k P: [1, 1]\n", "&k", "ground"),
], ids=["anchor", "undefined-alias", "anchored-key"])
def test_any_anchor_or_alias_is_refused(old, new, needle, path):
    text = edit(BASE, old, new)
    p = only(text)
    check(p, line_of(text, needle), path, "anchors and aliases (&name, *name) are not allowed",
          "write each value out in full")


def test_anchor_on_a_list_item_is_refused():
    text = edit(BASE, "at: [45]", "at: [&a 45]")
    p = only(text)
    check(p, line_of(text, "at: [&a"), "at[0]", "anchor '&a'")


def test_anchor_and_alias_in_a_valid_looking_spec_are_refused():
    text = edit(BASE, "shape: {bar: {length: 1, height: 0.01, depth: 0.001}}\n  rod:",
                "shape: &bar {bar: {length: 1, height: 0.01, depth: 0.001}}\n  rod:")
    text = edit(text, "    shape: {bar: {length: 1, height: 0.01, depth: 0.001}}\n  slider:",
                "    shape: *bar\n  slider:")
    assert "anchor '&bar'" in only(text).message


# -- nesting depth -------------------------------------------------------------------------

@pytest.mark.parametrize("text", [
    "a: " + "[" * 450 + "]" * 450 + "\n",
    "a: " + "{a: " * 450 + "1" + "}" * 450 + "\n",
    "".join("  " * k + "a:\n" for k in range(250)) + "  " * 250 + "1\n",   # 64 KB
    "- " * 450 + "1\n",
    "a: " + "[" * 100000 + "\n",                       # unclosed as well
], ids=["flow-lists", "flow-mappings", "block-mappings", "block-lists", "100k-unclosed"])
def test_deep_nesting_is_refused(text, events):
    p = refused_within(text, events, 3 * MAX_DEPTH)[0]       # at the level too deep
    assert p.message.startswith(f"nested more than {MAX_DEPTH} levels deep")
    assert p.line is not None


def test_nesting_up_to_the_cap_is_read():
    inner = "[" * (MAX_DEPTH - 1) + "1" + "]" * (MAX_DEPTH - 1)
    src = Source(FILE, f"a: {inner}\n")
    value, depth = src.data["a"], 1
    while isinstance(value, list):
        value, depth = value[0], depth + 1
    assert depth == MAX_DEPTH and value == 1


def test_nesting_beyond_the_cap_names_the_place():
    text = edit(BASE, "at: [45]", "at: " + "[" * 40 + "45" + "]" * 40)
    p = only(text)
    assert p.line == line_of(text, "at: [[[")
    assert p.path.startswith("at[0][0]")


# -- tags ----------------------------------------------------------------------------------

@pytest.mark.parametrize("value, shown", [
    ("!!python/name:os.system ''", "!!python/name:os.system"),
    ("!!python/object/apply:os.system ['echo hi']", "!!python/object/apply:os.system"),
    ("!!python/tuple [1, 2]", "!!python/tuple"),
    ("!custom 1", "!custom"),
    ("!<tag:example.com,2000:x> 1", "tag:example.com,2000:x"),
    ("!!binary aGVsbG8=", "!!binary"),
    ("!!timestamp 2001-12-14", "!!timestamp"),
    ("!!set {a, b}", "!!set"),
    ("!!omap [{a: 1}]", "!!omap"),
    ("!!map [1, 2]", "!!map"),
    ("!!seq {a: 1}", "!!seq"),
    ("!!str [1]", "!!str"),
], ids=lambda v: v if len(v) < 20 else v[:20])
def test_non_core_tags_are_refused(value, shown):
    text = edit(BASE, "omega: 1}", f"omega: {value}}}")
    p = only(text)
    check(p, line_of(text, "driver:"), "driver.omega", f"tag '{shown}' is not allowed",
          "needs no tags")


def test_tag_on_a_key_is_refused():
    text = edit(BASE, "  O: [0, 0]\n", "  O: [0, 0]\n  !!python/str P: [1, 1]\n")
    assert "tag '!!python/str' is not allowed" in only(text).message


def test_core_tags_keep_their_meaning():
    text = edit(BASE, "    mass: 2\n", "    mass: !!float 2\n")
    text = edit(text, "omega: 1}", "omega: !!int 1}")
    text = edit(text, "  O: [0, 0]\n", "  O: !!seq [0, 0]\n  !!str 7: !!seq [1, 1]\n")
    text = edit(text, "at: [45]", "at: [!!float 45]")
    spec = parse_spec(text, FILE)
    assert spec.link("rod").mass == 2.0
    assert spec.ground["7"] == (1.0, 1.0)
    assert spec.at == (45.0,)


@pytest.mark.parametrize("value", ["!!int abc", "!!int 1.5", "!!float x", "!!bool yes",
                                   "!!null 0"])
def test_core_tag_with_wrong_content_is_refused(value):
    text = edit(BASE, "omega: 1}", f"omega: {value}}}")
    p = only(text)
    check(p, line_of(text, "driver:"), "driver.omega", "is not a valid !!")


# -- text encoding -------------------------------------------------------------------------

def test_non_utf8_bytes_report_offset_and_line(tmp_path):
    data = BASE.encode() + b"name2: caf\xe9\n"
    offset = data.index(b"\xe9")
    for how in ("bytes", "file"):
        if how == "bytes":
            with pytest.raises(SpecError) as info:
                parse_spec(data, FILE)
            name = FILE
        else:
            path = tmp_path / "latin1.yaml"
            path.write_bytes(data)
            with pytest.raises(SpecError) as info:
                load_spec(path)
            name = str(path)
        (p,) = info.value.problems
        assert p.file == name
        assert p.line == BASE.count("\n") + 1
        assert p.message == (f"the file is not UTF-8 text: byte 0xe9 at offset {offset} cannot "
                             "be decoded; save the file as UTF-8")


def test_utf16_file_is_refused_with_a_hint():
    p = only(BASE.encode("utf-16"))
    assert "(it looks like UTF-16)" in p.message and "save the file as UTF-8" in p.message


def test_utf8_byte_order_mark_is_accepted(tmp_path):
    path = tmp_path / "bom.yaml"
    path.write_bytes(b"\xef\xbb\xbf" + BASE.encode())
    assert load_spec(path).name == "slider-crank"


@pytest.mark.parametrize("char, code", [("\x00", "U+0000"), ("\x07", "U+0007"),
                                        ("\x1b", "U+001B"), ("\ud800", "U+D800"),
                                        ("\uffff", "U+FFFF")])
def test_characters_yaml_forbids_are_refused_with_their_line(char, code):
    text = edit(BASE, "name: slider-crank", f"name: slider{char}crank")
    p = only(text)
    assert p.line == 2 and p.message.startswith(f"character {code} (")
    assert "is not allowed in YAML text" in p.message


@pytest.mark.parametrize("escape, code", [("\\x00", "U+0000"), ("\\ud800", "U+D800"),
                                          ("\\uFFFE", "U+FFFE"), ("\\x1b", "U+001B")])
def test_escaped_characters_yaml_forbids_are_refused(escape, code, monkeypatch):
    text = edit(BASE, "name: slider-crank", f'name: "slider{escape}crank"')
    for reader in ("libyaml", "python"):
        if reader == "python":
            monkeypatch.setattr(yaml_source, "_CParser", None)
        p = only(text)
        assert p.line == 2, str(p)
        # libyaml itself refuses a surrogate escape as malformed; otherwise the reader does
        assert (f"escaped character {code} is not allowed" in p.message
                or (reader == "libyaml" and "malformed YAML" in p.message)), str(p)


def test_non_text_input_is_a_spec_error():
    p = only(12345)
    assert "spec text must be str or bytes" in p.message


# -- numbers: range, overflow --------------------------------------------------------------

def test_range_constants():
    assert (NUMBER_MAX, NUMBER_MIN) == (1e20, 1e-20)
    assert loader.NUMBER_RANGE == RANGE


def test_rpm_1e160_is_out_of_range():
    text = edit(BASE, "omega: 1}", "rpm: 1e160}")
    p = only(text)
    assert str(p) == (f"{FILE}:{line_of(text, 'driver:')}: driver.rpm: must be a number "
                      f"{RANGE}, got 1e+160")


def test_shape_height_1e200_is_out_of_range():
    text = edit(BASE, "height: 0.01, depth: 0.001}}\n  rod:",
                "height: 1e200, depth: 0.001}}\n  rod:")
    p = only(text)
    check(p, line_of(text, "1e200"), "links.crank.shape.bar.height")
    assert p.message == f"must be a positive number {POSITIVE_RANGE}, got 1e+200"


@pytest.mark.parametrize("digits", [25, 400, 4000, 5000, 100000])
def test_integer_too_large_for_float_is_an_error(digits):
    # 400 digits overflowed int -> float; above 4300 Python refuses to convert at all
    text = edit(BASE, "    mass: 2\n", "    mass: " + "9" * digits + "\n")
    p = only(text)
    shown = "9" * 25 if digits == 25 else f"9.99e+{digits - 1}"
    check(p, line_of(text, "mass: 999"), "links.rod.mass",
          f"must be a positive number {POSITIVE_RANGE}, got {shown}")


def test_negative_huge_integer_in_a_vector():
    text = edit(BASE, "gravity: [0, -10]", "gravity: [0, -1" + "0" * 400 + "]")
    p = only(text)
    check(p, line_of(text, "gravity:"), "gravity[1]", f"must be a number {RANGE}, got -1.00e+400")


@pytest.mark.parametrize("old, new, path", [
    ("gravity: [0, -10]", "gravity: [0, -1e21]", "gravity[1]"),
    ("  O: [0, 0]", "  O: [0, 1e-21]", "ground.O[1]"),
    ("points: {A: [0, 0], B: [1, 0]}", "points: {A: [0, 0], B: [1e300, 0]}",
     "links.crank.points.B[0]"),
    ("    mass: 2\n", "    mass: 2\n    com: [-1e25, 0]\n    inertia: 1\n", "links.rod.com[0]"),
    ("    mass: 2\n", "    mass: 2\n    inertia: 1e-300\n", "links.rod.inertia"),
    ("    mass: 2\n", "    density: 1e21\n", "links.rod.density"),
    ("omega: 1}", "omega: 1, alpha: 1e308}", "driver.alpha"),
    ("omega: 1}", "omega: -1e-320}", "driver.omega"),
    ("sweep: {start: 0,", "sweep: {start: -1e30,", "sweep.start"),
    ("at: [45]", "at: [45, 1e25]", "at[1]"),
    ("direction: 0}", "direction: 1e21}", "joints.C_T.line.direction"),
    ("direction: 0}", "direction: [1, 1e-25]}", "joints.C_T.line.direction[1]"),
    ("through: O,", "through: [0, 1e99],", "joints.C_T.line.through[1]"),
    ("assembly: {C: [1.4, 0]}", "assembly: {C: [1.4e22, 0]}", "assembly.C[0]"),
    ("value: [100, 0], oppose", "value: [1e21, 0], oppose", "loads[0].value[0]"),
    ("value: [100, 0], oppose: velocity", "direction: [1, 0], profile: [[0, 1e30]]",
     "loads[0].profile[0][1]"),
    ("value: 1.4142136}", "value: 1e40}", "expect[0].value"),
    ("value: -1}", "value: -1, tol: 1e-30}", "expect[1].tol"),
])
def test_numbers_out_of_range_everywhere(old, new, path):
    text = edit(BASE, old, new)
    p = only(text)
    assert p.path == path, str(p)
    assert p.line is not None
    assert (RANGE in p.message or POSITIVE_RANGE in p.message), str(p)


@pytest.mark.parametrize("value, shown", [(".inf", "inf"), ("-.inf", "-inf"), (".NaN", "nan"),
                                          ("1e400", "inf"), ("-1e999", "-inf")])
def test_infinite_and_nan_are_refused(value, shown):
    text = edit(BASE, "gravity: [0, -10]", f"gravity: [0, {value}]")
    p = only(text)
    check(p, line_of(text, "gravity:"), "gravity[1]", f"must be a number {RANGE}, got {shown}")


def test_numbers_at_the_limits_are_accepted():
    text = edit(BASE, "gravity: [0, -10]", "gravity: [-0.0, -1e20]")
    text = edit(text, "value: [100, 0], oppose", "value: [1e20, 1e-20], oppose")
    text = edit(text, "    mass: 2\n", "    mass: 2\n    com: [0.5, -1e-20]\n")
    spec = parse_spec(text, FILE)
    assert spec.gravity == (0.0, -1e20)
    assert spec.loads[0].value == (1e20, 1e-20)


def test_range_is_checked_in_si_units_too():
    text = edit(BASE, "units: {length: m, mass: kg}", "units: {length: mm, mass: g}")
    text = edit(text, "points: {A: [0, 0], B: [1, 0]}", "points: {A: [0, 0], B: [1e-20, 0]}")
    text = edit(text, "    mass: 3\n", "    mass: 1e-19\n")
    found = refused(text)
    assert [(p.path, p.message) for p in found] == [
        ("links.crank.points.B[0]", f"1e-20 mm is 1e-23 in SI units; numbers must lie {RANGE} "
                                    "in SI units too"),
        ("links.slider.mass", f"1e-19 g is 1e-22 in SI units; numbers must lie {RANGE} in SI "
                              "units too"),
    ]


def test_rpm_is_checked_as_rad_per_s_too():
    text = edit(BASE, "omega: 1}", "rpm: 1e-20}")
    p = only(text)
    check(p, line_of(text, "driver:"), "driver.rpm", "1e-20 rpm is 1.0472e-21 rad/s", RANGE)


def test_mass_and_inertia_derived_from_a_shape_stay_in_range():
    text = edit(BASE, "    mass: 2\n    shape: {bar: {length: 1, height: 0.01, depth: 0.001}}",
                "    density: 1e20\n    shape: {bar: {length: 1e20, height: 1e20, depth: 1}}")
    p = only(text)
    check(p, line_of(text, "density:"), "links.rod.density",
          "density x shape volume gives a mass of 1e+60 kg", RANGE)
    text = edit(BASE, "    mass: 2\n    shape: {bar: {length: 1, height: 0.01, depth: 0.001}}",
                "    mass: 1e10\n    shape: {bar: {length: 1e10, height: 1, depth: 1}}")
    p = only(text)
    check(p, line_of(text, "shape: {bar: {length: 1e10"), "links.rod.shape",
          "the shape gives an inertia of 8.33333e+28 kg m^2", RANGE)


# -- YAML 1.1 surprises --------------------------------------------------------------------

def test_sexagesimal_is_text_not_600():
    text = edit(BASE, "omega: 1}", "rpm: 10:00}")
    p = only(text)
    check(p, line_of(text, "driver:"), "driver.rpm", "must be a number, got '10:00'",
          "base-60")


@pytest.mark.parametrize("word", ["yes", "no", "on", "off", "Yes", "OFF", "y", "n"])
def test_yes_no_on_off_are_not_numbers(word):
    text = edit(BASE, "    mass: 2\n", f"    mass: {word}\n")
    p = only(text)
    check(p, line_of(text, f"mass: {word}"), "links.rod.mass",
          f"must be a positive number, got '{word}'", "not true/false")


@pytest.mark.parametrize("word", ["yes", "no", "on", "off"])
def test_sheet_yes_says_use_true_or_false(word):
    text = BASE + f"sheet: {word}\n"
    p = only(text)
    check(p, line_of(text, "sheet:"), "sheet", f"must be true or false, got '{word}'",
          "write true or false")


@pytest.mark.parametrize("word, value", [("true", True), ("True", True), ("FALSE", False)])
def test_true_and_false_are_booleans(word, value):
    assert parse_spec(BASE + f"sheet: {word}\n", FILE).sheet is value


@pytest.mark.parametrize("key, shown", [("~", "'~' reads as null"), ("null", "'null' reads as null"),
                                        ("NULL", "'NULL' reads as null")])
def test_null_key_is_refused_not_named_none(key, shown):
    text = edit(BASE, "  O: [0, 0]\n", f"  O: [0, 0]\n  {key}: [1, 1]\n")
    p = only(text)
    check(p, line_of(text, f"{key}: [1, 1]"), "ground", f"keys must be names; {shown}")


def test_empty_key_is_refused():
    text = edit(BASE, "  O: [0, 0]\n", "  O: [0, 0]\n  ? \n  : [1, 1]\n")
    assert "keys must be names; an empty key reads as null" in only(text).message


@pytest.mark.parametrize("key, kind", [("1", "a number"), ("2.5", "a number"), ("0x1F", "a number"),
                                       ("true", "true/false"), ("False", "true/false")])
def test_number_and_boolean_keys_are_refused(key, kind):
    text = edit(BASE, "  O: [0, 0]\n", f"  O: [0, 0]\n  {key}: [1, 1]\n")
    p = only(text)
    check(p, line_of(text, f"  {key}: [1, 1]"), "ground",
          f"keys must be names; {key} reads as {kind}: quote it ('{key}') if it is a name")


def test_quoted_number_key_is_a_name():
    text = edit(BASE, "  O: [0, 0]\n", "  O: [0, 0]\n  '1': [1, 1]\n")
    assert parse_spec(text, FILE).ground["1"] == (1.0, 1.0)


@pytest.mark.parametrize("name", ["yes", "no", "on", "off", "y", "n", "Yes"])
def test_yaml11_boolean_words_are_plain_names(name):
    # a ground point named `on` is the name 'on', not True
    text = BASE.replace("  O: [0, 0]", f"  {name}: [0, 0]").replace("through: O,",
                                                                    f"through: {name},")
    spec = parse_spec(text, FILE)
    assert name in spec.ground
    assert spec.joint("C_T").line.through_name == name


@pytest.mark.parametrize("written, hint", [
    ("'2'", "a quoted number is text: remove the quotes"),
    ('"1e-3"', "a quoted number is text: remove the quotes"),
    ("1_000", "write numbers without '_'"),
    ("2001-12-14", ""),
    ("=", ""),
])
def test_text_where_a_number_is_expected(written, hint):
    text = edit(BASE, "    mass: 2\n", f"    mass: {written}\n")
    p = only(text)
    assert p.path == "links.rod.mass" and p.message.startswith("must be a positive number, got")
    assert hint in p.message


@pytest.mark.parametrize("written, value", [
    ("010", 10.0), ("1e-3", 0.001), ("1E3", 1000.0), ("+2e0", 2.0), (".5", 0.5), ("5.", 5.0),
    ("0x10", 16.0), ("0o10", 8.0), ("-0", 0.0),
])
def test_yaml12_number_forms(written, value):
    text = edit(BASE, "gravity: [0, -10]", f"gravity: [{written}, -10]")
    assert parse_spec(text, FILE).gravity[0] == value


def test_second_document_is_refused():
    text = BASE + "---\nmechreport: 1\n"
    p = only(text)
    assert p.line == line_of(text, "---") and "one YAML document" in p.message


# -- values of the wrong type where a name is expected -------------------------------------

@pytest.mark.parametrize("old, new, path, expected", [
    ("link: slider, point: C", "link: {}, point: C", "loads[0].link", "must be a name, got {}"),
    ("link: slider, point: C", "link: [slider], point: C", "loads[0].link", "must be a name"),
    ("link: slider, point: C", "link: slider, point: {C: 1}", "loads[0].point", "must be a name"),
    ("link: slider, point: C", "link: slider, point: 7", "loads[0].point",
     "must be a name, got 7 (quote a name"),
    ("{type: force, link", "{type: [force], link", "loads[0].type", "must be one of force, moment"),
    ("oppose: velocity", "oppose: {a: 1}", "loads[0].oppose", "must be one of velocity"),
    ("driver: {joint: A,", "driver: {joint: {A: 1},", "driver.joint", "must be a name"),
    ("driver: {joint: A,", "driver: {joint: [A],", "driver.joint", "must be a name"),
    ("driver: {joint: A,", "driver: {joint: ~,", "driver.joint", "must be a name, got null"),
    ("links: [crank, rod]", "links: [crank, {rod: 1}]", "joints.B.links", "two link names"),
    ("links: [crank, rod]", "links: [crank, 5]", "joints.B.links", "quote a name"),
    ("B: {type: R,", "B: {type: {R: 1},", "joints.B.type", "must be one of R, T"),
    ("point: C, line:", "point: [C], line:", "joints.C_T.point", "must be a name"),
    ("through: O,", "through: {O: 1},", "joints.C_T.line.through", "[x, y], a point name or {r: R, angle: A}"),
    ("direction: 0}", "direction: {x: 1}}", "joints.C_T.line.direction", "must be a number"),
    ("line: {through: O, direction: 0}", "line: [O, 0]", "joints.C_T.line", "must be a mapping"),
    ("line: {through: O, direction: 0}", "line: ~", "joints.C_T.line", "got null"),
    ("quantity: link.rod.omega", "quantity: {a: 1}", "expect[1].quantity",
     "must be a quantity name"),
    ("quantity: link.rod.omega", "quantity: [link, rod]", "expect[1].quantity",
     "must be a quantity name"),
    ("units: {length: m,", "units: {length: [m],", "units.length", "must be one of m, cm, mm"),
    ("mass: kg}", "mass: {kg: 1}}", "units.mass", "must be one of kg, g"),
    ("name: slider-crank", "name: {a: 1}", "name", "must be a name"),
    ("name: slider-crank", "name: 2024", "name", "quote a name"),
    ("name: slider-crank", "name: slider-crank\ndescription: [a]", "description", "must be text"),
    ("name: slider-crank", "name: slider-crank\ndescription: 0", "description", "must be text"),
    ("mechreport: 1", "mechreport: {a: 1}", "mechreport", "format version must be 1"),
    # 1.0 is the number 1 (in JSON too, as the published schema sees it): the same version
    ("mechreport: 1", "mechreport: 2.0", "mechreport", "format version must be 1, got 2.0"),
    ("mechreport: 1", "mechreport: true", "mechreport", "format version must be 1, got true"),
    ("shape: {block: {width: 0.01,", "shape: {block: [0.01,", None, None),
    ("assembly: {C: [1.4, 0]}", "assembly: [C, 1.4]", "assembly", "must map point names"),
    ("at: [45]", "at: {a: 45}", "at", "must be a list of crank angles"),
    ("sweep: {start: 0, stop: 360, step: 1}", "sweep: [0, 360]", "sweep", "must be a mapping"),
    ("gravity: [0, -10]", "gravity: {x: 0, y: -10}", "gravity", "must be a pair"),
    ("points: {C: [0, 0]}", "points: [C]", "links.slider.points", "must map at least one point"),
    ("points: {C: [0, 0]}", "points: {C: {x: 0}}", "links.slider.points.C", "must be a pair"),
])
def test_wrong_type_where_a_name_or_value_is_expected(old, new, path, expected):
    text = edit(BASE, old, new)
    found = refused(text)
    if path is None:   # malformed YAML or several follow-ons: only "no traceback" is asserted
        return
    assert any(p.path == path and expected in p.message for p in found), \
        "\n".join(map(str, found))


@pytest.mark.parametrize("section", ["links", "joints", "driver", "name"])
def test_required_section_given_as_null(section):
    lines = BASE.splitlines(keepends=True)
    start = next(k for k, l in enumerate(lines) if l.startswith(section + ":"))
    end = next((k for k in range(start + 1, len(lines)) if not lines[k].startswith(" ")),
               len(lines))
    text = "".join(lines[:start] + [f"{section}: ~\n"] + lines[end:])
    found = refused(text)
    assert any(p.path == section and "got null" in p.message for p in found), \
        "\n".join(map(str, found))


@pytest.mark.parametrize("text, path", [
    ("? [a, b]\n: 1\n", ""),
    ("? {a: 1}\n: 1\n", ""),
    (BASE.replace("  O: [0, 0]\n", "  O: [0, 0]\n  [P, Q]: [1, 1]\n"), "ground"),
    (BASE.replace("points: {C: [0, 0]}", "points: {[C]: [0, 0]}"), "links.slider.points"),
], ids=["top-list-key", "top-map-key", "ground-list-key", "points-list-key"])
def test_key_that_is_a_list_or_mapping(text, path):
    found = refused(text)
    assert any(p.path == path and "keys must be plain names" in p.message for p in found), \
        "\n".join(map(str, found))


def test_scalar_documents_are_refused():
    for text in ("42\n", "'text'\n", "[1, 2]\n", "~\n", "---\n", "# only a comment\n", "\n"):
        p = refused(text)[0]
        assert p.message.startswith(("must be a mapping", "the file is empty")), str(p)


# -- zero-length links ---------------------------------------------------------------------

def test_zero_length_rr_link():
    text = edit(BASE, "points: {B: [0, 0], C: [1, 0]}", "points: {B: [0.5, 0], C: [0.5, 0]}")
    p = only(text)
    assert str(p) == (f"{FILE}:{line_of(text, 'points: {B: [0.5')}: links.rod.points.C: link "
                      "'rod' has zero length: its joint points 'B' and 'C' are at the same "
                      "place; a link's pins must be apart (did you mean another coordinate?)")


def test_zero_length_crank():
    text = edit(BASE, "points: {A: [0, 0], B: [1, 0]}", "points: {A: [0, 0], B: [0, 0.0]}")
    p = only(text)
    check(p, line_of(text, "points: {A: [0, 0], B"), "links.crank.points.B",
          "link 'crank' has zero length: its joint points 'A' and 'B'")


def test_zero_length_in_other_units():
    text = edit(BASE, "units: {length: m, mass: kg}", "units: {length: mm, mass: kg}")
    text = edit(text, "points: {A: [0, 0], B: [1, 0]}", "points: {A: [3, 4], B: [3, 4]}")
    assert "link 'crank' has zero length" in only(text).message


def test_pins_may_coincide_when_another_pin_is_elsewhere():
    # a compound hinge: arm is pinned to rod at B2, on top of B; rod still has C elsewhere
    text = edit(BASE, "points: {B: [0, 0], C: [1, 0]}",
                "points: {B: [0, 0], C: [1, 0], B2: [0, 0]}")
    text = edit(text, "joints:\n", "  arm:\n    points: {B2: [0, 0], D: [1, 0]}\n    mass: 1\n"
                                   "    com: [0.5, 0]\n    inertia: 0.1\n"
                                   "  lever:\n    points: {D: [0, 0], E: [1, 0]}\n    mass: 1\n"
                                   "    com: [0.5, 0]\n    inertia: 0.1\njoints:\n")
    text = edit(text, "  O: [0, 0]\n", "  O: [0, 0]\n  E: [1, 2]\n")
    text = edit(text, "driver:", "  B2: {type: R, links: [rod, arm]}\n"
                                 "  D: {type: R, links: [arm, lever]}\n"
                                 "  E: {type: R, links: [lever, ground]}\ndriver:")
    spec = parse_spec(text, FILE)
    assert spec.link("rod").points["B2"] == spec.link("rod").points["B"]


def test_slider_point_may_sit_on_the_pin():
    # a block's pin and its sliding point are one place: that is not a zero-length link
    text = edit(BASE, "points: {C: [0, 0]}", "points: {C: [0, 0], S: [0, 0]}")
    text = edit(text, "point: C, line:", "point: S, line:")
    parse_spec(text, FILE)


# -- many problems, speed, memory ----------------------------------------------------------

def test_problem_list_is_capped():
    text = edit(BASE, "at: [45]", "at: [" + ", ".join(["x"] * 5000) + "]")
    found = refused(text)
    assert len(found) == MAX_PROBLEMS + 1
    assert found[-1].line is None
    assert found[-1].message == (f"... and {5000 - MAX_PROBLEMS} more problem(s); only the first "
                                 f"{MAX_PROBLEMS} are listed")


def _fill(prefix: str, item: str, suffix: str) -> str:
    room = MAX_FILE_BYTES - len(prefix.encode()) - len(suffix.encode())
    return prefix + item * (room // len(item.encode())) + suffix


WORST_CASES = {
    "list-of-bad-numbers": _fill(edit(BASE, "at: [45]\n", "") + "at: [", "x,", "x]\n"),
    "list-of-numbers": _fill(edit(BASE, "at: [45]\n", "") + "at: [", "1,", "1]\n"),
    "duplicate-keys": _fill(edit(BASE, "assembly: {C: [1.4, 0]}\n", "") + "assembly:\n",
                            "  C: [1.4, 0]\n", ""),
    "number-keys": _fill(BASE, "0: 1\n", ""),
    "unknown-keys": _fill(BASE + "x:\n", "  a: 1\n", ""),
    "long-text": _fill(BASE + "description: ", "x", "\n"),
    "long-quoted-text": _fill(BASE + 'description: "', "\\t", '"\n'),
}


@pytest.mark.slow
@pytest.mark.parametrize("name", list(WORST_CASES))
def test_worst_case_input_at_the_size_cap_costs_one_event_per_byte_at_most(name, events):
    """The reader's work grows with the file, not faster: at most one YAML event per byte,
    every problem from the loader's own checks, at most MAX_PROBLEMS listed (the time it
    takes is bench/bench_loader.py's)."""
    text = WORST_CASES[name]
    size = len(text.encode())
    assert MAX_FILE_BYTES - 100 < size <= MAX_FILE_BYTES
    try:
        parse_spec(text, FILE)
    except SpecError as exc:
        assert all(p.file == FILE and "internal error" not in p.message for p in exc.problems)
        assert len(exc.problems) <= MAX_PROBLEMS + 1         # (+ "and N more")
    assert events and max(events) <= size


@pytest.mark.slow       # traces every allocation: seconds
@pytest.mark.parametrize("name", ["list-of-bad-numbers", "list-of-numbers"])
def test_worst_case_input_at_the_size_cap_needs_little_memory(name):
    # the most values per byte; measured peak about 20 MB (the cap is 200 MB)
    assert peak_memory_mb(lambda: parse_spec(WORST_CASES[name], FILE)) < 200


@pytest.mark.parametrize("path", SPECS, ids=[p.stem for p in SPECS])
def test_libyaml_and_pure_python_readers_agree(path, monkeypatch):
    text = path.read_text(encoding="utf-8")
    fast = Source(str(path), text)
    monkeypatch.setattr(yaml_source, "_CParser", None)
    slow = Source(str(path), text)
    assert fast.data == slow.data
    assert fast.lines == slow.lines and fast.lines
    assert fast.lines[("driver",)] == line_of(text, "driver:")


@pytest.mark.parametrize("text", [
    BASE.replace("    mass: 2\n", "    mass: 2: kg\n"),
    BASE.replace("    mass: 2\n", "\tmass: 2\n"),
    BASE.replace("name: slider-crank", 'name: "a\\qb"'),
    BASE.replace("at: [45]", "at: [45"),
    ALIAS_BOMB,
], ids=["mapping-value", "tab", "escape", "unclosed", "alias-bomb"])
def test_libyaml_and_pure_python_readers_refuse_alike(text, monkeypatch):
    fast = refused(text)
    monkeypatch.setattr(yaml_source, "_CParser", None)
    slow = refused(text)
    assert [(p.line, p.path) for p in fast] == [(p.line, p.path) for p in slow]
    assert fast[0].message.split(":")[0] == slow[0].message.split(":")[0]


# -- the last line of defence --------------------------------------------------------------

def test_an_unexpected_exception_becomes_a_spec_error(monkeypatch):
    def broken(data, ck):
        raise KeyError("boom")
    monkeypatch.setattr(loader, "_build", broken)
    with pytest.raises(SpecError) as info:
        parse_spec(BASE, FILE)
    (p,) = info.value.problems
    assert p.file == FILE and p.message.startswith("internal error while loading the spec "
                                                   "(KeyError: 'boom')")


@pytest.mark.parametrize("content", [ALIAS_BOMB.encode(), b"mechreport: 1\nname: \xff\n",
                                     ("a: " + "[" * 450 + "]" * 450 + "\n").encode(),
                                     b"mechreport: 1\nname: x\ndriver: {rpm: 1e160}\n"],
                         ids=["alias-bomb", "non-utf8", "deep", "rpm-1e160"])
def test_cli_validate_reports_hostile_files_without_traceback(tmp_path, content):
    bad = tmp_path / "hostile.yaml"
    bad.write_bytes(content)
    run = subprocess.run([sys.executable, "-m", "mechreport.app.cli", "validate", str(bad)],
                         cwd=ROOT, capture_output=True, text=True, timeout=60)
    assert run.returncode == 1
    assert "Traceback" not in run.stderr + run.stdout
    assert run.stderr.startswith(str(bad))


# -- names that display as other than they are (issue 40) ---------------------------------

BIDI = ["\u202a", "\u202b", "\u202c", "\u202d", "\u202e", "\u2066", "\u2067", "\u2068",
        "\u2069", "\u200e", "\u200f", "\u061c"]


@pytest.mark.parametrize("char", BIDI, ids=[f"U+{ord(c):04X}" for c in BIDI])
def test_bidi_control_characters_in_names_are_refused_where_they_are(char):
    """A right-to-left override in a name passed into report.md and report.pdf, where the
    name displays reversed: refused in the spec's name, a load's name and every key (link,
    point, joint names), each at its line, the character escaped in the message."""
    text = edit(BASE, "name: slider-crank", f'name: "slider{char}-crank"')
    text = edit(text, "  rod:\n", f"  r{char}od:\n")
    text = edit(text, "links: [crank, rod]", f"links: [crank, r{char}od]")
    text = edit(text, "links: [rod, slider]", f"links: [r{char}od, slider]")
    text = edit(text, "quantity: link.rod.omega", f"quantity: link.r{char}od.omega")
    text = edit(text, "value: [100, 0], oppose: velocity}",
                f'value: [100, 0], oppose: velocity, name: "push{char}"}}')
    found = refused(text)
    escaped = char.encode("unicode_escape").decode()
    assert [(p.line, p.path) for p in found] == [
        (line_of(text, "name: \"slider"), "name"),
        (line_of(text, f"  r{char}od:"), f"links.r{escaped}od"),
        (line_of(text, "name: \"push"), "loads[0].name")]
    for p in found:
        assert p.message.startswith(f"must not hold U+{ord(char):04X} (")
        assert "bidirectional control character" in p.message
        assert str(p).isprintable()
