"""``mechreport build``: one report folder per spec, in parallel, and a batch index.

    OUT/<name>/report.md, report.pdf, results.csv, summary.json, figures/*.svg
    OUT/<name>/animation.gif, mechanism.dxf        (report.animation, report.dxf)
    OUT/index.md, OUT/index.pdf, OUT/index.csv, OUT/index.json

Folder names, the lock on ``OUT`` and the whole-folder swap are described in
:mod:`mechreport.app.outdir`. One failing spec is reported (stderr, and a FAIL row with its
message in the index) and does not stop the others; its earlier report, if any, is kept and
marked out of date (``FAILED.json``, see :mod:`.outdir`). The index lists every report
folder in ``OUT`` (read back from each folder's summary.json), with this run's failures and
the folders marked out of date as FAIL rows.
The exit code is 1 if any spec of this run failed to build or failed its check.

The specs are built by the study's executor (:mod:`mechreport.study.executor`): a worker
process that dies is replaced and its spec built again; workers end with the build
(:mod:`.workers`).
"""
from __future__ import annotations

import os
import sys
import time
import traceback
from dataclasses import replace
from pathlib import Path

from ..errors import MechreportError, describe_failure
from . import outdir as od
from .console import spec_files
from .process import Terminated, check_stop
from .progress import Progress
from .workers import worker_init

DEFAULT_WAIT = 120.0


def build_key(path: Path, sheet: bool, exact: bool, sheet_options=None,
              animation: bool = True) -> dict:
    """What decides whether a report is up to date: the spec's bytes (SHA-256), its path, the
    mechreport version and the options that change the output (``sheet_options``: the
    sheets' methods and angles, a :class:`~mechreport.report.sheet.SheetOptions`;
    ``animation`` False: ``--no-animation``)."""
    from ..report.provenance import spec_sha256
    from ..version import __version__
    key = {"spec": str(path), "spec_sha256": spec_sha256(path),
           "mechreport_version": __version__, "sheet": bool(sheet), "exact": bool(exact),
           "animation": bool(animation)}
    if sheet_options is not None:
        key.update(sheet_options.key())
    return key


def up_to_date(out: Path, name: str, key: dict) -> dict | None:
    """The summary of ``out/name`` when it was built from the same ``key``, its files are all
    there and its latest build did not fail (then the spec need not be built again); None
    otherwise."""
    import json
    folder = Path(out) / name
    if od.failure_of(folder) is not None:
        return None
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
              exact: bool = False, stage=None, sheet_options=None,
              animation: bool = True) -> dict:
    """Analyse ``path`` and write its report into ``folder`` (a private folder inside
    ``out``, later renamed to ``out/name``); the run's row. ``stage(i, n, what)`` is called
    before each stage (progress for long single specs). ``animation`` False: no
    animation.gif (``--no-animation``), whatever the spec's ``report.animation`` says.

    Raises whatever the analysis or rendering raises (see :func:`build_safe`)."""
    from ..pipeline import analyse
    from ..report.build import write_report_folder
    from ..spec import load_spec

    stage = stage or (lambda i, n, what: None)
    path, folder = Path(path), od.inside(out, folder)
    key = build_key(path, sheet, exact, sheet_options, animation)
    spec = load_spec(path)
    do_sheet = sheet or spec.sheet
    stage(1, 4 if do_sheet else 3, "analysing")
    analysis = analyse(spec)
    options = sheet_source = None
    if do_sheet:
        from ..report.sheet import SheetOptions, sheet_spec
        options = replace(sheet_options or SheetOptions(), exact=exact)
        wanted = sheet_spec(spec, options)
        if wanted is not spec:              # the sheet's angles are not all in the sweep
            sheet_source = analyse(wanted, tol=analysis.tol)
    row = write_report_folder(analysis, folder, path, key["spec_sha256"], name=name,
                              build_key=key, sheet=do_sheet, sheet_options=options,
                              sheet_source=sheet_source, stage=stage, animation=animation)
    from .tolerance import carry_into_report         # a tolerance analysis there stays
    carry_into_report(folder / "summary.json", out / name / "tolerance.json",
                      key["spec_sha256"])
    if do_sheet and spec.sheet_settings.variants is not None:   # one problem per student
        from ..study.sheet_variants import write_class
        stage(4, 4, "writing the variants")
        write_class(path, folder, options, check_stop)
    for written in folder.rglob("*"):                   # nothing escaped the folder
        od.inside(folder, written)
    return dict(row, folder=name)


def _stages(label: str, shown: bool):
    """The stage callback of one spec: a safe point for a stop request (:func:`check_stop`)
    and, if ``shown``, a line on stderr: ``[1/4] specs/x.yaml: analysing``."""
    def stage(i: int, n: int, what: str) -> None:
        check_stop()
        if shown:
            print(f"[{i}/{n}] {label}: {what}", file=sys.stderr, flush=True)
    return stage


