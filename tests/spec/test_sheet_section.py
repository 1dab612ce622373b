"""The ``sheet`` key (format 1.2): true/false as before, or a mapping {enabled, statement,
variants} declared once in the models; its mistakes said with file, line and key path."""
from __future__ import annotations

import re
from pathlib import Path

import pytest

from mechreport.errors import SpecError
from mechreport.spec import parse_spec

ROOT = Path(__file__).resolve().parents[2]
BASE = re.sub(r"(?m)^sheet: true.*$", "",
              (ROOT / "specs" / "slider_crank.yaml").read_text(encoding="utf-8"))


def load(extra: str):
    return parse_spec(BASE + extra + "\n", "x.yaml")


@pytest.mark.parametrize("extra, on", [("sheet: true", True), ("sheet: false", False),
                                       ("sheet: {statement: Find M.}", True),
                                       ("sheet: {enabled: false, statement: x}", False), ("", False)])
def test_sheet_on_or_off(extra, on):
    assert load(extra).sheet is on


def test_variants_are_read_in_spec_units():
    spec = load("sheet:\n  variants:\n    vary:\n"
                "      - {key: links.crank.points.B.0, from: 0.9, to: 1.1, step: 0.05}\n"
                "      - {key: driver.rpm, values: [10, 20]}\n"
                "    count: 12\n    seed: 5\n    digits: 2\n"
                "    require: {transmission_angle_min: 35}")
    v = spec.sheet_settings.variants
    assert (v.count, v.seed, v.digits, v.require) == (12, 5, 2, (("transmission_angle_min", 35.0),))
    assert v.vary[0].path == ("links", "crank", "points", "B", 0)
    assert (v.vary[0].start, v.vary[0].stop, v.vary[0].step) == (0.9, 1.1, 0.05)
    assert v.vary[1].values == (10.0, 20.0)
    assert spec.sheet_settings.statement is None


def test_defaults():
    v = load("sheet: {variants: {vary: [{key: driver.rpm, values: [10, 20]}]}}")
    v = v.sheet_settings.variants
    assert (v.count, v.seed, v.digits, v.require) == (30, 0, 3, ())


@pytest.mark.parametrize("extra, where, says", [
    ("sheet: {statment: x}", "sheet.statment", "did you mean 'statement'"),
    ("sheet: {variants: {vary: [{key: driver.rpm, from: 1}]}}", "sheet.variants.vary[0]",
     "{key, from, to}"),
    ("sheet: {variants: {vary: [{key: driver.rpm, from: 1, to: 1}]}}",
     "sheet.variants.vary[0]", "'from' and 'to' different"),
    ("sheet: {variants: {vary: [{key: links.crank.points.Z.0, values: [1]}]}}",
     "sheet.variants.vary[0].key", "has no key 'Z'"),
    ("sheet: {variants: {vary: [{key: driver.rpm, values: [1]}], digits: 9}}",
     "sheet.variants.digits", "from 2 to 6"),
    ("sheet: {variants: {vary: [{key: driver.rpm, values: [1]}], require: {mu_min: 1}}}",
     "sheet.variants.require.mu_min", "unknown key"),
    ("sheet: {statement: 3}", "sheet.statement", "text"),
    # a varied `at` printed one angle on the problem while the key took the answers at the
    # spec's `at`: the sheet's angles are not varied
    ("sheet: {variants: {vary: [{key: at.0, values: [30, 60]}]}}",
     "sheet.variants.vary[0].key", "the sheet's angles (at) are not varied"),
])
def test_mistakes_name_the_key(extra, where, says):
    with pytest.raises(SpecError) as err:
        load(extra)
    text = str(err.value)
    assert f"x.yaml:{BASE.count(chr(10)) + 1}: {where}:" in text and says in text, text
