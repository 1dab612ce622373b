"""--cross-check draws only variants the study computed (a row lost with a worker has
nothing to compare), and agrees with a row the study failed because one method could not
vouch for it when the methods disagree there too."""
from __future__ import annotations

from types import SimpleNamespace

from mechreport.study import cross_check as cc


def test_lost_rows_are_never_drawn(monkeypatch):
    drawn = []
    monkeypatch.setattr(cc, "check_one",
                        lambda base, table, i, tol: drawn.append(i) or cc.CrossRow(i, True, 0.0, ""))
    table = SimpleNamespace(n=10, method="dyad")
    cc.cross_check(None, table, 5, seed=1, skip=range(0, 8))
    assert sorted(drawn) == [8, 9]
    drawn.clear()
    cc.cross_check(None, table, 3, seed=1)
    assert drawn == list(cc.pick(10, 3, 1))          # no skip: the draw of before
