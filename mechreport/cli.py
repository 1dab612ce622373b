"""Command line: a thin layer over the public load -> solve -> render API."""
from __future__ import annotations

import argparse
import sys
from pathlib import Path

import numpy as np

from .errors import MechreportError, SpecError


def spec_files(args: list[str]) -> list[Path]:
    """Expand SPEC|DIR arguments into spec files (a directory gives its *.yaml, sorted)."""
    out: list[Path] = []
    for arg in args:
        p = Path(arg)
        if p.is_dir():
            found = sorted(list(p.glob("*.yaml")) + list(p.glob("*.yml")))
            if not found:
                print(f"{p}: no spec files (*.yaml) in this folder", file=sys.stderr)
            out.extend(found)
        else:
            out.append(p)
    return out


def _cmd_validate(ns: argparse.Namespace) -> int:
    from .kinematics import solve_kinematics
    from .model import build_mechanism
    from .spec import load_spec

    failed = 0
    for path in spec_files(ns.specs):
        try:
            spec = load_spec(path)
            kin = solve_kinematics(build_mechanism(spec), np.asarray(spec.at, float))
            note = f" ({len(kin.flags)} reference angle(s) singular)" if kin.flags else ""
            print(f"{path}: OK{note}")
        except MechreportError as exc:
            failed += 1
            print(str(exc), file=sys.stderr)
    return 1 if failed else 0


def _cmd_kin(ns: argparse.Namespace) -> int:
    from .kinematics import solve_kinematics
    from .model import build_mechanism
    from .report.text import kinematics_table
    from .spec import load_spec

    spec = load_spec(ns.spec)
    angles = np.asarray(ns.angle if ns.angle else spec.at, float)
    kin = solve_kinematics(build_mechanism(spec), angles)
    print(kinematics_table(kin))
    for flag in kin.flags:
        print(f"crank angle {flag.angle:g} deg left out: {flag.reason}")
    return 0


def _cmd_check(ns: argparse.Namespace) -> int:
    from .checks.run import check_files
    return check_files(spec_files(ns.specs), ns.tol)


def _cmd_build(ns: argparse.Namespace) -> int:
    from .report.build import build_files
    return build_files(spec_files(ns.specs), Path(ns.out), jobs=ns.jobs, sheet=ns.sheet,
                       exact=ns.exact)


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(
        prog="mechreport",
        description="Dynamic force analysis of planar linkages from YAML specs.")
    sub = parser.add_subparsers(dest="command", required=True)

    p = sub.add_parser("validate", help="load specs and assemble them at their reference angles")
    p.add_argument("specs", nargs="+", metavar="SPEC|DIR")
    p.set_defaults(func=_cmd_validate)

    p = sub.add_parser("kin", help="print positions, velocities, accelerations")
    p.add_argument("spec", metavar="SPEC")
    p.add_argument("--angle", type=float, action="append",
                   help="crank angle in degrees (repeatable; default: the spec's `at`)")
    p.set_defaults(func=_cmd_kin)

    p = sub.add_parser("check", help="solve by every method; compare methods and expectations")
    p.add_argument("specs", nargs="+", metavar="SPEC|DIR")
    p.add_argument("--tol", type=float, default=1e-6,
                   help="largest relative disagreement between methods (default 1e-6)")
    p.set_defaults(func=_cmd_check)

    p = sub.add_parser("build", help="write Markdown and PDF reports")
    p.add_argument("specs", nargs="+", metavar="SPEC|DIR")
    p.add_argument("-o", "--out", default="out", help="output folder (default: out)")
    p.add_argument("--jobs", type=int, default=None, help="parallel specs (default: cores)")
    p.add_argument("--sheet", action="store_true", help="also write worked solution sheets")
    p.add_argument("--exact", action="store_true",
                   help="solution sheets also show closed forms (needs sympy)")
    p.set_defaults(func=_cmd_build)

    ns = parser.parse_args(argv)
    try:
        return ns.func(ns)
    except SpecError as exc:
        print(str(exc), file=sys.stderr)
        return 1
    except MechreportError as exc:
        print(f"error: {exc}", file=sys.stderr)
        return 1


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
