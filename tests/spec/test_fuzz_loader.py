"""Property-based fuzzing of the spec loader (and of what it lets through).

Each example takes a shipped spec (specs/*.yaml, tests/data/*.yaml), reads it into plain
Python values with the loader's own YAML reader, applies a few random mutations (delete a key
or item, put a value of another type in place of a value, extreme numbers, text that looks
like a number, huge integers, rename a name that something refers to, swap two values,
scale a number), writes it back with ``yaml.safe_dump`` and loads the text:

- ``parse_spec`` returns a Spec or raises ``SpecError`` whose every problem names the file,
  and nothing else, ever (strict);
- when it loads, ``analyse`` raises nothing but ``MechreportError`` subclasses, and every
  array of its results is finite.

``derandomize=True`` makes every run (and CI) see the same examples.
"""
from __future__ import annotations

import copy
import dataclasses
import math
from pathlib import Path

import numpy as np
import pytest
import yaml
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from mechreport.errors import MechreportError, SpecError
from mechreport.spec import Sweep, parse_spec
from mechreport.spec.yaml_source import Source

pytestmark = pytest.mark.slow      # builds reports, starts processes or fuzzes: not in the fast tier

ROOT = Path(__file__).resolve().parents[2]
SPEC_PATHS = (sorted((ROOT / "specs").glob("*.yaml"))
              + sorted((ROOT / "tests" / "data").glob("*.yaml")))
FILENAME = "fuzzed/spec.yaml"
BASES = {p.name: Source(str(p), p.read_text(encoding="utf-8")).data for p in SPEC_PATHS}
MAX_ANGLES = 24   # analyse() runs on a coarse sweep: the loader, not the solver, is fuzzed here

EXTREME_NUMBERS = [1e308, -1e308, 1e-320, -1e-320, 5e-324, 0.0, -0.0, 1e20, -1e20, 1e-20,
                   1.0000001e20, 9.99e-21, 10**400, -10**400, 10**20, 10**21, 2**63, -2**64,
                   math.inf, -math.inf, math.nan]
TRICKY_TEXT = ["nan", "NaN", ".nan", "inf", "-inf", ".inf", "-.inf", "infinity", "1e400",
               "1e-3", "1_000", "10:00", "1:30:00", "0x10", "0o17", "010", "yes", "no", "on",
               "off", "y", "n", "~", "null", "None", "true", "True", "", " ", "=", "<<",
               "2001-12-14", "R", "T", "ground", "force", "moment", "velocity", "rotation",
               "driver.torque", "point.A.x", "link.crank.omega", "joint.A.fx", "m", "mm", "g"]

scalars = st.one_of(
    st.sampled_from(EXTREME_NUMBERS),
    st.sampled_from(TRICKY_TEXT),
    st.integers(),
    st.integers(min_value=10**20, max_value=10**500),
    st.floats(allow_nan=True, allow_infinity=True),
    st.booleans(),
    st.none(),
    st.text(max_size=6),
)
values = st.recursive(scalars, lambda inner: st.one_of(
    st.lists(inner, max_size=3), st.dictionaries(st.text(max_size=4), inner, max_size=3)),
    max_leaves=6)
FACTORS = [0.0, -1.0, 1e-300, 1e-25, 1e-12, 1e-6, 1e6, 1e12, 1e19, 1e25, 1e300]


# -- mutations -----------------------------------------------------------------------------

def _paths(node, path=()):
    """Every path below the root, depth first."""
    if isinstance(node, dict):
        for key, value in node.items():
            yield path + (key,)
            yield from _paths(value, path + (key,))
    elif isinstance(node, list):
        for i, value in enumerate(node):
            yield path + (i,)
            yield from _paths(value, path + (i,))


def _get(root, path):
    for part in path:
        root = root[part]
    return root


def _set(root, path, value):
    _get(root, path[:-1])[path[-1]] = value


def _names(root) -> set[str]:
    """Mapping keys: link, joint and point names (what references point at)."""
    return {p[-1] for p in _paths(root) if isinstance(p[-1], str)}


