"""The one wrapper of every command's work on one spec (``console.attempt``): a result, or
the failure said in one line (the error's own message, or an internal error with a traceback
only when MECHREPORT_DEBUG is set), and the command goes on."""
from __future__ import annotations

import pytest

from mechreport.app.console import attempt
from mechreport.errors import MechreportError


def test_a_result_comes_back():
    assert attempt("x.yaml", lambda: 42) == (True, 42)


def test_a_mechreport_error_is_its_own_message_on_stderr(capsys):
    def fail():
        raise MechreportError("x.yaml:3: links: a problem")
    assert attempt("x.yaml", fail) == (False, None)
    assert capsys.readouterr() == ("", "x.yaml:3: links: a problem\n")


@pytest.mark.parametrize("debug", ["", "1"])
def test_anything_else_is_an_internal_error_in_the_commands_own_line(capsys, monkeypatch,
                                                                     debug):
    monkeypatch.setenv("MECHREPORT_DEBUG", debug)
    said = []

    def fail():
        raise ValueError("a bug")
    assert attempt("x.yaml", fail, say=said.append) == (False, None)
    assert len(said) == 1 and said[0].startswith("internal error: ValueError: a bug")
    err = capsys.readouterr().err
    assert ("Traceback" in err) == bool(debug)


def test_an_interrupt_goes_on():
    def stop():
        raise KeyboardInterrupt
    with pytest.raises(KeyboardInterrupt):
        attempt("x.yaml", stop)


@pytest.mark.parametrize("exc, said", [
    (MechreportError("no such scheduler"), "error: no such scheduler\n"),
    (ValueError("a bug"), "error: internal error: ValueError: a bug")])
def test_a_command_that_cannot_run_is_one_line(capsys, monkeypatch, exc, said):
    from mechreport.app.console import report_command_failure
    monkeypatch.delenv("MECHREPORT_DEBUG", raising=False)
    report_command_failure(exc)
    out, err = capsys.readouterr()
    assert out == "" and err.startswith(said) and err.count("\n") == 1
