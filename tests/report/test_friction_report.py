"""The report and the solution sheets of a spec with friction in its joints (issue 32, items
4 and 5): the Friction section (its table, efficiency and energy, the plot of the driver
torque with and without friction), summary.json's ``friction`` record, and the sheets'
friction convention, iteration and power terms. Small sweeps (every 10 degrees) keep the
fast tier fast; building the PDFs is slow."""
from __future__ import annotations

import json
import math
import re
from pathlib import Path

import numpy as np
import pytest

import mechreport
from mechreport.report import plots
from mechreport.report.model import build_model
from mechreport.report.render import report_markdown, report_typst
from mechreport.report.sheet import build_problem, build_sheet, render_problem_markdown
from mechreport.report.sheet.render import render_markdown, render_typst
from test_figure_layout import layout_problems   # noqa: E402 - tests/report's layout check

ROOT = Path(__file__).resolve().parents[2]
FRICTION = """
friction:
  A: {mu: 0.08, radius: 10}
  B: {mu: 0.08, radius: 8}
  D: {mu: 0.08, radius: 10}
"""


def coarse(text: str) -> str:
    """A spec's text with its sweep every 10 degrees."""
    out = re.sub(r"sweep: \{start: 0, stop: 360, step: 1\}",
                 "sweep: {start: 0, stop: 360, step: 10}", text)
    assert out != text
    return out


@pytest.fixture(scope="module")
def specs(tmp_path_factory) -> dict[str, Path]:
    """The four-bar without and with friction in A, B and D, the crank press with friction
    in its pins and its guide (a slider with a length), and the four-bar with friction over
    half a turn (no cycle): all every 10 degrees."""
    folder = tmp_path_factory.mktemp("friction_specs")
    four_bar = coarse((ROOT / "specs" / "four_bar.yaml").read_text(encoding="utf-8"))
    press = coarse((ROOT / "specs" / "crank_press_friction.yaml").read_text(encoding="utf-8"))
    half = four_bar[:four_bar.index("\ndesign:")]       # no design review, no expectations
    texts = {"plain": four_bar, "friction": four_bar + FRICTION, "press": press,
             "half": half.replace("stop: 360, step: 10", "stop: 180, step: 10") + FRICTION}
    out = {}
    for name, text in texts.items():
        out[name] = folder / f"{name}.yaml"
        out[name].write_text(text, encoding="utf-8")
    return out


@pytest.fixture(scope="module")
def analyses(specs):
    return {name: mechreport.analyse(path) for name, path in specs.items()}


@pytest.fixture(scope="module")
def models(analyses):
    return {name: build_model(a) for name, a in analyses.items()}


def markdown(model) -> str:
    return report_markdown(model)


# ------------------------------------------------------------------------------ report

def test_the_friction_section_appears_only_with_friction(models):
    plain, with_friction = markdown(models["plain"]), markdown(models["friction"])
    assert models["plain"].friction is None and "friction" not in models["plain"].figures
    assert "## Friction" not in plain and "(#friction)" not in plain
    assert "## Friction" in with_friction and "- [Friction](#friction)" in with_friction
    assert "(figures/friction.svg)" in with_friction
    typst = report_typst(models["friction"])
    assert "= Friction" in typst and "figures/friction.svg" in typst
    assert "= Friction" not in report_typst(models["plain"])
    for text in (plain, with_friction, typst):
        assert "nan" not in text.lower()


def test_the_table_lists_every_friction_joint_and_its_energies_sum_to_the_total(
        models, analyses):
    for name in ("friction", "press"):
        fs, rev, spec = models[name].friction, analyses[name].review, analyses[name].spec
        assert [r[0] for r in fs.rows] == [fr.joint for fr in spec.friction]
        total = rev.values["cycle.friction.energy"]
        assert sum(rev.friction.values()) == pytest.approx(total, rel=1e-12)
        printed = [float(r[5]) for r in fs.rows]        # 4 significant digits each
        assert sum(printed) == pytest.approx(total, rel=2e-3)
        assert float(fs.total[5]) == pytest.approx(total, rel=1e-3)
        shares = [float(r[6].rstrip(" %")) for r in fs.rows]
        assert sum(shares) == pytest.approx(100, abs=0.2)
        assert fs.energy == f"{mechreport.units.fmt(total)} J"
        eff = rev.values["cycle.efficiency"]
        assert fs.efficiency == f"{mechreport.units.fmt(100 * eff)} %"
    press = models["press"].friction
    assert press.size_head == "r or L [mm]"
    assert [r[2] for r in press.rows] == ["Mf01", "Mf12", "Mf23", "Ff03"]
    assert press.rows[3][4] == "L = 150" and press.rows[0][4] == "r = 40"
    assert press.rows[3][7].endswith(" kN")             # a slider's friction is a force
    assert models["friction"].friction.size_head == "journal radius r [mm]"


