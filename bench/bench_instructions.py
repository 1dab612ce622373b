"""Benchmark: the fixed cost of one spec (load + analyse of a 36-angle sweep) in CPU
instructions, stage by stage, counted by valgrind's callgrind: unlike CPU time, the count
does not move with the machine's load (here timings vary up to 2x within an hour), so a
change of a few percent can be measured in one run.

    .venv/bin/python bench/bench_instructions.py [--only STAGE,...] [--against REV]
                                                 [SPEC_NAME ...]   (default: r_rtr_rtr)

``--only analyse`` counts the whole load and analyse alone (about 15 s a spec, where every
stage takes a few minutes); ``--against REV`` counts the code of git revision REV too (a
temporary ``git worktree``, imported first), on the same specs of this checkout, and
prints both columns: a before/after table in one command. The stages other than analyse
call the package's internals as they are now: against an older revision, ``--only
analyse``.

Needs valgrind (Debian package valgrind); each spec takes a few minutes under it. Each
stage is counted over 5 runs after 3 warm-up runs in the same process (the structure
caches warm, as for the second spec of a batch), less the cost of switching the count on
and off. The force stages follow ``solve_forces``: every method's equations, then their
blocks prepared together, then each method's solve. Not a test.
"""
from __future__ import annotations

import argparse
import dataclasses
import os
import re
import shutil
import subprocess
import sys
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
STAGES = ("empty", "parse", "kinematics", "context", "equations", "prepare", "newton_euler",
          "dalembert", "dyad", "contour", "power", "checks", "analyse")
RUNS, WARM = 5, 3


def _child(name: str, stage: str) -> None:
    """Run inside valgrind: count ``stage`` of RUNS analyses of specs/NAME.yaml."""
    os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")
    from mechreport.analysis import analyse
    from mechreport.spec import Sweep
    from mechreport.spec.loader import parse_spec
    if stage not in ("empty", "analyse"):   # as the code is now (older revisions: --only analyse)
        from mechreport.checks.agreement import agreement
        from mechreport.checks.residuals import residuals
        from mechreport.forces import METHODS, ForceContext
        from mechreport.forces.equations import prepare_blocks
        from mechreport.forces.result import chain, method_steps
        from mechreport.kinematics import solve_kinematics
        from mechreport.model import build_mechanism
        from mechreport.post.review import design_review

    text = (ROOT / "specs" / f"{name}.yaml").read_text()
    pid = str(os.getpid())

    def count(on: bool) -> None:
        subprocess.run(["callgrind_control", "-i", "on" if on else "off", pid],
                       capture_output=True, check=False)

    def short(spec):
        return dataclasses.replace(spec, sweep=Sweep(0.0, 360.0, 10.0), at=(30.0,),
                                   expect=())

    def run(measure: bool) -> None:
        def at(what: str, on: bool) -> None:
            if measure and stage == what:
                count(on)
        at("empty", True)
        at("empty", False)
        at("analyse", True)
        if stage == "analyse":
            analyse(short(parse_spec(text, f"{name}.yaml")))
            at("analyse", False)
            return
        at("parse", True)
        spec = parse_spec(text, f"{name}.yaml")
        at("parse", False)
        at("kinematics", True)
        kin = solve_kinematics(build_mechanism(short(spec)))
        at("kinematics", False)
        at("context", True)
        ctx = ForceContext(kin)
        at("context", False)
        at("equations", True)        # every method's steps, as solve_forces builds them
        chains = [chain(ctx, method_steps(ctx, method, module.build_steps))
                  for method, module in METHODS.items()]
        at("equations", False)
        at("prepare", True)          # and their blocks, prepared together
        ctx.cache["prepared blocks"] = prepare_blocks(chains, ctx.n)
        at("prepare", False)
        forces = {}
        for method, module in METHODS.items():
            at(method, True)
            forces[method] = module.solve(ctx)
            at(method, False)
        at("checks", True)
        residuals(ctx, forces)
        agreement(forces)
        design_review(kin, forces, ctx.loads)
        at("checks", False)

    for _ in range(WARM):
        run(False)
    for _ in range(RUNS):
        run(True)


