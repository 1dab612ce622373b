"""Buckling as machine-design books compute it (format 1.2 ``buckling``): Rankine's formula
with different end fixity in and out of the plane, and Euler, against handbook examples. The
handbook numbers are worked out here from the books' formulas, independently of
mechreport.post.strength.
"""
from __future__ import annotations

import math
from pathlib import Path

import pytest

from mechreport.pipeline.analysis import analyse
from mechreport.post.strength import column
from mechreport.spec import Buckling, Material, Section, parse_spec


STEEL = Material("", 200e9, 324e6, 150e6, 450e6)


def _i_section(t: float) -> tuple[float, float, float]:
    """The I-section of a connecting rod, flanges and web t thick, width B = 4t, depth H =
    5t (R. S. Khurmi, A Textbook of Machine Design, 32.12-32.13): A = 11 t^2, Ixx (bending
    in the plane of motion) = 419 t^4 / 12, Iyy (out of it) = 131 t^4 / 12."""
    area = 2 * (4 * t * t) + 3 * t * t
    ixx = (4 * t * (5 * t) ** 3 - 3 * t * (3 * t) ** 3) / 12
    iyy = 2 * t * (4 * t) ** 3 / 12 + 3 * t * t ** 3 / 12
    return area, ixx, iyy


def test_rankine_connecting_rod_i_section_khurmi_machine_design_32_12():
    """Khurmi 32.12: a connecting rod buckles about X (in the plane, both ends hinged: L = l)
    or about Y (out of the plane, both ends fixed: L = l / 2); W_B = sigma_c A / (1 + a
    (L / k)^2), a = 1/7500 for mild steel, sigma_c = 320 MPa. With Ixx / Iyy = 419 / 131 =
    3.2 < 4 it buckles about X: the plane of motion governs."""
    t, l = 0.0064, 0.300
    area, ixx, iyy = _i_section(t)
    assert ixx / iyy == pytest.approx(3.2, abs=0.01)         # the book's 3.2
    sec = Section("area", area, ixx, 2.5 * t, min(ixx, iyy),
                  (("area", area), ("inertia", ixx), ("c", 2.5 * t), ("inertia_out", iyy)))
    sigma_c, a = 320e6, 1 / 7500
    w_x = sigma_c * area / (1 + a * (l / math.sqrt(ixx / area)) ** 2)
    w_y = sigma_c * area / (1 + a * (l / 2 / math.sqrt(iyy / area)) ** 2)
    rod = Buckling(k=1.0, k_out=0.5, formula="rankine", crushing=sigma_c, a=a)
    c = column(sec, STEEL, l, rod)
    assert w_x < w_y
    assert c.plane == 1 and c.rule == "Rankine"
    assert c.load == pytest.approx(w_x, rel=1e-12)
    assert c.slenderness == pytest.approx(l / math.sqrt(ixx / area), rel=1e-12)
    # Ixx > 4 Iyy (a deeper section): out of the plane governs
    deep = Section("area", area, 5 * iyy, 2.5 * t, iyy,
                   (("area", area), ("inertia", 5 * iyy), ("c", 2.5 * t), ("inertia_out", iyy)))
    c = column(deep, STEEL, l, rod)
    w_y = sigma_c * area / (1 + a * (l / 2 / math.sqrt(iyy / area)) ** 2)
    assert c.plane == 2 and c.load == pytest.approx(w_y, rel=1e-12)


@pytest.mark.parametrize("length, rule", [(2.7, "Euler"), (1.5, "Johnson")])
def test_euler_and_rankine_gordon_tubular_strut_44_5_by_2_5_mm_pinned(length, rule):
    """A tubular steel strut, 44.5 mm outside, 2.5 mm wall, pin ended; E = 200 GPa, yield 324
    MPa (a strength-of-materials exercise: the Euler and Rankine-Gordon loads at 2.7 m and
    1.5 m). Euler: pi^2 E I / L^2; Rankine-Gordon: sigma_y A / (1 + a (L / r)^2) with a =
    sigma_y / (pi^2 E); at 1.5 m the strut is below the transition slenderness pi sqrt(2 E /
    sigma_y) = 110.4, where Johnson's parabola applies."""
    D, t = 0.0445, 0.0025
    d = D - 2 * t
    area = math.pi / 4 * (D ** 2 - d ** 2)
    inertia = math.pi / 64 * (D ** 4 - d ** 4)
    r = math.sqrt(inertia / area)
    sec = Section("tube", area, inertia, D / 2, inertia, (("d", D), ("t", t)))
    euler = math.pi ** 2 * 200e9 * inertia / length ** 2
    johnson = area * (324e6 - (324e6 * length / r / (2 * math.pi)) ** 2 / 200e9)
    c = column(sec, STEEL, length)
    assert c.rule == rule and c.plane == 1
    assert c.load == pytest.approx(euler if rule == "Euler" else johnson, rel=1e-9)
    a = 324e6 / (math.pi ** 2 * 200e9)
    gordon = 324e6 * area / (1 + a * (length / r) ** 2)
    c = column(sec, STEEL, length, Buckling(formula="rankine", crushing=324e6, a=a))
    assert c.rule == "Rankine" and c.load == pytest.approx(gordon, rel=1e-9)
    assert gordon < euler           # Rankine-Gordon lies below Euler's curve


