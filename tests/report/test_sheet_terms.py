"""The decoder beside the encoder: every term of every method, read back by
``forces.builders.read_term`` into the products a solution sheet prints, sums to the very
coefficients and constant the solver used (issue 15: sheets render what a term says it is
instead of reverse-engineering its coefficients)."""
from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from mechreport.pipeline.analysis import analyse
from mechreport.forces.builders import read_term
from mechreport.forces.equations import TERM_KINDS

ROOT = Path(__file__).resolve().parents[2]
SPECS = [ROOT / "specs" / f"{s}.yaml" for s in ("slider_crank", "r_rtr_rtr", "hydraulic_boom",
                                                 "spring_loaded_slider_crank")]
SPECS.append(ROOT / "tests" / "data" / "class_iii_triad.yaml")


@pytest.mark.parametrize("spec", SPECS, ids=[p.stem for p in SPECS])
def test_read_term_inverts_every_term(spec):
    a = analyse(spec)
    count = 0
    for name in a.forces:
        for step in a.worked_steps(name):
            for eq in step.equations:
                for t in eq.terms:
                    assert t.kind in TERM_KINDS, (eq.label, t.action.symbol)
                    pieces = read_term(t)
                    scale = 1.0 + float(np.max(np.abs(t.coeffs), initial=0)) + \
                        float(np.max(np.abs(t.const)))
                    const = sum((p.const() for p in pieces if p.unknown is None),
                                np.zeros(len(t.const)))
                    assert np.allclose(const, t.const, rtol=0, atol=1e-12 * scale), \
                        (eq.label, t.action.symbol)
                    for i, u in enumerate(t.action.unknowns):
                        c = sum((p.coeff() for p in pieces if p.unknown == u),
                                np.zeros(len(t.const)))
                        assert np.allclose(c, t.coeffs[:, i], rtol=0, atol=1e-12 * scale), \
                            (eq.label, t.action.symbol, u)
                    count += 1
    assert count > 50


def test_a_wrong_factor_is_caught():
    """The check above can fail: a term whose named lever disagrees with its coefficients."""
    from dataclasses import replace
    a = analyse(SPECS[0])
    eq = next(e for e in a.worked_steps("dalembert")[0].equations if e.kind == "moment")
    t = next(t for t in eq.terms if t.kind == "moment" and t.action.unknowns)
    bad = replace(t, lever=t.lever * 2)
    c = sum(p.coeff() for p in read_term(bad) if p.unknown == t.action.unknowns[1])
    assert not np.allclose(c, t.coeffs[:, 1])
