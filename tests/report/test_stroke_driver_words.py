"""A linear actuator's sweep is a stroke in the spec's length unit, never a crank angle in
degrees (issue 30, item 3): report headings and their anchors, kin, check and JUnit."""
from __future__ import annotations

import re
from pathlib import Path

import mechreport
from mechreport.app.cli import main
from mechreport.report.check_text import problems
from mechreport.report.model import build_model
from mechreport.report.render import report_markdown, report_typst

ROOT = Path(__file__).resolve().parents[2]
BOOM = ROOT / "specs" / "hydraulic_boom.yaml"


def _anchor(heading: str) -> str:
    """GitHub's anchor of a Markdown heading."""
    return re.sub(r"[^\w\- ]", "", heading.strip().lower()).replace(" ", "-")


def test_report_headings_say_stroke_and_every_contents_link_has_its_heading():
    md = report_markdown(build_model(mechreport.analyse(BOOM)))
    assert "## Stroke 300 mm" in md and "Crank angle" not in md
    headings = {_anchor(h) for h in re.findall(r"^#+ (.+)$", md, flags=re.M)}
    links = re.findall(r"\]\(#([^)]+)\)", md)
    assert links and set(links) <= headings, set(links) - headings


def test_kin_says_stroke_in_the_spec_unit(capsys):
    assert main(["kin", str(BOOM)]) == 0
    out = capsys.readouterr().out
    assert "stroke 300 mm" in out and "crank angle" not in out and " deg" not in out.split("\n")[0]


def test_check_and_junit_name_a_stroke_in_its_unit(tmp_path, capsys):
    text = BOOM.read_text(encoding="utf-8")
    text += "\nexpect:\n  - {angle: 300, quantity: driver.force, value: 1}\n" \
        if "\nexpect:" not in text else ""
    spec = tmp_path / "boom.yaml"
    spec.write_text(text, encoding="utf-8")
    a = mechreport.analyse(spec)
    lines = problems(a, 1e-6)
    assert any("at 300 mm" in line for line in lines), lines
    assert not any(" deg" in line for line in lines)
    junit = tmp_path / "j.xml"
    assert main(["check", str(spec), "--junit", str(junit)]) == 1
    xml = junit.read_text(encoding="utf-8")
    assert "at 300 mm" in xml and "300 deg" not in xml


def test_a_stroke_drivers_columns_and_summary_are_named_for_a_stroke_and_a_force(tmp_path):
    """results.csv's first column was `crank_angle [deg]` and the effort
    `driver.torque [N m]` for strokes in mm and forces in N; summary.json's `driver_torque`
    held a force. They are named for what they are."""
    import mechreport
    from mechreport.report.model import build_model
    a = mechreport.analyse(ROOT / "specs" / "hydraulic_boom.yaml")
    m = build_model(a)
    assert m.csv_header[0] == "stroke [mm]"
    efforts = [c for c in m.csv_header if ".driver." in c]
    assert efforts and all(c.endswith(".driver.force [N]") for c in efforts)
    assert "driver_force" in m.summary and "driver_torque" not in m.summary
    assert m.summary["driver_force"]["unit"] == "N"
    for ref in m.summary["reference_angles"].values():
        assert "driver_force" in ref and ref["units"]["driver_force"] == "N"
    df_names = [c.name for c in a.columns()]
    assert not [n for n in df_names if "driver.torque" in n]


def test_every_machine_readable_unit_is_spelled_one_way():
    import mechreport
    from mechreport.report.model import build_model
    for spec in ("slider_crank", "hydraulic_boom", "crank_press_friction"):
        m = build_model(mechreport.analyse(ROOT / "specs" / f"{spec}.yaml"))
        units = [c[c.index("[") + 1:-1] for c in m.csv_header if "[" in c]
        assert not [u for u in units if u in ("N m", "kg m^2", "N m/rad")], spec
