"""Write a study's files into ``OUT/<spec>/``, safely.

    OUT/<spec>/study.parquet, study.csv      one row per variant (columns: study.table)
    OUT/<spec>/study.md, study.pdf           the study report (study.report)
    OUT/<spec>/study-figures/*.svg           its figures
    OUT/<spec>/study-reports/NN-variant-I/   --reports K: full reports of the K best

``<spec>`` is the spec's file name without .yaml, made safe as ``mechreport build`` does
(:func:`mechreport.report.outdir.safe_stem`). The study shares ``OUT/.mechreport.lock`` with
builds (a study and a build into the same OUT take turns while writing; the variants are
computed before the lock is taken). Everything is written into a private folder
``OUT/.tmp-<spec>-<pid>`` first; when complete, it is swapped in for ``OUT/<spec>`` with two
renames, carrying over (as hard links) whatever else that folder held (a report built there
by ``mechreport build``), and replacing the files of an earlier study. So an interrupted study
leaves ``OUT/<spec>`` as it was, and the next build or study deletes the leftover private
folder. Only a folder holding a report (summary.json), a study (study.parquet) or nothing is
ever replaced.
"""
from __future__ import annotations

import csv
from pathlib import Path

import numpy as np

from ..report import outdir as od
from .table import Table

#: what a study writes in OUT/<spec>/ (replaced by the next study, kept by nothing else)
STUDY_ENTRIES = od.STUDY_ENTRIES


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


def _cell(value) -> str:
    """A number's shortest exact form (``-10``, ``0.125``, ``1e+20``), empty if undefined."""
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
    passed = {1: "true", 0: "false", -1: ""}
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
                    row.append(passed[int(v)])
                elif name == "variant":
                    row.append(str(int(v)))
                else:
                    row.append(_cell(v))
            w.writerow(row)
    return Path(path)


# ----------------------------------------------------------------------------- folder

def install(out: Path, tmp: Path, name: str) -> Path:
    """Make ``tmp`` (a complete study folder) ``OUT/name``, carrying over the entries of the
    old folder that are not a study's (its report); two renames, undone if the second fails."""
    return od.swap_in(out, tmp, name, carry=lambda entry: entry not in STUDY_ENTRIES)
