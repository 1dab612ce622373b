"""Mutated specs judged by the JSON Schema (``jsonschema``) and by the loader: where one
value decides, the two must agree (issue 42). Shared by the test and by a by-hand run::

    python tests/spec/differential.py          # every disagreement found, one a line
"""
from __future__ import annotations

import copy
from pathlib import Path

from mechreport.errors import SpecError
from mechreport.spec.loader import spec_from_data
from mechreport.spec.schema import json_schema
from mechreport.spec.yaml_source import Source, format_path

ROOT = Path(__file__).resolve().parents[2]
#: specs that together hold every section of the format
SPECS = ("specs/four_bar_motor.yaml", "specs/crank_press_friction.yaml",
         "specs/crank_press_strength.yaml", "specs/offset_slider_crank.yaml",
         "specs/slider_crank.yaml", "specs/spring_loaded_slider_crank.yaml",
         "specs/static_press.yaml", "specs/toggle_press.yaml", "specs/scotch_yoke.yaml")
#: what a leaf is replaced by: numbers of every kind (whole, whole floats, fractions, the
#: edges 0, 1, 2, 360), text, true/false, null and empty containers
VALUES = (0, 1, -1, 2, 1.0, 2.0, 3.0, 0.5, -0.5, 90, 90.5, 360, 359.5, 1e-30, 1e21, "x", "",
          "R", True, None, [], {}, [1, 2], [[0, 1]], [[0, 1], [400, 2]])
#: the messages of a problem that one value decides (its type, range or enumeration) ...
ONE_VALUE = ("must be", "format version must be", "unknown key", "angles must lie in",
             "give exactly one of")
#: ... but for these, which compare it with another value
TWO_VALUES = ("must be greater than start",)
#: mappings keyed by the spec's own names: one of their entries stands for all
NAMED = {"links", "joints", "ground", "points", "materials", "friction", "bearings",
         "assembly"}


def generic(path: tuple) -> tuple:
    """``path`` with list indices and the spec's own names made alike, so that one of many
    alike places (every point of every link) is mutated once."""
    out = []
    for key in path:
        named = bool(out) and out[-1] in NAMED
        out.append("[]" if isinstance(key, int) else "*" if named else key)
    return tuple(out)


def leaves(node, path=()):
    """Every key path of ``node`` to a value (containers included, the root excepted)."""
    items = node.items() if isinstance(node, dict) else (
        enumerate(node) if isinstance(node, list) else ())
    for key, value in items:
        yield path + (key,)
        yield from leaves(value, path + (key,))


def replaced(data, path, value):
    out = copy.deepcopy(data)
    node = out
    for key in path[:-1]:
        node = node[key]
    node[path[-1]] = value
    return out


def loader_problems(data, src) -> list | None:
    try:
        spec_from_data(data, src)
    except SpecError as exc:
        return exc.problems
    return None


def disagreements(specs=SPECS, values=VALUES, every_place=False):
    """(file, key path, value, what differs) for every mutation the two judge differently:
    the schema accepts and the loader refuses for a one-value reason at or below the mutated
    key, or the schema refuses and the loader accepts. Each alike place once, unless
    ``every_place``."""
    import jsonschema
    validator = jsonschema.Draft202012Validator(json_schema())
    seen = set()
    for name in specs:
        src = Source(name, (ROOT / name).read_text(encoding="utf-8"))
        for path in list(leaves(src.data)):
            if not every_place and generic(path) in seen:
                continue
            seen.add(generic(path))
            for value in values:
                data = replaced(src.data, path, value)
                schema_ok = validator.is_valid(data)
                problems = loader_problems(data, src)
                shown = format_path(path)
                if schema_ok and problems:
                    mine = [p.message for p in problems
                            if p.path.startswith(shown) and p.message.startswith(ONE_VALUE)
                            and not p.message.startswith(TWO_VALUES)]
                    if mine:
                        yield name, shown, value, f"schema accepts, loader: {mine[0]}"
                elif not schema_ok and problems is None:
                    error = next(validator.iter_errors(data))
                    yield (name, shown, value,
                           f"loader accepts, schema: {error.message[:120]}")


if __name__ == "__main__":
    for found in disagreements():
        print(*found, sep=" | ")


#: the places issue 42 found the two disagreeing, each (spec, key path, value)
KNOWN = (("specs/offset_slider_crank.yaml", ("mechreport",), 1.0),
         ("specs/offset_slider_crank.yaml", ("report",), {"revision": 2.0}),
         ("specs/offset_slider_crank.yaml", ("study", "seed"), 1.0),
         ("specs/offset_slider_crank.yaml", ("study", "vary", 0, "count"), 3.0),
         ("specs/offset_slider_crank.yaml", ("study", "vary", 0, "count"), 1),
         ("specs/four_bar_motor.yaml", ("dynamics", "motor"), {}),
         ("specs/four_bar_motor.yaml", ("dynamics", "motor"),
          {"torque": 1, "linear": {"stall_torque": 2, "no_load_rpm": 100}}),
         # a point at the cycle's end (360 here) that repeats the point at 0 (format 1.2)
         ("specs/spring_loaded_slider_crank.yaml", ("loads",),
          [{"type": "moment", "link": "crank", "profile": [[0, 1], [360, 1]]}]))


def known_verdicts():
    """(the schema's verdict, the loader's) on each of :data:`KNOWN`: True accepts."""
    import jsonschema
    validator = jsonschema.Draft202012Validator(json_schema())
    for name, path, value in KNOWN:
        src = Source(name, (ROOT / name).read_text(encoding="utf-8"))
        data = replaced(src.data, path, value)
        yield (name, path, value), validator.is_valid(data), loader_problems(data, src) is None
