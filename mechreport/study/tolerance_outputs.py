"""A tolerance analysis's samples as files: tolerance.parquet and tolerance.csv, one row per
sample. Where they go, safely, is the command's (:mod:`mechreport.app.tolerance`).

Columns:

- ``sample``: 1, 2, ... in the order drawn;
- one per uncertain key, named by the key as written, in the spec's own units;
- one per kept quantity, ``<quantity> [<SI unit>]`` (as study.csv and results.csv);
- ``design_pass``: every design verdict passed; then ``verdict.<item>`` per design item
  (``verdict.motor.rated_torque``): true, false, or empty when the sample was not judged
  (its status is not ok);
- ``status``: ok, invalid, no assembly, untrusted or failed; ``reason``: why, when not ok.
"""
from __future__ import annotations

from pathlib import Path

import numpy as np

from .outputs import write_columns_csv, write_columns_parquet
from .table import column_name


def columns(table) -> dict[str, tuple[str, object]]:
    """Column name -> (kind, values): kind ``int``, ``float``, ``tri`` (1/0/-1 int8: true,
    false, empty) or ``text``, in file order."""
    cols: dict[str, tuple[str, object]] = {"sample": ("int", np.arange(1, table.n + 1))}
    for j, key in enumerate(table.plan.keys):
        cols[key] = ("float", table.plan.values[:, j])
    for j, q in enumerate(table.keep):
        cols[column_name(q)] = ("float", table.values[:, j])
    cols["design_pass"] = ("tri", table.design_pass)
    for k, item in enumerate(table.items):
        cols[f"verdict.{item}"] = ("tri", table.passes[:, k])
    cols["status"] = ("text", table.status)
    cols["reason"] = ("text", table.reason)
    return cols


def write_parquet(table, path: Path, metadata: dict[str, str] | None = None) -> Path:
    """tolerance.parquet: one row per sample (:func:`columns`)."""
    return write_columns_parquet(columns(table), path, metadata)


def write_csv(table, path: Path) -> Path:
    """tolerance.csv: the columns of tolerance.parquet; numbers written exactly (shortest
    round-trip form), undefined values and unjudged verdicts as empty cells."""
    return write_columns_csv(columns(table), table.n, path)
