"""``mechreport dynamics SPEC... [-o OUT]``: the machine dynamics of each spec alone (its
``dynamics:`` section): the time histories into OUT/<spec>/dynamics.csv and .parquet, and
the steady state's quantities and verdicts printed. Exit status 1 if any spec fails (bad
input, a stall, no steady state, a verdict not met)."""
from __future__ import annotations

import sys
from pathlib import Path

from ..errors import MechreportError, describe_failure
from .console import print_traceback_if_debug


def dynamics_command(paths: list[str], out: str = "out") -> int:
    status = 0
    for path in paths:
        status = max(status, _one(path, Path(out)))
    return status


def _one(path: str, out: Path) -> int:
    from ..model import build_mechanism
    from ..pipeline.analysis import analysis_of
    from ..pipeline.dynamics import run_dynamics
    from ..report.dynamics import histories_of, write_histories
    from ..spec import load_spec
    from ..units import fmt

    try:
        spec = load_spec(path)
        if spec.dynamics is None:
            print(f"{path}: no 'dynamics:' section: nothing to simulate (docs/spec.md, "
                  "'Machine dynamics')", file=sys.stderr)
            return 1
        dyn = run_dynamics(build_mechanism(spec), analysis_of)
        folder = out / Path(path).stem
        folder.mkdir(parents=True, exist_ok=True)
        files = write_histories(histories_of(dyn.simulation), folder)
    except MechreportError as exc:               # its message names the file
        print(str(exc), file=sys.stderr)
        return 1
    except Exception as exc:  # noqa: BLE001 - a message, not a traceback
        print(f"{path}: {describe_failure(exc)}", file=sys.stderr)
        print_traceback_if_debug()
        return 1
    sim, cycle = dyn.simulation, dyn.simulation.steady
    if cycle is None:
        print(f"{path}: transient to t = {fmt(sim.time[-1])} s, {sim.turns} whole turns; "
              f"final speed {fmt(sim.omega[-1] * 30 / 3.141592653589793)} rpm")
    else:
        print(f"{path}: steady after {sim.turns} turns (t = {fmt(cycle.t0 + cycle.period)} s)")
        for name, value in dyn.values.items():
            from ..quantities import unit_of
            unit = unit_of(name)
            print(f"  {name} = {fmt(value)}{' ' + unit if unit else ''}")
        print(f"  flywheel estimate of the speed fluctuation = {fmt(dyn.estimate[2])}")
        for v in dyn.verdicts:
            print(f"  {'PASS' if v.passed else 'FAIL'} {v.describe(fmt)}")
    for f in files:
        print(f"  wrote {f}")
    passed = all(v.passed for v in dyn.verdicts) and (
        dyn.steady is None or dyn.steady.worst is None
        or dyn.steady.worst.relative <= dyn.steady.tol)
    return 0 if passed else 1
