"""A full disk during a build (issue 40, point 8): the spec fails with "no space left on
device writing <file>" (the file as it would be in place, not a private folder), its previous
report is left as it was, the index failure is one line too, never a traceback."""
from __future__ import annotations

import errno
import os
import types
from pathlib import Path

from mechreport.app.cli import main
from mechreport.report import files

from helpers import tiny_spec


class _FullDisk:
    """A file opened for writing on a disk with no space left: every write fails."""

    def __init__(self, fh):
        self.fh = fh

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.fh.close()

    def write(self, data):
        raise OSError(errno.ENOSPC, os.strerror(errno.ENOSPC))

    def fileno(self):
        return self.fh.fileno()


def _disk_full(monkeypatch) -> None:
    """Every file mechreport writes (all go through report.files) meets a full disk."""
    full_os = types.ModuleType("os")
    full_os.__dict__.update(vars(os))
    full_os.fdopen = lambda fd, *a, **k: _FullDisk(os.fdopen(fd, *a, **k))
    monkeypatch.setattr(files, "os", full_os)


def _files(folder: Path) -> dict[str, bytes]:
    return {str(p.relative_to(folder)): p.read_bytes() for p in folder.rglob("*")
            if p.is_file()}


def test_no_space_left_fails_the_spec_clearly_and_keeps_its_report(tmp_path, monkeypatch,
                                                                     capsys):
    spec = tiny_spec(tmp_path / "tiny.yaml")
    out = tmp_path / "out"
    args = ["build", str(spec), "-o", str(out), "-q", "--no-animation", "--jobs", "1"]
    assert main(args) == 0
    before = _files(out / "tiny")
    capsys.readouterr()

    _disk_full(monkeypatch)
    assert main(args + ["--force"]) == 1
    err = capsys.readouterr().err
    assert f"FAIL {spec}: no space left on device writing {out / 'tiny'}{os.sep}" in err
    assert f"error: index: no space left on device writing {out / 'index.csv'}" in err
    assert "Traceback" not in err and "internal error" not in err and ".tmp-" not in err
    assert _files(out / "tiny") == before                    # left as it was
    assert sorted(p.name for p in out.iterdir() if p.name.startswith(".")) == \
        [".mechreport-html", ".mechreport.lock"]   # report.html's script: no leftover


def test_a_failed_write_names_the_file_being_written(tmp_path, monkeypatch):
    _disk_full(monkeypatch)
    target = tmp_path / "report.md"
    try:
        files.atomic_write_text(target, "text")
    except OSError as exc:
        assert (exc.errno, exc.filename) == (errno.ENOSPC, str(target))
    else:
        raise AssertionError("the write did not fail")
    assert list(tmp_path.iterdir()) == []                    # no temporary file left
