"""``mechreport build``: one report folder per spec, in parallel, and a batch index.

    OUT/<stem>/report.md, report.pdf, results.csv, summary.json, figures/*.png|svg
    OUT/index.md, OUT/index.pdf

One failing spec is reported (stderr, and a FAIL row with its message in the index) and does
not stop the others; the exit code is 1 if any spec failed to build.
"""
from __future__ import annotations

import multiprocessing
import os
import sys
import time
from concurrent.futures import ProcessPoolExecutor, as_completed
from pathlib import Path

from ..errors import MechreportError


def build_one(path: Path, out: Path, sheet: bool = False, exact: bool = False) -> dict:
    """Analyse ``path`` and write its report folder under ``out``; the index row.

    Raises whatever the analysis or rendering raises (see :func:`build_safe`)."""
    from ..analysis import analyse
    from .drawing import write_drawings
    from .model import build_model
    from .plots import write_plots
    from .render import write_report

    path = Path(path)
    analysis = analyse(path)
    model = build_model(analysis, path)
    outdir = Path(out) / model.stem
    write_plots(model, outdir / "figures")
    write_drawings(model, outdir / "figures")
    write_report(model, outdir)
    row = dict(model.index_row, sheets=[])
    if sheet or analysis.spec.sheet:
        from .sheet import write_sheet
        written = write_sheet(analysis, outdir, exact=exact)
        row["sheets"] = [Path(p).resolve().relative_to(Path(out).resolve()).as_posix()
                         for p in written if str(p).endswith((".md", ".pdf"))]
    return row


def build_safe(path: str, out: str, sheet: bool, exact: bool) -> dict:
    """:func:`build_one` that never raises: a failure becomes a row with ``ok`` False and
    the error ``message``. Adds ``seconds``. (Top-level so worker processes can run it.)"""
    start = time.perf_counter()
    try:
        row = build_one(Path(path), Path(out), sheet, exact)
    except MechreportError as exc:
        row = _failure(path, str(exc))
    except Exception as exc:  # noqa: BLE001 - one bad spec must not stop the batch
        row = _failure(path, f"{type(exc).__name__}: {exc}")
    row["seconds"] = time.perf_counter() - start
    row["spec"] = str(path)
    return row


def _failure(path, message: str) -> dict:
    return {"ok": False, "spec": str(path), "stem": Path(path).stem, "name": Path(path).stem,
            "status": "FAIL", "message": message.strip() or "unknown error", "sheets": []}


class Progress:
    """A one-line bar on a terminal; plain lines otherwise (both on stderr)."""

    def __init__(self, total: int, stream=None):
        self.total, self.done = total, 0
        self.stream = stream or sys.stderr
        self.tty = hasattr(self.stream, "isatty") and self.stream.isatty()

    def update(self, row: dict) -> None:
        self.done += 1
        spec, secs = row["spec"], row.get("seconds", 0.0)
        if not row["ok"]:
            self._clear()
            print(f"FAIL {spec}: {row['message']}", file=self.stream)
        elif not self.tty:
            print(f"built {spec} ({secs:.1f} s)", file=self.stream)
        if self.tty:
            width = 30
            fill = int(width * self.done / max(self.total, 1))
            self.stream.write(f"\r[{'#' * fill}{'.' * (width - fill)}] {self.done}/"
                              f"{self.total} {Path(spec).name[:40]:<40}")
            self.stream.flush()

    def _clear(self) -> None:
        if self.tty:
            self.stream.write("\r" + " " * 80 + "\r")

    def close(self) -> None:
        if self.tty:
            self.stream.write("\n")
            self.stream.flush()


def _run(paths: list[Path], out: Path, jobs: int, sheet: bool, exact: bool,
         progress: Progress) -> list[dict]:
    rows: dict[str, dict] = {}
    if jobs <= 1 or len(paths) <= 1:
        for p in paths:
            rows[str(p)] = build_safe(str(p), str(out), sheet, exact)
            progress.update(rows[str(p)])
    else:
        # fresh interpreters: forking a process whose Typst/BLAS threads are running can
        # deadlock the child (seen under pytest, after a report was typeset in-process)
        ctx = multiprocessing.get_context("spawn")
        with ProcessPoolExecutor(max_workers=jobs, mp_context=ctx) as pool:
            futs = {pool.submit(build_safe, str(p), str(out), sheet, exact): str(p)
                    for p in paths}
            for fut in as_completed(futs):
                try:
                    row = fut.result()
                except Exception as exc:  # noqa: BLE001 - a worker died
                    row = _failure(futs[fut], f"{type(exc).__name__}: {exc}")
                rows[futs[fut]] = row
                progress.update(row)
    return [rows[str(p)] for p in paths]


def build_files(paths: list[Path], out: Path, jobs: int | None = None, sheet: bool = False,
                exact: bool = False) -> int:
    """Build every spec in ``paths`` into ``out`` and write the index; exit code 0 if all
    built, 1 otherwise. ``jobs``: parallel processes (default: the number of cores)."""
    from .render import write_index

    paths = [Path(p) for p in paths]
    if not paths:
        print("no spec files given", file=sys.stderr)
        return 1
    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    jobs = max(1, min(jobs or os.cpu_count() or 1, len(paths)))
    start = time.perf_counter()
    progress = Progress(len(paths))
    rows = _run(paths, out, jobs, sheet, exact, progress)
    progress.close()
    failed = [r for r in rows if not r["ok"]]
    try:
        write_index(rows, out)
    except MechreportError as exc:
        print(f"error: index: {exc}", file=sys.stderr)
        return 1
    print(f"{len(rows) - len(failed)} of {len(rows)} report(s) built in {out} "
          f"({time.perf_counter() - start:.1f} s)", file=sys.stderr)
    return 1 if failed else 0
