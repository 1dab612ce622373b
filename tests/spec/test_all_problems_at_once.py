"""Every problem of a file at once (issue 30, item 7): a broken part does not hide what can
be checked without it (the driver's numbers, the sweep's fit to a design review)."""
from __future__ import annotations

import re
from pathlib import Path

import pytest

from mechreport.errors import SpecError
from mechreport.spec import parse_spec

ROOT = Path(__file__).resolve().parents[2]


def _problems(text: str) -> list[str]:
    with pytest.raises(SpecError) as info:
        parse_spec(text, "x.yaml")
    return [f"{p.path}: {p.message}" for p in info.value.problems]


def test_a_typo_in_a_link_does_not_hide_a_bad_driver_speed():
    text = (ROOT / "specs" / "slider_crank.yaml").read_text(encoding="utf-8")
    text = text.replace("    mass: 1\n", "    densty: 1\n", 1)
    text = text.replace("rpm: 9.549296585513721}", "rpm: 60 rpm}")
    found = _problems(text)
    assert any(p.startswith("links.crank.densty") for p in found), found
    assert any(p.startswith("driver.rpm: must be a number") for p in found), found


def test_a_typo_in_a_link_does_not_hide_a_sweep_the_design_review_cannot_use():
    text = (ROOT / "specs" / "four_bar.yaml").read_text(encoding="utf-8")
    text = re.sub(r"sweep: \{[^}]*\}", "sweep: {start: 0, stop: 360, step: 7}", text)
    text = text.replace("    mass:", "    densty:", 1)
    found = _problems(text)
    assert any("densty" in p for p in found), found
    assert any(p.startswith("design: the design review is undefined") and "7 deg" in p
               for p in found), found
