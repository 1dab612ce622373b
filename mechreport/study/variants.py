"""A study's variants: the spec's data tree with the varied leaves replaced, validated by the
loader like any spec (so a variant's bad value is reported with the file, line and key path of
the leaf it replaced).

The YAML is read once. Each variant copies only the mappings and lists on the paths to its
varied leaves (the rest of the tree is shared, never modified), and is validated from that
tree: no YAML text is written or parsed per variant.

A variant is the spec without its ``study`` section (the study is about the mechanism) and
without its ``expect`` entries (they hold the base spec's values, which a variant is not meant
to reproduce).
"""
from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, Mapping

from ..spec import Spec
from ..spec.loader import load_source, spec_from_data
from ..spec.yaml_source import Source

#: top-level keys a variant leaves out (see the module docstring)
DROPPED = ("study", "expect")


@dataclass(frozen=True)
class BaseSpec:
    """The spec a study varies: ``spec`` (validated, with its ``study``), ``data`` (its data
    tree without ``study`` and ``expect``, as written: the spec's own units), ``source`` (file
    name and the line of every key path, for messages) and ``paths`` (each varied key -> its
    path of keys and list indices)."""

    spec: Spec
    data: dict
    source: Source = field(repr=False)
    paths: dict[str, tuple]

    @property
    def file(self) -> str:
        return self.spec.file

    def __getstate__(self):
        # the source's text and line table are all a worker needs of it
        src = Source.__new__(Source)
        src.filename, src.text, src.lines, src.problems = (self.source.filename, "",
                                                           self.source.lines, [])
        return {"spec": self.spec, "data": self.data, "source": src, "paths": self.paths}

    def __setstate__(self, state):
        for k, v in state.items():
            object.__setattr__(self, k, v)


def load_base(path: str | Path) -> BaseSpec:
    """Read and validate the spec at ``path`` (raises ``SpecError``); its study section must
    be there (else a ``SpecError`` saying so)."""
    return study_base(load_source(path))


def study_base(src: Source) -> BaseSpec:
    """The :class:`BaseSpec` of the spec read into ``src``, validated (raises ``SpecError``);
    its study section must be there (else a ``SpecError`` saying so)."""
    from ..errors import Problem, SpecError
    spec = spec_from_data(src.data, src)
    if spec.study is None:
        raise SpecError([Problem(src.filename, None, "", "this spec has no 'study:' section; "
                                 "`mechreport study` needs one saying what to vary and what "
                                 "to keep (docs/spec.md, section 17)")])
    return base_of(spec, src)


def base_of(spec: Spec, src: Source) -> BaseSpec:
    """The :class:`BaseSpec` of a validated ``spec`` read from ``src``."""
    return section_base(spec, src, spec.study.vary if spec.study is not None else ())


def section_base(spec: Spec, src: Source, vary, drop: tuple[str, ...] = ()) -> BaseSpec:
    """The :class:`BaseSpec` of a validated ``spec`` read from ``src`` whose varied keys are
    those of ``vary`` (a section's entries, each with its ``key`` and ``path``): the data
    tree without ``DROPPED`` and the section's own keys ``drop``."""
    data = {k: v for k, v in src.data.items() if k not in DROPPED + drop}
    return BaseSpec(spec, data, src, {v.key: v.path for v in vary})


def replaced(data: Any, changes: Mapping[tuple, Any]) -> Any:
    """``data`` with the leaf at each path of ``changes`` set to its value. Only the mappings
    and lists on those paths are copied; ``data`` itself is not modified."""
    if not changes:
        return data
    out = dict(data) if isinstance(data, dict) else list(data)
    heads: dict[Any, dict[tuple, Any]] = {}
    for path, value in changes.items():
        if len(path) == 1:
            out[path[0]] = value
        else:
            heads.setdefault(path[0], {})[path[1:]] = value
    for head, sub in heads.items():
        out[head] = replaced(out[head], sub)
    return out


