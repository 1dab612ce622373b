"""Project exceptions. Their messages are for users: file, line, key path, what was expected."""
from __future__ import annotations

import errno
from dataclasses import dataclass


@dataclass(frozen=True)
class Problem:
    """One problem found in a spec file.

    ``line`` is 1-based (None when the problem has no single place, e.g. mobility).
    ``path`` is the key path, e.g. ``links.rod.mass`` or ``loads[0].value``.
    """

    file: str
    line: int | None
    path: str
    message: str

    def __str__(self) -> str:
        where = f"{self.file}:{self.line}" if self.line else self.file
        return f"{where}: {self.path}: {self.message}" if self.path else f"{where}: {self.message}"


class MechreportError(Exception):
    """Base class: anything the CLI reports to a user without a traceback."""


class SpecError(MechreportError):
    """A spec file that cannot be loaded; carries every problem found in it."""

    def __init__(self, problems: list[Problem]):
        self.problems = list(problems)
        super().__init__("\n".join(str(p) for p in self.problems))


class AssemblyError(MechreportError):
    """The mechanism cannot be assembled (e.g. at its first reference angle)."""


class UnsupportedMechanism(MechreportError):
    """A mechanism that the analysis does not handle (e.g. no split into dyads)."""


class AnalysisError(MechreportError):
    """The analysis cannot give a trustworthy result (no solvable angle, a non-finite value)."""


def internal_error(exc: BaseException, attach: str = "the spec file") -> str:
    """One line for a failure that is a bug in mechreport, not in the spec."""
    text = " ".join(str(exc).split())
    return (f"internal error: {type(exc).__name__}{': ' + text if text else ''} — please "
            f"report this with {attach}")


#: errno -> what a full disk is called in a message
_FULL = {errno.ENOSPC: "no space left on device"}
if hasattr(errno, "EDQUOT"):
    _FULL[errno.EDQUOT] = "disk quota exceeded"


def describe_failure(exc: BaseException) -> str:
    """The one text users read for a spec that failed with ``exc``: the error's own message
    for a :class:`MechreportError`, what the system said for a file problem, otherwise an
    internal error (see :func:`internal_error`)."""
    if isinstance(exc, MechreportError):
        return str(exc)
    if isinstance(exc, UnicodeDecodeError):
        return (f"cannot read file: not UTF-8 text (byte {exc.start}: {exc.reason}); save it "
                "as UTF-8")
    if isinstance(exc, OSError) and exc.errno in _FULL:
        where = f" writing {exc.filename}" if exc.filename else ""
        return f"{_FULL[exc.errno]}{where}; free some space and run it again"
    if isinstance(exc, OSError) and exc.strerror:
        where = f"{exc.filename}: " if exc.filename else ""
        return f"{where}{exc.strerror}"
    return internal_error(exc)
