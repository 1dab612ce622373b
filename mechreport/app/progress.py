"""Progress on stderr: a build's specs (:class:`Progress`) and a study's variants
(:class:`StudyProgress`).

A study's, on a terminal, is one line redrawn at most ten times a second,

    [##########..........] 5000/10000 variants 50%  (3 failed)  31 s, ETA 31 s

elsewhere (CI logs, files) one such line at every tenth of the study."""
from __future__ import annotations

import sys
import time
from pathlib import Path


def duration(seconds: float) -> str:
    """``42 s``, ``3 min 05 s``, ``1 h 02 min``."""
    s = int(round(max(seconds, 0.0)))
    if s < 60:
        return f"{s} s"
    if s < 3600:
        return f"{s // 60} min {s % 60:02d} s"
    return f"{s // 3600} h {s % 3600 // 60:02d} min"


class StudyProgress:
    """Progress of ``total`` variants. ``update(done, failed)`` with running totals."""

    WIDTH = 20

    def __init__(self, total: int, stream=None, quiet: bool = False, items: str = "variants",
                 bad: str = "failed"):
        self.items, self.bad = items, bad      # what is counted, what the second count is
        self.total = max(int(total), 1)
        self.stream = stream or sys.stderr
        self.quiet = quiet
        self.tty = (not quiet) and hasattr(self.stream, "isatty") and self.stream.isatty()
        self.start = time.monotonic()
        self.done = self.failed = 0
        self._drawn = 0.0
        self._tenth = 0
        self._open = False

    def line(self) -> str:
        elapsed = time.monotonic() - self.start
        frac = self.done / self.total
        fill = int(self.WIDTH * frac)
        bar = "#" * fill + "." * (self.WIDTH - fill)
        failed = f"  ({self.failed} {self.bad})" if self.failed else ""
        if self.done >= self.total:
            when = f"{duration(elapsed)}"
        elif self.done:
            when = f"{duration(elapsed)}, ETA {duration(elapsed * (1 - frac) / frac)}"
        else:
            when = f"{duration(elapsed)}, ETA unknown"
        return (f"[{bar}] {self.done}/{self.total} {self.items} {int(100 * frac)}%{failed}  "
                f"{when}")

    def update(self, done: int, failed: int = 0) -> None:
        self.done, self.failed = done, failed
        if self.quiet:
            return
        now = time.monotonic()
        if self.tty:
            if now - self._drawn >= 0.1 or done >= self.total:
                self.stream.write("\r" + self.line() + "\x1b[K")
                self.stream.flush()
                self._drawn, self._open = now, True
            return
        tenth = int(10 * done / self.total)
        if tenth > self._tenth:
            self._tenth = tenth
            print(self.line(), file=self.stream, flush=True)

    def say(self, line: str) -> None:
        """A line for the user between the bar's updates (the executor's ``notify``): the
        bar's line ended first, so that the two do not share a line."""
        self.close()
        print(line, file=self.stream, flush=True)

    def close(self) -> None:
        """End the bar's line (a terminal's cursor goes to a fresh line)."""
        if self.tty and self._open:
            self.stream.write("\n")
            self.stream.flush()
            self._open = False


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
