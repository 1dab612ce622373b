"""A study row is as trustworthy as `check` would find its variant, as far as one method can
tell (issue 36, item 9): a variant whose one method's numbers are the small difference of
huge terms fails its row with the reason, never an ok row that `check` fails."""
from __future__ import annotations

from pathlib import Path

import mechreport
from mechreport.checks.trust import untrusted
from mechreport.study import evaluate_chunk
from mechreport.study.variants import base_of
from mechreport.spec.loader import parse_source, spec_from_data

ROOT = Path(__file__).resolve().parents[2]
TEXT = (ROOT / "specs" / "offset_slider_crank.yaml").read_text(encoding="utf-8")
STUDY = """study:
  vary:
    - {key: gravity.1, values: [-9.81, -1e-20]}
    - {key: links.crank.mass, values: [600, 1e20]}
  sample: grid
  keep: [joint.A.f_max, cycle.torque.rms]
"""


def _base():
    text = TEXT[:TEXT.index("study:")] + STUDY
    src = parse_source(text, "x.yaml")
    return base_of(spec_from_data(src.data, src), src)


def test_a_variant_check_fails_is_a_failed_row_with_its_reason():
    base = _base()
    variants = [{"gravity.1": g, "links.crank.mass": m}
                for g in (-9.81, -1e-20) for m in (600, 1e20)]
    for method in ("newton_euler", "dyad"):
        rows = evaluate_chunk(base, variants, method, base.spec.study.keep)
        assert [r.ok for r in rows] == [True, True, True, False], method
        assert "cannot be trusted" in rows[3].reason and "N·m" in rows[3].reason


def test_the_failed_variant_indeed_fails_check_and_the_others_pass():
    text = TEXT[:TEXT.index("study:")]
    heavy = text.replace("    mass: 600                     # g, web and counterweight",
                         "    mass: 1e20")
    assert heavy != text
    light_g = heavy.replace("gravity: [0, -9.81]", "gravity: [0, -1e-20]")
    assert not mechreport.analyse(light_g).passed            # methods disagree: FAIL
    assert mechreport.analyse(heavy).passed
    a = mechreport.analyse(light_g)
    assert untrusted(a.forces["newton_euler"], 1e-6)
    assert not untrusted(mechreport.analyse(text).forces["newton_euler"], 1e-6)


def test_every_shipped_spec_is_trusted_by_every_method():
    paths = sorted((ROOT / "specs").glob("*.yaml")) + sorted((ROOT / "tests" / "data")
                                                             .glob("*.yaml"))
    for path in paths:
        a = mechreport.analyse(path)
        for name, res in a.forces.items():
            assert untrusted(res, a.tol, a.spec.axis_unit, a.trust_inputs()) == "", \
                (path.stem, name)


def _cancelling_loads() -> str:
    """The four-bar with two 1e16 N loads at E that cancel: nothing changes physically, but
    every method's torque is the small difference of 1e16 N terms."""
    text = (ROOT / "specs" / "four_bar.yaml").read_text(encoding="utf-8")
    return text.replace("loads:\n", "loads:\n"
                        "  - {type: force, link: coupler, point: E, value: [0, -1e16]}\n"
                        "  - {type: force, link: coupler, point: E, value: [0, 1e16]}\n", 1)


def test_loads_that_cancel_are_not_trusted_by_one_method_and_fail_check():
    a = mechreport.analyse(_cancelling_loads())
    assert not a.passed                                      # the methods disagree
    for name, res in a.forces.items():
        assert untrusted(res, a.tol, "deg", a.trust_inputs()), name


def test_a_long_sweep_variant_is_trust_checked_when_streamed(monkeypatch):
    from mechreport.pipeline import batch
    monkeypatch.setattr(batch, "STREAM_ANGLES", 100)         # 360 angles is "long" now
    base = _base()
    variants = [{"gravity.1": -1e-20, "links.crank.mass": m} for m in (600, 1e20)]
    rows = evaluate_chunk(base, variants, "newton_euler", base.spec.study.keep)
    assert rows[0].ok and not rows[1].ok
    assert "cannot be trusted" in rows[1].reason
