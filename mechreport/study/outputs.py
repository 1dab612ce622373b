"""A study's table as files: study.parquet and study.csv (one row per variant, columns:
:mod:`.table`). Where they go, safely, is the command's (:mod:`mechreport.app.study`)."""
from __future__ import annotations

import csv
from pathlib import Path

import numpy as np

from .table import Table

#: what a study writes in OUT/<spec>/ (replaced by the next study, kept by nothing else)


# ----------------------------------------------------------------------------- tables

def write_parquet(table: Table, path: Path, metadata: dict[str, str] | None = None) -> Path:
    import pyarrow as pa
    import pyarrow.parquet as pq
    arrays, names = [], []
    for name, col in table.columns().items():
        if name == "design_pass":
            p = np.asarray(col)
            arr = pa.array(p == 1, mask=p < 0)
        elif isinstance(col, np.ndarray) and col.dtype.kind == "f":
            arr = pa.array(col, mask=~np.isfinite(col))
        elif isinstance(col, np.ndarray):
            arr = pa.array(col.astype(np.int64))
        else:
            arr = pa.array(col, type=pa.string())
        arrays.append(arr)
        names.append(name)
    meta = {f"mechreport.{k}".encode(): str(v).encode() for k, v in (metadata or {}).items()}
    t = pa.Table.from_arrays(arrays, names=names).replace_schema_metadata(meta)
    pq.write_table(t, str(path))        # into the study's private folder: no half file shows
    return Path(path)


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


def write_csv(table: Table, path: Path) -> Path:
    """study.csv: the same columns as study.parquet; numbers written exactly (shortest
    round-trip form), undefined values and a failed variant's design_pass as empty cells."""
    cols = table.columns()
    names = list(cols)
    data = [cols[k] for k in names]
    # streamed, row by row, into the study's private folder (no copy of the whole text)
    with open(path, "w", encoding="utf-8", newline="") as fh:
        w = csv.writer(fh, lineterminator="\n")
        w.writerow(names)
        for i in range(table.n):
            row = []
            for name, col in zip(names, data):
                v = col[i]
                if name == "design_pass":
                    row.append(TRI[int(v)])
                elif name == "variant":
                    row.append(str(int(v)))
                else:
                    row.append(csv_cell(v))
            w.writerow(row)
    return Path(path)
