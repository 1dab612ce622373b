"""``mechreport.run_study``, the Python entry point of a study: the same table as
``mechreport study`` writes to study.csv, nothing printed."""
from __future__ import annotations

from pathlib import Path

import pytest

import mechreport
from mechreport.errors import MechreportError, SpecError
from mechreport.study.outputs import write_csv

ROOT = Path(__file__).resolve().parents[2]
COARSE = (ROOT / "specs" / "four_bar.yaml").read_text(encoding="utf-8").replace(
    "sweep: {start: 0, stop: 360, step: 1}", "sweep: {start: 0, stop: 360, step: 10}")
SMALL = COARSE + """
study:
  vary:
    - {key: links.coupler.mass, values: [200, 240]}
    - {key: driver.rpm, values: [250, 300]}
  keep: [cycle.torque.rms, joint.C.f_max, cycle.transmission_angle.min]
"""


def _cli_csv(spec: Path, out: Path) -> str:
    from mechreport.app.cli import main
    assert main(["study", str(spec), "-o", str(out), "--jobs", "1"]) == 0
    return (out / spec.stem / "study.csv").read_text(encoding="utf-8")


def test_run_study_gives_the_table_the_command_writes(tmp_path, capsys):
    spec = tmp_path / "four_bar.yaml"
    spec.write_text(SMALL, encoding="utf-8")
    want = _cli_csv(spec, tmp_path / "out")
    capsys.readouterr()
    table = mechreport.run_study(spec, jobs=1)
    assert capsys.readouterr() == ("", "")                      # nothing printed
    write_csv(table, tmp_path / "api.csv")
    assert (tmp_path / "api.csv").read_text(encoding="utf-8") == want
    assert table.n == 4 and table.ok.all()


def test_run_study_takes_yaml_text_and_reports_progress():
    seen = []
    table = mechreport.run_study(SMALL, jobs=1, chunk=3,
                                 progress=lambda done, failed: seen.append((done, failed)))
    assert seen == [(3, 0), (4, 0)]
    assert list(table.columns())[:3] == ["variant", "links.coupler.mass", "driver.rpm"]


def test_run_study_refuses_what_the_command_refuses():
    with pytest.raises(SpecError, match="no 'study:' section"):
        mechreport.run_study(COARSE)
    with pytest.raises(MechreportError, match="method power: the power balance"):
        mechreport.run_study(SMALL, method="power")


@pytest.mark.slow
def test_run_study_on_local_processes_gives_the_serial_table(tmp_path):
    serial = mechreport.run_study(SMALL, jobs=1)
    pool = mechreport.run_study(SMALL, jobs=2, chunk=1)
    write_csv(serial, tmp_path / "serial.csv")
    write_csv(pool, tmp_path / "pool.csv")
    assert (tmp_path / "pool.csv").read_bytes() == (tmp_path / "serial.csv").read_bytes()
