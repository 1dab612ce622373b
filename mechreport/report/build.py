"""``mechreport build``: one report folder per spec, in parallel, and a batch index.

    OUT/<name>/report.md, report.pdf, results.csv, summary.json, figures/*.svg
    OUT/index.md, OUT/index.pdf, OUT/index.csv, OUT/index.json

Folder names, the lock on ``OUT`` and the whole-folder swap are described in
:mod:`mechreport.report.outdir`. One failing spec is reported (stderr, and a FAIL row with its
message in the index) and does not stop the others. The index lists every report folder in
``OUT`` (read back from each folder's summary.json), with this run's failures as FAIL rows.
The exit code is 1 if any spec of this run failed to build or failed its check.

Workers end with the build: Ctrl-C or SIGTERM stops the pool and terminates the workers, and
a worker whose parent has died exits by itself within a second.
"""
from __future__ import annotations

import multiprocessing
import os
import signal
import sys
import threading
import time
import traceback
from concurrent.futures import ProcessPoolExecutor, as_completed
from contextlib import contextmanager
from pathlib import Path

from ..errors import MechreportError
from . import outdir as od

DEFAULT_WAIT = 120.0


class Terminated(KeyboardInterrupt):
    """SIGTERM, handled like Ctrl-C."""


def build_key(path: Path, sheet: bool, exact: bool, sheet_options=None) -> dict:
    """What decides whether a report is up to date: the spec's bytes (SHA-256), its path, the
    mechreport version and the options that change the output (``sheet_options``: the
    sheets' methods and angles, a :class:`~mechreport.report.sheet.SheetOptions`)."""
    from .. import __version__
    from .model import spec_sha256
    key = {"spec": str(path), "spec_sha256": spec_sha256(path),
           "mechreport_version": __version__, "sheet": bool(sheet), "exact": bool(exact)}
    if sheet_options is not None:
        key.update(sheet_options.key())
    return key


def up_to_date(out: Path, name: str, key: dict) -> dict | None:
    """The summary of ``out/name`` when it was built from the same ``key`` and its files are
    all there (then the spec need not be built again); None otherwise."""
    import json
    folder = Path(out) / name
    try:
        summary = json.loads((folder / "summary.json").read_text(encoding="utf-8"))
    except (OSError, ValueError):
        return None
    if not isinstance(summary, dict) or summary.get("build") != key or not key["spec_sha256"]:
        return None
    if not all((folder / f).is_file() for f in ("report.md", "report.pdf", "results.csv")):
        return None
    return summary


def build_one(path: Path, out: Path, name: str, folder: Path, sheet: bool = False,
              exact: bool = False, stage=None, sheet_options=None) -> dict:
    """Analyse ``path`` and write its report into ``folder`` (a private folder inside
    ``out``, later renamed to ``out/name``); the run's row. ``stage(i, n, what)`` is called
    before each stage (progress for long single specs).

    Raises whatever the analysis or rendering raises (see :func:`build_safe`)."""
    from ..analysis import analyse
    from .drawing import write_drawings
    from .model import index_row, build_model
    from .plots import write_plots
    from .render import write_report

    stage = stage or (lambda i, n, what: None)
    from ..spec import load_spec

    path, folder = Path(path), od.inside(out, folder)
    key = build_key(path, sheet, exact, sheet_options)
    spec = load_spec(path)
    do_sheet = sheet or spec.sheet
    n = 4 if do_sheet else 3
    stage(1, n, "analysing")
    analysis = analyse(spec)
    model = build_model(analysis, path, sha256=key["spec_sha256"])
    model.summary["build"] = key
    model.stem, model.index_row = name, index_row(model.summary, name)
    stage(2, n, "figures")
    write_plots(model, folder / "figures")
    write_drawings(model, folder / "figures")
    stage(3, n, "report (Markdown, PDF, CSV, JSON)")
    write_report(model, folder)
    if do_sheet:
        from .sheet import SheetOptions, sheet_analysis, write_sheet
        stage(4, n, "solution sheet and problem")
        options = SheetOptions(sheet_options.methods if sheet_options else None,
                               sheet_options.angles if sheet_options else None, exact)
        write_sheet(sheet_analysis(analysis, options), folder, options)
    for written in folder.rglob("*"):                   # nothing escaped the folder
        od.inside(folder, written)
    return dict(model.index_row, folder=name)


def _stage_printer(label: str):
    """Stage lines on stderr for a single spec: ``[1/4] specs/x.yaml: analysing``."""
    def stage(i: int, n: int, what: str) -> None:
        print(f"[{i}/{n}] {label}: {what}", file=sys.stderr, flush=True)
    return stage


