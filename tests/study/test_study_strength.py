"""A study may keep the members' quantities (sizing a rod's section): each row equals the
analysis of its variant written out by hand, batched or not, whole turn or not."""
from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from mechreport.study.run import run_variants
from mechreport.errors import SpecError
from mechreport.pipeline.analysis import analyse
from mechreport.spec import parse_spec
from mechreport.spec.loader import parse_source, spec_from_data
from mechreport.study import plan_of
from mechreport.study.variants import base_of

ROOT = Path(__file__).resolve().parents[2]
PRESS = (ROOT / "specs" / "crank_press_strength.yaml").read_text(encoding="utf-8").replace(
    "sweep: {start: 0, stop: 360, step: 1}", "sweep: {start: 0, stop: 360, step: 10}")
KEEP = ["member.rod.buckling_safety", "member.rod.fatigue_safety", "member.crank.stress_max",
        "cycle.torque.rms"]
STUDY = ("\nstudy:\n  vary:\n    - {key: links.rod.section.rect.width, values: [8, 10, 14]}\n"
         f"  keep: [{', '.join(KEEP)}]\n")


def test_rows_keep_member_quantities_equal_to_each_variants_analysis():
    src = parse_source(PRESS + STUDY, "press.yaml")
    base = base_of(spec_from_data(src.data, src), src)
    plan = plan_of(base.spec.study)
    table = run_variants(base, plan, "newton_euler", KEEP, jobs=1, chunk=3)
    assert table.done.all() and table.ok.all()
    for i, width in enumerate([8, 10, 14]):
        text = PRESS.replace("section: {rect: {width: 12, height: 20}}",
                             f"section: {{rect: {{width: {width}, height: 20}}}}")
        assert text != PRESS
        ref = analyse(parse_spec(text), methods=["newton_euler"])
        values = {**ref.strength.values, **ref.review.values}
        np.testing.assert_allclose(table.values[i], [values[q] for q in KEEP], rtol=1e-12)
        assert bool(table.passed[i]) == all(v.passed for v in ref.verdicts)
    assert list(table.passed) == [False, False, True]      # the buckling limit, 3


def test_a_study_of_members_alone_needs_no_whole_turn():
    text = PRESS.replace("sweep: {start: 0, stop: 360, step: 10}",
                         "sweep: {start: 200, stop: 280, step: 10}")
    keep = "member.rod.buckling_safety"
    spec = parse_spec(text + STUDY.replace(", ".join(KEEP), keep))
    assert spec.study.keep == (keep,)
    with pytest.raises(SpecError, match="a study tabulates cycle quantities"):
        parse_spec(text + STUDY)
    with pytest.raises(SpecError, match="'member.ram.stress_max': link 'ram' has no "
                                        "'section'"):
        parse_spec(text + STUDY.replace(", ".join(KEEP), "member.ram.stress_max"))
