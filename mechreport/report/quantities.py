"""Plot helpers over report data: nothing mechanical (that is :mod:`mechreport.post`)."""
from __future__ import annotations

import numpy as np


def with_gaps(angles: np.ndarray, *arrays: np.ndarray):
    """Angles and arrays with NaN inserted where the sweep skips angles (left-out angles), so
    plotted lines break there instead of bridging the gap. For plotting only."""
    angles = np.asarray(angles, float)
    if len(angles) < 3:
        return (angles, *arrays)
    step = np.median(np.diff(angles))
    cut = np.flatnonzero(np.diff(angles) > 1.5 * step) + 1
    out_a = np.insert(angles, cut, np.nan)
    return (out_a, *(np.insert(np.asarray(a, float), cut, np.nan, axis=0) for a in arrays))
