"""``mechreport dynamics SPEC... [-o OUT]``: the machine dynamics of each spec alone (its
``dynamics:`` section): the time histories into OUT/<name>/dynamics.csv and .parquet, and
the steady state's quantities and verdicts printed. Exit status 1 if any spec fails (bad
input, a stall, no steady state, a verdict not met, a folder that cannot be written).

``OUT`` and ``<name>`` are those of ``mechreport build`` (:mod:`.outdir`: the same folder
names, the same lock, the same whole-folder swap, nothing written outside ``OUT``); the
other files of the folder (a report, a study) are kept."""
from __future__ import annotations

import sys
from pathlib import Path

from . import outdir as od
from .console import attempt


def dynamics_command(paths: list[str], out: str = "out", wait: float = 120.0) -> int:
    """Simulate each spec of ``paths`` into ``out``; one failing spec does not stop the
    others. Raises :class:`~mechreport.app.outdir.OutputError` if ``out`` cannot be used."""
    files = od.unique_specs([Path(p) for p in paths])
    names = od.folder_names(files)
    status = 0
    with od.writing(Path(out), wait) as folder:
        for path, name in zip(files, names):
            status = max(status, _one(path, folder, name))
    return status


def _one(path: Path, out: Path, name: str) -> int:
    from ..model import build_mechanism
    from ..pipeline.analysis import analysis_of
    from ..pipeline.dynamics import run_dynamics
    from ..report.dynamics import histories_of, write_histories
    from ..spec import load_spec
    from ..units import fmt, rad_s_to_rpm

    def simulated():
        spec = load_spec(path)
        if spec.dynamics is None:
            return None
        dyn = run_dynamics(build_mechanism(spec), analysis_of)
        final = od.write_folder(out, name,
                                lambda tmp: write_histories(histories_of(dyn.simulation), tmp),
                                carry=od.all_but(od.DYNAMICS_ENTRIES))
        return dyn, final

    ok, done = attempt(path, simulated)
    if not ok:
        return 1
    if done is None:
        print(f"{path}: no 'dynamics:' section: nothing to simulate (docs/spec.md, "
              "'Machine dynamics')", file=sys.stderr)
        return 1
    dyn, final = done
    sim, cycle = dyn.simulation, dyn.simulation.steady
    if cycle is None:
        print(f"{path}: transient to t = {fmt(sim.time[-1])} s, {sim.turns} whole turns; "
              f"final speed {fmt(rad_s_to_rpm(sim.omega[-1]))} rpm")
    else:
        if sim.drive_torque is not None:
            print(f"{path}: periodic state at the mean speed found directly, under a constant "
                  f"driving torque of {fmt(sim.drive_torque)} N·m")
        else:
            print(f"{path}: steady after {sim.turns} turns (t = "
                  f"{fmt(cycle.t0 + cycle.period)} s)")
        for qname, value in dyn.values.items():
            from ..quantities import unit_of
            unit = unit_of(qname)
            print(f"  {qname} = {fmt(value)}{' ' + unit if unit else ''}")
        for v in dyn.verdicts:
            print(f"  {'PASS' if v.passed else 'FAIL'} {v.describe(fmt)}")
    for entry in od.DYNAMICS_ENTRIES:
        print(f"  wrote {final / entry}")
    passed = all(v.passed for v in dyn.verdicts) and (
        dyn.steady is None or dyn.steady.worst is None
        or dyn.steady.worst.relative <= dyn.steady.tol)
    return 0 if passed else 1
