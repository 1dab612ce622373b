"""Benchmark: the fixed cost of one spec (load + analyse of a 36-angle sweep) in CPU
instructions, stage by stage, counted by valgrind's callgrind: unlike CPU time, the count
does not move with the machine's load (here timings vary up to 2x within an hour), so a
change of a few percent can be measured in one run.

    .venv/bin/python bench/bench_instructions.py [--only STAGE,...] [--against REV]
                                                 [--function MODULE:NAME,...]
                                                 [SPEC_NAME ...]   (default: r_rtr_rtr)

``--only analyse`` counts the whole load and analyse alone (about 15 s a spec, where every
stage takes a few minutes); ``--against REV`` counts the code of git revision REV too (a
temporary ``git worktree``, imported first), on the same specs of this checkout, and
prints both columns: a before/after table in one command. The stages other than analyse
call the package's internals as they are now: against an older revision, ``--only
analyse``. ``--function mechreport.forces.contour:_search`` counts what each named function
(``module:name`` or ``module:Class.method``) costs, callees included, per load and analyse,
and how often it is called: a call inside another measured one is counted once. It needs
valgrind's callgrind.h and a C compiler (a client request switches the count, a few thousand
instructions a call, where ``callgrind_control`` costs half a million).

Needs valgrind (Debian package valgrind); each spec takes a few minutes under it. Each
stage is counted over 5 runs after 3 warm-up runs in the same process (the structure
caches warm, as for the second spec of a batch), the objects made until then collected
and frozen (a full collection falls where allocations trigger it, and moved one spec's
count by a million and a half between revisions), less the cost of switching the count
on and off. The force stages follow ``solve_forces``: every method's equations, then their
blocks prepared together, then every method's chain solved level by level. Not a test.
"""
from __future__ import annotations

import argparse
import dataclasses
import gc
import os
import re
import shutil
import subprocess
import sys
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
STAGES = ("empty", "parse", "kinematics", "context", "equations", "prepare", "solves",
          "checks", "analyse")
RUNS, WARM = 5, 3
FUNCTIONS = "functions="           # the child's stage for --function
SHIM = "#include <valgrind/callgrind.h>\nvoid toggle(void) { CALLGRIND_TOGGLE_COLLECT; }\n"


def _child(name: str, stage: str) -> None:
    """Run inside valgrind: count ``stage`` of RUNS analyses of specs/NAME.yaml."""
    os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")
    if stage.startswith(FUNCTIONS):
        _child_function(name, stage[len(FUNCTIONS):])
        return
    from mechreport.pipeline.analysis import analyse
    from mechreport.spec.loader import parse_spec
    if stage not in ("empty", "analyse"):   # as the code is now (older revisions: --only analyse)
        from mechreport.checks.agreement import agreement
        from mechreport.checks.residuals import residuals
        from mechreport.forces import METHODS, ForceContext
        from mechreport.forces.equations import prepare_blocks
        from mechreport.forces.result import chain, method_steps, run_methods
        from mechreport.kinematics import solve_kinematics
        from mechreport.model import build_mechanism
        from mechreport.post.review import design_review

    text = (ROOT / "specs" / f"{name}.yaml").read_text()
    pid = str(os.getpid())

    def count(on: bool) -> None:
        subprocess.run(["callgrind_control", "-i", "on" if on else "off", pid],
                       capture_output=True, check=False)

    def run(measure: bool) -> None:
        def at(what: str, on: bool) -> None:
            if measure and stage == what:
                count(on)
        at("empty", True)
        at("empty", False)
        at("analyse", True)
        if stage == "analyse":
            analyse(_short(parse_spec(text, f"{name}.yaml")))
            at("analyse", False)
            return
        at("parse", True)
        spec = parse_spec(text, f"{name}.yaml")
        at("parse", False)
        at("kinematics", True)
        kin = solve_kinematics(build_mechanism(_short(spec)))
        at("kinematics", False)
        at("context", True)
        ctx = ForceContext(kin)
        at("context", False)
        at("equations", True)        # every method's steps, as solve_forces builds them
        chains = [chain(ctx, method_steps(ctx, method, module.build_steps))
                  for method, module in METHODS.items()]
        at("equations", False)
        at("prepare", True)          # and their blocks, prepared together
        prepared = prepare_blocks(chains, ctx.n)
        at("prepare", False)
        at("solves", True)           # every method's chain, level by level
        forces = run_methods({method: method_steps(ctx, method, module.build_steps)
                              for method, module in METHODS.items()},
                             ctx, prepared)
        at("solves", False)
        at("checks", True)
        residuals(ctx, forces)
        agreement(forces)
        design_review(kin, forces, ctx.loads)
        at("checks", False)

    for _ in range(WARM):
        run(False)
    _settle()
    for _ in range(RUNS):
        run(True)


