"""The executor on its own (mechreport.study.executor, run_chunks): any task over items in
chunks, results as they finish, a stop check that ends the run, the caller's words in its
lines. (A study's retries and partial results: test_study_faults.py.)"""
from __future__ import annotations

import pytest

from mechreport.study.executor import Words, chunks
from mechreport.study.run import run_chunks


def _square(shared, a, b):
    """A task: the squares of items ``a`` to ``b - 1``, plus ``shared``."""
    return a, [shared + i * i for i in range(a, b)]


def _args(chunk):
    return chunk


def _collect(n, size, jobs, stop_check=None):
    got = {}

    def on_done(chunk, result):
        start, values = result
        got.update(enumerate(values, start))
    run_chunks(_square, 10, n, size, _args, on_done, jobs=jobs, stop_check=stop_check)
    return got


def test_chunks_cover_every_item_once():
    assert chunks(7, 3) == [(0, 3), (3, 6), (6, 7)]
    assert chunks(0, 3) == []


def test_in_this_process_every_item_is_computed():
    assert _collect(7, 3, jobs=1) == {i: 10 + i * i for i in range(7)}


def test_a_stop_check_that_raises_ends_the_run_in_this_process():
    calls = []

    def stop_check():
        calls.append(1)
        if len(calls) == 2:
            raise KeyboardInterrupt
    with pytest.raises(KeyboardInterrupt):
        _collect(7, 3, jobs=1, stop_check=stop_check)


def test_words_name_a_chunk_for_the_user():
    assert Words().span((2, 4)) == "variant(s) 3-4"
    assert Words(item="spec").span((0, 1)) == "spec(s) 1"
    assert Words(label=lambda chunk: "specs/x.yaml").span((0, 1)) == "specs/x.yaml"


@pytest.mark.slow
def test_on_local_processes_every_item_is_computed_and_a_stop_ends_them():
    import multiprocessing
    assert _collect(7, 2, jobs=2) == {i: 10 + i * i for i in range(7)}

    def stop_check():
        raise KeyboardInterrupt
    # children of earlier tests in this pytest worker (a Dask cluster's) are not this run's
    before = set(multiprocessing.active_children())
    with pytest.raises(KeyboardInterrupt):
        _collect(40, 1, jobs=2, stop_check=stop_check)
    left = set(multiprocessing.active_children()) - before
    for p in left:              # stopped (terminated, then killed), if not yet reaped: on a
        p.join(10.0)            # busy machine a worker may outlive stop_pool's 4 s of joins
    assert not [p for p in left if p.exitcode is None], [(p.name, p.pid) for p in left]
