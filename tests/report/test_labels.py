"""The one label placer measures text as matplotlib lays it out, and never puts two labels
on top of each other where there is room."""
from __future__ import annotations

import pytest

from mechreport.report.labels import Labels, measure
from mechreport.report.mpl import style, text_renderer


def _axes():
    from matplotlib.figure import Figure
    fig = Figure(figsize=(4, 3))
    ax = fig.add_axes((0, 0, 1, 1))
    ax.set_xlim(0, 4)
    ax.set_ylim(0, 3)
    ax.axis("off")
    return fig, ax


@pytest.mark.parametrize("text, bold", [("F12", False), ("A/O", True), ("a\\$b", False),
                                        ("$F_{21x}$", False), ("M3ext = 4 N·m", False)])
def test_measured_size_is_the_drawn_size(text, bold):
    with style():
        fig, ax = _axes()
        t = ax.text(1, 1, text, fontsize=8, fontweight="bold" if bold else "normal")
        r = text_renderer(fig)
        w, h = measure(r, text, 8, "bold" if bold else "normal")
        box = t.get_window_extent(r)
    assert w == pytest.approx(box.width, abs=0.5)
    assert h == pytest.approx(box.height, abs=1.0)      # a glyph's ink may reach further


def test_labels_at_one_point_never_overlap_and_take_the_boxes_they_measured():
    with style():
        fig, ax = _axes()
        labels = Labels(ax)
        labels.block(2, 1.5, 4.0)                      # a pin
        names = ["F12", "F23 = 1043 N", "M", "Fk3", "A/O", "F3ext,2"]
        for name in names:
            labels.place(name, 2, 1.5)
        r = text_renderer(fig)
        drawn = [t.get_window_extent(r) for t in ax.texts]
    assert len(drawn) == len(names)
    for box, placed in zip(drawn, labels.boxes[1:]):           # after the pin's
        assert placed == pytest.approx(tuple(box.extents), abs=1.0)
    for i, a in enumerate(drawn):
        for b in drawn[i + 1:]:
            assert min(a.x1, b.x1) - max(a.x0, b.x0) <= 0.5 or \
                min(a.y1, b.y1) - max(a.y0, b.y0) <= 0.5


def test_overlap_sum_over_arrays_is_the_loop_bit_for_bit():
    """Labels._overlaps (issue 48) is sum(_overlap(a, b) for b in boxes), NaN included."""
    import numpy as np

    from mechreport.report.labels import Labels
    rng = np.random.default_rng(48)
    for n in (0, 1, 7, 40):
        boxes = rng.uniform(0, 100, (n, 4))
        boxes[:, 2:] = boxes[:, :2] + rng.uniform(0, 30, (n, 2))
        if n > 5:
            boxes[3, 1] = np.nan
        for _ in range(20):
            a = tuple(float(v) for v in rng.uniform(0, 100, 2)) * 2
            a = (a[0], a[1], a[0] + 17.3, a[1] + 9.1)
            loop = sum(Labels._overlap(a, tuple(b)) for b in boxes)
            assert Labels._overlaps(a, boxes) == loop