def test_the_largest_friction_is_where_the_solved_friction_peaks(models, analyses):
    a, fs = analyses["friction"], models["friction"].friction
    for row, fr in zip(fs.rows, a.spec.friction):
        values = np.abs(a.kinematics.friction[fr.joint])
        k = int(np.argmax(values))
        assert row[8] == f"{a.angles[k]:g}"
        assert row[7] == f"{mechreport.units.fmt(values[k])} N·m"


def test_summary_json_friction_equals_the_review(models, analyses):
    assert models["plain"].summary["friction"] is None
    for name in ("friction", "press"):
        s, rev = models[name].summary["friction"], analyses[name].review
        json.dumps(s, allow_nan=False)
        assert s["energy_per_cycle"] == {"value": rev.values["cycle.friction.energy"],
                                         "unit": "J"}
        assert s["efficiency"] == {"value": rev.values["cycle.efficiency"], "unit": ""}
        assert s["efficiency_undefined"] is None
        assert set(s["joints"]) == set(rev.friction)
        for joint, lost in rev.friction.items():
            entry = s["joints"][joint]
            assert entry["energy_per_cycle"] == {"value": lost, "unit": "J"}
            assert entry["share"] == pytest.approx(lost / rev.values["cycle.friction.energy"])
            assert entry["largest"]["unit"] == ("N·m" if entry["type"] == "R" else "N")
    joints = models["press"].summary["friction"]["joints"]
    assert joints["T"]["length"] == {"value": 0.15, "unit": "m"} and joints["T"]["radius"] is None
    assert joints["A"]["radius"] == {"value": 0.04, "unit": "m"}


def test_the_plot_shows_the_torque_with_and_without_friction(models, analyses, tmp_path):
    m, a = models["friction"], analyses["friction"]
    fp = m.friction.plot
    rev = a.review
    np.testing.assert_array_equal(fp.torque, rev.torque)
    np.testing.assert_allclose(fp.frictionless,
                               rev.torque - a.cycle_torque_by_source()["friction"])
    # the means differ by the energy friction takes per turn, over 2 pi (as the caption says)
    assert 2 * math.pi * (fp.means[0] - fp.means[1]) == pytest.approx(
        rev.values["cycle.friction.energy"], rel=1e-9)
    written = plots.write_plots(m, tmp_path)
    assert tmp_path / "friction.svg" in written
    with plots.style():
        fig = plots.friction_figure(fp, m.display)
    ax = fig.axes[0]
    labels = [t.get_text() for t in ax.get_legend().get_texts()]
    assert labels[0].startswith("with friction") and labels[1].startswith("without friction")
    lines = {ln.get_label(): ln for ln in ax.get_lines()}
    np.testing.assert_allclose(lines[labels[0]].get_ydata(), fp.torque)
    np.testing.assert_allclose(lines[labels[1]].get_ydata(), fp.frictionless)


@pytest.mark.parametrize("name", ["friction", "press", "half"])
def test_the_friction_figure_has_no_overlapping_or_cut_text(models, name):
    with plots.style():
        fig = plots.friction_figure(models[name].friction.plot, models[name].display)
        assert not layout_problems(fig)


def test_self_locking_angles_are_named_and_marked(specs, tmp_path):
    """The four-bar with friction self-locks at 96 degrees (of a 2-degree grid): friction
    alone reverses the driver torque there."""
    path = tmp_path / "locking.yaml"
    path.write_text(specs["friction"].read_text().replace("step: 10}", "step: 2}"))
    a = mechreport.analyse(path)
    assert 96.0 in a.kinematics.reversed_by_friction
    m = build_model(a)
    fs = m.friction
    assert any(r.startswith("At 96°, friction alone reverses the sign of the driver torque")
               for r in fs.remarks), fs.remarks
    assert fs.plot.reversed == [float(x) for x in a.kinematics.reversed_by_friction]
    with plots.style():
        fig = plots.friction_figure(fs.plot, m.display)
        assert not layout_problems(fig)
    labels = [t.get_text() for t in fig.axes[0].get_legend().get_texts()]
    assert "sign reversed by friction" in labels


def test_angles_left_out_for_friction_are_counted(models, analyses):
    left = [f for f in analyses["press"].flags if f.by_friction]
    assert left
    assert any(r.startswith(f"{len(left)} angles are left out because the friction")
               for r in models["press"].friction.remarks)
    assert models["press"].summary["friction"]["left_out_deg"] == [f.angle for f in left]