def build_safe(path: str, out: str, name: str, sheet: bool, exact: bool,
               owner: int | None = None, stages: bool = False, sheet_options=None,
               animation: bool = True) -> dict:
    """:func:`build_one` into ``OUT/.tmp-<name>-<owner>`` that never raises an Exception: a
    failure becomes a row with ``ok`` False and the error ``message`` (the private folder is
    then removed). Adds ``seconds`` and ``tmp``. (Top-level so worker processes can run it.)"""

    start = time.perf_counter()
    tmp = None
    try:
        tmp = od.make_tmp_dir(Path(out), name, owner)
        row = build_one(Path(path), Path(out), name, tmp, sheet, exact,
                        _stages(str(path), stages), sheet_options, animation)
        row["tmp"] = str(tmp)
    except Exception as exc:  # noqa: BLE001 - one bad spec must not stop the batch
        if tmp is not None:
            od.remove(tmp)
            od.as_in_place(exc, tmp, Path(out) / name)
        # a stop that landed in an import leaves a half-made module whose next use fails:
        # that failure is the stop's, not the spec's (no FAIL row, no mark on its report)
        check_stop()
        row = _failure(path, name, describe_failure(exc))
        if os.environ.get("MECHREPORT_DEBUG"):
            row["traceback"] = traceback.format_exc()
    except BaseException:
        if tmp is not None:
            od.remove(tmp)
        raise
    row["seconds"] = time.perf_counter() - start
    row["spec"] = shown_path(path)
    return row


def shown_path(path) -> str:
    """``path`` as the index shows it: relative to where the build runs when it is below
    it, else as given."""
    rel = os.path.relpath(os.path.abspath(path))
    return rel if not rel.startswith(os.pardir) else str(path)


def _failure(path, name: str, message: str) -> dict:
    return {"ok": False, "spec": shown_path(path), "folder": name, "stem": name, "name": name,
            "status": "FAIL", "message": message.strip() or "unknown error", "sheets": []}


def _mark_out_of_date(out: Path, name: str, row: dict) -> None:
    """A failed spec's earlier report, if any, marked out of date (``OUT/name/FAILED.json``);
    when the mark cannot be written the row's message says so. Never once a stop was
    requested: a stopped build leaves every earlier report as it was."""
    check_stop()
    try:
        od.mark_failed(out, name, row["spec"], row["message"])
    except (OSError, MechreportError) as exc:
        row["message"] += (f" (its earlier report in {name}/ could not be marked out of date: "
                           f"{describe_failure(exc)})")


def _build_task(options: tuple, i: int, path: str, name: str) -> tuple[int, dict]:
    """One spec's build in a worker of the executor: ``(i, its row)`` (:func:`build_safe`
    with the build's ``options``: out, sheet, exact, owner, stages, sheet_options,
    animation). Top-level, so that worker processes can run it."""
    out, sheet, exact, owner, stages, sheet_options, animation = options
    return i, build_safe(path, out, name, sheet, exact, owner, stages, sheet_options,
                         animation)


def _run(todo: list[tuple[int, Path, str]], out: Path, jobs: int, sheet: bool, exact: bool,
         finish, stages: bool = False, sheet_options=None, animation: bool = True) -> None:
    """Build each ``(i, path, name)`` of ``todo`` through the study's executor (one spec per
    job, on ``jobs`` worker processes, or in this process for one); ``finish(i, row)`` is
    called in this process as each one ends (in completion order). A worker process that
    dies is replaced and its spec built again (up to three tries, then a FAIL row saying so;
    a warning on stderr for each retry). ``stages``: print each stage of a spec (for a build
    of one spec)."""
    from functools import partial

    from ..study.executor import Words
    from ..study.run import run_chunks

    owner = os.getpid()
    options = (str(out), sheet, exact, owner, stages, sheet_options, animation)

    def args_of(chunk) -> tuple:
        i, p, name = todo[chunk[0]]
        return i, str(p), name

    def on_done(chunk, result) -> None:
        finish(*result)

    def on_lost(start: int, stop: int, reason: str) -> None:
        for i, p, name in todo[start:stop]:
            finish(i, _failure(p, name, reason))

    def notify(line: str) -> None:
        print(line, file=sys.stderr, flush=True)

    words = Words(item="spec", part="specs", run="build", kept="the reports built are kept",
                  label=lambda chunk: str(todo[chunk[0]][1]))
    run_chunks(_build_task, options, len(todo), 1, args_of, on_done,
               jobs=1 if len(todo) <= 1 else jobs, on_lost=on_lost, notify=notify,
               stop_check=check_stop, setup=partial(worker_init, owner), words=words)


# -------------------------------------------------------------------------------- index