def _settle() -> None:
    """After the warm-up: every object made so far (the imports', the warm-up's) collected
    or frozen out of the collector's reach, so that a full collection, whose cost is that
    of every object alive and which falls wherever the allocations happen to trigger it,
    does not land in some revisions' counted runs and not in others' (it moved the
    hydraulic boom's count by 1.4 million between two revisions)."""
    gc.collect()
    gc.freeze()


def _short(spec):
    """``spec`` over the fixed cost's 36 angles."""
    from mechreport.spec import Sweep
    return dataclasses.replace(spec, sweep=Sweep(0.0, 360.0, 10.0), at=(30.0,), expect=())


def _child_function(name: str, target: str) -> None:
    """Run inside valgrind (collection off at start): switch the count on around each
    outermost call of ``target`` (``module:name``; ``empty``: a switch on and off per run,
    nothing between) over RUNS analyses; print the calls."""
    import ctypes
    import importlib
    from mechreport.pipeline.analysis import analyse
    from mechreport.spec.loader import parse_spec
    toggle = ctypes.CDLL(os.environ["BENCH_SHIM"]).toggle
    state = {"depth": 0, "measure": False, "calls": 0}

    def counted(fn):
        def wrapper(*args, **kwargs):
            outer = state["depth"] == 0 and state["measure"]
            state["depth"] += 1
            if outer:
                state["calls"] += 1
                toggle()
            try:
                return fn(*args, **kwargs)
            finally:
                if outer:
                    toggle()
                state["depth"] -= 1
        return wrapper

    if target != "empty":
        module, _, qualname = target.partition(":")
        owner = importlib.import_module(module)
        *path, attr = qualname.split(".")
        for part in path:
            owner = getattr(owner, part)
        fn = getattr(owner, attr)
        wrapped = counted(fn)
        setattr(owner, attr, wrapped)
        if not path:                          # and where it was imported by name
            for mod in list(sys.modules.values()):
                if getattr(mod, "__name__", "").startswith("mechreport") \
                        and getattr(mod, attr, None) is fn:
                    setattr(mod, attr, wrapped)
    text = (ROOT / "specs" / f"{name}.yaml").read_text()
    for _ in range(WARM):
        analyse(_short(parse_spec(text, f"{name}.yaml")))
    _settle()
    state["measure"] = True
    for _ in range(RUNS):
        if target == "empty":
            state["calls"] += 1
            toggle()
            toggle()
        analyse(_short(parse_spec(text, f"{name}.yaml")))
    print(f"calls: {state['calls']}", file=sys.stderr)


def _shim(tmp: Path) -> Path:
    """The client-request shim (a shared library), compiled into ``tmp``."""
    src, lib = tmp / "shim.c", tmp / "shim.so"
    src.write_text(SHIM)
    cc = shutil.which("cc") or shutil.which("gcc")
    made = subprocess.run([cc or "cc", "-O2", "-shared", "-fPIC", "-o", str(lib), str(src)],
                          capture_output=True, text=True, check=False) if cc else None
    if made is None or made.returncode != 0:
        raise SystemExit("--function needs a C compiler and valgrind's callgrind.h "
                         "(Debian: gcc, valgrind)" + (f":\n{made.stderr}" if made else ""))
    return lib