def _mutate(data, draw, within=lambda path: True) -> list[str]:
    """Apply one random mutation to ``data`` in place; returns a description. ``within``:
    which paths may be mutated (default every one)."""
    paths = [p for p in _paths(data) if within(p)]
    if not paths:
        return ["nothing to mutate"]
    op = draw(st.sampled_from(["delete", "replace", "replace", "extreme", "rename-ref",
                               "rename-key", "swap", "scale"]))
    path = draw(st.sampled_from(paths))
    parent = _get(data, path[:-1])
    if op == "delete":
        del parent[path[-1]]
    elif op == "replace":
        _set(data, path, draw(values))
    elif op == "extreme":
        numbers = [p for p in paths if isinstance(_get(data, p), (int, float))
                   and not isinstance(_get(data, p), bool)]
        path = draw(st.sampled_from(numbers)) if numbers else path
        _set(data, path, draw(st.sampled_from(EXTREME_NUMBERS + TRICKY_TEXT)))
    elif op == "rename-ref":
        names = _names(data)
        refs = [p for p in paths if isinstance(_get(data, p), str) and _get(data, p) in names]
        if refs:
            path = draw(st.sampled_from(refs))
            _set(data, path, draw(st.sampled_from(["nonexistent", "ground", ""])))
    elif op == "rename-key":
        keyed = [p for p in paths if isinstance(_get(data, p[:-1]), dict)]
        path = draw(st.sampled_from(keyed))
        owner = _get(data, path[:-1])
        new = draw(st.sampled_from(["nonexistent", "ground", "A", "B", "C", "crank", "x"]))
        items = [(new if k == path[-1] else k, v) for k, v in owner.items()]
        owner.clear()
        owner.update(items)           # keeps the order; a clash keeps the last value
    elif op == "swap":
        other = draw(st.sampled_from(paths))
        if not (other[:len(path)] == path or path[:len(other)] == other):
            a, b = copy.deepcopy(_get(data, path)), copy.deepcopy(_get(data, other))
            _set(data, path, b)
            _set(data, other, a)
    else:  # scale
        numbers = [p for p in paths if isinstance(_get(data, p), (int, float))
                   and not isinstance(_get(data, p), bool)]
        if numbers:
            path = draw(st.sampled_from(numbers))
            factor = draw(st.sampled_from(FACTORS))
            try:
                _set(data, path, _get(data, path) * factor)
            except OverflowError:      # a huge integer put there by an earlier mutation
                _set(data, path, factor)
    return [f"{op} {path}"]


@st.composite
def mutated_specs(draw):
    name = draw(st.sampled_from(sorted(BASES)))
    data = copy.deepcopy(BASES[name])
    done = []
    for _ in range(draw(st.integers(min_value=1, max_value=4))):
        done += _mutate(data, draw)
    text = yaml.safe_dump(data, sort_keys=False, allow_unicode=True, width=4096)
    return name, done, text


IN_RANGE_EDGES = [0.0, -0.0, 1e-20, -1e-20, 1e20, -1e20, 1e-12, 1e12, -1.0, 360.0, 90.0,
                  180.0, 1e-3, 7.0]


@st.composite
def tweaked_specs(draw):
    """Milder mutants that mostly still load: one to three numbers replaced by edge values
    inside the accepted range, or scaled (kept in range), or two numbers swapped. These reach
    analyse() with odd geometry, masses, speeds and loads."""
    name = draw(st.sampled_from(sorted(BASES)))
    data = copy.deepcopy(BASES[name])
    numbers = [p for p in _paths(data) if isinstance(_get(data, p), (int, float))
               and not isinstance(_get(data, p), bool) and p[0] != "mechreport"]
    done = []
    for _ in range(draw(st.integers(min_value=1, max_value=3))):
        path = draw(st.sampled_from(numbers))
        how = draw(st.sampled_from(["edge", "scale", "swap"]))
        if how == "edge":
            value = draw(st.sampled_from(IN_RANGE_EDGES))
        elif how == "scale":
            value = _get(data, path) * draw(st.sampled_from([f for f in FACTORS
                                                               if 1e-15 <= abs(f) <= 1e15]
                                                              + [0.0, -1.0]))
        else:
            other = draw(st.sampled_from(numbers))
            value, _ = _get(data, other), _set(data, other, _get(data, path))
        _set(data, path, value)
        done.append(f"{how} {path}")
    text = yaml.safe_dump(data, sort_keys=False, allow_unicode=True, width=4096)
    return name, done, text


def _under_format_1_1_keys(path) -> bool:
    """Paths below the format 1.1 keys: friction, dynamics, a link's strength data, the
    materials, and polar points ({r, angle})."""
    if path[0] in ("friction", "dynamics", "materials"):
        return True
    if path[0] == "links" and len(path) > 2 and path[2] in ("section", "material", "members"):
        return True
    return any(part in ("r", "angle") for part in path[1:]) and path[0] in ("links", "ground")


NEW_KEY_BASES = sorted(n for n, d in BASES.items()
                       if any(_under_format_1_1_keys(p) for p in _paths(d)))


