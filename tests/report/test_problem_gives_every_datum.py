"""A problem sheet states every datum its answer key uses (issue 30, item 13): a load given
by a profile is stated with every point of it and how values between them are read."""
from __future__ import annotations

from pathlib import Path

import mechreport
from mechreport.report.sheet import build_problem, render_problem_markdown

ROOT = Path(__file__).resolve().parents[2]


def test_a_profile_load_is_stated_with_its_points():
    a = mechreport.analyse(ROOT / "specs" / "four_bar.yaml")
    text = render_problem_markdown(build_problem(a))
    line = next(l for l in text.splitlines() if "profile" in l)
    for angle, value in ((0, 40), (60, 180), (120, 180), (180, 40), (270, 0)):
        assert f"{angle}°: {value}" in line, line
    assert "linear between these points" in line and "every turn" in line
