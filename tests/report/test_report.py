"""Reports of the two textbook specs (Marghitu, *Dynamic Force Analysis*, sections 4.6 and
4.7), built once into a temporary folder.

Values are printed to the one formatter's 4 significant figures in report.md (the solution
sheets keep the book's 6); summary.json and results.csv must agree with the solver to full
precision.
"""
from __future__ import annotations

import csv
import json
import math
import shutil
import subprocess
from pathlib import Path

import numpy as np
import pytest

from mechreport.pipeline.analysis import analyse
from mechreport.app.build import build_files
from mechreport.report.model import build_model

pytestmark = [pytest.mark.filterwarnings("ignore::DeprecationWarning"),
              pytest.mark.slow]      # builds reports: not in the fast tier

STEMS = {"4.6": "slider_crank", "4.7": "r_rtr_rtr"}


@pytest.fixture(scope="module")
def built(tmp_path_factory, textbook_specs):
    out = tmp_path_factory.mktemp("reports")
    code = build_files([textbook_specs["4.6"], textbook_specs["4.7"]], out, jobs=1)
    assert code == 0
    return out


@pytest.fixture(scope="module")
def analyses(textbook_specs):
    return {k: analyse(p) for k, p in textbook_specs.items()}


def read(out: Path, book: str, name: str) -> str:
    return (out / STEMS[book] / name).read_text(encoding="utf-8")


@pytest.mark.parametrize("book", ["4.6", "4.7"])
def test_every_file_is_written(built, book):
    folder = built / STEMS[book]
    for name in ("report.md", "report.pdf", "results.csv", "summary.json"):
        assert (folder / name).stat().st_size > 0, name
    for fig in ("torque", "reactions", "polar", "shaking"):
        assert b"<svg" in (folder / "figures" / f"{fig}.svg").read_bytes()[:1000]
    assert not list(folder.rglob("*.png")), "one SVG per figure, shown by both reports"
    assert not list(folder.rglob("*.tmp")), "temporary files left behind"
    assert (built / "index.md").exists() and (built / "index.pdf").exists()
    index = (built / "index.md").read_text()
    for label, file in (("sheet pdf", "solution.pdf"), ("problem pdf", "problem.pdf")):
        assert f"[{label}]({folder.name}/{file})" in index     # sheet: true in the spec


def test_slider_crank_textbook_values_in_markdown(built):
    md = read(built, "4.6", "report.md")
    assert "| driver | M [N·m] | 151.5 |" in md             # 3 + 105 sqrt2
    assert "F01 = -102.8 i + 116.4 j N" in md               # -2 (50 + sqrt2), 115 + sqrt2
    assert "F23 = -101.4 i + 97.12 j N" in md               # -100 - sqrt2, 95 + 3 sqrt2/2
    assert "## Crank angle 45°" in md
    assert "![" in md and "(figures/drawing_45.svg)" in md
    assert "nan" not in md.lower()


def test_r_rtr_rtr_textbook_values_in_markdown(built):
    md = read(built, "4.7", "report.md")
    assert "driver torque M = 17.54 N·m" in md
    assert "F01 = -11.42 i + 138.1 j N" in md
    assert "F03 = -256.7 i - 272.2 j N" in md               # joint C
    for title in ("Newton-Euler", "D'Alembert", "Dyad (Assur groups)", "Contour"):
        assert title in md
    assert "nan" not in md.lower()


def test_left_out_angles_are_listed(built):
    md = read(built, "4.6", "report.md")
    assert "| 90 | dyad" in md and "| 270 | dyad" in md


@pytest.mark.parametrize("book", ["4.6", "4.7"])
def test_summary_agrees_with_solver(built, analyses, book):
    s = json.loads(read(built, book, "summary.json"))
    a = analyses[book]
    t = a.forces["newton_euler"].driver_torque
    assert s["status"] == "PASS"
    if a.flags:       # over a whole turn: the cycle's, left-out angles interpolated
        assert s["driver_torque"]["mean"] == a.review.values["cycle.torque.mean"]
        assert s["driver_torque"]["rms"] == a.review.values["cycle.torque.rms"]
    else:
        assert s["driver_torque"]["mean"] == pytest.approx(np.mean(t), rel=1e-12)
        assert s["driver_torque"]["rms"] == pytest.approx(np.sqrt(np.mean(t**2)), rel=1e-12)
    k = int(np.argmax(np.abs(t)))
    assert s["driver_torque"]["peak"] == {"value": pytest.approx(t[k]), "unit": "N·m",
                                          "angle_deg": pytest.approx(a.angles[k])}
    ref = str(int(a.spec.at[0]))
    for m, res in a.forces.items():
        kk = a.kinematics.at(a.spec.at[0])
        assert s["reference_angles"][ref]["driver_torque"][m] == pytest.approx(
            res.driver_torque[kk], rel=1e-12)
    assert s["agreement"]["worst"]["relative"] == pytest.approx(a.worst.relative)
    assert len(s["flags"]) == len(a.flags)
    big = s["largest_bearing_load"]
    r = a.forces["newton_euler"].reactions[big["joint"]]
    assert big["value"] == pytest.approx(np.max(r.f))


