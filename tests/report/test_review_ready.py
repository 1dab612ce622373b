"""Reports a reviewer pastes as they are, and outputs CI can diff: display units and the one
number formatter, traceability and reproducible PDFs, near-singular peaks, branch choices,
failed checks explained, drawings, the command line (version, help, progress, quiet, skip
unchanged), index.csv/json, `mechreport diff`, `check --junit`, and Kinematics.at."""
from __future__ import annotations

import csv
import hashlib
import json
import math
import re
import shutil
import subprocess
import sys
import xml.etree.ElementTree as ET
from pathlib import Path

import numpy as np
import pytest

from mechreport import __version__
from mechreport.app import cli
from mechreport.pipeline.analysis import analyse
from mechreport.errors import SpecError
from mechreport.app.build import build_files
from mechreport.report.model import build_model
from mechreport.report.mpl import PALETTE
from mechreport.spec import parse_spec
from mechreport.units import Display, fmt

from helpers import tiny_spec as tiny  # the 30-degree slider-crank, written once

pytestmark = pytest.mark.slow      # builds reports, starts processes or fuzzes: not in the fast tier

ROOT = Path(__file__).resolve().parents[2]
FOUR_BAR = ROOT / "specs" / "four_bar.yaml"
SLIDER = ROOT / "specs" / "slider_crank.yaml"
TAB10 = {"#1f77b4", "#ff7f0e", "#2ca02c", "#d62728", "#9467bd", "#8c564b", "#e377c2",
         "#7f7f7f", "#bcbd22", "#17becf"}


def four_bar_text() -> str:
    """specs/four_bar.yaml without its own ``report`` section."""
    return re.sub(r"(?m)^report:.*\n(?:  .*\n)*", "", FOUR_BAR.read_text())


def run(*args, env=None, cwd=ROOT):
    return subprocess.run([sys.executable, "-m", "mechreport", *map(str, args)], cwd=cwd,
                          capture_output=True, text=True, env=env, timeout=300)


# ------------------------------------------------------------------------ the formatter

@pytest.mark.parametrize("x, text", [(5746.87, "5747"), (155.3, "155.3"), (148.0, "148"),
                                     (0.0433013, "0.0433"), (-0.0, "0"), (-1e-17, "-1e-17"),
                                     (99999.6, "100000"), (1.5e-7, "1.5e-07"), (None, "—"),
                                     (float("nan"), "—"), (-4e-5, "-4e-05")])
def test_one_formatter_significant_digits_and_no_minus_zero(x, text):
    assert fmt(x) == text


def test_round_off_of_its_quantity_prints_as_zero():
    d = Display(scales={"force": 5747.0})
    assert d.num(-3e-13, "force") == "0"          # below 1e-9 of the largest force
    assert d.num(-0.004, "force") == "-0.004"       # a small but real value stays
    assert Display("mm", "kN", "N*mm", "g").q(0.0433013, "length") == "43.3 mm"
    assert Display("mm", "kN", "N*mm", "g").q(1500.0, "force") == "1.5 kN"
    assert Display("in", "lbf", "lbf*in", "lb").q(1.0, "moment") == "8.851 lbf·in"


# ----------------------------------------------------------------------- report: units

REPORT = """
report:
  units: {length: mm, force: kN, moment: N*mm, mass: g}
  title: "Press 7 main drive"
  project: "P-1042"
  author: "J. Doe"
  revision: "B"
"""


def test_report_section_is_loaded():
    spec = parse_spec(four_bar_text() + REPORT, "x.yaml")
    assert spec.report.units == {"length": "mm", "force": "kN", "moment": "N*mm", "mass": "g"}
    assert (spec.report.title, spec.report.project, spec.report.author,
            spec.report.revision) == ("Press 7 main drive", "P-1042", "J. Doe", "B")
    default = parse_spec(four_bar_text(), "x.yaml").report
    assert default.units == {} and default.title == ""


@pytest.mark.parametrize("bad, message", [
    ("report: {units: {length: furlong}}", "report.units.length: must be one of m, cm, mm, "
                                           "in, ft, got 'furlong'"),
    ("report: {units: {torque: N*m}}", "report.units.torque: unknown key"),
    ("report: {autor: x}", "report.autor: unknown key; did you mean 'author'?"),
    ("report: {title: [1]}", "report.title: must be text"),
    ("report: {units: {moment: Nm}}", "report.units.moment: must be one of N*m, N*mm, kN*m, "
                                      "lbf*in"),
])
def test_report_section_errors_are_located(bad, message):
    text = four_bar_text() + bad + "\n"
    line = text.count("\n")
    with pytest.raises(SpecError) as err:
        parse_spec(text, "x.yaml")
    assert f"x.yaml:{line}: {message}" in str(err.value)


