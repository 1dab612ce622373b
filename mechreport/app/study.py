"""``mechreport study SPEC``: load, plan, run the variants, cross-check, write the outputs.

Exit status: 0 when the study ran and was written (whatever its variants' outcomes: failed
variants are rows with their reason); 1 when it cannot run (the spec or its study section is
invalid, the method cannot give the kept quantities, the scheduler address is malformed or
the scheduler cannot be reached or used, the output folder cannot be written), when
``--cross-check`` finds a disagreement, when a report asked for with ``--reports`` could not
be written ("error: no report for rank ..."), or when variants could not be computed because
a worker process, a Dask task or the Dask scheduler was lost (see
:mod:`mechreport.study.executor`: a lost chunk is computed again, up to three tries in all).
In those last cases the study is still written, with the variants not computed as failed
rows saying why, and one line on stderr says how many ("error: N of M variant(s) could not
be computed ..."). 130 when interrupted (nothing is written then).

Local processes: ``--jobs`` is lowered to the usable cores and to the number of chunks,
with one line on stderr saying so ("--jobs 1000: using 2 process(es), because ...").

The files, written into ``OUT/<spec>/`` safely:

    OUT/<spec>/study.parquet, study.csv      one row per variant (columns: study.table)
    OUT/<spec>/study.md, study.pdf           the study report (study.report)
    OUT/<spec>/study-figures/*.svg           its figures
    OUT/<spec>/study-reports/NN-variant-I/   --reports K: full reports of the K best

``<spec>`` is the spec's file name without .yaml, made safe as ``mechreport build`` does
(:func:`mechreport.app.outdir.safe_stem`). The study shares ``OUT/.mechreport.lock`` with
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

import os
import sys
import time
from pathlib import Path

from ..errors import describe_failure
from . import outdir as od
from .runs import cluster_client, lost_line, placement, stop_said


def study_command(path, out="out", method: str | None = None, scheduler: str | None = None,
                  jobs: int | None = None, reports: int = 0, cross: int = 0,
                  chunk: int | None = None, wait: float = 120.0, stream=None) -> int:
    """Run the study of the spec at ``path`` into ``out``; the exit status (see the module
    docstring). Raises ``SpecError``/``MechreportError`` when the study cannot run and
    KeyboardInterrupt when interrupted."""
    from functools import partial

    from ..study.methods import choose_method
    from ..study.plan import SAMPLING_NAMES, plan_of
    from ..study.run import run_variants
    from ..study.variants import load_base
    from .process import check_stop, stop_requests
    from .progress import StudyProgress, duration
    from .workers import worker_init

    err = stream or sys.stderr
    path = Path(path)
    base = load_base(path)
    study = base.spec.study
    method, why = choose_method(method, study.keep, base.spec.design)
    plan = plan_of(study)
    out = od.prepare(Path(out))            # fail early on an unusable -o
    name = od.safe_stem(path)
    lost: list = []
    with stop_requests():
        with cluster_client(scheduler, err) as client:
            workers, size, where = placement(client, scheduler, plan.n, jobs, chunk, err)
            note = (" (study.count is for random and lhs sampling: not used by grid)"
                    if study.sample == "grid" and study.count else "")
            print(f"study {path}: {plan.n} variant(s), {SAMPLING_NAMES[study.sample]} "
                  f"sampling{note}; method {method} ({why}); on {where}, chunks of {size}",
                  file=err, flush=True)
            progress = StudyProgress(plan.n, err)

            start = time.perf_counter()
            with stop_said(err, lambda: f"interrupted after {progress.done} of {plan.n} "
                                        "variant(s); nothing was written", progress.close):
                table = run_variants(base, plan, method, study.keep, jobs=workers,
                                     chunk=size, client=client, progress=progress.update,
                                     lost=lost, notify=progress.say, stop_check=check_stop,
                                     setup=partial(worker_init, os.getpid()))
                progress.close()
        seconds = time.perf_counter() - start
        n_ok = int(table.ok.sum())
        n_pass = int(table.passing.sum())
        print(f"{plan.n} variant(s) in {duration(seconds)}: {n_ok} completed, "
              f"{plan.n - n_ok} failed, {n_pass} pass the design review", file=err,
              flush=True)
        cc = None
        if cross:
            from ..study.cross_check import cross_check

            def tick(i, n):
                print(f"cross-check [{i}/{n}]", file=err, flush=True)
            never = [i for x in lost for i in range(x.start, x.stop)]
            cc = cross_check(base, table, cross, study.seed, progress=tick, skip=never)
        from ..study.report import StudyRun
        from ..report.provenance import build_time, spec_sha256
        run = StudyRun(base, table, method, why, seconds, where, size,
                       sha256=spec_sha256(path), cross=cc,
                       date=build_time().strftime("%Y-%m-%d %H:%M UTC"))
        print(f"writing {out / name}/ ...", file=err, flush=True)
        with stop_said(err, lambda: f"interrupted while writing; {out / name} was left as it "
                                    "was"):
            final = write_study(run, out, name, reports, wait, err)
    failed_reports = [r for r in run.reports if not r[2]]
    print(f"{spec_line(run)}; written to {final}/ (study.parquet, study.csv, study.md, "
          f"study.pdf{', study-reports/' if run.reports else ''})")
    if cc is not None:
        print(f"cross-check: {cc.summary()}")
        for r in cc.rows:
            if not r.ok:
                print(f"  variant {r.index + 1} DISAGREES: {r.where}")
    for rank, i, _folder, message in failed_reports:
        print(f"error: no report for rank {rank} (variant {i + 1}): {message}", file=err)
    if lost:
        print(f"error: {lost_line(lost, plan.n)}", file=err)
    return 1 if (cc is not None and not cc.ok) or failed_reports or lost else 0


def spec_line(run) -> str:
    t = run.table
    n_ok = int(t.ok.sum())
    return (f"{run.base.spec.file}: {t.n} variant(s) by {run.method}: {n_ok} completed, "
            f"{t.n - n_ok} failed, {int(t.passing.sum())} pass the design review")


def write_study(run, out: Path, name: str, reports: int = 0, wait: float = 120.0,
                err=None) -> Path:
    """Write every file of ``run`` into ``OUT/name`` (see :mod:`.outputs`); the folder."""
    from ..report.pdf import compile_typst
    from ..report.write_markdown import markdown
    from ..report.write_typst import typst
    from ..report.files import atomic_write_text
    from ..study.outputs import write_csv, write_parquet
    from ..study.report import FIGURES, build_document, write_figures
    err = err or sys.stderr

    def write(tmp: Path) -> None:
        t = run.table
        meta = {"spec": run.base.file, "spec_sha256": run.sha256, "method": run.method,
                "sample": run.plan.sample, "seed": run.plan.seed, "variants": t.n,
                "version": _version()}
        write_parquet(t, tmp / "study.parquet", meta)
        write_csv(t, tmp / "study.csv")
        if reports:
            run.reports = write_best_reports(run, tmp, reports, err)
        figures = write_figures(run, tmp / FIGURES)
        doc = build_document(run, figures)
        atomic_write_text(tmp / "study.md", markdown(doc))
        compile_typst(typst(doc), tmp / "study.pdf", tmp)

    with od.writing(out, wait) as out:
        return od.write_folder(out, name, write, carry=od.all_but(od.STUDY_ENTRIES))


def _version() -> str:
    from ..version import __version__
    return __version__


def write_best_reports(run, tmp: Path, k: int, err) -> list[tuple]:
    """Full reports (every method, as ``mechreport build`` writes them) of the ``k`` best
    passing variants into ``tmp/study-reports/NN-variant-I/``, each with its variant's spec
    file; (rank, index, folder or None, message) per report."""
    t = run.table
    ranked = list(t.ranked()[:k])
    if len(ranked) < k:
        print(f"--reports {k}: only {len(ranked)} variant(s) pass the design review; "
              f"building {len(ranked)} report(s)", file=err)
    done = []
    for rank, i in enumerate(ranked, 1):
        folder = f"study-reports/{rank:02d}-variant-{i + 1}"
        print(f"report [{rank}/{len(ranked)}]: variant {i + 1}", file=err, flush=True)
        try:
            variant_report(run, int(i), rank, tmp, folder)
            done.append((rank, int(i), folder, ""))
        except Exception as exc:  # noqa: BLE001 - one report must not lose the study
            od.remove(tmp / folder)
            done.append((rank, int(i), None, describe_failure(exc)))
    return done


def variant_report(run, i: int, rank: int, tmp: Path, folder: str) -> None:
    """The full report of variant ``i`` into ``tmp/folder``, with its spec file."""
    from ..pipeline import analyse
    from ..report.build import write_report_folder
    from ..report.files import atomic_write_text
    from ..report.provenance import spec_sha256
    from ..spec import load_spec
    from ..study.variants import variant_yaml
    base, plan = run.base, run.plan
    values = plan.variant(i)
    where = od.inside(tmp, tmp / folder)
    where.mkdir(parents=True)
    spec_file = where / f"variant-{i + 1}.yaml"
    header = (f"Variant {i + 1} of the design study of {base.file} (rank {rank} of the "
              "variants that pass the design review), written by mechreport study:\n"
              + "\n".join(f"  {k} = {v:.12g}" for k, v in values.items())
              + "\nThe spec's expect entries and study section are left out.")
    changed = ", ".join(f"{k} = {v:.12g}" for k, v in values.items())
    about = (f"Variant {i + 1} of a design study of {Path(base.file).name} (rank {rank} of "
             f"the variants that pass the design review): {changed}. The base spec's "
             "description follows; its numbers are the base spec's.")
    description = about + ("\n\n" + base.spec.description if base.spec.description else "")
    text = variant_yaml(base, values, header, name=f"{base.spec.name} (study variant {i + 1})",
                        description=description)
    atomic_write_text(spec_file, text)
    analysis = analyse(load_spec(spec_file))
    write_report_folder(analysis, where, f"{folder}/{spec_file.name}", spec_sha256(spec_file))


def install(out: Path, tmp: Path, name: str) -> Path:
    """Make ``tmp`` (a complete study folder) ``OUT/name``, carrying over the entries of the
    old folder that are not a study's (its report); two renames, undone if the second fails."""
    return od.swap_in(out, tmp, name, carry=od.all_but(od.STUDY_ENTRIES))
