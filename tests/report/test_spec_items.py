"""One description of the spec for the report and the sheets (issue 42, item 6): the
driver and the loads are described once (report/spec_items.py) and both phrase those items,
so the two never print two speeds or two names for one driver."""
from __future__ import annotations

from pathlib import Path

from mechreport.report.sheet.model import driver_datum as sheet_driver
from mechreport.report.sheet.statement import driver_statement
from mechreport.report.spec_items import driver_item, load_items
from mechreport.report.spec_text import driver_text, load_texts
from mechreport.spec import parse_spec
from mechreport.units import Display

ROOT = Path(__file__).resolve().parents[2]


def _spec(name: str, old: str = "", new: str = ""):
    text = (ROOT / "specs" / name).read_text(encoding="utf-8")
    assert old in text
    return parse_spec(text.replace(old, new), name)


def test_the_report_and_the_sheets_print_the_rpm_the_spec_wrote():
    spec = _spec("four_bar.yaml", "rpm: 300", "rpm: 33.3")
    d = driver_item(spec)
    assert d.rpm == 33.3 and d.kind == "R" and d.crank and not d.at_rest
    assert "(33.3 rpm)" in driver_text(spec)
    assert "(33.3 rpm)" in "".join(p for p in sheet_driver(spec) if isinstance(p, str))
    assert "at 33.3 rpm" in driver_statement(spec)
    assert d.label in driver_statement(spec) and d.label in sheet_driver(spec)[0]


def test_a_stroke_driver_is_described_as_a_force_over_its_stroke():
    spec = _spec("hydraulic_boom.yaml")
    d = driver_item(spec)
    assert (d.kind, d.effort, d.coordinate, d.rpm) == ("T", "force", "stroke", None)
    assert d.axis_suffix == " " + spec.units.get("length", "m")
    assert d.rate_unit == "m/s" and d.accel_unit == "m/s²"


def test_every_load_is_described_once_with_its_link_and_point():
    spec = _spec("spring_loaded_slider_crank.yaml")
    items = load_items(spec)
    assert [i.load for i in items] == list(spec.loads)
    d = Display("m", "N", "N*m", "kg", {})
    for item, text in zip(items, load_texts(spec, d)):
        assert text.startswith(f"{item.label}: {item.what} on {item.link}")
        assert item.where.startswith(f"link {spec.number(item.link)} ({item.link})")