_SWITCHING: dict = {}      # (spec, code) -> the switching's count and its pairs


def function_counts(name: str, target: str, shim: Path,
                    code: Path | None = None) -> tuple[float, int]:
    """Million instructions per analysis of ``target`` (switching taken off) and its
    outermost calls per analysis."""
    def once(which: str) -> tuple[int, int]:
        count, err = _valgrind(name, FUNCTIONS + which, code, "--collect-atstart=no",
                               BENCH_SHIM=str(shim))
        calls = re.search(r"calls: (\d+)", err)
        if calls is None:
            raise SystemExit(f"no count of calls for {name} {which}:\n{err[-2000:]}")
        return count, int(calls.group(1))
    total, calls = once(target)               # first: a misspelt target fails at once
    if (name, code) not in _SWITCHING:
        _SWITCHING[name, code] = once("empty")
    empty, pairs = _SWITCHING[name, code]
    return (total - calls * empty / pairs) / RUNS / 1e6, calls // RUNS


def _valgrind(name: str, stage: str, code: Path | None, start: str,
              **env_extra: str) -> tuple[int, str]:
    """Run the child for ``stage`` under callgrind with option ``start`` (how counting
    starts): the instructions collected and the child's stderr."""
    env = dict(os.environ, **env_extra)
    env.setdefault("PYTHONHASHSEED", "0")     # string hashes move the count by about 1 %
    if code is not None:
        env["PYTHONPATH"] = os.pathsep.join(filter(None, [str(code),
                                                          env.get("PYTHONPATH")]))
    out = subprocess.run(
        ["valgrind", "--tool=callgrind", start, "--callgrind-out-file=/dev/null",
         sys.executable, __file__, "--child", name, stage],
        capture_output=True, text=True, check=False, cwd=code or ROOT, env=env)
    found = re.search(r"Collected\s*:\s*(\d+)", out.stderr)
    if found is None:
        raise SystemExit(f"valgrind gave no count for {name} {stage}:\n{out.stderr[-2000:]}")
    return int(found.group(1)), out.stderr


def instructions(name: str, stage: str, code: Path | None = None) -> int:
    """Instructions counted for ``stage`` over RUNS runs (switching cost included), of the
    package in ``code`` (a checkout imported first) or of this one."""
    return _valgrind(name, stage, code, "--instr-atstart=no")[0]


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
    parser.add_argument("--function", type=lambda v: v.split(","), metavar="MODULE:NAME,...",
                        help="count these functions (callees included) instead of stages")
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
        shim = _shim(Path(tmp)) if args.function else None
        before = None
        if against is not None:
            before = Path(tmp) / "code"
            made = subprocess.run(["git", "worktree", "add", "--detach", str(before), against],
                                  capture_output=True, text=True, cwd=ROOT, check=False)
            if made.returncode != 0:
                raise SystemExit(f"git worktree add {against}: {made.stderr.strip()}")
        try:
            for name in names:
                if shim is not None:
                    _report_functions(name, args.function, shim, before, against)
                else:
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


def _report_functions(name: str, targets: list[str], shim: Path, before: Path | None,
                      against: str | None) -> None:
    print(f"{name}: million instructions per load and analyse (36 angles), callees included")
    for target in targets:
        now, calls = function_counts(name, target, shim)
        line = f"  {target:<56}{now:8.3f}  ({calls} calls)"
        if before is not None:
            old, old_calls = function_counts(name, target, shim, before)
            line = (f"  {target:<56}{old:8.3f} ({old_calls} calls, {against[:8]})"
                    f"{now:8.3f}  ({calls} calls)")
        print(line)


if __name__ == "__main__":
    main()
