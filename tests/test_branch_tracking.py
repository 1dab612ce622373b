"""Branch tracking: the vectorised flip chain equals the sequential rule it replaces."""
from __future__ import annotations

import numpy as np

from mechreport.kinematics.position import _chain


def sequential(if_kept, if_flipped):
    out, prev = [], False
    for k in range(len(if_kept)):
        prev = bool(if_flipped[k] if prev else if_kept[k])
        out.append(prev)
    return out


def test_chain_matches_sequential_rule():
    rng = np.random.default_rng(7)
    for _ in range(500):
        n = int(rng.integers(1, 15))
        a, b = rng.random(n) < 0.5, rng.random(n) < 0.5
        assert _chain(a, b).tolist() == sequential(a, b)