@pytest.fixture(scope="module")
def units_model(tmp_path_factory):
    d = tmp_path_factory.mktemp("units")
    spec = d / "press.yaml"
    spec.write_text(four_bar_text() + REPORT)
    out = d / "out"
    assert build_files([spec], out, jobs=1, quiet=True) == 0
    return spec, out / "press"


def test_report_shows_display_units_and_metadata(units_model):
    spec, folder = units_model
    md = (folder / "report.md").read_text()
    assert "# Press 7 main drive" in md and "| Project | P-1042 |" in md
    assert "| Revision | B |" in md and "| Author | J. Doe |" in md
    assert "x [mm]" in md and "vx [mm/s]" in md and "mass [g]" in md
    assert "| C (coupler) | 196.2 | 119.9 |" in md             # 0.1962270 m
    assert re.search(r"F01 = 0\.01682 i \+ 0\.07989 j kN", md)  # 16.82 N, 79.89 N
    assert "driver torque M = 3022 N·mm" in md
    assert "lengths in mm, forces in kN, moments in N·mm, masses in g" in md


def test_csv_and_json_stay_si_with_units(units_model):
    _, folder = units_model
    header = (folder / "results.csv").read_text().splitlines()[0]
    assert "C.x [m]" in header and "newton_euler.joint.A.fx [N]" in header
    s = json.loads((folder / "summary.json").read_text())
    assert s["quantities"]["cycle.torque.rms"]["unit"] == "N·m"
    assert s["quantities"]["cycle.torque.rms"]["value"] == pytest.approx(2.27821, rel=1e-5)
    assert s["reference_angles"]["30"]["reactions"]["A"]["newton_euler"]["fx"] == \
        pytest.approx(16.82, abs=0.01)


def test_csv_has_no_minus_zero_and_no_round_off_noise(tmp_path):
    out = tmp_path / "out"
    assert build_files([ROOT / "specs" / "scotch_yoke.yaml"], out, jobs=1, quiet=True) == 0
    rows = list(csv.reader((out / "scotch_yoke" / "results.csv").read_text().splitlines()))
    cells = [c for r in rows[1:] for c in r[2:] if c]
    assert not [c for c in cells if c in ("-0", "-0.0")]
    assert not [c for c in cells if c not in ("0",) and abs(float(c)) < 1e-12]


# -------------------------------------------------------------------------- traceability

def test_report_and_summary_name_version_sha_and_date(units_model):
    spec, folder = units_model
    sha = hashlib.sha256(spec.read_bytes()).hexdigest()
    s = json.loads((folder / "summary.json").read_text())
    assert s["mechreport_version"] == __version__ and s["spec_sha256"] == sha
    assert re.fullmatch(r"\d{4}-\d\d-\d\d \d\d:\d\d UTC", s["date"])
    md = (folder / "report.md").read_text()
    assert sha in md and f"| mechreport | {__version__} |" in md and s["date"] in md
    if shutil.which("pdftotext"):
        text = subprocess.run(["pdftotext", str(folder / "report.pdf"), "-"],
                              capture_output=True, text=True, check=True).stdout
        assert sha in text and __version__ in text
        assert "; shaking moment peak" in text          # the Typst semicolon is printed


def test_source_date_epoch_gives_byte_identical_pdfs(tmp_path):
    import os
    spec = tiny(tmp_path / "t.yaml")
    env = dict(os.environ, SOURCE_DATE_EPOCH="1700000000")
    pdfs = []
    for k in (1, 2):
        out = tmp_path / f"out{k}"
        r = run("build", spec, "-o", out, "-q", env=env)
        assert r.returncode == 0, r.stderr
        pdfs.append((out / "t" / "report.pdf").read_bytes())
        summary = json.loads((out / "t" / "summary.json").read_text())
        assert summary["date"] == "2023-11-14 22:13 UTC"
    assert pdfs[0] == pdfs[1]


# ------------------------------------------------------------------ near-singular, branches

@pytest.fixture(scope="module")
def slider_model():
    return build_model(analyse(SLIDER))