def test_johnson_transition_is_taken_with_the_effective_length():
    """Fixed-fixed (k = 0.5) doubles the length at which Euler gives way to Johnson."""
    D, t = 0.0445, 0.0025
    d = D - 2 * t
    area, inertia = math.pi / 4 * (D ** 2 - d ** 2), math.pi / 64 * (D ** 4 - d ** 4)
    sec = Section("tube", area, inertia, D / 2, inertia, (("d", D), ("t", t)))
    c = column(sec, STEEL, 2.7, Buckling(k=0.5, k_out=0.5))
    assert c.rule == "Johnson" and c.slenderness == pytest.approx(
        0.5 * 2.7 / math.sqrt(inertia / area), rel=1e-12)


ROOT = Path(__file__).resolve().parents[2]


def test_a_rod_fixed_out_of_the_plane_through_a_spec():
    """A rect rod 12 wide (normal to the plane) and 25 high (in it): out of the plane its I
    is height width^3 / 12. Pinned both ways, out of the plane governs (plane 2); with
    k_out = 0.5 (fixed against out-of-plane bending), the plane of motion does."""
    base = (ROOT / "specs" / "crank_press_strength.yaml").read_text(encoding="utf-8")
    spec = parse_spec(base, "press.yaml")
    sec = spec.link("rod").strength.section
    w, h = dict(sec.sizes)["width"], dict(sec.sizes)["height"]
    assert w < h and sec.inertia_out == h * w ** 3 / 12
    text = base.replace("mechreport: 1.1", "mechreport: 1.2")
    text = text.replace("  rod:\n", "  rod:\n    buckling: {k: 1, k_out: 0.5}\n", 1)
    pinned, fixed = (analyse(s).strength.members["rod"]
                     for s in (spec, parse_spec(text, "press.yaml")))
    assert pinned.buckling_safety is not None
    assert pinned.buckling_plane == 2 and pinned.plane_text == "out of the plane"
    # out of the plane now at half the length: four times the Euler load (h/w)^2 / 4 > 1
    assert fixed.buckling_plane == 1 and fixed.buckling_safety > pinned.buckling_safety
    assert fixed.values()["member.rod.buckling_plane"] == 1.0


def test_the_solution_sheet_works_the_rankine_check_of_the_rod():
    """The sheet's cut of the rod ends with the column check as the book writes it: kL/r in
    each plane, Rankine's load in each, the smaller governing (numbers worked here)."""
    from mechreport.report.sheet.expr import fmt
    from mechreport.report.sheet.strength import cuts
    base = (ROOT / "specs" / "crank_press_strength.yaml").read_text(encoding="utf-8")
    text = base.replace("mechreport: 1.1", "mechreport: 1.2").replace(
        "  rod:\n", "  rod:\n    buckling: {k: 1, k_out: 0.5, formula: rankine, "
                    "rankine: {crushing: 320e6, a: 1.3333e-4}}\n", 1)
    a = analyse(parse_spec(text, "press.yaml"))
    rod = next(c for c in cuts(a, 0) if c.title == "Cut of member rod")
    words = " ".join(x for x in rod.result if isinstance(x, str))
    w, h, L = 0.012, 0.020, 0.400
    area = w * h
    p_in = 320e6 * area / (1 + 1.3333e-4 * (L / math.sqrt(h * h / 12)) ** 2)
    p_out = 320e6 * area / (1 + 1.3333e-4 * (0.5 * L / math.sqrt(w * w / 12)) ** 2)
    assert p_in < p_out
    assert f"k = 1: kL/r = {fmt(L / math.sqrt(h * h / 12))}" in words
    assert f"= {fmt(p_in)} N (Rankine)" in words and f"= {fmt(p_out)} N (Rankine)" in words
    assert f"P_cr = {fmt(p_in)} N, in the plane" in words
    # a link without buckling data: no column check in its cut (its report gives P_cr)
    crank = next(c for c in cuts(a, 0) if c.title == "Cut of member crank")
    assert not any("Column check" in x for x in crank.result if isinstance(x, str))


def test_the_sheet_column_check_writes_powers_of_ten_as_a_textbook():
    """Sheets write 2.88·10⁻⁹ m⁴, never 2.88e-09 (the out-of-plane I of a 12 x 20 mm rod)."""
    from mechreport.report.sheet.strength import cuts
    base = (ROOT / "specs" / "crank_press_strength.yaml").read_text(encoding="utf-8")
    text = base.replace("mechreport: 1.1", "mechreport: 1.2").replace(
        "  rod:\n", "  rod:\n    buckling: {k: 1, k_out: 0.5, formula: rankine, "
                    "rankine: {crushing: 320e6, a: 1.3333e-4}}\n", 1)
    a = analyse(parse_spec(text, "press.yaml"))
    rod = next(c for c in cuts(a, 0) if c.title == "Cut of member rod")
    words = " ".join(x for x in rod.result if isinstance(x, str))
    check = words[words.index("Column check"):]
    assert "I_out = 2.88·10⁻⁹ m⁴" in check
    assert "e-0" not in check and "e+" not in check
