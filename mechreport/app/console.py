"""What every command shares on the terminal: the spec arguments, failures (one wrapper,
:func:`attempt`, for every command's work on one spec; :func:`report_command_failure` for a
command that cannot run at all), debug tracebacks."""
from __future__ import annotations

import os
import stat
import sys
import traceback
from pathlib import Path

from ..errors import MechreportError, SpecError, describe_failure, internal_error


def debug() -> bool:
    """MECHREPORT_DEBUG set (and not 0): print tracebacks of internal errors."""
    return os.environ.get("MECHREPORT_DEBUG", "") not in ("", "0")


def print_traceback_if_debug() -> None:
    if debug():
        traceback.print_exc(file=sys.stderr)


def report_failure(path, exc: BaseException) -> None:
    """One spec's failure on stderr: a :class:`MechreportError`'s own message (it names the
    file), anything else after the spec's path (:func:`describe_failure`), with a traceback
    when MECHREPORT_DEBUG is set."""
    if isinstance(exc, MechreportError):
        print(str(exc), file=sys.stderr)
        return
    print(f"{path}: {describe_failure(exc)}", file=sys.stderr)
    print_traceback_if_debug()


def report_command_failure(exc: Exception) -> None:
    """A command that could not run, on stderr in one line: a spec's problems as the loader
    words them (``SpecError``: they name the file and line), any other
    :class:`MechreportError` after ``error:``, anything else as an internal error, with a
    traceback when MECHREPORT_DEBUG is set."""
    if isinstance(exc, SpecError):
        print(str(exc), file=sys.stderr)
    elif isinstance(exc, MechreportError):
        print(f"error: {exc}", file=sys.stderr)
    else:
        print(f"error: {internal_error(exc, 'the command you ran')}", file=sys.stderr)
        print_traceback_if_debug()


def attempt(path, work, say=None) -> tuple[bool, object]:
    """``work()`` for the spec at ``path``, the one way every command treats a spec that
    fails: ``(True, its result)``, or ``(False, None)`` when it raised an Exception (one bad
    spec must not stop the others). The failure is said in one line: by ``say(text)`` with
    :func:`describe_failure`'s text when the command has its own line for it (``check``:
    ``FAIL path: text``), else on stderr by :func:`report_failure`; a traceback follows an
    internal error when MECHREPORT_DEBUG is set. KeyboardInterrupt and the like go on."""
    try:
        return True, work()
    except Exception as exc:  # noqa: BLE001 - one bad spec must not stop the others
        if say is None:
            report_failure(path, exc)
        else:
            say(describe_failure(exc))
            if not isinstance(exc, MechreportError):
                print_traceback_if_debug()
        return False, None


def _blocks(path: Path) -> bool:
    """Whether ``path`` is a pipe, socket or device (not a file or folder)."""
    try:
        mode = path.stat().st_mode
    except OSError:
        return False                    # a dangling link: the command reports it
    return not (stat.S_ISREG(mode) or stat.S_ISDIR(mode))


def spec_files(args: list[str]) -> list[Path]:
    """Expand SPEC|DIR arguments into spec files: a directory gives its *.yaml and *.yml
    entries, sorted, except pipes, sockets and devices (a read could block forever: they
    are skipped and named on stderr; anything else that cannot be read is reported by the
    command, spec by spec); a file named is read whatever it is (``<(generate-spec)`` is a
    pipe)."""
    out: list[Path] = []
    for arg in args:
        p = Path(arg)
        if p.is_dir():
            found = sorted(list(p.glob("*.yaml")) + list(p.glob("*.yml")))
            skipped = [f for f in found if _blocks(f)]
            if skipped:
                print(f"{p}: skipped (a pipe, socket or device, not a file): "
                      + ", ".join(f.name for f in skipped), file=sys.stderr)
            found = [f for f in found if f not in skipped]
            if not found and not skipped:
                print(f"{p}: no spec files (*.yaml, *.yml) in this folder", file=sys.stderr)
            out.extend(found)
        else:
            out.append(p)
    return out
