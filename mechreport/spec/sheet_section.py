"""The ``sheet`` key (format 1.2): ``true``/``false`` or ``{enabled, statement, variants}``,
as validated by the models of :mod:`.schema`, converted to ``(enabled, SheetSettings)``.

The varied keys' paths are resolved with the same rule as ``study.vary`` (a key path must
lead to a number of the spec)."""
from __future__ import annotations

from typing import Any, Callable

from .schema import SheetVariants as VariantsModel
from .schema import SpecFile
from .types import SheetSettings, SheetVariants, SheetVary


def sheet_section(value: Any, refused: bool, key_path: Callable, line: Callable
                  ) -> tuple[bool, SheetSettings]:
    """``(enabled, settings)`` of the validated ``sheet`` value (``refused``: the models
    refused it; the default then). ``key_path(key, where)`` resolves a varied key (None when
    it reported a problem); ``line(where)`` the line of a key path."""
    default = SpecFile.model_fields["sheet"].default
    if refused or value is None:
        return default, SheetSettings()
    if not isinstance(value, dict):
        return bool(value), SheetSettings()
    enabled = value.get("enabled", True)
    body = value.get("variants")
    variants = None
    if isinstance(body, dict):
        vary = []
        for i, item in enumerate(body.get("vary", ())):
            where = ("sheet", "variants", "vary", i)
            path = key_path(item["key"], where + ("key",))
            if path is None:
                continue
            vary.append(SheetVary(
                item["key"], path,
                values=tuple(float(v) for v in item["values"]) if "values" in item else None,
                start=float(item["from"]) if "from" in item else None,
                stop=float(item["to"]) if "to" in item else None,
                step=float(item["step"]) if "step" in item else None,
                line=line(where)))
        fields = VariantsModel.model_fields
        require = body.get("require") or {}
        variants = SheetVariants(
            tuple(vary), int(body.get("count", fields["count"].default)),
            int(body.get("seed", fields["seed"].default)),
            int(body.get("digits", fields["digits"].default)),
            tuple((k, float(v)) for k, v in require.items() if v is not None),
            line(("sheet", "variants")))
    return bool(enabled), SheetSettings(value.get("statement"), variants)
