"""The machine-dynamics outputs agree with the simulation they come from: dynamics.csv and
dynamics.parquet (the format's columns, one row per output step, the last at `until`),
summary.json's `dynamics`, the report's section, `mechreport dynamics`."""
from __future__ import annotations

import json
import math
from pathlib import Path

import numpy as np
import pytest

import mechreport
from mechreport.app.cli import main
from mechreport.report.build import write_report_folder
from mechreport.report.dynamics import HISTORY_COLUMNS

ROOT = Path(__file__).resolve().parents[2]
MOTOR = ROOT / "specs" / "four_bar_motor.yaml"


@pytest.fixture(scope="module")
def built(tmp_path_factory):
    a = mechreport.analyse(MOTOR)
    folder = tmp_path_factory.mktemp("dyn") / "four_bar_motor"
    write_report_folder(a, folder, MOTOR, "0" * 64)
    return a, folder


def read_csv(path: Path):
    lines = path.read_text(encoding="utf-8").splitlines()
    return lines[0].split(","), np.array([[float(x) for x in ln.split(",")] for ln in lines[1:]])


@pytest.mark.slow
def test_the_time_histories_are_the_simulation_sampled_per_output_step(built):
    a, folder = built
    sim = a.dynamics.simulation
    header, rows = read_csv(folder / "dynamics.csv")
    assert tuple(header) == HISTORY_COLUMNS
    step = sim.steady.period / 200                       # the default: 200 per steady turn
    assert np.allclose(np.diff(rows[:, 0]), step, rtol=1e-9)
    assert rows[0, 0] == 0 and rows[-1, 0] <= sim.steady.t0 + sim.steady.period
    assert np.array_equal(rows[:, 2], sim.omega) and np.array_equal(rows[:, 1],
                                                                    np.degrees(sim.angle))
    assert rows[-1, 1] > 360 * 15                        # unwrapped: past the 15th turn
    import pyarrow.parquet as pq
    table = pq.read_table(folder / "dynamics.parquet")
    assert tuple(table.column_names) == HISTORY_COLUMNS
    assert np.array_equal(table.column("crank.omega [rad/s]").to_numpy(), rows[:, 2])


@pytest.mark.slow
def test_summary_and_report_show_the_simulations_numbers(built):
    a, folder = built
    summary = json.loads((folder / "summary.json").read_text(encoding="utf-8"))
    dyn = summary["dynamics"]
    for name, value in a.dynamics.values.items():
        assert dyn["quantities"][name]["value"] == value
        assert summary["quantities"][name]["value"] == pytest.approx(value, rel=1e-12)
    assert dyn["flywheel_estimate"]["speed_fluctuation"]["value"] == a.dynamics.estimate[2]
    report = (folder / "report.md").read_text(encoding="utf-8")
    assert "## Machine dynamics" in report and "figures/dynamics.svg" in report
    rpm = a.dynamics.values["dynamics.mean_rpm"]
    from mechreport.units import fmt
    assert f"| dynamics.mean\\_rpm | {fmt(rpm)} rpm |" in report
    assert (folder / "figures" / "dynamics.svg").is_file()


UNTIL = MOTOR.read_text(encoding="utf-8").replace("  until: steady\n",
                                                  "  until: 0.25\n  output_step: 0.01\n")
UNTIL = UNTIL[:UNTIL.index("expect:")] + "\n"
UNTIL = UNTIL.replace("    speed_fluctuation: 0.07        # the simulated (max - min) / mean "
                      "speed, at most\n", "")


def test_until_a_time_gives_the_transient_with_its_last_row_at_that_time(tmp_path):
    spec = tmp_path / "transient.yaml"
    spec.write_text(UNTIL, encoding="utf-8")
    assert main(["dynamics", str(spec), "-o", str(tmp_path / "out")]) == 0
    header, rows = read_csv(tmp_path / "out" / "transient" / "dynamics.csv")
    assert rows[-1, 0] == 0.25 and len(rows) == 26
    assert np.allclose(rows[:, 0], np.arange(26) * 0.01, rtol=0, atol=1e-12)
    assert rows[0, 2] == 0 and np.all(np.diff(rows[:, 2]) > 0)      # from rest, speeding up
    assert np.allclose(rows[:, 4], 15 * (1 - rows[:, 2] / (310 * math.pi / 30)))


def test_the_dynamics_command_refuses_a_spec_without_dynamics(tmp_path, capsys):
    assert main(["dynamics", str(ROOT / "specs" / "four_bar.yaml"), "-o", str(tmp_path)]) == 1
    assert "no 'dynamics:' section" in capsys.readouterr().err


def test_the_sheet_states_the_equation_of_motion_with_its_numbers():
    """At each reference angle the sheet gives J(phi) from the velocity coefficients (the
    value generalized_inertia computes) and the acceleration of the steady turn there."""
    from mechreport.dynamics import generalized_inertia
    from mechreport.report.sheet.model import build_sheet
    from mechreport.units import fmt
    a = mechreport.analyse(MOTOR)
    sheet = build_sheet(a)
    cycle = a.dynamics.simulation.steady
    for am in sheet.angles:
        text = " ".join(p[0] for p in am.dynamics)
        k = a.kinematics.index_of(am.angle)
        j = generalized_inertia(a.kinematics.take(np.array([k]), ()))[0]
        assert f"= {fmt(j)} kg·m² at φ = {fmt(am.angle)}°" in text
        i = int(np.flatnonzero(np.isclose(cycle.angles, am.angle))[0])
        assert f"= {fmt(cycle.alpha[i])} rad/s²" in text


def test_design_summary_rows_of_the_dynamics_have_a_meaning_and_a_unit():
    """four_bar_motor: the machine-dynamics rows of the Design summary's cycle quantities
    said only their name and "293.5", "0.7632": each now says what it is and its unit,
    like the other cycle-quantity rows."""
    from mechreport.quantities import DYNAMICS_QUANTITIES, unit_of
    from mechreport.report.design import MEANING
    from mechreport.report.model import build_model
    m = build_model(mechreport.analyse(MOTOR))
    rows = {name: (meaning, value) for meaning, name, value in m.design.values}
    assert set(DYNAMICS_QUANTITIES) <= set(rows)
    for name in DYNAMICS_QUANTITIES:
        meaning, value = rows[name]
        assert meaning == MEANING[name] != name
        unit = unit_of(name)
        assert value.endswith(f" {unit}") if unit else " " not in value, (name, value)
    assert rows["dynamics.mean_rpm"][1] == "293.5 rpm"
    assert rows["dynamics.startup_time"][1] == "0.7632 s"
