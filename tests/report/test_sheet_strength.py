"""The solution sheet's cuts (mechreport.report.sheet.strength): each member cut at its
middle, the free part's actions summed by hand here give the N, V, M the diagrams give."""
from __future__ import annotations

from pathlib import Path

import numpy as np

from mechreport.pipeline.analysis import analyse
from mechreport.report.sheet.strength import cuts

ROOT = Path(__file__).resolve().parents[2]
PRESS = ROOT / "specs" / "crank_press_strength.yaml"


def test_the_free_part_beyond_the_middle_gives_the_diagrams_values():
    a = analyse(PRESS)
    k = int(np.flatnonzero(np.isclose(a.angles, 260))[0])
    got = cuts(a, k)
    assert [c.title for c in got] == ["Cut of member crank", "Cut of member rod"]
    for c in got:
        m = a.strength.members[c.title.rsplit(" ", 1)[1]]
        mid = len(m.diagram.s) // 2
        assert m.diagram.s[mid] == m.length / 2
        # the rows add up to the force on the section: sum them independently of the text
        fx = sum(float(r[2] or 0) for r in c.rows)
        fy = sum(float(r[3] or 0) for r in c.rows)
        moment = sum(float(r[4]) for r in c.rows)
        th = a.kinematics.theta[k, a.spec.number(m.link)]
        e = np.array([np.cos(th), np.sin(th)])
        n = np.array([-e[1], e[0]])
        scale = max(abs(m.diagram.N[k, mid]), 1.0)
        assert abs(fx * e[0] + fy * e[1] - m.diagram.N[k, mid]) < 1e-4 * scale
        assert abs(fx * n[0] + fy * n[1] - m.diagram.V[k, mid]) < 1e-4 * scale
        assert abs(moment - m.diagram.M[k, mid]) < 1e-4 * max(abs(m.diagram.M[k, mid]), 1.0)
        text = "".join(x for x in c.result if isinstance(x, str))
        assert f"{m.diagram.N[k, mid]:.6g}" in text.replace("-0 ", "0 ")
    assert {r[1] for c in got for r in c.rows} >= {"B", "C", "distributed"}


def test_no_section_no_cuts():
    a = analyse(ROOT / "specs" / "slider_crank.yaml")
    assert cuts(a, 0) == []


def test_strength_note_is_in_the_reports_length_unit():
    """crank_press_strength (lengths in mm): the note on the crank's mass gave its lengths
    in m ("0.05 m from its members' middle (0.05, 0) m"); the report prints it in its own
    units by the one formatter, summary.json keeps SI."""
    from pathlib import Path
    import mechreport
    from mechreport.report.model import build_model
    spec = Path(__file__).resolve().parents[2] / "specs" / "crank_press_strength.yaml"
    a = mechreport.analyse(spec)
    m = build_model(a)
    (note,) = m.strength.notes
    assert "its centre of mass is 50 mm from its members' middle (50, 0) mm" in note
    assert " m " not in note and " m)" not in note
    si = a.strength.members["crank"].note
    assert "0.05 m from its members' middle (0.05, 0) m" in si
    assert m.summary["strength"]["members"]["crank"]["note"] == si