def build_safe(path: str, out: str, name: str, sheet: bool, exact: bool,
               owner: int | None = None, stages: bool = False, sheet_options=None) -> dict:
    """:func:`build_one` into ``OUT/.tmp-<name>-<owner>`` that never raises an Exception: a
    failure becomes a row with ``ok`` False and the error ``message`` (the private folder is
    then removed). Adds ``seconds`` and ``tmp``. (Top-level so worker processes can run it.)"""
    from ..cli import describe_failure

    start = time.perf_counter()
    tmp = None
    try:
        tmp = od.make_tmp_dir(Path(out), name, owner)
        row = build_one(Path(path), Path(out), name, tmp, sheet, exact,
                        _stage_printer(str(path)) if stages else None, sheet_options)
        row["tmp"] = str(tmp)
    except Exception as exc:  # noqa: BLE001 - one bad spec must not stop the batch
        if tmp is not None:
            od.remove(tmp)
        row = _failure(path, name, describe_failure(exc))
        if os.environ.get("MECHREPORT_DEBUG"):
            row["traceback"] = traceback.format_exc()
    except BaseException:
        if tmp is not None:
            od.remove(tmp)
        raise
    row["seconds"] = time.perf_counter() - start
    row["spec"] = str(path)
    return row


def _failure(path, name: str, message: str) -> dict:
    return {"ok": False, "spec": str(path), "folder": name, "stem": name, "name": name,
            "status": "FAIL", "message": message.strip() or "unknown error", "sheets": []}


class Progress:
    """``[n/N]`` progress on stderr: a one-line bar on a terminal, plain lines otherwise.
    ``quiet``: only failures are printed."""

    def __init__(self, total: int, stream=None, quiet: bool = False):
        self.total, self.done = total, 0
        self.stream = stream or sys.stderr
        self.quiet = quiet
        self.tty = (not quiet) and hasattr(self.stream, "isatty") and self.stream.isatty()

    def update(self, row: dict) -> None:
        self.done += 1
        spec, secs = row["spec"], row.get("seconds", 0.0)
        n = f"[{self.done}/{self.total}]"
        if not row["ok"]:
            self._clear()
            print(f"{n} FAIL {spec}: {row['message']}", file=self.stream)
            if row.get("traceback"):
                print(row["traceback"].rstrip(), file=self.stream)
        elif row.get("status") == "FAIL":
            self._clear()
            what = f"built {spec} ({secs:.1f} s)"
            if row.get("skipped"):
                what = f"{spec} unchanged (not rebuilt)"
            print(f"{n} {what}, but its check FAILED: see "
                  f"{row.get('folder', '?')}/report.md", file=self.stream)
        elif self.quiet:
            pass
        elif not self.tty:
            if row.get("skipped"):
                print(f"{n} unchanged {spec}: not rebuilt (--force rebuilds it)",
                      file=self.stream)
            else:
                print(f"{n} built {spec} ({secs:.1f} s)", file=self.stream)
        if self.tty:
            width = 30
            fill = int(width * self.done / max(self.total, 1))
            label = Path(spec).name[:40].encode("ascii", "replace").decode()
            label = "".join(c if c.isprintable() else "?" for c in label)
            self.stream.write(f"\r[{'#' * fill}{'.' * (width - fill)}] {self.done}/"
                              f"{self.total} {label:<40}")
            self.stream.flush()

    def _clear(self) -> None:
        if self.tty:
            self.stream.write("\r" + " " * 80 + "\r")

    def close(self) -> None:
        if self.tty:
            self.stream.write("\n")
            self.stream.flush()


# ------------------------------------------------------------------------------ workers

def worker_init(parent: int) -> None:
    """In each worker: leave Ctrl-C to the parent (the terminal sends it to every process of
    the group; the parent then terminates the workers), and exit if the parent dies."""
    signal.signal(signal.SIGINT, signal.SIG_IGN)
    signal.signal(signal.SIGTERM, signal.SIG_DFL)
    threading.Thread(target=_watch_parent, args=(parent,), daemon=True,
                     name="mechreport-parent-watch").start()


def _watch_parent(parent: int, every: float = 0.5) -> None:
    while True:
        time.sleep(every)
        if os.getppid() != parent:
            os._exit(1)                    # orphaned: the build is gone, stop writing


def stop_pool(pool: ProcessPoolExecutor) -> None:
    """Cancel what has not started and terminate the workers (they must not outlive us)."""
    procs = list((getattr(pool, "_processes", None) or {}).values())
    pool.shutdown(wait=False, cancel_futures=True)
    for p in procs:
        if p.is_alive():
            p.terminate()
    deadline = time.monotonic() + 3.0
    for p in procs:
        p.join(max(0.0, deadline - time.monotonic()))
        if p.is_alive():
            p.kill()
            p.join(1.0)


