"""What every command shares on the terminal: the spec arguments, debug tracebacks."""
from __future__ import annotations

import os
import sys
import traceback
from pathlib import Path


def debug() -> bool:
    """MECHREPORT_DEBUG set (and not 0): print tracebacks of internal errors."""
    return os.environ.get("MECHREPORT_DEBUG", "") not in ("", "0")


def print_traceback_if_debug() -> None:
    if debug():
        traceback.print_exc(file=sys.stderr)


def spec_files(args: list[str]) -> list[Path]:
    """Expand SPEC|DIR arguments into spec files (a directory gives its *.yaml and *.yml,
    sorted)."""
    out: list[Path] = []
    for arg in args:
        p = Path(arg)
        if p.is_dir():
            found = sorted(list(p.glob("*.yaml")) + list(p.glob("*.yml")))
            if not found:
                print(f"{p}: no spec files (*.yaml, *.yml) in this folder", file=sys.stderr)
            out.extend(found)
        else:
            out.append(p)
    return out