def test_summary_textbook_reference_values(built):
    s = json.loads(read(built, "4.7", "summary.json"))
    ref = s["reference_angles"]["30"]
    assert ref["driver_torque"]["dyad"] == pytest.approx(17.5356, abs=1e-4)
    assert ref["reactions"]["A"]["contour"]["fx"] == pytest.approx(-11.4214, abs=1e-4)
    assert ref["reactions"]["A"]["contour"]["fy"] == pytest.approx(138.092, abs=1e-3)
    s46 = json.loads(read(built, "4.6", "summary.json"))
    assert s46["reference_angles"]["45"]["driver_torque"]["power"] == pytest.approx(
        3 + 105 * math.sqrt(2), abs=1e-9)


def test_csv_has_a_row_per_angle_and_empty_cells_for_left_out_angles(built, analyses):
    rows = list(csv.DictReader(read(built, "4.6", "results.csv").splitlines()))
    assert len(rows) == 360                                 # 358 solved + 90 and 270
    by_angle = {float(r["crank_angle [deg]"]): r for r in rows}
    assert by_angle[90.0]["flag"] and by_angle[90.0]["dyad.driver.torque [N·m]"] == ""
    assert float(by_angle[45.0]["dyad.driver.torque [N·m]"]) == pytest.approx(
        3 + 105 * math.sqrt(2), abs=1e-7)
    assert float(by_angle[45.0]["newton_euler.joint.A.fx [N]"]) == pytest.approx(
        -2 * (50 + math.sqrt(2)), abs=1e-7)
    assert not any("nan" in v.lower() for r in rows for v in r.values() if v)


def test_model_shaking_force_is_the_sum_of_ground_reactions(analyses):
    """R-RTR-RTR: the frame joints are A, C, E, all [ground, X]: the frame receives -F."""
    a = analyses["4.7"]
    model = build_model(a)
    res = a.forces["newton_euler"].reactions
    expected = -(res["A"].fx + res["C"].fx + res["E"].fx)
    assert np.allclose(model.sweep.shaking.fx, expected)
    # static check: weights are carried by the frame, inertia averages out over a turn
    k = a.kinematics.at(30)
    assert model.sweep.shaking.fy[k] == pytest.approx(
        -(res["A"].fy[k] + res["C"].fy[k] + res["E"].fy[k]))


def test_polar_trace_is_in_the_carrier_frame(analyses):
    a = analyses["4.6"]
    model = build_model(a)
    pol = {p.name: p for p in model.sweep.polar}
    assert pol["A"].carrier == "ground" and pol["B"].carrier == "rod"
    # |F| is frame-independent; the rod-frame components differ from the global ones
    r = a.forces["newton_euler"].reactions["B"]
    assert np.allclose(np.hypot(pol["B"].x, pol["B"].y), r.f)
    assert not np.allclose(pol["B"].x, r.fx)


def _pgm_pages(pdf: Path, tmp: Path) -> list[np.ndarray]:
    subprocess.run(["pdftoppm", "-r", "30", "-gray", str(pdf), str(tmp / "p")], check=True)
    pages = []
    for f in sorted(tmp.glob("p-*.pgm")):
        data = f.read_bytes()
        parts = data.split(maxsplit=4)      # P5 width height maxval pixels
        w, h = int(parts[1]), int(parts[2])
        pages.append(np.frombuffer(parts[4][-w * h:], np.uint8).reshape(h, w))
    return pages


@pytest.mark.skipif(shutil.which("pdftoppm") is None, reason="pdftoppm not installed")
@pytest.mark.parametrize("book", ["4.6", "4.7"])
def test_pdf_pages_are_not_blank(built, book, tmp_path):
    pages = _pgm_pages(built / STEMS[book] / "report.pdf", tmp_path)
    assert len(pages) >= 4
    for i, page in enumerate(pages):
        assert (page < 128).mean() > 0.002, f"page {i + 1} is blank"


@pytest.mark.skipif(shutil.which("pdftotext") is None, reason="pdftotext not installed")
@pytest.mark.parametrize("book", ["4.6", "4.7"])
def test_pdf_has_every_figure(built, analyses, book):
    model = build_model(analyses[book])
    text = subprocess.run(["pdftotext", str(built / STEMS[book] / "report.pdf"), "-"],
                          check=True, capture_output=True, text=True).stdout
    pages = text.split("\f")
    with_fig = [i for i, p in enumerate(pages) if "Figure " in p]
    n = sum(p.count("Figure ") for p in pages)
    # drawings + 4 sweep plots + the design summary's flywheel, breakdown and balance plots,
    # and a transmission-angle plot where a group has one (4.6: RRT; 4.7: only RTR groups)
    design = 4 if book == "4.6" else 3
    strip = 1 if model.animation is not None and model.animation.strip else 0   # filmstrip
    assert strip == 1
    assert n - strip == len(model.figures) == len(analyses[book].spec.at) + 4 + design
    assert len(with_fig) >= 3
