"""``mechreport tolerance SPEC``: load, sample the spec's ``tolerances:``, run the samples,
write the outputs.

Exit status: 0 when the analysis ran and was written (whatever its samples' outcomes:
samples that cannot be assembled or analysed are counted, reported and are rows with their
reason); 1 when it cannot run (the spec or its tolerances section is invalid, the spec as
written cannot be analysed, the scheduler cannot be used, the output folder cannot be
written) or when samples could not be computed because a worker process or the Dask cluster
was lost (they are written as failed rows saying why; one line on stderr says how many). 130
when interrupted (nothing is written then).

The files, written into ``OUT/<spec>/`` safely (as ``mechreport study`` writes its own: a
private folder swapped in, a report or study there kept):

    OUT/<spec>/tolerance.parquet, tolerance.csv   one row per sample (study.tolerance_outputs)
    OUT/<spec>/tolerance.md, tolerance.pdf        the report (study.tolerance_report)
    OUT/<spec>/tolerance-figures/*.svg            its histograms
    OUT/<spec>/tolerance.json                     the tolerance.* quantities
    OUT/<spec>/summary.json                       a report's, with the tolerance.* quantities
                                                  added (only where a report is there; a
                                                  later build of the same spec content
                                                  adds them again: carry_into_report)
"""
from __future__ import annotations

import json
import os
import sys
import time
from pathlib import Path

from . import outdir as od

EPILOG = """\
exit status: 0 when the analysis ran and its files were written (samples that cannot be
assembled or analysed are counted, reported and written with their reason); 1 when it cannot
run (a spec problem, no tolerances: section, a spec that cannot be analysed as written, a
malformed or unreachable --scheduler, an unusable output folder) or when samples could not be
computed because a worker process or the Dask cluster was lost (written as failed rows,
stderr says how many); 2 on a usage error; 130 if interrupted (nothing is written then).

Writes OUT/<name>/tolerance.parquet, tolerance.csv (one row per sample), tolerance.md,
tolerance.pdf and tolerance.json, and adds the tolerance.* quantities to a report's
summary.json there; a report or study there is kept. Progress and an ETA go to stderr."""


