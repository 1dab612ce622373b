"""The JSON Schema and the loader agree wherever one value decides (issue 42): mutated specs
(one value replaced at each kind of place) judged by ``jsonschema`` and by the loader. The
schema may accept what the loader refuses only for a reason that needs more than that value
(a name that must exist, mobility, two values compared); it never refuses what the loader
accepts."""
from __future__ import annotations

import pytest

pytest.importorskip("jsonschema")

from differential import KNOWN, disagreements, known_verdicts   # noqa: E402

SHORT = (1.0, 2.0, 1, 360, "x", True, None, {})


@pytest.mark.parametrize("case", range(len(KNOWN)))
def test_the_cases_issue_42_found_are_judged_alike(case):
    where, schema_ok, loader_ok = list(known_verdicts())[case]
    assert schema_ok == loader_ok, where


@pytest.mark.slow                   # every mutated spec, judged by the schema and the loader
def test_no_mutation_is_judged_differently():
    assert list(disagreements(values=SHORT)) == []
