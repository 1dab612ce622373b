"""The fixed cost of a command: the CPU time (user + system, of the child process, from
``resource.getrusage``) of ``python -m mechreport --version`` and of ``python -m mechreport
check specs/four_bar.yaml``, by the working tree and, if given, by a revision (exported into a
temporary git worktree), best of N runs each; once with the modules compiled from source on
every run (as with PYTHONDONTWRITEBYTECODE=1, so that the size of the source counts), once
with their bytecode cached (as an installed package runs; in a temporary PYTHONPYCACHEPREFIX,
written by a first run that is not counted).

    .venv/bin/python bench/bench_startup.py [REV] [-n 7]

CPU time, not wall-clock time, so that other work on the machine disturbs it less; still,
measure on a quiet machine. Not a test: run by hand (issue 42 item 7). Exit status 0.
"""
from __future__ import annotations

import argparse
import os
import resource
import shutil
import subprocess
import sys
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
COMMANDS = {"--version": ["--version"], "check four_bar": ["check", "specs/four_bar.yaml"]}


def cpu_seconds(source: Path, args: list[str], cache: Path | None = None) -> float:
    """CPU seconds (user + system) of one ``python -m mechreport ARGS`` run by the package in
    ``source`` (its working directory); bytecode cached under ``cache`` if given, else
    none written."""
    env = dict(os.environ, PYTHONPATH=str(source), OPENBLAS_NUM_THREADS="1")
    if cache is None:
        env["PYTHONDONTWRITEBYTECODE"] = "1"
    else:
        env.pop("PYTHONDONTWRITEBYTECODE", None)
        env["PYTHONPYCACHEPREFIX"] = str(cache)
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    subprocess.run([sys.executable, "-m", "mechreport", *args], cwd=source, env=env,
                   stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, check=False)
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    return (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)


def measure(sources: dict[str, Path], runs: int,
            caches: dict[str, Path] | None) -> dict[str, dict[str, float]]:
    """Seconds by source and command (bytecode cached per source in ``caches``, if given);
    the sources' runs interleaved, so that a busy moment falls on all of them alike."""
    out: dict[str, dict[str, float]] = {name: {} for name in sources}
    for command, args in COMMANDS.items():
        for k in range(runs + (caches is not None)):
            for name, source in sources.items():
                seconds = cpu_seconds(source, args, caches and caches[name])
                if k or caches is None:     # a caching run's first run writes the cache
                    out[name][command] = min(out[name].get(command, seconds), seconds)
    return out


def show(title: str, seconds: dict[str, dict[str, float]], names: list[str]) -> None:
    print(title)
    print(f"  {'command':16}" + "".join(f"{name:>16}" for name in names)
          + ("        ratio" if len(names) > 1 else ""))
    for command in COMMANDS:
        row = [seconds[name][command] for name in names]
        ratio = f"{row[0] / row[1]:>12.2f}x" if len(row) > 1 and row[1] > 0 else ""
        print(f"  {command:16}" + "".join(f"{s:>16.3f}" for s in row) + ratio)


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("rev", nargs="?", help="a revision to compare with (e.g. bf87766)")
    ap.add_argument("-n", "--runs", type=int, default=7, help="runs per command (best of)")
    ns = ap.parse_args()
    sources = {"working tree": ROOT}
    work = tree = None
    work_cache = Path(tempfile.mkdtemp(prefix="bench-startup-pycache-"))
    if ns.rev:
        work = Path(tempfile.mkdtemp(prefix="bench-startup-"))
        tree = work / "tree"
        subprocess.run(["git", "worktree", "add", "--detach", str(tree), ns.rev], cwd=ROOT,
                       check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        sources[ns.rev] = tree
    try:
        source_runs = measure(sources, ns.runs, None)
        cached_runs = measure(sources, ns.runs, {name: work_cache / name.replace(" ", "_")
                                                 for name in sources})
    finally:
        shutil.rmtree(work_cache, ignore_errors=True)
        if tree is not None:
            subprocess.run(["git", "worktree", "remove", "--force", str(tree)], cwd=ROOT,
                           stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
            work.rmdir()
    names = list(sources)
    show(f"CPU seconds, best of {ns.runs} (user + system of the child), compiled from source "
         "on every run:", source_runs, names)
    show("the same, bytecode cached:", cached_runs, names)
    return 0


if __name__ == "__main__":
    sys.exit(main())
