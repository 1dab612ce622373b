"""Arguments that must not hang or crash a command (issue 36, item 12): a pipe named like a
spec in a spec folder, an unwritable JUnit path, a crank angle that is not a number."""
from __future__ import annotations

import os
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

from mechreport.app.cli import main

ROOT = Path(__file__).resolve().parents[2]


@pytest.mark.parametrize("command", ["validate", "check"])
def test_a_fifo_in_a_spec_folder_is_skipped_not_waited_on(tmp_path, command):
    shutil.copy(ROOT / "specs" / "four_bar.yaml", tmp_path / "a.yaml")
    os.mkfifo(tmp_path / "b.yaml")
    # a guard against a hang, not a timing: the command must end by itself
    out = subprocess.run([sys.executable, "-m", "mechreport", command, str(tmp_path)],
                         capture_output=True, text=True, timeout=120, cwd=ROOT)
    assert out.returncode == 0, out.stderr
    assert "b.yaml" in out.stderr and "pipe" in out.stderr
    assert "a.yaml" in out.stdout


def test_a_named_pipe_given_by_name_is_still_read(tmp_path):
    """`mechreport check <(generate-spec)`: a pipe named on the command line is a spec."""
    fifo = tmp_path / "spec.yaml"
    os.mkfifo(fifo)
    proc = subprocess.Popen([sys.executable, "-m", "mechreport", "validate", str(fifo)],
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, cwd=ROOT)
    with open(fifo, "w") as fh:
        fh.write((ROOT / "specs" / "four_bar.yaml").read_text())
    out, err = proc.communicate(timeout=120)
    assert proc.returncode == 0, err
    assert "OK" in out


def test_junit_to_an_unwritable_path_is_a_clear_error(tmp_path, capsys):
    target = tmp_path / "no" / "such" / "folder" / "x.xml"
    (tmp_path / "no").write_text("a file, not a folder")
    assert main(["check", str(ROOT / "specs" / "four_bar.yaml"), "--junit", str(target)]) == 1
    err = capsys.readouterr().err
    assert "cannot write the JUnit XML" in err and "internal error" not in err


@pytest.mark.parametrize("bad", ["nan", "inf", "-inf", "x"])
def test_kin_refuses_an_angle_that_is_not_a_finite_number(bad, capsys):
    with pytest.raises(SystemExit) as exc:
        main(["kin", str(ROOT / "specs" / "four_bar.yaml"), f"--angle={bad}"])
    assert exc.value.code == 2
    assert "must be a finite number" in capsys.readouterr().err
