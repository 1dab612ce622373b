"""The key tables of docs/spec.md, made from the models of :mod:`.schema`: one row per key,
its meaning the field's description (the same text the JSON Schema gives an editor), its
"required" column from the model (or a :class:`~.schema.DocRequired` marker).

In docs/spec.md each table stands between ``<!-- key table NAME -->`` and ``<!-- end key
table -->``; :func:`updated` rewrites them, and a test (tests/spec/test_doc_tables.py) keeps
the file equal to what it gives. Nothing here reads or writes files.
"""
from __future__ import annotations

import re

from . import schema

__all__ = ["TABLES", "table", "updated"]

#: name -> (model, whether the table has a "required" column, the keys shown in order)
TABLES = {
    "top": (schema.SpecFile, True, None),
    "link": (schema.Link, False, ("points", "mass", "density", "com", "inertia", "shape")),
    "strength": (schema.Link, False, ("section", "material", "members", "buckling")),
    "study": (schema.Study, True, None),
    "tolerances": (schema.Tolerances, True, None),
    "tolerance vary": (schema.TolVary, False, None),
    "optimize": (schema.Optimize, True, None),
    "optimize_bound": (schema.OptimizeBound, True, None),
    "report": (schema.Report, False, None),
    "sheet": (schema.SheetSection, True, None),
    "sheet_variants": (schema.SheetVariants, True, None),
    "dynamics": (schema.Dynamics, False, None),
}

_REGION = re.compile(r"(<!-- key table (\w+(?: \w+)*) -->\n)(.*?)(<!-- end key table -->)", re.S)


def _cell(text: str) -> str:
    """Text for a Markdown table cell (a ``|`` escaped, on one line)."""
    return " ".join(text.split()).replace("|", "\\|")


def _required(field) -> str:
    marker = next((m for m in field.metadata if isinstance(m, schema.DocRequired)), None)
    if marker is not None:
        return marker.text
    return "yes" if field.is_required() else "no"


def table(name: str) -> str:
    """The Markdown table ``name`` of :data:`TABLES`, ending in a newline."""
    model, with_required, keys = TABLES[name]
    fields = {(field.alias or key): field for key, field in model.model_fields.items()}
    head = ["key", "required", "meaning"] if with_required else ["key", "meaning"]
    lines = ["| " + " | ".join(head) + " |", "|" + "---|" * len(head)]
    for key in keys or tuple(fields):
        field = fields[key]
        cells = [f"`{key}`"] + ([_required(field)] if with_required else [])
        lines.append("| " + " | ".join(cells + [_cell(field.description or "")]) + " |")
    return "\n".join(lines) + "\n"


def updated(text: str) -> str:
    """``text`` (docs/spec.md) with every key table region holding what :func:`table`
    gives."""
    return _REGION.sub(lambda m: m.group(1) + table(m.group(2)) + m.group(4), text)
