"""optimum.yaml: the user's own spec text with the optimal values written in.

Only the varied values change, each written where it stands in the text (a flow list
``[50, 0]`` keeps its form, comments and layout stay); the ``expect:`` section is taken out
(its values are the original design's, which the optimum is not meant to reproduce: with it
``mechreport check optimum.yaml`` would fail on them), with a comment saying so, and a header
says where the file comes from. The text is read back and must give the data tree of the
optimum exactly (else ValueError: a bug, never a silently different spec).
"""
from __future__ import annotations

from typing import Any, Mapping

from .variants import _plain


def _node_at(root, path: tuple):
    """The YAML node (``yaml.compose``) at ``path`` (keys and list indices)."""
    import yaml
    node = root
    for part in path:
        if isinstance(node, yaml.MappingNode):
            node = next(v for k, v in node.value if k.value == part)
        elif isinstance(node, yaml.SequenceNode):
            node = node.value[int(part)]
        else:
            raise ValueError(f"no node at {path}")
    return node


def _offset(lines: list[int], mark) -> int:
    return lines[mark.line] + mark.column


def optimum_text(text: str, paths: Mapping[str, tuple], values: Mapping[str, float],
                 header: str = "") -> str:
    """``text`` (a spec) with the leaf at ``paths[k]`` set to ``values[k]`` for every varied
    key ``k`` (in the spec's own units), its top-level ``expect:`` block removed (a comment
    says why) and ``header`` lines as comments in front."""
    import yaml
    root = yaml.compose(text, Loader=yaml.SafeLoader)
    starts = [0]
    for line in text.splitlines(keepends=True):
        starts.append(starts[-1] + len(line))
    edits: list[tuple[int, int, str]] = []
    for key, path in paths.items():
        node = _node_at(root, path)
        edits.append((_offset(starts, node.start_mark), _offset(starts, node.end_mark),
                      str(_plain(values[key]))))     # as the spec writes numbers
    for k, v in root.value:
        if k.value == "expect" and k.start_mark.column == 0:
            a = _offset(starts, k.start_mark)
            end = _offset(starts, v.end_mark)
            edits.append((a, end, "# expect: removed by mechreport optimize (its values are "
                                  "the original design's)\n"))
    out = text
    for a, b, new in sorted(edits, reverse=True):
        out = out[:a] + new + out[b:]
    head = "".join(f"# {line}\n" if line else "#\n" for line in header.splitlines())
    return head + out


def check_text_gives(text: str, data: Any, filename: str) -> None:
    """Raise ValueError unless ``text`` reads back as ``data`` (``expect`` left out)."""
    from ..spec.loader import parse_source
    from .variants import _same_tree
    back = parse_source(text, filename)
    got = {k: v for k, v in (back.data or {}).items() if k != "expect"}
    want = {k: v for k, v in data.items() if k != "expect"}
    if back.problems or not _same_tree(want, got):
        raise ValueError("optimum.yaml does not read back as the optimum's data")
