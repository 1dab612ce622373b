"""Benchmark: the fixed cost of one spec (load + analyse of a 36-angle sweep) in CPU
instructions, stage by stage, counted by valgrind's callgrind: unlike CPU time, the count
does not move with the machine's load (here timings vary up to 2x within an hour), so a
change of a few percent can be measured in one run.

    .venv/bin/python bench/bench_instructions.py [SPEC_NAME ...]   (default: r_rtr_rtr)

Needs valgrind (Debian package valgrind); each spec takes a few minutes under it. Each
stage is counted over 5 runs after 3 warm-up runs in the same process (the structure
caches warm, as for the second spec of a batch), less the cost of switching the count on
and off. The force stages follow ``solve_forces``: every method's equations, then their
small blocks prepared together, then each method's solve. Not a test.
"""
from __future__ import annotations

import dataclasses
import os
import re
import shutil
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
STAGES = ("empty", "parse", "kinematics", "context", "equations", "prepare", "newton_euler",
          "dalembert", "dyad", "contour", "power", "checks", "analyse")
RUNS, WARM = 5, 3


def _child(name: str, stage: str) -> None:
    """Run inside valgrind: count ``stage`` of RUNS analyses of specs/NAME.yaml."""
    os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")
    from mechreport.analysis import analyse
    from mechreport.checks.agreement import agreement
    from mechreport.checks.residuals import residuals
    from mechreport.forces import METHODS, ForceContext
    from mechreport.forces.equations import prepare_blocks
    from mechreport.forces.result import chain, method_steps
    from mechreport.kinematics import solve_kinematics
    from mechreport.model import build_mechanism
    from mechreport.post.review import design_review
    from mechreport.spec import Sweep
    from mechreport.spec.loader import parse_spec

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
        at("prepare", True)          # and their small blocks, prepared together
        ctx.cache["small systems"] = prepare_blocks(chains, ctx.n)
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


def instructions(name: str, stage: str) -> int:
    """Instructions counted for ``stage`` over RUNS runs (switching cost included)."""
    out = subprocess.run(
        ["valgrind", "--tool=callgrind", "--instr-atstart=no", "--callgrind-out-file=/dev/null",
         sys.executable, __file__, "--child", name, stage],
        capture_output=True, text=True, check=False, cwd=ROOT)
    found = re.search(r"Collected\s*:\s*(\d+)", out.stderr)
    if found is None:
        raise SystemExit(f"valgrind gave no count for {name} {stage}:\n{out.stderr[-2000:]}")
    return int(found.group(1))


def main() -> None:
    if len(sys.argv) == 4 and sys.argv[1] == "--child":
        _child(sys.argv[2], sys.argv[3])
        return
    if shutil.which("valgrind") is None or shutil.which("callgrind_control") is None:
        raise SystemExit("bench_instructions needs valgrind (Debian: apt-get install valgrind)")
    for name in sys.argv[1:] or ["r_rtr_rtr"]:
        switching = instructions(name, "empty")
        print(f"{name}: million instructions per spec (load + analyse, 36 angles)")
        total = 0.0
        for stage in STAGES[1:]:
            m = (instructions(name, stage) - switching) / RUNS / 1e6
            if stage != "analyse":
                total += m
            print(f"  {stage:<14}{m:8.2f}")
        print(f"  {'(sum of stages)':<14}{total:8.2f}")


if __name__ == "__main__":
    main()