@st.composite
def new_key_specs(draw):
    """Mutants of the specs that use the format 1.1 keys, mutated below those keys only."""
    name = draw(st.sampled_from(NEW_KEY_BASES))
    data = copy.deepcopy(BASES[name])
    done = []
    for _ in range(draw(st.integers(min_value=1, max_value=3))):
        done += _mutate(data, draw, _under_format_1_1_keys)
    text = yaml.safe_dump(data, sort_keys=False, allow_unicode=True, width=4096)
    return name, done, text


# -- the properties ------------------------------------------------------------------------

def _load(text: str):
    """The Spec, or None if refused; fails on anything but a well-formed SpecError."""
    try:
        return parse_spec(text, FILENAME)
    except SpecError as exc:
        assert exc.problems, "SpecError without problems"
        for p in exc.problems:
            assert p.file == FILENAME, str(p)
            assert "internal error" not in p.message, str(p)
        return None


COMMON = dict(deadline=None, derandomize=True, database=None,
              suppress_health_check=[HealthCheck.too_slow, HealthCheck.data_too_large])


@settings(max_examples=400, **COMMON)
@given(mutated_specs())
def test_loader_raises_only_spec_errors_naming_the_file(case):
    name, done, text = case
    _load(text)


YAML_ALPHABET = "[]{}:,-&*!|>'\"#%@`?~ \n\t\r\\\x00\x85\u2028\ufeffab01.eE+_xyAB"


@settings(max_examples=300, **COMMON)
@given(st.one_of(st.binary(max_size=120), st.text(alphabet=YAML_ALPHABET, max_size=120),
                 st.text(max_size=60)))
def test_loader_survives_random_bytes_and_yaml_punctuation(data):
    _load(data)


@settings(max_examples=25, **COMMON)
@given(st.sampled_from(sorted(BASES)))
def test_unmutated_round_trip_loads(name):
    # the fuzz starts from valid specs: dumping them back must not change that
    text = yaml.safe_dump(BASES[name], sort_keys=False, allow_unicode=True, width=4096)
    assert parse_spec(text, FILENAME).name


def _finite_results(result) -> None:
    kin = result.kinematics
    for field in ("angles", "r", "theta", "v", "omega", "a", "alpha"):
        assert np.all(np.isfinite(getattr(kin, field))), f"kinematics.{field} not finite"
    for method, forces in result.forces.items():
        assert np.all(np.isfinite(forces.driver_torque)), f"{method}: driver torque"
        for joint, reaction in forces.reactions.items():
            for part in ("fx", "fy", "moment"):
                values = getattr(reaction, part)
                if values is not None:
                    assert np.all(np.isfinite(values)), f"{method}: joint {joint}.{part}"


def _coarse(spec):
    """The spec with at most MAX_ANGLES sweep angles (a mutated step can ask for 100000)."""
    sweep = spec.sweep
    span = sweep.stop - sweep.start
    if span / sweep.step > MAX_ANGLES:
        sweep = Sweep(sweep.start, sweep.stop, span / MAX_ANGLES)
    return dataclasses.replace(spec, sweep=sweep, at=spec.at[:4], expect=spec.expect[:4])


@settings(max_examples=200, **COMMON)
@given(st.one_of(tweaked_specs(), mutated_specs()))
def test_analyse_of_what_loads_is_finite_or_a_project_error(case):
    _analysed_finite_or_refused(case[2])


def _analysed_finite_or_refused(text: str) -> None:
    """What loads analyses (on a coarse sweep) to finite numbers or a project error."""
    from mechreport.pipeline.analysis import analyse
    spec = _load(text)
    if spec is None:
        return
    try:
        result = analyse(_coarse(spec))
    except MechreportError:
        return
    _finite_results(result)


def test_the_format_1_1_keys_have_specs_to_fuzz():
    for key in ("friction", "dynamics", "materials"):
        assert any(key in BASES[n] for n in NEW_KEY_BASES), key
    assert any(_under_format_1_1_keys(p) and p[-1] == "r" for n in NEW_KEY_BASES
               for p in _paths(BASES[n])), "no spec with polar points"


@settings(max_examples=150, **COMMON)
@given(new_key_specs())
def test_format_1_1_keys_load_or_raise_only_spec_errors_naming_the_file(case):
    name, done, text = case
    _load(text)


@settings(max_examples=150, **COMMON)
@given(new_key_specs())
def test_format_1_1_keys_analyse_finite_or_a_project_error(case):
    """What loads after a mutation below friction, dynamics, strength or polar points
    analyses to finite numbers or raises a project error (a dynamics spec's simulation is
    bounded in its work, never endless)."""
    _analysed_finite_or_refused(case[2])
