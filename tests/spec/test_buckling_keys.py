"""The format 1.2 ``buckling`` keys: per link, per member (``{points: [P, Q], buckling}``),
``inertia_out`` of a section given by its properties, and what is refused."""
from __future__ import annotations

from pathlib import Path

import pytest

from mechreport.errors import SpecError
from mechreport.spec import Buckling, parse_spec


ROOT = Path(__file__).resolve().parents[2]
BASE = (ROOT / "specs" / "crank_press_strength.yaml").read_text(encoding="utf-8")
ROD = "    section: {rect: {width: 12, height: 20}}\n    material: C45\n  ram:"


def rod(extra: str) -> str:
    assert BASE.count(ROD) == 1
    return BASE.replace(ROD, ROD.replace("  ram:", extra + "  ram:"))


def problems(text: str) -> list[str]:
    with pytest.raises(SpecError) as info:
        parse_spec(text, "x.yaml")
    return [f"{p.path}: {p.message}" for p in info.value.problems]


def test_a_links_buckling_and_its_defaults():
    spec = parse_spec(rod("    buckling: {k: 0.7, formula: rankine, "
                          "rankine: {crushing: 320e6, a: 1.3333e-4}}\n"), "x.yaml")
    assert spec.link("rod").strength.buckling == (
        Buckling(0.7, 0.7, "rankine", 320e6, 1.3333e-4),)       # k_out defaults to k
    assert parse_spec(BASE, "x.yaml").link("rod").strength.buckling == ()


def test_a_members_own_buckling_and_inertia_out():
    text = rod("    buckling: {k_out: 0.5}\n    members: [{points: [B, C], buckling: {k: 2}}]\n")
    text = text.replace("section: {rect: {width: 12, height: 20}}",
                        "section: {area: 240, inertia: 8000, c: 10, inertia_out: 2880}")
    st = parse_spec(text, "x.yaml").link("rod").strength
    assert st.members == (("B", "C"),) and st.buckling == (Buckling(2.0, 2.0),)
    assert st.section.inertia_out == pytest.approx(2880e-12, rel=1e-15)
    assert st.section.inertia_min == st.section.inertia_out


@pytest.mark.parametrize("extra, expected", [
    ("    buckling: {formula: rankine}\n",
     "links.rod.buckling: formula: rankine needs 'rankine: {crushing, a}'"),
    ("    buckling: {rankine: {crushing: 1, a: 1}}\n",
     "links.rod.buckling.rankine: goes with 'formula: rankine'"),
    ("    buckling: {k: 0}\n", "links.rod.buckling.k: must be a positive number, got 0"),
    ("    buckling: {formula: gordon}\n", "links.rod.buckling.formula: must be one of "
                                          "euler-johnson, rankine, got 'gordon'"),
    ("    members: [{points: [B, X]}]\n", "links.rod.members[0].points: link 'rod' has no "
                                          "point named 'X'"),
])
def test_what_is_refused(extra, expected):
    assert any(p.startswith(expected) for p in problems(rod(extra))), problems(rod(extra))