def index_rows(out: Path, failures: dict[str, dict] | None = None) -> list[dict]:
    """The index of ``out``: one row per report folder on disk (from its summary.json; a FAIL
    row for one marked out of date), with ``failures`` (folder name -> this run's FAIL row)
    in place of, or beside, the folders."""
    from ..report.records import index_row

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
        why = od.failure_of(Path(out) / name)
        if why is not None:
            spec = data.get("spec") if isinstance(data, dict) else None
            spec = spec if isinstance(spec, str) else name
            rows.append(_failure(spec, name, f"the latest build failed: {why} (the report of "
                                             f"an earlier build is still in {name}/)"))
            continue
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
        if (Path(out) / name / "animation.gif").is_file():
            row["animation"] = f"{name}/animation.gif"
        rows.append(row)
    return rows


def _write_index(out: Path, failures: dict[str, dict]) -> None:
    from ..report.render import write_index
    write_index(index_rows(out, failures), out)


# -------------------------------------------------------------------------------- batch

def build_files(paths: list[Path], out: Path, jobs: int | None = None, sheet: bool = False,
                exact: bool = False, wait: float = DEFAULT_WAIT, force: bool = False,
                quiet: bool = False, sheet_options=None, animation: bool = True) -> int:
    """Build every spec in ``paths`` into ``out`` and rewrite the index; exit code 0 if all
    built and passed their checks, 1 otherwise. ``jobs``: parallel processes (default: the
    number of cores); ``wait``: seconds to wait for another build writing to ``out``. A spec
    whose report in ``out`` was built from the same bytes, path, options and mechreport
    version is not built again unless ``force``. ``quiet``: no progress, only failures.
    ``sheet_options``: the methods and angles of the solution sheets (a
    :class:`~mechreport.report.sheet.SheetOptions`; None: all methods, the spec's ``at``).
    ``animation`` False: no animation.gif in any report (``--no-animation``).

    Raises :class:`~mechreport.app.outdir.OutputError` if ``out`` cannot be used, and
    KeyboardInterrupt (or :class:`Terminated`) if interrupted: then the workers are stopped,
    finished reports are in place, unfinished ones left as they were, and the index rebuilt."""
    paths = od.unique_specs([Path(p) for p in paths])
    if not paths:
        print("no spec files given", file=sys.stderr)
        return 1
    names = od.folder_names(paths)
    jobs = max(1, min(jobs or os.cpu_count() or 1, len(paths)))
    start = time.perf_counter()
    with od.writing(Path(out), wait) as out:
        progress = Progress(len(paths), quiet=quiet)
        failures: dict[str, dict] = {}
        rows: list[dict] = [{} for _ in paths]

        def finish(i: int, row: dict) -> None:
            if row["ok"]:
                try:
                    od.swap_in(out, Path(row.pop("tmp")), names[i])
                except (OSError, MechreportError) as exc:
                    od.remove(od.tmp_dir(out, names[i]))
                    row = _failure(paths[i], names[i], "cannot put the report in place: "
                                   + describe_failure(exc))
            if not row["ok"]:
                od.remove(od.tmp_dir(out, names[i]))           # a worker that died
                _mark_out_of_date(out, names[i], row)
                failures[names[i]] = row
            progress.update(row)
            rows[i] = row

        todo = []
        for i, (path, name) in enumerate(zip(paths, names)):
            why = od.occupied(out, name)      # not a report folder: never replaced
            if why:
                finish(i, dict(_failure(path, name, why), seconds=0.0))
                continue
            same = None if force else up_to_date(out, name, build_key(
                path, sheet, exact, sheet_options, animation))
            if same is not None:
                from ..report.records import index_row
                try:
                    row = dict(index_row(same, name), folder=name, spec=shown_path(path),
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
                 stages=len(paths) == 1 and not quiet, sheet_options=sheet_options,
                 animation=animation)
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
        except (OSError, MechreportError) as exc:
            print(f"error: index: {describe_failure(exc)}", file=sys.stderr)
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


def build_command(ns) -> int:
    """``mechreport build`` from its parsed arguments (see :mod:`.cli`)."""
    options = None
    if not ns.sheet:
        given = [o for o, v in (("--exact", ns.exact), ("--sheet-methods", ns.sheet_methods),
                                ("--sheet-angles", ns.sheet_angles),
                                ("--variants", ns.variants), ("--seed", ns.seed is not None))
                 if v]
        if given:
            print(f"error: {', '.join(given)} need{'s' if len(given) == 1 else ''} --sheet: "
                  f"{'it changes' if len(given) == 1 else 'they change'} only the solution "
                  "sheets, which --sheet writes", file=sys.stderr)
            return 2
    else:
        from ..report.sheet import SheetOptions
        if ns.exact:
            from ..report.sheet.exact import require_sympy
            require_sympy()                 # a clear message now, not one per spec
        options = SheetOptions(ns.sheet_methods, ns.sheet_angles, ns.exact, ns.variants,
                               ns.seed)
    return build_files(spec_files(ns.specs), Path(ns.out), jobs=ns.jobs, sheet=ns.sheet,
                       exact=ns.exact, wait=ns.wait, force=ns.force, quiet=ns.quiet,
                       sheet_options=options, animation=not ns.no_animation)
