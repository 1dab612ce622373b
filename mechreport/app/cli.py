"""The command line: ``mechreport COMMAND``, one module per command beside this one.

Every command goes through all the specs it is given: a spec that cannot be read or analysed
is reported (one message naming the file) and the others still run; the exit code is 1 if
any spec failed. Errors never print a traceback, unless MECHREPORT_DEBUG=1 is set. The
process is set up (:mod:`.process`) before any command imports numpy.

Every command stops on Ctrl-C (exit status 130) and SIGTERM (143), always, even when the
signal's exception was lost (:func:`.process.stop_requests`); a closed stdout or stderr
(``mechreport kin X | head -2``) ends it quietly, with exit status 141, as a Unix tool
killed by SIGPIPE.
"""
from __future__ import annotations

import argparse
import math
import signal
import sys
import textwrap

from ..errors import describe_failure, internal_error
from .args import (add_run_options, add_wait, checked, filled, finite_number, int_at_least_0,
                   int_at_least_1, number_above_0)
from .console import report_command_failure
from .process import Terminated

EXIT_INTERRUPTED = 130          # 128 + SIGINT, as a shell reports Ctrl-C
EXIT_BROKEN_PIPE = 141          # 128 + SIGPIPE: stdout closed early (`| head`), as a shell
EXIT_TERMINATED = 143           # 128 + SIGTERM


def _cmd_validate(ns: argparse.Namespace) -> int:
    from .validate import validate_command
    return validate_command(ns.specs)


def _cmd_kin(ns: argparse.Namespace) -> int:
    from .kin import kin_command
    return kin_command(ns.spec, ns.angle)


def _cmd_check(ns: argparse.Namespace) -> int:
    from .check import check_command
    return check_command(ns.specs, ns.tol, junit=ns.junit)


def _cmd_build(ns: argparse.Namespace) -> int:
    from .build import build_command
    return build_command(ns)


def _cmd_diff(ns: argparse.Namespace) -> int:
    from pathlib import Path
    from .diff import diff_command
    return diff_command(Path(ns.old), Path(ns.new), ns.rtol, ns.html)


def _cmd_study(ns: argparse.Namespace) -> int:
    from pathlib import Path
    from .study import study_command
    return study_command(Path(ns.spec), Path(ns.out), method=ns.method,
                         scheduler=ns.scheduler, jobs=ns.jobs, reports=ns.reports,
                         cross=ns.cross_check, chunk=ns.chunk, wait=ns.wait)


def _cmd_dynamics(ns: argparse.Namespace) -> int:
    from .dynamics import dynamics_command
    return dynamics_command(ns.specs, ns.out, ns.wait)


def _cmd_schema(ns: argparse.Namespace) -> int:
    from .schema import schema_command
    return schema_command(ns.output)


# ------------------------------------------------------------------- argument checks

_sheet_seed = checked(int, lambda v: 0 <= v < 2**63, "a whole number from 0 to 2^63 - 1")
_sheet_count = checked(int, lambda v: 1 <= v <= 500, "a whole number from 1 to 500")


def _sheet_methods(text: str) -> tuple[str, ...]:
    """``--sheet-methods``: comma-separated method names, each known, none twice."""
    from ..quantities import METHOD_NAMES
    names = [t.strip() for t in text.split(",")]
    bad = [n for n in names if n not in METHOD_NAMES]
    if not text.strip() or bad or len(set(names)) != len(names):
        what = f"unknown method {bad[0]!r}; " if bad and bad[0] else ""
        raise argparse.ArgumentTypeError(
            f"{what}must be method names separated by commas, each once, from: "
            f"{', '.join(METHOD_NAMES)}; got {text!r}")
    return tuple(names)


def _sheet_angles(text: str) -> tuple[float, ...]:
    """``--sheet-angles``: comma-separated finite numbers (deg, or the stroke's unit), each
    once (as for ``--sheet-methods``)."""
    try:
        values = tuple(float(t) for t in text.split(","))
    except ValueError:
        values = ()
    if not values or not all(math.isfinite(v) for v in values) or len(set(values)) < len(values):
        raise argparse.ArgumentTypeError(
            f"must be angles in degrees (strokes in the spec's length unit for a linear "
            f"actuator) separated by commas, each once, e.g. 30,45; got {text!r}")
    return values


