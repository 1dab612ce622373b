"""The house rules, checked: no import cycle in the package (function-level imports
included), importing the package changes nothing in the process, and nothing below the
application layer prints, exits or touches signals and the environment. The layers
themselves are import-linter's (``lint-imports``, in ``make test``)."""
from __future__ import annotations

import ast
import functools
import os
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
PACKAGE = ROOT / "mechreport"


def _module_name(path: Path) -> str:
    parts = list(path.relative_to(ROOT).with_suffix("").parts)
    return ".".join(parts[:-1] if parts[-1] == "__init__" else parts)


@functools.lru_cache(maxsize=1)
def import_graph() -> dict[str, set[str]]:
    """Every module of the package -> the package's modules it imports anywhere in its
    body (top level or inside functions)."""
    files = {_module_name(p): p for p in PACKAGE.rglob("*.py")}
    graph: dict[str, set[str]] = {}
    for mod, path in files.items():
        package = mod.split(".") if path.name == "__init__.py" else mod.split(".")[:-1]
        deps = set()
        for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
            if isinstance(node, ast.ImportFrom):
                base = (package[:len(package) - node.level + 1] if node.level else [])
                name = ".".join(base + ([node.module] if node.module else []))
                names = [f"{name}.{a.name}" for a in node.names] + [name]
            elif isinstance(node, ast.Import):
                names = [a.name for a in node.names]
            else:
                continue
            for target in names:
                while target and target not in files:
                    target = target.rpartition(".")[0]
                if target and target != mod:
                    deps.add(target)
        graph[mod] = deps
    return graph


def cycles(graph: dict[str, set[str]]) -> list[list[str]]:
    """The strongly connected components of more than one module (the block solver's own
    Tarjan, :func:`mechreport.forces.equations._strong_components`)."""
    from mechreport.forces.equations import _strong_components
    names = sorted(graph)
    at = {name: k for k, name in enumerate(names)}
    parts = _strong_components([sorted(at[d] for d in graph[name]) for name in names])
    return sorted(sorted(names[k] for k in part) for part in parts if len(part) > 1)


def test_no_import_cycle_in_the_package():
    assert cycles(import_graph()) == []


def test_the_cycle_finder_finds_a_cycle():
    graph = {"a": {"b"}, "b": {"c"}, "c": {"a"}, "d": {"a"}}
    assert cycles(graph) == [["a", "b", "c"]]


def test_function_level_imports_count():
    graph = import_graph()
    # the command line imports its commands inside functions, so that numpy loads after the
    # process is set up: those edges must be in the graph
    assert "mechreport.app.build" in graph["mechreport.app.cli"]


def test_importing_the_package_changes_nothing_in_the_process():
    code = ("import os, sys; e = dict(os.environ); import mechreport; "
            "assert dict(os.environ) == e, 'environment changed'; "
            "loaded = sorted(m for m in sys.modules if m.startswith(('numpy', 'mechreport.')));"
            "assert loaded == ['mechreport.version'], loaded")
    env = {k: v for k, v in os.environ.items() if k != "OPENBLAS_NUM_THREADS"}
    subprocess.run([sys.executable, "-c", code], check=True, env=env, cwd=ROOT)


def test_the_top_level_analyse_is_the_pipelines():
    import mechreport
    from mechreport.pipeline import analyse
    assert mechreport.analyse is analyse


FORBIDDEN_BELOW_APP = {("print",), ("sys", "exit"), ("os", "_exit"), ("signal", "signal"),
                       ("os", "putenv"), ("os", "environ", "setdefault"),
                       ("os", "environ", "update")}


def _dotted(node: ast.AST) -> tuple[str, ...]:
    if isinstance(node, ast.Name):
        return (node.id,)
    if isinstance(node, ast.Attribute):
        return _dotted(node.value) + (node.attr,)
    return ()


def test_nothing_below_the_application_prints_exits_or_changes_the_process():
    offenders = []
    for path in PACKAGE.rglob("*.py"):
        rel = path.relative_to(PACKAGE)
        if rel.parts[0] == "app" or rel.name == "__main__.py":
            continue
        for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
            if isinstance(node, ast.Call) and _dotted(node.func) in FORBIDDEN_BELOW_APP:
                offenders.append(f"{rel}:{node.lineno}: {'.'.join(_dotted(node.func))}")
            if isinstance(node, ast.Assign) and any(
                    isinstance(t, ast.Subscript) and _dotted(t.value) == ("os", "environ")
                    for t in node.targets):
                offenders.append(f"{rel}:{node.lineno}: os.environ[...] =")
            if isinstance(node, ast.Global):
                offenders.append(f"{rel}:{node.lineno}: global {', '.join(node.names)}")
    assert offenders == []


SOLVERS = {"solve_kinematics", "at_unit_rate", "with_rates", "solve_forces", "worked_steps",
           "split_by_source", "solve_friction", "simulate", "equation_of_motion"}


def _imported_names(path: Path):
    """(module as written, name) of every ``from X import name`` in ``path``."""
    for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
        if isinstance(node, ast.ImportFrom):
            for alias in node.names:
                yield "." * node.level + (node.module or ""), alias.name


def test_the_report_reads_results_and_solves_nothing():
    """Nothing under mechreport/report imports a kinematics, force or dynamics solver: the
    report and the sheets read results (issue 42, item 3)."""
    found = [(str(p.relative_to(ROOT)), name) for p in (PACKAGE / "report").rglob("*.py")
             for _, name in _imported_names(p) if name in SOLVERS]
    assert found == []


def test_no_private_name_is_imported_from_another_package():
    """A name starting with _ is imported only within its own package (issue 42)."""
    found = []
    for p in PACKAGE.rglob("*.py"):
        for module, name in _imported_names(p):
            if name.startswith("_") and not name.startswith("__") and \
                    module.startswith("..") and "mechreport" not in module:
                found.append((str(p.relative_to(ROOT)), module, name))
    assert found == []