def instructions(name: str, stage: str, code: Path | None = None) -> int:
    """Instructions counted for ``stage`` over RUNS runs (switching cost included), of the
    package in ``code`` (a checkout imported first) or of this one."""
    env = dict(os.environ)
    env.setdefault("PYTHONHASHSEED", "0")     # string hashes move the count by about 1 %
    if code is not None:
        env["PYTHONPATH"] = os.pathsep.join(filter(None, [str(code),
                                                          env.get("PYTHONPATH")]))
    out = subprocess.run(
        ["valgrind", "--tool=callgrind", "--instr-atstart=no", "--callgrind-out-file=/dev/null",
         sys.executable, __file__, "--child", name, stage],
        capture_output=True, text=True, check=False, cwd=code or ROOT, env=env)
    found = re.search(r"Collected\s*:\s*(\d+)", out.stderr)
    if found is None:
        raise SystemExit(f"valgrind gave no count for {name} {stage}:\n{out.stderr[-2000:]}")
    return int(found.group(1))


def _counts(name: str, stages: list[str], code: Path | None) -> dict[str, float]:
    """Million instructions per run of each of ``stages``, switching cost taken off."""
    switching = instructions(name, "empty", code)
    return {stage: (instructions(name, stage, code) - switching) / RUNS / 1e6
            for stage in stages}


def _options(argv: list[str]) -> argparse.Namespace:
    parser = argparse.ArgumentParser(description="The fixed cost in CPU instructions.")
    parser.add_argument("--only", type=lambda v: v.split(","), default=list(STAGES[1:]),
                        metavar="STAGE,...", help=f"stages: {', '.join(STAGES[1:])}")
    parser.add_argument("--against", metavar="REV", help="count git revision REV too")
    parser.add_argument("names", nargs="*", default=["r_rtr_rtr"], metavar="SPEC_NAME")
    args = parser.parse_args(argv)
    unknown = [stage for stage in args.only if stage not in STAGES[1:]]
    if unknown:
        parser.error(f"unknown stage(s) {', '.join(unknown)}")
    return args


def main() -> None:
    if len(sys.argv) == 4 and sys.argv[1] == "--child":
        _child(sys.argv[2], sys.argv[3])
        return
    if shutil.which("valgrind") is None or shutil.which("callgrind_control") is None:
        raise SystemExit("bench_instructions needs valgrind (Debian: apt-get install valgrind)")
    args = _options(sys.argv[1:])
    stages, against, names = args.only, args.against, args.names
    with tempfile.TemporaryDirectory(prefix="bench-before-") as tmp:
        before = None
        if against is not None:
            before = Path(tmp) / "code"
            made = subprocess.run(["git", "worktree", "add", "--detach", str(before), against],
                                  capture_output=True, text=True, cwd=ROOT, check=False)
            if made.returncode != 0:
                raise SystemExit(f"git worktree add {against}: {made.stderr.strip()}")
        try:
            for name in names:
                _report(name, stages, before, against)
        finally:
            if before is not None:
                subprocess.run(["git", "worktree", "remove", "--force", str(before)],
                               capture_output=True, cwd=ROOT, check=False)


def _report(name: str, stages: list[str], before: Path | None, against: str | None) -> None:
    after = _counts(name, stages, None)
    old = _counts(name, stages, before) if before is not None else None
    print(f"{name}: million instructions per spec (load + analyse, 36 angles)")
    if old is not None:
        print(f"  {'':<14}{against[:8]:>8}{'now':>8}")
    for stage in stages:
        print(f"  {stage:<14}" + (f"{old[stage]:8.2f}" if old is not None else "")
              + f"{after[stage]:8.2f}")
    parts = [s for s in stages if s != "analyse"]
    if len(parts) > 1:
        print(f"  {'(sum of stages)':<14}"
              + (f"{sum(old[s] for s in parts):8.2f}" if old is not None else "")
              + f"{sum(after[s] for s in parts):8.2f}")


if __name__ == "__main__":
    main()
