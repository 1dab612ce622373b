"""docs/spec.md's key tables are what the models give (mechreport/spec/doc_tables.py): each
key's meaning is its field's description, so that the format is described once. To rewrite
them after a model changes, run from the repository root::

    python tests/spec/test_doc_tables.py
"""
from __future__ import annotations

import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
SPEC_MD = ROOT / "docs" / "spec.md"


def test_docs_spec_md_key_tables_are_what_the_models_give():
    from mechreport.spec.doc_tables import updated
    text = SPEC_MD.read_text(encoding="utf-8")
    assert updated(text) == text, ("docs/spec.md's key tables are out of date: run "
                                   "`python tests/spec/test_doc_tables.py`")


def test_every_table_is_in_the_docs_once():
    from mechreport.spec.doc_tables import TABLES
    text = SPEC_MD.read_text(encoding="utf-8")
    for name in TABLES:
        assert text.count(f"<!-- key table {name} -->") == 1, name


def test_every_key_of_the_tabled_models_is_in_a_table():
    from mechreport.spec.doc_tables import TABLES
    from mechreport.spec.schema import keys_of
    shown: dict = {}
    for model, _, keys in TABLES.values():
        shown.setdefault(model, set()).update(keys or keys_of(model))
    for model, keys in shown.items():
        assert keys == set(keys_of(model)), model.__name__


if __name__ == "__main__":
    sys.path.insert(0, str(ROOT))
    from mechreport.spec.doc_tables import updated
    SPEC_MD.write_text(updated(SPEC_MD.read_text(encoding="utf-8")), encoding="utf-8")
