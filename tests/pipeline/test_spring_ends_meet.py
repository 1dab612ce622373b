"""A spring or damper whose two ends meet has no direction (issue 36, item 3): that angle is
flagged with its reason and left out, never analysed with a silent zero force; everywhere
else the numbers are those of the spec as written."""
from __future__ import annotations

import dataclasses
from pathlib import Path

import numpy as np

import mechreport
from mechreport.pipeline.batch import analyse_variants
from mechreport.spec import parse_spec

ROOT = Path(__file__).resolve().parents[2]
TEXT = (ROOT / "specs" / "spring_loaded_slider_crank.yaml").read_text(encoding="utf-8")


def _spec(s_x: str):
    assert "  S: [300, 0]" in TEXT
    return TEXT.replace("  S: [300, 0]", f"  S: [{s_x}, 0]")


def test_coinciding_spring_ends_leave_the_angle_out_with_the_reason():
    a = mechreport.analyse(_spec("160"))            # S on the slider's top dead centre
    (flag,) = [f for f in a.flags if f.angle == 0.0]
    assert "return spring" in flag.reason and "damper" in flag.reason
    assert "no direction" in flag.reason
    assert a.kinematics.index_of(0.0) is None
    assert a.passed                                 # the rest of the sweep checks out


def test_ends_a_round_off_apart_are_left_out_too():
    """1e-9 m apart at 0.16 m from the origin: the direction is not trustworthy to 1e-6."""
    a = mechreport.analyse(_spec("160.000001"))
    assert [f.angle for f in a.flags] == [0.0]


def test_ends_clearly_apart_keep_every_angle():
    a = mechreport.analyse(_spec("160.01"))
    assert not a.flags
    k = a.kinematics.index_of(0.0)
    fx = a.forces["dyad"].reactions["A"].fx[k]
    assert np.isfinite(fx)


def test_a_study_variant_whose_spring_ends_meet_is_analysed_alone_and_flagged():
    specs = [parse_spec(_spec(x), "v.yaml") for x in ("300", "160")]
    specs = [dataclasses.replace(s, expect=()) for s in specs]
    out = analyse_variants(specs, "dyad")
    assert out[0].batched and not out[1].batched    # the clean one stays in the batch
    assert out[1].exception is None


def test_a_study_varying_a_springs_free_length_stays_batched():
    """The stacked batch's free length is an array over its rows: the check of coinciding
    ends reads it per row (it raised, and every variant fell back to being analysed
    alone)."""
    specs = [dataclasses.replace(parse_spec(TEXT.replace("free_length: 200",
                                                         f"free_length: {f}"), "v.yaml"),
                                 expect=()) for f in (150, 200, 250)]
    assert "free_length: 200" in TEXT
    out = analyse_variants(specs, "dyad")
    assert all(o.batched for o in out)
