"""What every command shares on the terminal: the spec arguments, a spec's failure, debug
tracebacks."""
from __future__ import annotations

import os
import stat
import sys
import traceback
from pathlib import Path

from ..errors import MechreportError, describe_failure


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