def test_near_singular_peaks_are_told_and_kept_off_the_scale(slider_model):
    m = slider_model
    near = set(np.round(m.sweep.angles[m.sweep.near], 6))
    assert {89.0, 91.0, 85.0, 269.0} <= near and 45.0 not in near
    assert "2 angle(s) left out" in m.left_out and "90°" in m.left_out
    assert "5747 N at joint C_T, 269°" in m.left_out or "5747 N at joint" in m.left_out
    row = next(r for r in m.bearings if r[0] == "C_T")
    assert row[3:5] == ["5747", "269"]                    # the peak, as every output gives it
    far = float(row[-1].split(" at ")[0])                 # the peak away from 90 and 270,
    assert far < 2000 and row[-1].endswith("°")           # told apart in its own column


def test_plot_scale_ignores_near_singular_values(slider_model):
    from mechreport.report.plots import figure, scale_to_trusted
    fig, axes = figure(3.0)
    ax = axes[0, 0]
    sw = slider_model.sweep
    f = [js.f for js in sw.joints]
    assert scale_to_trusted(ax, sw, f, "N")
    assert ax.get_ylim()[1] < 0.5 * max(float(np.max(x)) for x in f)


def test_branch_choices_in_report_kin_and_validate(slider_model):
    assert slider_model.branches == [["B C C_T (rod, slider)", "RRT",
                                      "chosen by the assembly hint (C)"]]
    for cmd in ("kin", "validate"):
        out = run(cmd, "specs/four_bar.yaml")
        assert out.returncode == 0
        assert "branch: dyad B C D (coupler, rocker) [RRR]: hint: C" in out.stdout


# ------------------------------------------------------------------ failed checks explained

def test_failed_expectation_is_explained_once_in_report_and_summary(tmp_path):
    spec = tiny(tmp_path / "bad.yaml", expect_torque=150.0)
    out = tmp_path / "out"
    assert build_files([spec], out, jobs=1, quiet=True) == 1
    s = json.loads((out / "bad" / "summary.json").read_text())
    (f,) = s["failures"]
    assert f["quantity"] == "driver.torque" and f["angle_deg"] == 45 and f["expected"] == 150
    assert f["computed"] == pytest.approx(3 + 105 * math.sqrt(2), abs=1e-6)
    assert f["difference"] == pytest.approx(f["computed"] - 150)
    assert f["tolerance"] == pytest.approx(0.015) and len(f["methods"]) == 5
    md = (out / "bad" / "report.md").read_text()
    assert ("| driver.torque | 45 | 150 N·m | 151.49 N·m | 1.49 N·m | ±0.015 N·m | "
            "Newton-Euler, D'Alembert") in md


def test_check_junit_has_a_case_per_spec_expectation_and_verdict(tmp_path):
    bad = tiny(tmp_path / "bad.yaml", expect_torque=150.0)
    xml = tmp_path / "junit.xml"
    out = run("check", bad, "specs/four_bar.yaml", "--junit", xml)
    assert out.returncode == 1
    root = ET.parse(xml).getroot()
    suites = {s.get("name"): s for s in root.iter("testsuite")}
    assert set(suites) == {str(bad), "specs/four_bar.yaml"}
    cases = {c.get("name"): c for c in suites[str(bad)].iter("testcase")}
    assert cases["check"].find("failure") is None    # the expectation's case states it
    fail = cases["expect driver.torque at 45 deg"].find("failure")
    assert "expected 150 N·m, computed 151.49 N·m" in fail.get("message")
    good = {c.get("name"): c for c in suites["specs/four_bar.yaml"].iter("testcase")}
    assert "design motor.rated_torque" in good and "expect point.C.x at 30 deg" in good
    assert all(c.find("failure") is None for c in good.values())
    assert int(root.get("failures")) == 1              # one failed expectation, counted once


# ------------------------------------------------------------------------------ drawing

RAM = """
links:
  crank:
    points: {A: [0, 0], B: [100, 0]}
    mass: 1000
    shape: {bar: {length: 100, height: 20, depth: 10}}
  rod:
    points: {B: [0, 0], C: [400, 0]}
    mass: 2000
    shape: {bar: {length: 400, height: 30, depth: 10}}
  ram:
    points: {C: [0, 0]}
    mass: 50000
    shape: {block: {width: 600, height: 120, depth: 100}}
"""


