"""A study's table as files: study.parquet and study.csv (one row per variant, columns:
:mod:`.table`), by the column writers a tolerance analysis's files use too
(:mod:`.tolerance_outputs`). Where they go, safely, is the command's
(:mod:`mechreport.app.study`)."""
from __future__ import annotations

import csv
from pathlib import Path

import numpy as np

from .table import Table


# ----------------------------------------------------------------------------- tables

#: a pass/fail column's cells in the study's and tolerance analysis's CSV files (1 pass, 0
#: fail, -1 not judged)
TRI = {1: "true", 0: "false", -1: ""}


def csv_cell(value) -> str:
    """A number's shortest exact form (``-10``, ``0.125``, ``1e+20``), empty if undefined
    (None, NaN, infinite); text as it is. The one cell writer of study.csv, tolerance.csv
    and the optimiser's history.csv."""
    if value is None:
        return ""
    if isinstance(value, (float, np.floating)):
        v = float(value)
        if not np.isfinite(v):
            return ""
        return str(int(v)) if v.is_integer() and abs(v) < 1e15 else repr(v)
    return str(value)


def study_columns(table: Table) -> dict[str, tuple[str, object]]:
    """study.csv's and study.parquet's columns (:meth:`.table.Table.columns`) with their
    kinds, as :func:`write_columns_parquet` takes them: ``variant`` int, ``design_pass``
    tri, the varied keys and kept quantities float, the rest text."""
    def kind(name: str, col) -> str:
        if name == "design_pass":
            return "tri"
        if isinstance(col, np.ndarray):
            return "float" if col.dtype.kind == "f" else "int"
        return "text"
    return {name: (kind(name, col), col) for name, col in table.columns().items()}


def write_columns_parquet(cols: dict[str, tuple[str, object]], path: Path,
                          metadata: dict[str, str] | None = None) -> Path:
    """A table's parquet file from its columns, name -> (kind, values): ``int``, ``float``
    (undefined values null), ``tri`` (1/0/-1: true, false, null) or ``text``; ``metadata``
    stored as ``mechreport.<key>``."""
    import pyarrow as pa
    import pyarrow.parquet as pq
    arrays, names = [], []
    for name, (kind, col) in cols.items():
        if kind == "tri":
            p = np.asarray(col)
            arr = pa.array(p == 1, mask=p < 0)
        elif kind == "float":
            arr = pa.array(col, mask=~np.isfinite(col))
        elif kind == "int":
            arr = pa.array(np.asarray(col).astype(np.int64))
        else:
            arr = pa.array(col, type=pa.string())
        arrays.append(arr)
        names.append(name)
    meta = {f"mechreport.{k}".encode(): str(v).encode() for k, v in (metadata or {}).items()}
    t = pa.Table.from_arrays(arrays, names=names).replace_schema_metadata(meta)
    pq.write_table(t, str(path))        # into the command's private folder: no half file shows
    return Path(path)


def write_columns_csv(cols: dict[str, tuple[str, object]], n: int, path: Path) -> Path:
    """The same columns (``n`` rows) as CSV: numbers written exactly (:func:`csv_cell`), a
    tri column as true/false/empty (:data:`TRI`), undefined values as empty cells; streamed
    row by row (no copy of the whole text)."""
    kinds = [kind for kind, _ in cols.values()]
    data = [col for _, col in cols.values()]
    with open(path, "w", encoding="utf-8", newline="") as fh:
        w = csv.writer(fh, lineterminator="\n")
        w.writerow(list(cols))
        for i in range(n):
            row = []
            for kind, col in zip(kinds, data):
                v = col[i]
                if kind == "tri":
                    row.append(TRI[int(v)])
                elif kind == "int":
                    row.append(str(int(v)))
                else:
                    row.append(csv_cell(v))
            w.writerow(row)
    return Path(path)


def write_parquet(table: Table, path: Path, metadata: dict[str, str] | None = None) -> Path:
    """study.parquet: one row per variant (:func:`study_columns`)."""
    return write_columns_parquet(study_columns(table), path, metadata)


def write_csv(table: Table, path: Path) -> Path:
    """study.csv: the same columns as study.parquet; numbers written exactly (shortest
    round-trip form), undefined values and a failed variant's design_pass as empty cells."""
    return write_columns_csv(study_columns(table), table.n, path)
