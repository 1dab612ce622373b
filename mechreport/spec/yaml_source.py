"""Read YAML into plain Python values while remembering where each value came from.

PyYAML's composer gives nodes with marks; we construct values ourselves so that every key path
maps to its line, and so that duplicate keys are reported instead of silently overwritten.
"""
from __future__ import annotations

from typing import Any

import yaml
from yaml.constructor import SafeConstructor

from ..errors import Problem, SpecError

Path = tuple  # of str keys and int indices


def format_path(path: Path) -> str:
    """``('links', 'rod', 'mass')`` -> ``links.rod.mass``; ``('loads', 0)`` -> ``loads[0]``."""
    out = ""
    for part in path:
        if isinstance(part, int):
            out += f"[{part}]"
        else:
            out += ("." if out else "") + str(part)
    return out


class Source:
    """The parsed document plus the line of every key path in it."""

    def __init__(self, filename: str, text: str):
        self.filename = filename
        self.lines: dict[Path, int] = {}
        self.problems: list[Problem] = []
        self._constructor = SafeConstructor()
        try:
            node = yaml.compose(text, Loader=yaml.SafeLoader)
        except yaml.YAMLError as exc:
            mark = getattr(exc, "problem_mark", None)
            line = mark.line + 1 if mark is not None else None
            what = getattr(exc, "problem", None) or str(exc)
            context = getattr(exc, "context", None)
            msg = f"malformed YAML: {what}" + (f" ({context})" if context else "")
            raise SpecError([Problem(filename, line, "", msg)]) from None
        self.data = self._convert(node, ()) if node is not None else None

    def line(self, path: Path) -> int | None:
        """Line of ``path``, or of its nearest ancestor that has one."""
        path = tuple(path)
        while path:
            if path in self.lines:
                return self.lines[path]
            path = path[:-1]
        return self.lines.get(())

    def _convert(self, node: yaml.Node, path: Path) -> Any:
        self.lines.setdefault(path, node.start_mark.line + 1)
        if isinstance(node, yaml.MappingNode):
            out: dict = {}
            for key_node, value_node in node.value:
                if not isinstance(key_node, yaml.ScalarNode):
                    self.problems.append(Problem(self.filename, key_node.start_mark.line + 1,
                                                 format_path(path), "keys must be plain names"))
                    continue
                key = self._constructor.construct_object(key_node)
                key = str(key) if not isinstance(key, str) else key
                child = path + (key,)
                if key in out:
                    self.problems.append(Problem(self.filename, key_node.start_mark.line + 1,
                                                 format_path(child), "duplicate key"))
                    continue
                self.lines[child] = key_node.start_mark.line + 1
                out[key] = self._convert(value_node, child)
            return out
        if isinstance(node, yaml.SequenceNode):
            return [self._convert(item, path + (i,)) for i, item in enumerate(node.value)]
        return self._constructor.construct_object(node)