def test_without_a_cycle_the_plot_runs_over_the_sweep_and_no_value_is_made_up(models,
                                                                              analyses):
    a, m = analyses["half"], models["half"]
    assert a.review is None
    fs = m.friction
    assert fs.problem and fs.energy == "—" and fs.efficiency == "—"
    assert all(r[5] == "—" and r[6] == "—" for r in fs.rows) and fs.total is None
    assert fs.plot.means is None and fs.plot.sweep is not None
    np.testing.assert_array_equal(fs.plot.angles, a.angles)
    res = a.forces[a.sweep_summary().method]
    np.testing.assert_allclose(fs.plot.torque - fs.plot.frictionless,
                               a.by_source(res.method)["friction"]["driver.torque"])
    s = m.summary["friction"]
    assert s["energy_per_cycle"] is None and s["efficiency"] is None
    assert s["efficiency_undefined"].startswith("no cycle quantities")
    md = markdown(m)
    assert "Energy lost per cycle and efficiency: undefined" in md
    assert "nan" not in md.lower()


# ------------------------------------------------------------------------------ sheets

def test_the_sheet_defines_the_friction_symbols_and_states_the_iteration(analyses):
    a = analyses["friction"]
    sheet = build_sheet(a)
    md = render_markdown(sheet)
    assert "is the friction couple of link i on link j" in md
    assert "A ($M_{f01}$): μ = 0.08, r = 0.01 m" in md
    assert md.count("### Friction in the joints") == len(a.spec.at)
    assert "Friction depends on the reactions it changes" in md
    assert "start from the frictionless reactions" in md and "Newton's method" in md
    # the power balance: each friction times its joint's relative rate
    assert r"M_{f12}\,(\omega_{2} - \omega_{1})" in md and r"M_{f01}\,\omega_{1}" in md
    assert "Here the joints rub" in md
    typ = render_typst(sheet)
    assert "Friction in the joints" in typ and "M_(f 12) (omega_(2) - omega_(1))" in typ
    plain = render_markdown(build_sheet(analyses["plain"]))
    assert "Friction in the joints" not in plain and "friction couple" not in plain


def test_the_first_iteration_starts_from_the_frictionless_reaction(analyses):
    """The first estimate at a reference angle is the law applied to the frictionless
    reaction (every source but friction), and the converged values are the analysis'."""
    a = analyses["friction"]
    md = render_markdown(build_sheet(a))
    parts = a.by_source()
    fr = a.spec.friction[0]
    for angle in a.spec.at:
        k = a.kinematics.index_of(angle)
        f0 = math.hypot(*(sum(p[f"joint.A.{c}"][k] for src, p in parts.items()
                              if src != "friction") for c in ("fx", "fy")))
        first = fr.mu * fr.radius * f0
        fmt = mechreport.report.sheet.expr.fmt
        assert (rf"|\mathbf{{F}}_{{01}}| = {fmt(f0)}\,\mathrm{{N}}" in md), angle
        assert f"= {fmt(first)}" + r"\,\mathrm{N\,m}" in md
        converged = a.kinematics.friction["A"][k]
        assert f"M_{{f01}} = {fmt(converged)}" + r"\,\mathrm{N\,m}" in md


def test_a_slider_with_friction_reads_in_the_sheet(analyses):
    a = analyses["press"]
    md = render_markdown(build_sheet(a))
    assert r"\mathbf{F}_{f03} \cdot \mathbf{v}_{3/0}" in md          # its power
    assert r"\mu\,(|N_1| + |N_2|)" in md and "L = 0.15 m" in md
    assert "nan" not in md.lower()


def test_the_problem_gives_the_friction_data(analyses):
    text = render_problem_markdown(build_problem(analyses["press"]))
    assert "Coulomb friction μ = 0.05, journal radius 0.04 m" in text
    assert "Coulomb friction μ = 0.1, slider length 0.15 m" in text
    assert "the friction in joints A (Mf01), B (Mf12), C (Mf23) and T (Ff03)" in text
    assert "Coulomb" not in render_problem_markdown(build_problem(analyses["plain"]))


# ------------------------------------------------------------------------------ PDFs

@pytest.mark.slow
def test_the_report_and_sheets_of_a_spec_with_friction_build(specs, tmp_path):
    from mechreport.app.build import build_files
    assert build_files([specs["press"]], tmp_path, jobs=1, sheet=True) == 0
    folder = tmp_path / "press"
    for name in ("report.pdf", "solution.pdf", "problem.pdf", "figures/friction.svg"):
        assert (folder / name).stat().st_size > 0, name
    md = (folder / "report.md").read_text(encoding="utf-8")
    assert "## Friction" in md and "nan" not in md.lower()
    summary = json.loads((folder / "summary.json").read_text(encoding="utf-8"))
    assert summary["friction"]["efficiency"]["value"] == pytest.approx(
        summary["design"]["cycle"]["cycle.efficiency"]["value"])