def ram_spec(tmp_path) -> Path:
    text = SLIDER.read_text()
    text = text[:text.index("# Textbook 4.6")]
    start, end = text.index("links:"), text.index("joints:")
    text = text[:start] + RAM.lstrip() + "\n" + text[end:]
    text = text.replace("slider]", "ram]").replace("units: {length: m, mass: kg}",
                                                    "units: {length: mm, mass: g}")
    text = re.sub(r"assembly: \{C: \[[^]]*\]\}", "assembly: {C: [470, 0]}", text)
    text = text.replace("link: slider", "link: ram")
    text = re.sub(r"(?m)^units:.*$", "units: {length: mm, mass: g}", text)
    text = text.replace("sheet: true ", "sheet: false")
    p = tmp_path / "ram.yaml"
    p.write_text(text)
    return p


def test_guide_walls_follow_the_block_height_and_crank_is_on_top(tmp_path):
    from mechreport.report.drawing import draw_scene
    a = analyse(ram_spec(tmp_path))
    m = build_model(a)
    scene = m.scenes[0]
    ((p0, p1, on_ground, normal, offset),) = scene.guides
    assert on_ground and offset == pytest.approx(0.06 * 1.04)        # 120 mm / 2, not 300
    fig = draw_scene(scene, m.display)
    ax = fig.axes[0]
    z = {}
    for patch in ax.patches:
        z.setdefault(round(patch.get_zorder(), 3), patch)
    crank_z = 2.2 + 0.6 + 0.01                                          # bar, driver, link 1
    assert max(p.get_zorder() for p in ax.patches if p.get_zorder() < 3) == \
        pytest.approx(crank_z)


def test_drawing_labels_do_not_overlap_and_colours_are_colour_blind_safe(slider_model):
    from mechreport.report.drawing import draw_scene
    from mechreport.report.scene import MOMENT_COLOR
    assert not {c.lower() for c in PALETTE} & TAB10
    assert MOMENT_COLOR not in PALETTE
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    fig = draw_scene(slider_model.scenes[0], slider_model.display)
    canvas = FigureCanvasAgg(fig)
    canvas.draw()
    r = canvas.get_renderer()
    ax = fig.axes[0]
    boxes = [t.get_window_extent(r) for t in ax.texts if t.get_text()
             and not t.get_text().isdigit() and t.get_text() != ax.get_title()]
    assert len(boxes) >= 8
    for i, a in enumerate(boxes):
        for b in boxes[i + 1:]:
            assert not a.overlaps(b), "two labels overlap"


# -------------------------------------------------------------------------- command line

def test_version_and_bare_command_prints_help(capsys):
    with pytest.raises(SystemExit) as exc:
        cli.main(["--version"])
    assert exc.value.code == 0 and capsys.readouterr().out.strip() == f"mechreport {__version__}"
    assert cli.main([]) == 0
    assert "usage: mechreport" in capsys.readouterr().out
    r = run()
    assert r.returncode == 0 and "usage: mechreport" in r.stdout
    for command in ("validate", "kin", "check", "build", "diff"):
        assert command in r.stdout


@pytest.fixture(scope="module")
def two_builds(tmp_path_factory):
    """Two specs built (progress on stderr), then built again unchanged (skipped), then with
    one spec changed."""
    d = tmp_path_factory.mktemp("cli")
    a, b = tiny(d / "a.yaml", "a"), tiny(d / "b.yaml", "b")
    out1 = d / "out1"
    first = run("build", a, b, "-o", out1, "--jobs", "1")
    second = run("build", a, b, "-o", out1, "--jobs", "1")
    quiet = run("build", a, b, "-o", out1, "-q", "--force")
    out2 = d / "out2"
    shutil.copytree(out1, out2)
    b.write_text(b.read_text().replace("value: [100, 0]", "value: [120, 0]"))
    changed = run("build", a, b, "-o", out2, "--jobs", "1")
    return dict(d=d, a=a, b=b, out1=out1, out2=out2, first=first, second=second,
                quiet=quiet, changed=changed)


def test_batch_progress_skip_unchanged_force_and_quiet(two_builds):
    first, second, quiet = two_builds["first"], two_builds["second"], two_builds["quiet"]
    assert first.returncode == 0
    assert re.search(r"^\[1/2\] built .*a\.yaml \(\d+\.\d s\)$", first.stderr, re.M)
    assert re.search(r"^\[2/2\] built .*b\.yaml", first.stderr, re.M)
    assert second.returncode == 0
    assert "[1/2] unchanged" in second.stderr and "2 unchanged (not rebuilt" in second.stderr
    assert quiet.returncode == 0 and quiet.stderr == "" and quiet.stdout == ""
    changed = two_builds["changed"]
    assert "unchanged" in changed.stderr and "built" in changed.stderr


