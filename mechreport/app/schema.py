"""``mechreport schema [--output FILE]``: print the JSON Schema of a spec file.

The schema comes from the models that the loader validates every spec with
(:mod:`mechreport.spec.schema`); an editor with a YAML language server uses it to check and
complete a spec as it is typed (docs/spec.md, "Editor support: the JSON Schema").
``docs/spec.schema.json`` is this command's output, kept in step by a test.
"""
from __future__ import annotations

import json
import sys
from pathlib import Path


def schema_text() -> str:
    """The JSON Schema as the command writes it: indented JSON and a final newline."""
    from ..spec.schema import json_schema
    return json.dumps(json_schema(), indent=2) + "\n"


def schema_command(output: str | None = None) -> int:
    """Print the schema, or write it to ``output``; exit status 1 when it cannot be
    written."""
    text = schema_text()
    if output is None:
        sys.stdout.write(text)
        return 0
    try:
        Path(output).write_text(text, encoding="utf-8")
    except (OSError, ValueError) as exc:   # ValueError: a NUL character in the path
        reason = getattr(exc, "strerror", None) or str(exc)
        print(f"error: cannot write {output}: {reason}", file=sys.stderr)
        return 1
    return 0
