"""One quantity, one value, in every output (issue 30, items 1 and 2): summary.json's
design.cycle and its quantities agree, round-off is 0 everywhere, and a counterweight that
gains nothing is not recommended."""
from __future__ import annotations

from pathlib import Path

import pytest

import mechreport
from mechreport.report.model import build_model

ROOT = Path(__file__).resolve().parents[2]
SPECS = sorted((ROOT / "specs").glob("*.yaml")) + sorted((ROOT / "tests" / "data").glob("*.yaml"))


@pytest.mark.parametrize("path", SPECS, ids=lambda p: p.stem)
def test_cycle_quantities_have_one_value_in_summary_json(path):
    summary = build_model(mechreport.analyse(path)).summary
    cycle = (summary["design"].get("cycle") or {})
    for name, entry in cycle.items():
        assert summary["quantities"][name]["value"] == entry["value"], name


def test_a_counterweight_that_gains_nothing_is_not_recommended():
    m = build_model(mechreport.analyse(ROOT / "specs" / "r_rtr_rtr.yaml"))
    text = m.design.counterweight
    assert text.startswith("No counterweight is recommended") and "brings" not in text
    assert "e-1" not in text                    # the angle's round-off is 0, not 8e-13
    assert m.summary["design"]["cycle"]["balance.counterweight.angle"]["value"] == 0.0


def test_a_counterweight_that_helps_is_recommended_with_its_gain():
    m = build_model(mechreport.analyse(ROOT / "specs" / "slider_crank.yaml"))
    assert m.design.counterweight.startswith("A point counterweight")
    assert "(-48.6 %)" in m.design.counterweight


@pytest.mark.parametrize("path", SPECS, ids=lambda p: p.stem)
def test_a_joint_peak_is_one_value_in_every_output(path):
    """The report's bearing table, its design summary, summary.json and the index give one
    peak per joint; the peak away from left-out angles is a second, labelled value."""
    from mechreport.report.records import index_row
    from mechreport.report.section import display_of
    a = mechreport.analyse(path)
    m = build_model(a)
    s = m.summary
    shown = display_of(a).factor("force")       # the table shows forces in display units
    for row in m.bearings:
        joint, peak = row[0], s["reactions"][row[0]]["peak"]
        assert float(row[3]) / shown == pytest.approx(peak["value"], rel=5e-4), joint
        cycle = (s["design"].get("cycle") or {}).get(f"joint.{joint}.f_max")
        if cycle is not None:                 # listed once, under its cycle name
            assert cycle["value"] == pytest.approx(abs(peak["value"]), rel=1e-12), joint
            assert f"joint.{joint}.f.peak" not in s["quantities"]
        else:
            assert s["quantities"][f"joint.{joint}.f.peak"]["value"] == peak["value"]
    big = s["largest_bearing_load"]
    if big is not None:
        data = index_row(s, "x")["data"]
        assert data["largest_bearing_load_N"] == big["value"]
        far = big["away_from_left_out"]
        if far and far["angle_deg"] != big["angle_deg"]:
            assert data["largest_bearing_load_away_N"] == far["value"]
            assert "away from left-out angles" in index_row(s, "x")["bearing"]


@pytest.mark.parametrize("path", SPECS, ids=lambda p: p.stem)
def test_the_mean_and_rms_effort_are_one_value_in_every_output(path):
    """Over a whole turn with angles left out (slider_crank's dead centres), the design
    summary once showed an RMS torque of 141.6 N·m and the "Over the sweep" table, the plot
    legends and the index 141.2 N·m. One definition (the cycle's: a left-out angle counts
    with its interpolated value), one value, one name in summary.json."""
    from mechreport.report.records import index_row
    a = mechreport.analyse(path)
    m = build_model(a)
    s = m.summary
    q = s["quantities"]
    if a.review is None:
        return
    t = s["driver_torque"]
    effort = "driver.force" if t["unit"] == "N" else "driver.torque"
    for stat in ("mean", "rms"):
        assert t[stat] == q[f"cycle.torque.{stat}"]["value"], stat
        assert f"{effort}.{stat}" not in q            # one name per quantity
    assert s["mean_power"]["value"] == pytest.approx(q["cycle.power.mean"]["value"],
                                                     rel=1e-12, abs=1e-9)
    assert "driver.power.mean" not in q
    data = index_row(s, "x")["data"]
    rms = data["rms_torque_N_m"] if t["unit"] != "N" else data["rms_driver_force_N"]
    assert rms == t["rms"]
    st = a.sweep_summary().torque
    assert st.rms == a.review.values["cycle.torque.rms"]
    assert st.mean == a.review.values["cycle.torque.mean"]


def test_slider_crank_left_out_dead_centres_give_one_rms_torque_in_the_report():
    from mechreport.report.render import report_markdown, report_typst
    a = mechreport.analyse(ROOT / "specs" / "slider_crank.yaml")
    assert a.flags                                   # the dead centres are left out
    text = report_markdown(build_model(a))
    design = [l for l in text.splitlines() if "`cycle.torque.rms`" in l]
    sweep = [l for l in text.splitlines() if l.startswith("| RMS |")]
    assert design and sweep
    value = design[0].rsplit("|", 2)[1].strip()
    assert sweep[0] == f"| RMS | {value} |"


def test_a_pin_joining_three_links_has_its_loads_in_the_design_summary():
    """toggle_press's pin C joins three links: its row was empty (`C — — — —`) although
    summary.json has joint.C.on.<link>.f_max; each of its links' loads is a row."""
    m = build_model(mechreport.analyse(ROOT / "specs" / "toggle_press.yaml"))
    rows = {r[0]: r for r in m.design.bearings}
    assert "C" not in rows
    cycle = m.summary["design"]["cycle"]
    for link in ("pullrod", "upper", "lower"):
        row = rows[f"C.on.{link}"]
        assert all(cell != "—" for cell in row[1:4]), row
        assert f"joint.C.on.{link}.f_max" in cycle
    assert not [r for r in m.design.bearings if all(c == "—" for c in r[1:])]