@contextmanager
def sigterm_as_interrupt():
    """SIGTERM raises :class:`Terminated` (a KeyboardInterrupt) in the main thread."""
    if threading.current_thread() is not threading.main_thread():
        yield
        return

    def handler(signum, frame):
        raise Terminated()

    previous = signal.signal(signal.SIGTERM, handler)
    try:
        yield
    finally:
        signal.signal(signal.SIGTERM, previous)


def _run(todo: list[tuple[int, Path, str]], out: Path, jobs: int, sheet: bool, exact: bool,
         finish, stages: bool = False, sheet_options=None) -> None:
    """Build each ``(i, path, name)`` of ``todo``; ``finish(i, row)`` is called in this
    process as each one ends (in completion order). ``stages``: print each stage of a spec
    (for a build of one spec)."""
    owner = os.getpid()
    if jobs <= 1 or len(todo) <= 1:
        for i, p, name in todo:
            finish(i, build_safe(str(p), str(out), name, sheet, exact, owner, stages,
                                 sheet_options))
        return
    # fresh interpreters: forking a process whose Typst/BLAS threads are running can
    # deadlock the child (seen under pytest, after a report was typeset in-process)
    ctx = multiprocessing.get_context("spawn")
    pool = ProcessPoolExecutor(max_workers=jobs, mp_context=ctx, initializer=worker_init,
                               initargs=(owner,))
    try:
        futs = {pool.submit(build_safe, str(p), str(out), name, sheet, exact, owner,
                            sheet_options=sheet_options): (i, p, name)
                for i, p, name in todo}
        for fut in as_completed(futs):
            i, p, name = futs[fut]
            try:
                row = fut.result()
            except Exception as exc:  # noqa: BLE001 - a worker died
                from ..cli import internal_error
                row = _failure(p, name, internal_error(exc))
            finish(i, row)
    except BaseException:
        stop_pool(pool)
        raise
    pool.shutdown(wait=True)


# -------------------------------------------------------------------------------- index

def index_rows(out: Path, failures: dict[str, dict] | None = None) -> list[dict]:
    """The index of ``out``: one row per report folder on disk (from its summary.json), with
    ``failures`` (folder name -> this run's FAIL row) in place of, or beside, the folders."""
    from .model import index_row

    failures = failures or {}
    disk = od.report_folders(out)
    rows = []
    for name in sorted(set(disk) | set(failures), key=lambda n: (n.casefold(), n)):
        if name in failures:
            row = dict(failures[name])
            if name in disk:
                row["message"] += f" (the report of an earlier build is still in {name}/)"
            rows.append(row)
            continue
        data = disk[name]
        try:
            if isinstance(data, str):
                raise ValueError(data)
            row = index_row(data, name)
        except (KeyError, TypeError, ValueError, IndexError) as exc:
            msg = str(exc) if isinstance(data, str) else \
                f"{name}/summary.json is not a mechreport summary ({type(exc).__name__}: {exc})"
            rows.append(_failure(name, name, msg))
            continue
        row["sheets"] = [(f"{label} {f.rsplit('.', 1)[-1]}", f"{name}/{f}")
                         for label, f in (("sheet", "solution.md"), ("sheet", "solution.pdf"),
                                          ("problem", "problem.md"), ("problem", "problem.pdf"))
                         if (Path(out) / name / f).is_file()]
        rows.append(row)
    return rows


def _write_index(out: Path, failures: dict[str, dict]) -> None:
    from .render import write_index
    write_index(index_rows(out, failures), out)


INDEX_FIELDS = ("folder", "name", "spec", "status", "peak_torque_N_m", "peak_torque_angle_deg",
                "rms_torque_N_m", "peak_driver_force_N", "rms_driver_force_N",
                "largest_bearing_load_N", "largest_bearing_joint",
                "mean_power_W", "worst_disagreement", "verdicts_passed", "verdicts_total",
                "failed_verdicts", "failed_expectations", "spec_sha256", "mechreport_version",
                "message")


def index_records(rows: list[dict]) -> list[dict]:
    """index.csv / index.json records: one per spec, SI, the unit in each field name."""
    out = []
    for r in rows:
        data = r.get("data") or {}
        rec = {"folder": r.get("stem") or r.get("folder"), "name": r.get("name"),
               "spec": r.get("spec"), "status": r.get("status", "FAIL"),
               **{k: data.get(k) for k in INDEX_FIELDS if k in data},
               "message": r.get("message") or ""}
        out.append({k: rec.get(k) for k in INDEX_FIELDS})
    return out