def variant_data(base: BaseSpec, values: Mapping[str, float]) -> dict:
    """The data tree of the variant taking ``values`` ({varied key: value}, spec units)."""
    return replaced(base.data, {base.paths[k]: _plain(v) for k, v in values.items()})


def variant_spec(base: BaseSpec, values: Mapping[str, float]) -> Spec:
    """The validated Spec of a variant (raises ``SpecError`` naming the replaced leaf when a
    value is not valid there, e.g. a negative mass)."""
    return spec_from_data(variant_data(base, values), base.source)


def variant_yaml(base: BaseSpec, values: Mapping[str, float], header: str = "",
                 name: str | None = None, description: str | None = None) -> str:
    """A variant as spec text (for the full reports of the best variants): ``header`` lines
    as comments, then the data tree as YAML (with ``name`` and ``description`` in place of
    the spec's, when given). The text reads back, with the spec loader's YAML 1.2 core
    schema, as exactly that data tree (see :func:`dump_yaml`)."""
    data = variant_data(base, values)
    if name is not None:
        data = dict(data, name=name)
    if description is not None:
        data = dict(data, description=description)
    lines = "".join(f"# {line}\n" if line else "#\n" for line in header.splitlines())
    return lines + dump_yaml(data)


def dump_yaml(data: Any) -> str:
    """``data`` (mappings, lists, text, numbers, true/false, null) as YAML text that the
    spec loader reads back as the same tree, value for value and type for type.

    PyYAML writes by YAML 1.1 rules, and the loader reads plain scalars by YAML 1.2 core
    rules (:func:`~mechreport.spec.yaml_source.resolve_plain`): a text that 1.2 would read as
    something else (``1e5``, ``0o17``, ``.5``, ``true``, ``null`` ...) is single-quoted.
    Floats are written by ``repr`` (PyYAML's own way: the shortest text that reads back as
    the same float, ``1.0e+20`` for ``1e+20``). The text is parsed back to check it: anything
    but the same tree raises ValueError (a bug, never a silently different spec)."""
    import yaml

    from ..spec.yaml_source import resolve_plain

    class Dumper(yaml.SafeDumper):
        pass

    def text(dumper, value: str):
        if "\n" in value:
            style = "|"                                # multi-line text as a literal block
        elif not value or not _reads_as(resolve_plain(value), value):
            style = "'"                                # 1.2 would not read it as this text
        else:
            style = None
        return dumper.represent_scalar("tag:yaml.org,2002:str", value, style=style)

    Dumper.add_representer(str, text)
    out = yaml.dump(data, Dumper=Dumper, sort_keys=False, allow_unicode=True,
                    default_flow_style=None, width=100)
    _check_round_trip(data, out)
    return out


def _reads_as(value: Any, text: str) -> bool:
    return isinstance(value, str) and value == text


def _check_round_trip(data: Any, text: str) -> None:
    from ..spec.loader import parse_source
    back = parse_source(text, "<variant>")
    if back.problems or not _same_tree(data, back.data):
        raise ValueError("the variant's YAML text does not read back as its data"
                         + (f": {back.problems[0].message}" if back.problems else ""))


def _same_tree(a: Any, b: Any) -> bool:
    """``a`` and ``b`` equal, with the same types (True is not 1, 1 is not 1.0; NaN equals
    NaN)."""
    if isinstance(a, (dict, list, tuple)):
        if isinstance(a, dict):
            return (isinstance(b, dict) and list(a) == list(b)
                    and all(_same_tree(a[k], b[k]) for k in a))
        return (isinstance(b, list) and len(a) == len(b)
                and all(_same_tree(x, y) for x, y in zip(a, b)))
    if type(a) is not type(b):
        return False
    if isinstance(a, float) and a != a:
        return b != b
    return a == b


def _plain(value: float) -> float | int:
    """A whole float written back as an int (``900.0`` -> ``900``), so that a variant's YAML
    and messages read like the spec."""
    f = float(value)
    return int(f) if f.is_integer() and abs(f) < 2**53 else f