def test_single_spec_build_reports_its_stages(tmp_path):
    r = run("build", tiny(tmp_path / "s.yaml"), "-o", tmp_path / "out")
    assert r.returncode == 0
    assert re.search(r"^\[1/3\] .*s\.yaml: analysing$", r.stderr, re.M)
    assert re.search(r"^\[3/3\] .*: report", r.stderr, re.M)


def test_index_csv_and_json(two_builds):
    out = two_builds["out1"]
    data = json.loads((out / "index.json").read_text())
    assert data["mechreport_version"] == __version__
    specs = {s["folder"]: s for s in data["specs"]}
    assert set(specs) == {"a", "b"} and specs["a"]["status"] == "PASS"
    assert specs["a"]["peak_torque_N_m"] == pytest.approx(
        json.loads((out / "a" / "summary.json").read_text())["driver_torque"]["peak"]["value"])
    rows = list(csv.DictReader((out / "index.csv").read_text().splitlines()))
    assert [r["folder"] for r in rows] == ["a", "b"]
    assert {"status", "rms_torque_N_m", "largest_bearing_load_N", "verdicts_passed",
            "failed_verdicts", "spec_sha256"} <= set(rows[0])


def test_diff_prints_changed_quantities_as_markdown(two_builds):
    same = run("diff", two_builds["out1"], two_builds["out1"])
    assert same.returncode == 0 and "nothing changed" in same.stdout
    diff = run("diff", two_builds["out1"], two_builds["out2"])
    assert diff.returncode == 1
    lines = diff.stdout.splitlines()
    assert "| spec | quantity | old | new | change |" in lines
    changed = [l for l in lines if l.startswith("| b |")]
    assert changed and not [l for l in lines if l.startswith("| a |")]
    assert any("cycle.torque.rms" in l for l in changed)
    loose = run("diff", two_builds["out1"], two_builds["out2"], "--rtol", "10")
    assert loose.returncode == 0
    bad = run("diff", two_builds["d"] / "nowhere", two_builds["out2"])
    assert bad.returncode == 2 and "not a folder" in bad.stderr


# ------------------------------------------------------------------------ Kinematics.at

def test_kinematics_at_raises_naming_the_nearest_angles(slider_model):
    kin = analyse(SLIDER).kinematics
    assert kin.index_of(90) is None and kin.index_of(45) == kin.at(45)
    with pytest.raises(KeyError, match=r"90 deg: it was left out: .*nearest analysed angles: "
                                       r"89 and 91 deg"):
        kin.at(90)
    with pytest.raises(KeyError, match="not analysed; nearest analysed angles: 45 and 46"):
        kin.at(45.5)


def test_solution_sheet_shows_results_in_the_report_units():
    from mechreport.report.sheet import build_sheet, render_markdown
    text = SLIDER.read_text() + "\nreport:\n  units: {length: mm, force: kN, moment: N*mm}\n"
    sheet = build_sheet(analyse(parse_spec(text, "s.yaml")))
    md = render_markdown(sheet)
    assert "Results in the report's units (lengths in mm, forces in kN" in md
    assert "| F01 | -0.1028 kN | 0.1164 kN | 0.1553 kN |" in md
    assert "| M (driver) |  |  |  | 151500 N·mm |" in md
    si = render_markdown(build_sheet(analyse(SLIDER)))
    assert "Results in the report's units" not in si          # SI: nothing to repeat


def test_junit_counts_each_failure_once(tmp_path):
    """Three failed expectations and a missed verdict were counted as five failures (the
    spec's summary case as well as each of its own)."""
    from mechreport.app.junit import junit_cases
    text = Path("specs/four_bar.yaml").read_text(encoding="utf-8")
    text = text.replace("{rated_torque: 3,", "{rated_torque: 0.001,", 1)
    assert "rated_torque: 0.001" in text
    a = analyse(parse_spec(text, "x.yaml"))
    assert not a.passed
    _, cases = junit_cases("x.yaml", a, 1e-6)
    failed = [name for name, message in cases if message is not None]
    missed = [v for v in a.verdicts if not v.passed]
    assert len(failed) == len(missed) + len({(e.expect.angle, e.expect.quantity)
                                             for e in a.expectations if not e.ok})
    assert "check" not in failed
