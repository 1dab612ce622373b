"""Nothing is written outside the output folder through its lock file (issue 36, item 2):
a lock file that is a symbolic link, a hard link to another file, or not a regular file is
refused with a clear message, and the file it points at is left as it was."""
from __future__ import annotations

import io
import os
from pathlib import Path

import pytest

from mechreport.app import outdir as od
from mechreport.app.cli import main

ROOT = Path(__file__).resolve().parents[2]
SPEC = str(ROOT / "specs" / "four_bar.yaml")


def _victim(tmp_path: Path) -> Path:
    victim = tmp_path / "victim.txt"
    victim.write_text("DATA\n")
    return victim


def test_a_symlinked_lock_file_is_not_followed(tmp_path, capsys):
    out = tmp_path / "o"
    out.mkdir()
    victim = _victim(tmp_path)
    (out / od.LOCK_NAME).symlink_to(victim)
    assert main(["build", SPEC, "-o", str(out), "-q"]) == 1
    assert "symbolic link" in capsys.readouterr().err
    assert victim.read_text() == "DATA\n"


def test_a_hard_linked_lock_file_is_not_emptied(tmp_path, capsys):
    out = tmp_path / "o"
    out.mkdir()
    victim = _victim(tmp_path)
    os.link(victim, out / od.LOCK_NAME)
    assert main(["build", SPEC, "-o", str(out), "-q"]) == 1
    assert "hard link" in capsys.readouterr().err
    assert victim.read_text() == "DATA\n"


def test_a_lock_file_that_is_a_fifo_is_refused_not_waited_on(tmp_path):
    out = tmp_path / "o"
    out.mkdir()
    os.mkfifo(out / od.LOCK_NAME)
    with pytest.raises(od.OutputError, match="not a regular file"):
        od.OutputLock(out).acquire(0)


def test_the_lock_still_serialises_and_records_its_holder(tmp_path):
    out = tmp_path / "o"
    out.mkdir()
    with od.OutputLock(out).acquire(0) as lock:
        assert lock.holder() == str(os.getpid())
        with pytest.raises(od.OutputError, match="still writing"):
            od.OutputLock(out, stream=io.StringIO()).acquire(0)
