"""``mechreport validate SPEC|DIR...``: load specs and assemble them at their reference
angles; exit status 1 if any spec fails or none is given."""
from __future__ import annotations

import sys

from .console import attempt, spec_files


def validate_command(args: list[str]) -> int:
    import numpy as np

    from ..kinematics import solve_kinematics
    from ..model import build_mechanism
    from ..report.text import branch_lines
    from ..spec import load_spec

    paths = spec_files(args)
    if not paths:
        print("no spec files given", file=sys.stderr)
        return 1
    def assembled(path):
        spec = load_spec(path)
        return solve_kinematics(build_mechanism(spec), np.asarray(spec.at, float))

    failed = 0
    for path in paths:
        ok, kin = attempt(path, lambda: assembled(path))
        if not ok:
            failed += 1
            continue
        note = f" ({len(kin.flags)} reference angle(s) left out)" if kin.flags else ""
        print(f"{path}: OK{note}")
        for text in branch_lines(kin):
            print(f"  branch: {text}")
        for text in kin.notes():
            print(f"  note: {text}")
    return 1 if failed else 0