BUILD_EPILOG = """\
exit status: 0 if every spec was built and passed its check; 1 if any spec failed to build,
or was built but failed its check (expectations or method agreement: the report and the
index say FAIL), or if the output folder cannot be used; 130 if interrupted (Ctrl-C),
143 if terminated (SIGTERM).

Each spec is written to OUT/<name>/, <name> being its file name without .yaml, with any
character other than letters, digits, '-', '_', '.' replaced by '_'; specs of one batch with
the same name get -2, -3, ... in argument order. A report folder is replaced as a whole when
its spec is built; OUT/index.md and index.pdf list every report folder in OUT. Two builds
into the same OUT take turns (OUT/.mechreport.lock)."""


STUDY_EPILOG = """\
exit status: 0 when the study ran and its files were written (variants that cannot be
analysed are rows with their reason); 1 when it cannot run (a spec problem, no study:
section, a --method that cannot give the kept quantities, a malformed or unreachable
--scheduler, an unusable output folder), when --cross-check finds a disagreement, when a
--reports report could not be written, or when variants could not be computed because a
worker process, a Dask task or the Dask scheduler was lost (a lost chunk is tried up to 3
times; the study is still written with those variants as failed rows saying why, and stderr
says how many); 2 on a usage error; 130 if interrupted (nothing is written then).

--jobs is at most the usable cores and the number of chunks (stderr says when it is
lowered). --scheduler takes tcp://HOST:PORT or HOST:PORT and gives up after 10 s.

Writes OUT/<name>/study.parquet, study.csv (one row per variant), study.md and study.pdf,
<name> being the spec's file name without .yaml, as for build; a report built there by
`mechreport build` is kept. Progress and an ETA go to stderr."""


