"""Does a change keep every output the same? Builds the specs (with solution sheets) by the
working tree and by a given revision (exported into a temporary git worktree), then compares
the two output folders file by file: every text output (Markdown, CSV, JSON, Typst sources
where kept, DXF) must be equal apart from the lines that carry a date or a build time, and
every other file must exist on both sides. PDFs, SVGs and GIFs are listed when their bytes
differ (they embed dates, fonts and rendering details; look at them as a reader would).

    .venv/bin/python bench/compare_builds.py REV [SPEC ...] [--keep DIR]

Exit status 0 when every text output is equal, 1 otherwise (the differences are printed).
Not a test: a refactoring's acceptance check, run by hand (a build takes a minute or two).
"""
from __future__ import annotations

import argparse
import difflib
import os
import re
import shutil
import subprocess
import sys
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
TEXT = {".md", ".csv", ".json", ".dxf", ".txt", ".typ", ".yaml"}
# lines that change from run to run: dates, build times, the version's source hash
VOLATILE = re.compile(r"\d{4}-\d{2}-\d{2}[ T]\d{2}:\d{2}|\"date\"|\"seconds\"|seconds|"
                      r"built in .* s\)|\(\d+\.\d s\)|\$DATE|creation_date")


def build(source: Path, specs: list[str], out: Path) -> None:
    """``mechreport build --sheet`` of ``specs`` into ``out`` by the package in ``source``."""
    env = dict(os.environ, PYTHONPATH=str(source), OPENBLAS_NUM_THREADS="1")
    cmd = [sys.executable, "-m", "mechreport", "build", *specs, "-o", str(out), "--sheet",
           "--force", "-q", "--jobs", "2"]
    subprocess.run(cmd, cwd=source, env=env, check=False, stdout=subprocess.DEVNULL)


def stable(text: str) -> list[str]:
    return [line for line in text.splitlines() if not VOLATILE.search(line)]


def compare(old: Path, new: Path) -> list[str]:
    """The differences between two output folders, one message each."""
    problems = []
    names = sorted({p.relative_to(old) for p in old.rglob("*") if p.is_file()}
                   | {p.relative_to(new) for p in new.rglob("*") if p.is_file()})
    for rel in names:
        a, b = old / rel, new / rel
        if rel.name == ".mechreport.lock":
            continue
        if not a.exists() or not b.exists():
            problems.append(f"{rel}: only in {'new' if b.exists() else 'old'}")
            continue
        if rel.suffix in TEXT:
            x, y = (stable(p.read_text(encoding="utf-8", errors="replace")) for p in (a, b))
            if x != y:
                diff = list(difflib.unified_diff(x, y, "old", "new", lineterm="", n=0))
                problems.append(f"{rel}:\n  " + "\n  ".join(diff[:12]))
        elif a.read_bytes() != b.read_bytes():
            print(f"(bytes differ: {rel})")
    return problems


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("rev", help="the revision to compare with (e.g. main, HEAD~3)")
    ap.add_argument("specs", nargs="*", help="spec files (default: specs/ and tests/data/)")
    ap.add_argument("--keep", type=Path, default=None, help="keep both builds in this folder")
    ns = ap.parse_args()
    specs = ns.specs or sorted(str(p) for p in list((ROOT / "specs").glob("*.yaml"))
                               + list((ROOT / "tests" / "data").glob("*.yaml")))
    specs = [str(Path(s).resolve()) for s in specs]
    work = Path(ns.keep or tempfile.mkdtemp(prefix="compare-builds-"))
    tree = work / "old-tree"
    if tree.exists():
        subprocess.run(["git", "worktree", "remove", "--force", str(tree)], cwd=ROOT)
    subprocess.run(["git", "worktree", "add", "--detach", str(tree), ns.rev], cwd=ROOT,
                   check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    try:
        build(tree, specs, work / "old")
        build(ROOT, specs, work / "new")
        problems = compare(work / "old", work / "new")
    finally:
        subprocess.run(["git", "worktree", "remove", "--force", str(tree)], cwd=ROOT)
        if ns.keep is None:
            shutil.rmtree(work, ignore_errors=True)
    for p in problems:
        print(p)
    print(f"{len(problems)} text output(s) differ" if problems else "every text output is equal")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
