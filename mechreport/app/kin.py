"""``mechreport kin SPEC [--angle A]...``: positions, velocities and accelerations at the
spec's reference angles (or the given ones), as a table."""
from __future__ import annotations

from .console import attempt


def kin_command(path: str, angles: list[float] | None = None) -> int:
    import numpy as np

    from ..kinematics import solve_kinematics
    from ..model import build_mechanism
    from ..report.text import branch_lines, kinematics_table
    from ..spec import load_spec

    def solved():
        spec = load_spec(path)
        at = np.asarray(angles if angles else spec.at, float)
        return spec, solve_kinematics(build_mechanism(spec), at)

    ok, done = attempt(path, solved)
    if not ok:
        return 1
    spec, kin = done
    print(kinematics_table(kin))
    print()
    for text in branch_lines(kin):
        print(f"branch: {text}")
    for flag in kin.flags:
        print(f"{spec.driver.coordinate} {flag.angle:g} {spec.axis_unit} left out: "
              f"{flag.reason}")
    for text in kin.notes():
        print(f"note: {text}")
    return 0