def _add_study_parser(sub) -> None:
    p = sub.add_parser("study", help="run many variants of a spec (its study: section)",
                       description=textwrap.fill(
                           "Run the variants that the spec's study: section describes (one "
                           "force method each), tabulate their cycle quantities and design "
                           "verdicts, and write the table and a study report.", 79),
                       epilog=filled(STUDY_EPILOG), formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("spec", metavar="SPEC")
    p.add_argument("-o", "--out", default="out", help="output folder (default: out)")
    add_run_options(p, "variant")
    p.add_argument("--reports", type=int_at_least_0, default=0, metavar="K",
                   help="also build full reports (every method) of the K best passing variants")
    p.add_argument("--cross-check", type=int_at_least_0, default=0, metavar="N",
                   help="re-run N random variants with every method; exit 1 on disagreement")
    add_wait(p)
    p.set_defaults(func=_cmd_study)


OPTIMIZE_EPILOG = """\
exit status: 0 when a feasible optimum was found and proven (re-analysed by every method
and checked as `mechreport check` does); 1 when no feasible design was found (the files are
written all the same and stderr names the least violating design and the constraints it
misses), or when it cannot run (a spec problem, no optimize: section, an unreachable
--scheduler, an unusable output folder); 2 on a usage error; 130 if interrupted.

Writes OUT/<name>/optimum.yaml, history.csv, optimize.md, optimize.pdf and the optimum's
full report in OUT/<name>/optimum/; a report built there by `mechreport build` is kept.
Progress goes to stderr."""


def _cmd_optimize(ns: argparse.Namespace) -> int:
    from pathlib import Path
    from .optimize import optimize_command
    return optimize_command(Path(ns.spec), Path(ns.out), scheduler=ns.scheduler,
                            jobs=ns.jobs, budget=ns.budget, seed=ns.seed, wait=ns.wait)


def _add_optimize_parser(sub) -> None:
    p = sub.add_parser("optimize", help="search the optimize: box for the best feasible "
                       "design", description=textwrap.fill(
                           "Search the box of the spec's optimize: section for the feasible "
                           "design (every design verdict, every subject_to bound, the spec's "
                           "assembly branch, no angle left out) with the best objective, "
                           "prove it with every force method, and write it and a report.", 79),
                       epilog=filled(OPTIMIZE_EPILOG),
                       formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("spec", metavar="SPEC")
    p.add_argument("-o", "--out", default="out", help="output folder (default: out)")
    add_run_options(p, "evaluation", method=False, chunk=False)
    p.add_argument("--budget", type=checked(int, lambda v: v >= 10, "a whole number >= 10"),
                   default=None, metavar="N",
                   help="evaluations at most, >= 10 (default: the spec's optimize.budget)")
    p.add_argument("--seed", type=int_at_least_0, default=None, metavar="S",
                   help="the search's seed (default: the spec's optimize.seed)")
    add_wait(p)
    p.set_defaults(func=_cmd_optimize)


def main(argv: list[str] | None = None) -> int:
    """``mechreport`` with ``argv`` (default: the command line's, and then the process ends
    with the command); the exit status."""
    from .process import set_up, stop_requests
    set_up()
    with stop_requests(then_default=argv is None):
        try:
            try:
                return _main(argv)
            finally:                        # --help and --version end in SystemExit
                sys.stdout.flush()          # a closed pipe is found here, not at exit
        except BrokenPipeError as exc:
            if not _closed_pipe():                  # not stdout or stderr: a bug
                print(f"error: {internal_error(exc, 'the command you ran')}", file=sys.stderr)
                return 1
            _silence_stdio()
            return EXIT_BROKEN_PIPE
        except OSError as exc:                      # stdout itself failed: a full disk
            print(f"error: cannot write the output: {describe_failure(exc)}", file=sys.stderr)
            return 1


def _closed_pipe() -> bool:
    """Whether stdout or stderr is a pipe whose reader is gone (``mechreport kin X | head``).
    Where poll() is missing, any BrokenPipeError is taken to be one."""
    import select
    if not hasattr(select, "poll"):
        return True
    for stream in (sys.stdout, sys.stderr):
        try:
            poller = select.poll()
            poller.register(stream.fileno(), select.POLLOUT)
            if any(events & select.POLLERR for _, events in poller.poll(0)):
                return True
        except (AttributeError, ValueError, OSError):     # no file behind it
            continue
    return False


def _silence_stdio() -> None:
    """stdout and stderr to /dev/null, so that nothing more (the final flush at exit
    included) meets the closed pipe: Python's documented recipe for a BrokenPipeError."""
    import os
    devnull = os.open(os.devnull, os.O_WRONLY)
    for stream in (sys.stdout, sys.stderr):
        try:
            os.dup2(devnull, stream.fileno())
        except (AttributeError, ValueError, OSError):
            pass
    os.close(devnull)


def _main(argv: list[str] | None) -> int:
    from .process import check_stop, stop_requested
    from ..version import __version__
    parser = argparse.ArgumentParser(
        prog="mechreport",
        description="Dynamic force analysis of planar linkages from YAML specs.")
    parser.add_argument("--version", action="version", version=f"mechreport {__version__}")
    sub = parser.add_subparsers(dest="command", metavar="COMMAND")

    p = sub.add_parser("validate", help="load specs and assemble them at their reference angles",
                       description="Load specs and assemble them at their reference angles. "
                       "Exit status 1 if any spec fails or none is given.")
    p.add_argument("specs", nargs="+", metavar="SPEC|DIR")
    p.set_defaults(func=_cmd_validate)

    p = sub.add_parser("kin", help="print positions, velocities, accelerations",
                       description="Print the positions, velocities and accelerations of every "
                       "named point and every link at the given crank angles, each dyad's "
                       "branch, and any angle left out with its reason. Exit status 1 if the "
                       "spec cannot be read or assembled.")
    p.add_argument("spec", metavar="SPEC")
    p.add_argument("--angle", type=finite_number, action="append",
                   help="crank angle in degrees (repeatable; default: the spec's `at`)")
    p.set_defaults(func=_cmd_kin)

    p = sub.add_parser("check", help="solve by every method; compare methods and expectations",
                       description="Solve by every method, compare the methods and check the "
                       "spec's expectations: one PASS/FAIL line per spec. Exit status 1 if any "
                       "spec fails or none is given.")
    p.add_argument("specs", nargs="+", metavar="SPEC|DIR")
    p.add_argument("--tol", type=number_above_0, default=None,   # checks.agreement.DEFAULT_TOL
                   help="largest relative disagreement between methods (default 1e-6)")
    p.add_argument("--junit", metavar="FILE",
                   help="also write JUnit XML to FILE: one test suite per spec, one test case "
                   "per check, expectation and design verdict")
    p.set_defaults(func=_cmd_check)

    p = sub.add_parser("build", help="write Markdown and PDF reports",
                       description="Write a Markdown and PDF report per spec, and an index.",
                       epilog=filled(BUILD_EPILOG), formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("specs", nargs="+", metavar="SPEC|DIR")
    p.add_argument("-o", "--out", default="out", help="output folder (default: out)")
    p.add_argument("--jobs", type=int_at_least_1, default=None,
                   help="parallel specs, >= 1 (default: cores)")
    p.add_argument("--sheet", action="store_true",
                   help="also write worked solution sheets: solution.md/.pdf (the answer "
                   "key) and problem.md/.pdf (statement, data, figure, what to find)")
    p.add_argument("--sheet-methods", type=_sheet_methods, metavar="M1,M2",
                   help="the methods the sheets work through, in this order (default: all): "
                   "newton_euler, dalembert, dyad, contour, power; needs --sheet")
    p.add_argument("--sheet-angles", type=_sheet_angles, metavar="A1,A2",
                   help="the reference angles of the sheets in degrees (strokes for a linear "
                   "actuator; default: the spec's `at`); needs --sheet")
    p.add_argument("--exact", action="store_true",
                   help="solution sheets also show exact closed forms in the spec's square "
                   "roots (needs sympy: pip install 'mechreport[exact]'); needs --sheet")
    p.add_argument("--variants", type=_sheet_count, default=None, metavar="N",
                   help="how many variants of a problem with `sheet.variants` (overrides its "
                   "count); needs --sheet")
    p.add_argument("--seed", type=_sheet_seed, default=None,
                   help="the variants' seed (overrides sheet.variants.seed); needs --sheet")
    p.add_argument("--no-animation", action="store_true",
                   help="leave out animation.gif (the mechanism moving with its forces), "
                   "which every spec with a whole-turn sweep gets unless its report says "
                   "animation: false; builds faster")
    add_wait(p)
    p.add_argument("--force", action="store_true",
                   help="rebuild every spec, even one whose report is up to date (same spec "
                   "bytes, path, options and mechreport version)")
    p.add_argument("-q", "--quiet", action="store_true",
                   help="print nothing but failures")
    p.set_defaults(func=_cmd_build)

    p = sub.add_parser("diff", help="compare two builds' summary.json files",
                       description="Compare the summary.json files of two build folders and "
                       "print the quantities that changed beyond the tolerance as a Markdown "
                       "table (for a pull-request comment). Exit status 1 when anything "
                       "changed (a quantity, a status or verdict, a spec added or removed, a "
                       "spec that no longer builds or builds again; a change to or from NaN "
                       "or infinity included), 0 when nothing did, 2 on a usage error, a "
                       "folder that is not a build, or a summary.json or index.json that "
                       "cannot be read or is not mechreport's.")
    p.add_argument("old", metavar="OLD_OUT")
    p.add_argument("new", metavar="NEW_OUT")
    p.add_argument("--rtol", type=number_above_0, default=None,   # kinematics.TRUST_RTOL
                   help="relative tolerance (default 1e-6: what every printed value promises)")
    p.add_argument("--html", action="store_true",
                   help="print the table as an HTML page of its own (no script, works "
                   "offline) instead of Markdown: mechreport diff A B --html > diff.html")
    p.set_defaults(func=_cmd_diff)

    _add_study_parser(sub)
    from .tolerance import add_parser as _add_tolerance_parser
    _add_tolerance_parser(sub)
    _add_optimize_parser(sub)

    p = sub.add_parser("dynamics", help="simulate the motion a motor and flywheel give "
                       "(a spec's dynamics: section)",
                       description="Simulate each spec's machine dynamics alone: the time "
                       "histories into OUT/<name>/dynamics.csv and dynamics.parquet (<name> and "
                       "the folder's rules as for build; the folder's other files are kept), "
                       "the steady state's quantities and verdicts printed. Exit status 1 if "
                       "any spec fails or misses a verdict.")
    p.add_argument("specs", nargs="+", metavar="SPEC", help="spec files with a dynamics: "
                   "section")
    p.add_argument("-o", "--out", "--output", dest="out", metavar="OUT", default="out",
                   help="output folder (default: out; --output is the same)")
    add_wait(p)
    p.set_defaults(func=_cmd_dynamics)

    p = sub.add_parser("schema", help="print the JSON Schema of a spec file (for editors)",
                       description="Print the JSON Schema of a spec file: an editor with a "
                       "YAML language server uses it to check and complete specs as they are "
                       "typed (docs/spec.md, 'Editor support'). Exit status 1 if FILE cannot "
                       "be written.")
    p.add_argument("-o", "--out", "--output", dest="output", metavar="FILE", default=None,
                   help="write the schema to FILE instead of printing it")
    p.set_defaults(func=_cmd_schema)

    ns = parser.parse_args(argv)
    if getattr(ns, "func", None) is None:           # bare `mechreport`
        parser.print_help()
        return 0
    try:
        code = ns.func(ns)
        check_stop()                        # a stop whose exception was lost still stops
        return code
    except KeyboardInterrupt as exc:
        terminated = (stop_requested() or (signal.SIGTERM if isinstance(exc, Terminated)
                                           else signal.SIGINT)) == signal.SIGTERM
        if not getattr(exc, "reported", False):
            print("terminated" if terminated else "interrupted", file=sys.stderr)
        return EXIT_TERMINATED if terminated else EXIT_INTERRUPTED
    except BrokenPipeError:
        raise                               # see main()
    except Exception as exc:  # noqa: BLE001 - said in one line (console.report_command_failure)
        report_command_failure(exc)
        return 1


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