def add_parser(sub) -> None:
    """The ``tolerance`` subcommand's parser."""
    import argparse
    import textwrap

    from .args import add_run_options, add_wait, filled
    p = sub.add_parser("tolerance", help="the chance the built machine passes (a spec's "
                       "tolerances: section)",
                       description=textwrap.fill(
                           "Sample the uncertain values of the spec's tolerances: section, "
                           "analyse every sample as a whole machine (one force method each, "
                           "with the study's trust test), and report the kept quantities' "
                           "statistics, each design verdict's probability of passing, the "
                           "probability of assembly and which tolerance matters.", 79),
                       epilog=filled(EPILOG), formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("spec", metavar="SPEC")
    p.add_argument("-o", "--out", default="out", help="output folder (default: out)")
    add_run_options(p, "sample")
    add_wait(p)
    p.set_defaults(func=_cmd)


def _cmd(ns) -> int:
    return tolerance_command(Path(ns.spec), Path(ns.out), method=ns.method,
                             scheduler=ns.scheduler, jobs=ns.jobs, chunk=ns.chunk,
                             wait=ns.wait)


def tolerance_command(path, out="out", method: str | None = None,
                      scheduler: str | None = None, jobs: int | None = None,
                      chunk: int | None = None, wait: float = 120.0, stream=None) -> int:
    """Run the tolerance analysis of the spec at ``path`` into ``out``; the exit status (see
    the module docstring). Raises ``SpecError``/``MechreportError`` when it cannot run and
    KeyboardInterrupt when interrupted."""
    from functools import partial

    from ..report.provenance import build_time, spec_sha256
    from ..study.methods import choose_method
    from ..study.plan import SAMPLING_NAMES
    from ..study.tolerance import (TOLERANCE_WORDS, checked_nominal, load_tolerance_base,
                                   run_samples, tolerance_plan)
    from ..study.tolerance_stats import analyse_samples
    from .process import check_stop, stop_requests
    from .progress import StudyProgress, duration
    from .runs import cluster_client, lost_line, placement, stop_said
    from .workers import worker_init

    err = stream or sys.stderr
    path = Path(path)
    base = load_tolerance_base(path)
    tol = base.spec.tolerances
    method, why = choose_method(method, tol.keep, base.spec.design)
    nominal, verdicts = checked_nominal(base, method, tol.keep)
    plan = tolerance_plan(tol)
    out = od.prepare(Path(out))            # fail early on an unusable -o
    name = od.safe_stem(path)
    lost: list = []
    with stop_requests():
        with cluster_client(scheduler, err) as client:
            workers, size, where = placement(client, scheduler, plan.n, jobs, chunk, err)
            print(f"tolerance {path}: {plan.n} sample(s) of {len(plan.keys)} uncertain "
                  f"value(s), {SAMPLING_NAMES[plan.sample]} sampling; method {method} ({why}); "
                  f"on {where}, chunks of {size}", file=err, flush=True)
            progress = StudyProgress(plan.n, err, items="samples")

            start = time.perf_counter()
            with stop_said(err, lambda: f"interrupted after {progress.done} of {plan.n} "
                                        "sample(s); nothing was written", progress.close):
                table = run_samples(base, plan, method, tol.keep, [v.item for v in verdicts],
                                    jobs=workers, chunk=size, client=client,
                                    progress=progress.update, lost=lost, notify=progress.say,
                                    stop_check=check_stop,
                                    setup=partial(worker_init, os.getpid()))
                progress.close()
        seconds = time.perf_counter() - start
        result = analyse_samples(base, table, nominal, verdicts, method, why, seconds, lost)
        print(f"{plan.n} sample(s) in {duration(seconds)}: "
              + ", ".join(f"{n} {s}" for s, n in result.counts.items() if s == "ok" or n),
              file=err, flush=True)
        date = build_time().strftime("%Y-%m-%d %H:%M UTC")
        sha = spec_sha256(path)
        print(f"writing {out / name}/ ...", file=err, flush=True)
        with stop_said(err, lambda: f"interrupted while writing; {out / name} was left as it "
                                    "was"):
            final = write_tolerance(result, out, name, wait, date=date, sha256=sha,
                                    where=where, chunk=size)
    print(result_line(result) + f"; written to {final}/ (tolerance.parquet, tolerance.csv, "
          "tolerance.md, tolerance.pdf, tolerance.json)")
    if lost:
        print(f"error: {lost_line(lost, plan.n, TOLERANCE_WORDS)}", file=err)
    return 1 if lost else 0


def result_line(result) -> str:
    """One line: the samples, the probability of assembly and of passing every verdict."""
    from ..study.tolerance_report import interval, percent   # as tolerance.md prints them
    a, d = result.assembly, result.design
    text = (f"{result.spec.file}: {result.table.n} sample(s): assembles "
            f"{percent(a.p)} (95 % interval {interval(a)})")
    if result.verdicts:
        text += f"; passes every design verdict {percent(d.p)} ({interval(d)})"
    return text


def write_tolerance(result, out: Path, name: str, wait: float = 120.0, *, date: str = "",
                    sha256: str = "", where: str = "", chunk: int | None = None) -> Path:
    """Write every file of ``result`` into ``OUT/name``; the folder."""
    from ..report.files import atomic_write_text
    from ..report.pdf import compile_typst
    from ..report.write_markdown import markdown
    from ..report.write_typst import typst
    from ..study.tolerance_outputs import write_csv, write_parquet
    from ..study.tolerance_report import FIGURES, build_document, write_figures
    from ..version import __version__

    quantities = result.summary()

    def write(tmp: Path) -> None:
        t = result.table
        meta = {"spec": result.base.file, "spec_sha256": sha256, "method": result.method,
                "sample": t.plan.sample, "seed": t.plan.seed, "samples": t.n,
                "version": __version__}
        write_parquet(t, tmp / "tolerance.parquet", meta)
        write_csv(t, tmp / "tolerance.csv")
        figures = write_figures(result, tmp / FIGURES)
        doc = build_document(result, figures, date=date, sha256=sha256, where=where,
                             chunk=chunk)
        atomic_write_text(tmp / "tolerance.md", markdown(doc))
        compile_typst(typst(doc), tmp / "tolerance.pdf", tmp)
        record = {"mechreport_version": __version__, "spec": result.base.file,
                  "spec_sha256": sha256, "date": date, "quantities": quantities}
        atomic_write_text(tmp / "tolerance.json", json.dumps(record, indent=2,
                                                             allow_nan=False) + "\n")
        merged = report_summary(out / name / "summary.json", quantities, sha256)
        if merged is not None:
            atomic_write_text(tmp / "summary.json", json.dumps(merged, indent=2,
                                                               allow_nan=False) + "\n")

    with od.writing(out, wait) as out:
        return od.write_folder(out, name, write, carry=od.all_but(od.TOLERANCE_ENTRIES))


def report_summary(report: Path, quantities: dict, sha256: str) -> dict | None:
    """The folder's report summary.json (``report``) with the ``tolerance.*``
    ``quantities``; None when there is no report, or it is not of this spec's content
    (``sha256``): another spec of the same file name, or this spec edited since its build,
    is another design, whose record must not get these figures (as
    :func:`carry_into_report`)."""
    if not report.is_file() or report.is_symlink():
        return None
    summary = json.loads(report.read_text(encoding="utf-8"))
    if not isinstance(summary, dict) or not sha256 or summary.get("spec_sha256") != sha256:
        return None
    return with_tolerance(summary, quantities)


def with_tolerance(summary: dict, quantities: dict) -> dict:
    """A report's summary.json with its ``tolerance.*`` quantities replaced by
    ``quantities``."""
    old = summary.get("quantities") if isinstance(summary.get("quantities"), dict) else {}
    kept = {k: v for k, v in old.items() if not k.startswith("tolerance.")}
    return {**summary, "quantities": {**kept, **quantities}}


def carry_into_report(summary: Path, record: Path, sha256: str) -> None:
    """A build's new ``summary`` (summary.json) gains the ``tolerance.*`` quantities of the
    folder's ``record`` (tolerance.json) when that was computed from the same spec content
    (``sha256``): a rebuild keeps them; a changed spec drops them (they were of another
    design). Nothing happens when there is no record, or it cannot be read."""
    try:
        if record.is_symlink() or not record.is_file():
            return
        data = json.loads(record.read_text(encoding="utf-8"))
    except (OSError, ValueError):
        return
    if not isinstance(data, dict) or data.get("spec_sha256") != sha256 \
            or not isinstance(data.get("quantities"), dict):
        return
    quantities = data["quantities"]
    from ..report.files import atomic_write_text
    merged = with_tolerance(json.loads(summary.read_text(encoding="utf-8")), quantities)
    atomic_write_text(summary, json.dumps(merged, indent=2, allow_nan=False) + "\n")