# -------------------------------------------------------------------------------- batch

def build_files(paths: list[Path], out: Path, jobs: int | None = None, sheet: bool = False,
                exact: bool = False, wait: float = DEFAULT_WAIT, force: bool = False,
                quiet: bool = False, sheet_options=None) -> int:
    """Build every spec in ``paths`` into ``out`` and rewrite the index; exit code 0 if all
    built and passed their checks, 1 otherwise. ``jobs``: parallel processes (default: the
    number of cores); ``wait``: seconds to wait for another build writing to ``out``. A spec
    whose report in ``out`` was built from the same bytes, path, options and mechreport
    version is not built again unless ``force``. ``quiet``: no progress, only failures.
    ``sheet_options``: the methods and angles of the solution sheets (a
    :class:`~mechreport.report.sheet.SheetOptions`; None: all methods, the spec's ``at``).

    Raises :class:`~mechreport.report.outdir.OutputError` if ``out`` cannot be used, and
    KeyboardInterrupt (or :class:`Terminated`) if interrupted: then the workers are stopped,
    finished reports are in place, unfinished ones left as they were, and the index rebuilt."""
    paths = od.unique_specs([Path(p) for p in paths])
    if not paths:
        print("no spec files given", file=sys.stderr)
        return 1
    out = od.prepare(Path(out))
    names = od.folder_names(paths)
    jobs = max(1, min(jobs or os.cpu_count() or 1, len(paths)))
    start = time.perf_counter()
    with sigterm_as_interrupt(), od.OutputLock(out).acquire(wait):
        od.clean_leftovers(out)
        progress = Progress(len(paths), quiet=quiet)
        failures: dict[str, dict] = {}
        rows: list[dict] = [{} for _ in paths]

        def finish(i: int, row: dict) -> None:
            if row["ok"]:
                try:
                    od.swap_in(out, Path(row.pop("tmp")), names[i])
                except (OSError, MechreportError) as exc:
                    from ..cli import describe_failure
                    od.remove(od.tmp_dir(out, names[i]))
                    row = _failure(paths[i], names[i], "cannot put the report in place: "
                                   + describe_failure(exc))
            if not row["ok"]:
                od.remove(od.tmp_dir(out, names[i]))           # a worker that died
                failures[names[i]] = row
            progress.update(row)
            rows[i] = row

        todo = []
        for i, (path, name) in enumerate(zip(paths, names)):
            why = od.occupied(out, name)      # not a report folder: never replaced
            if why:
                finish(i, dict(_failure(path, name, why), seconds=0.0))
                continue
            same = None if force else up_to_date(out, name, build_key(path, sheet, exact,
                                                                      sheet_options))
            if same is not None:
                from .model import index_row
                try:
                    row = dict(index_row(same, name), folder=name, spec=str(path),
                               skipped=True, seconds=0.0)
                except (KeyError, TypeError, ValueError, IndexError):
                    todo.append((i, path, name))
                    continue
                progress.update(row)
                rows[i] = row
            else:
                todo.append((i, path, name))
        try:
            _run(todo, out, min(jobs, max(len(todo), 1)), sheet, exact, finish,
                 stages=len(paths) == 1 and not quiet, sheet_options=sheet_options)
        except KeyboardInterrupt as exc:
            progress.close()
            for name in names:
                od.remove(od.tmp_dir(out, name))
            try:
                _write_index(out, failures)
            except Exception:  # noqa: BLE001 - interrupted anyway; the next build rewrites it
                pass
            what = "terminated" if isinstance(exc, Terminated) else "interrupted"
            print(f"{what} after {progress.done} of {len(paths)} spec(s): finished reports "
                  f"are in {out}, the others were left as they were", file=sys.stderr)
            exc.reported = True
            raise
        progress.close()
        failed = [r for r in rows if not r["ok"]]
        check_failed = [r for r in rows if r["ok"] and r.get("status") != "PASS"]
        try:
            _write_index(out, failures)
        except MechreportError as exc:
            print(f"error: index: {exc}", file=sys.stderr)
            return 1
    skipped = sum(1 for r in rows if r.get("skipped"))
    built = len(rows) - len(failed) - skipped
    note = (f"; {len(check_failed)} failed {'its' if len(check_failed) == 1 else 'their'} "
            "check" if check_failed else "")
    unchanged = f", {skipped} unchanged (not rebuilt; --force rebuilds)" if skipped else ""
    if not quiet:
        print(f"{built} of {len(rows)} report(s) built in {out}{unchanged} "
              f"({time.perf_counter() - start:.1f} s){note}", file=sys.stderr)
    return 1 if failed or check_failed else 0
