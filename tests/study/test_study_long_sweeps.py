"""A study of a long sweep runs in bounded memory, as `check` does (issue 36, item 11): a
variant of more than STREAM_ANGLES analysed angles is checked chunk by chunk, never stacked
into one batch, and its row is what the in-memory analysis gives."""
from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from mechreport.pipeline import batch, streamed
from mechreport.study import evaluate_chunk
from mechreport.study.variants import load_base

ROOT = Path(__file__).resolve().parents[2]


def test_long_sweep_variants_are_streamed_with_the_in_memory_rows(monkeypatch):
    base = load_base(ROOT / "specs" / "offset_slider_crank.yaml")
    keep = base.spec.study.keep
    variants = [{"links.crank.com.0": x, "links.crank.mass": 600.0, "driver.rpm": 1450.0}
                for x in (-15.0, -5.0)]
    in_memory = evaluate_chunk(base, variants, "dyad", keep)
    calls = []
    real = streamed.check_sweep
    monkeypatch.setattr(batch, "check_sweep", lambda *a, **k: calls.append(1) or real(*a, **k))
    monkeypatch.setattr(batch, "STREAM_ANGLES", 100)          # 360 angles is "long" now
    monkeypatch.setattr(batch, "solve_stacked", lambda *a: pytest.fail("stacked"))
    rows = evaluate_chunk(base, variants, "dyad", keep)
    assert len(calls) == len(variants)
    for got, want in zip(rows, in_memory):
        assert got.ok and want.ok and got.passed == want.passed
        np.testing.assert_allclose(got.values, want.values, rtol=1e-9)
