"""`mechreport dynamics` writes its folders as `build` does (issue 40, point 2): the same safe
folder names, the same refusal of links, the same lock, the same whole-folder swap, and
the same `-o`/`--out` spelling (`--output` kept)."""
from __future__ import annotations

import shutil
from pathlib import Path

from mechreport.app import outdir as od
from mechreport.app.cli import main

ROOT = Path(__file__).resolve().parents[2]
MOTOR = ROOT / "specs" / "four_bar_motor.yaml"


def _spec(folder: Path, name: str) -> Path:
    folder.mkdir(parents=True, exist_ok=True)
    return Path(shutil.copy(MOTOR, folder / name))


def _tree(folder: Path) -> list[str]:
    return sorted(str(p.relative_to(folder)) for p in folder.rglob("*"))


def test_dynamics_of_a_dot_named_spec_writes_inside_out(tmp_path, capsys):
    spec = _spec(tmp_path / "specs", "...yaml")
    out = tmp_path / "a" / "out"
    assert main(["dynamics", str(spec), "-o", str(out)]) == 0
    assert _tree(tmp_path / "a") == ["out", "out/.mechreport.lock", "out/spec",
                                     "out/spec/dynamics.csv", "out/spec/dynamics.parquet"]
    assert f"wrote {out / 'spec' / 'dynamics.csv'}" in capsys.readouterr().out


def test_dynamics_refuses_a_planted_symlink_folder(tmp_path, capsys):
    spec = _spec(tmp_path / "specs", "motor.yaml")
    outside = tmp_path / "outside"
    outside.mkdir()
    out = tmp_path / "out"
    out.mkdir()
    (out / "motor").symlink_to(Path("..") / "outside")
    assert main(["dynamics", str(spec), "--out", str(out)]) == 1
    assert list(outside.iterdir()) == []
    err = capsys.readouterr().err
    assert f"{out / 'motor'} exists and is not a report folder" in err
    assert "Traceback" not in err


def test_dynamics_replaces_its_histories_whole_and_keeps_the_report(tmp_path, capsys):
    spec = _spec(tmp_path / "specs", "motor.yaml")
    out = tmp_path / "out"
    old = out / "motor"
    old.mkdir(parents=True)
    (old / "summary.json").write_text("{}")
    (old / "report.md").write_text("the report")
    (old / "dynamics.csv").write_text("stale")
    (out / ".tmp-motor-99999").mkdir()                  # an interrupted command's leftover
    assert main(["dynamics", str(spec), "--output", str(out)]) == 0
    assert (old / "report.md").read_text() == "the report"
    assert (old / "dynamics.csv").read_text().startswith("time [s],")
    assert (old / "dynamics.parquet").is_file()
    assert sorted(p.name for p in out.iterdir()) == [".mechreport.lock", "motor"]


def test_dynamics_takes_turns_with_a_build_on_the_output_lock(tmp_path, capsys):
    out = tmp_path / "out"
    out.mkdir()
    with od.OutputLock(out).acquire(0):
        assert main(["dynamics", str(MOTOR), "-o", str(out), "--wait", "0"]) == 1
    assert "is still writing to" in capsys.readouterr().err
    assert sorted(p.name for p in out.iterdir()) == [".mechreport.lock"]


def test_dynamics_and_schema_spell_the_output_option_as_build_does(tmp_path, capsys):
    for option in ("-o", "--out", "--output"):
        out = tmp_path / option.strip("-")
        assert main(["dynamics", str(tmp_path / "missing.yaml"), option, str(out)]) == 1
        assert (out / ".mechreport.lock").is_file()       # the folder it was given
        target = tmp_path / f"schema{option}.json"
        assert main(["schema", option, str(target)]) == 0
        assert target.read_text().startswith("{")
