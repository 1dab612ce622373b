"""Draw an :class:`~mechreport.report.frames.Animation`: ``animation.gif`` (the mechanism
moving over the sweep) and the SVG frames at the reference angles (the PDF's filmstrip).

Every frame is :func:`~mechreport.report.drawing.draw_scene` of its scene in one shared
:class:`~mechreport.report.drawing.View`: the same data limits, figure size and arrow scale
[m per N] for the whole sweep, set so that the reference force (``Animation.force_ref``:
the largest force away from near-singular angles, at most a few times the typical frame's,
see :func:`~mechreport.report.frames.force_reference`) is ARROW_LEN of the drawing's extent;
a longer arrow is cut at CLIP times that, marked // and labelled with its value. Around
the drawing each frame shows the arrow scale (top right), the driver's effort as a bar
gauge (right) and the sweep as a strip (bottom): the effort over the sweep (near-singular
stretches left out of the curve), the frame's place on it, the left-out angles (red). The GIF is written with Pillow
(matplotlib's own dependency), looping, with the first frame's palette for all (the same
colours in every frame: no flicker, and quicker)."""
from __future__ import annotations

import io
import math
from dataclasses import replace
from pathlib import Path

import numpy as np

from .drawing import ARROW_LEN, View, _arrow_geometry, _bounds, draw_scene, view_axes
from .files import atomic_write_bytes
from .frames import CLIP
from .mpl import CUT_COLOR, MOMENT_COLOR, save, styled

FRAME_WIDTH = 4.2      # [in]; two frames side by side fill most of the PDF's text width
GAUGE_W = 0.62         # [in] the effort gauge's column, right
STRIP_H = 0.46         # [in] the sweep strip, bottom
TITLE_H = 0.26         # [in] the title row, top
KEY_ROW = 0.15         # [in] a row of the arrows' key, under the title
KEY_ENTRY = 0.62       # [in] an entry of the key
DPI = 90               # GIF pixels per inch: 378 px wide
COLORS = 96            # palette size of a GIF frame


def view_of(anim) -> View:
    """The view every frame of ``anim`` shares: limits holding every frame's mechanism and
    (cut) arrows, with equal units in x and y."""
    ext = anim.extent
    scale = ARROW_LEN * ext / anim.force_ref if anim.force_ref > 0 else 0.0
    probe = View((0, 0), (1, 1), (1, 1), (0, 0, 1, 1), scale, CLIP * ARROW_LEN * ext)
    los, his = [], []
    for f in anim.frames + anim.strip:
        lo, hi = _bounds(f.scene, _arrow_geometry(f.scene, ext, probe))
        los.append(lo)
        his.append(hi)
    lo, hi = np.min(los, axis=0), np.max(his, axis=0)
    pad = 0.1 * ext                            # room for the names around the drawing
    lo, hi = lo - pad, hi + pad
    span = np.maximum(hi - lo, 1e-9)
    ax_w = FRAME_WIDTH - GAUGE_W - 0.08
    ax_h = float(np.clip(ax_w * span[1] / span[0], 1.5, 3.0))
    want = ax_w / ax_h                         # widen one axis: one unit as long in x as y
    mid = (lo + hi) / 2
    span = (np.array([span[1] * want, span[1]]) if span[0] / span[1] < want
            else np.array([span[0], span[0] / want]))
    top = TITLE_H + KEY_ROW * _key_rows(anim)
    height = top + ax_h + STRIP_H
    rect = (0.04 / FRAME_WIDTH, STRIP_H / height, ax_w / FRAME_WIDTH, ax_h / height)
    return View(tuple(mid - span / 2), tuple(mid + span / 2), (FRAME_WIDTH, height), rect,
                scale, CLIP * ARROW_LEN * ext)


def _nice(x: float) -> float:
    """The largest 1, 2 or 5 times a power of ten not above ``x`` (> 0)."""
    e = math.floor(math.log10(x))
    for m in (5, 2, 1):
        if m * 10 ** e <= x:
            return m * 10 ** e
    return 10 ** e


@styled
def draw_frame(anim, frame, view: View, d):
    """One frame as one figure: :func:`draw_scene` of ``frame.scene`` in ``view``, with the
    arrow scale, the effort gauge and the sweep strip (values in ``d``'s display units)."""
    fig = draw_scene(frame.scene, d, frame.title, view=view)
    _static_decor(fig, anim, view, d)
    _frame_decor(fig, anim, frame, view, d)
    return fig


@styled
def draw_gif_frame(anim, frame, view: View, d):
    """One frame as the GIF shows it, as one figure: the drawing without text, the key of
    its arrows under the title, the scale, gauge and strip (what :func:`gif_bytes` lays
    over a shared background; for checks and contact sheets)."""
    fig = draw_scene(frame.scene, d, frame.title, view=replace(view, labels=False))
    _static_decor(fig, anim, view, d)
    _key(fig, anim, view, d)
    _frame_decor(fig, anim, frame, view, d)
    return fig


class _Places:
    """Where the gauge and the sweep strip sit in a frame (figure fractions), and the
    effort's range ``lo``..``hi`` [SI] they show."""

    def __init__(self, anim, view: View):
        w, h = view.size
        self.w, self.h = w, h
        self.lo, self.hi = _away_range(anim)
        self.gx, self.gw = 1 - (GAUGE_W - 0.16) / w, 0.16 / w
        self.gy, self.gh = view.rect[1] + 0.22 / h, view.rect[3] - 0.62 / h
        self.sx, self.sw = 0.10, 0.86 - GAUGE_W / w
        self.sy, self.sh = 0.16 / h, (STRIP_H - 0.24) / h
        self.x0, self.x1 = sorted(anim.xrange)

    def gauge_y(self, v: float) -> float:
        v = min(max(v, self.lo), self.hi)
        return self.gy + self.gh * (v - self.lo) / (self.hi - self.lo)

    def strip_xy(self, a, v):
        """Figure fractions of sweep value(s) ``a`` and effort(s) ``v`` [SI], clipped to the
        range."""
        span = self.hi - self.lo
        v = np.clip(v, self.lo, self.hi)
        x = self.sx + self.sw * (np.asarray(a, float) - self.x0) / max(self.x1 - self.x0,
                                                                        1e-300)
        y = self.sy + self.sh * (0.08 + 0.84 * (v - self.lo) / span)
        return x, y


def _static_decor(fig, anim, view: View, d) -> None:
    """What every frame shows alike: the arrow scale (top right), the gauge's frame and
    range, the effort over the sweep with the left-out angles (red)."""
    from matplotlib.lines import Line2D
    from matplotlib.patches import Rectangle
    p = _Places(anim, view)
    w, h = p.w, p.h
    _scale_note(fig, anim, view, d)
    kind, tf = anim.effort_kind, fig.transFigure
    fig.add_artist(Rectangle((p.gx, p.gy), p.gw, p.gh, transform=tf, fill=False, lw=0.8,
                             ec="0.3"))
    fig.text(p.gx + p.gw / 2, p.gy + p.gh + 0.05 / h, f"{anim.effort_symbol} [{d.unit(kind)}]",
             ha="center", va="bottom", fontsize=7)
    for value in (p.hi, p.lo):
        fig.text(p.gx - 0.03 / w, p.gauge_y(value), d.num(value, kind), ha="right",
                 va="center", fontsize=5.5, color="0.3")
    y = np.where(anim.near, np.nan, anim.effort)
    fig.add_artist(Line2D(*p.strip_xy(anim.angles, y), transform=tf, color="0.55", lw=0.8))
    fig.add_artist(Line2D(*p.strip_xy([p.x0, p.x1], [0.0, 0.0]), transform=tf, color="0.75",
                          lw=0.5))
    for a in anim.flagged:
        x, _ = p.strip_xy([a, a], [0.0, 0.0])
        fig.add_artist(Line2D(x, [p.sy, p.sy + p.sh], transform=tf, color=CUT_COLOR, lw=1.0))
    unit = anim.unit
    fig.text(p.sx, 0.06 / h, f"{anim.xrange[0]:g}{unit}", ha="center", va="bottom",
             fontsize=6)
    fig.text(p.sx + p.sw, 0.06 / h, f"{anim.xrange[1]:g}{unit}", ha="center", va="bottom",
             fontsize=6)
    what = f"{anim.effort_symbol} over the sweep" + ("; red: left out" if anim.flagged else "")
    fig.text(p.sx + p.sw / 2, 0.06 / h, what, ha="center", va="bottom", fontsize=6,
             color="0.35")


def _frame_decor(fig, anim, frame, view: View, d) -> None:
    """What changes from frame to frame beside the drawing: the note near a left-out angle,
    the gauge's bar and value, the frame's place on the sweep strip."""
    from matplotlib.lines import Line2D
    from matplotlib.patches import Rectangle
    p = _Places(anim, view)
    w, h, tf = p.w, p.h, fig.transFigure
    if frame.note:
        fig.text(0.95 / w, 1 - 0.04 / h, frame.note, ha="left", va="top", fontsize=6.5,
                 color=CUT_COLOR)
    z, v = p.gauge_y(0.0), p.gauge_y(frame.effort)
    fig.add_artist(Rectangle((p.gx, min(z, v)), p.gw, abs(v - z), transform=tf,
                             color=MOMENT_COLOR, lw=0))
    fig.add_artist(Line2D([p.gx - 0.03 / w, p.gx + p.gw + 0.03 / w], [z, z], transform=tf,
                          color="k", lw=0.8))
    off = not p.lo <= frame.effort <= p.hi
    fig.text(p.gx + p.gw / 2, p.gy - 0.05 / h, d.num(frame.effort, anim.effort_kind),
             ha="center", va="top", fontsize=7, fontweight="bold",
             color=CUT_COLOR if off else MOMENT_COLOR)
    x, y = p.strip_xy([frame.angle], [frame.effort])
    fig.add_artist(Line2D([x[0], x[0]], [p.sy, p.sy + p.sh], transform=tf,
                          color=MOMENT_COLOR, lw=0.8))
    fig.add_artist(Line2D(x, y, transform=tf, marker="o", ms=3.5, color=MOMENT_COLOR, lw=0))


def _key_entries(anim) -> list[tuple[str, str]]:
    """(label, colour) of each arrow the frames draw, once each, in scene order."""
    out: list[tuple[str, str]] = []
    for a in anim.frames[0].scene.arrows if anim.frames else ():
        entry = (a.label + (" (load)" if a.kind == "load" else ""), a.color)
        if entry not in out:
            out.append(entry)
    return out


def _key_rows(anim) -> int:
    n = len(_key_entries(anim))
    return math.ceil(n / max(1, int((FRAME_WIDTH - 0.2) / KEY_ENTRY))) if n else 0


def _key(fig, anim, view: View, d) -> None:
    """The frames' key (a GIF's frames carry no text on the drawing): each arrow's colour and
    symbol, in rows under the title."""
    from matplotlib.lines import Line2D
    entries = _key_entries(anim)
    if not entries:
        return
    handles = [Line2D([], [], color=c, lw=2, label=t) for t, c in entries]
    w, h = view.size
    fig.legend(handles=handles, loc="upper left", bbox_to_anchor=(0.0, 1 - 0.2 / h),
               ncols=math.ceil(len(handles) / _key_rows(anim)), fontsize=6, frameon=False,
               handlelength=1.2, handletextpad=0.4, columnspacing=0.8, borderaxespad=0.2,
               labelspacing=0.2)


def _scale_note(fig, anim, view: View, d) -> None:
    """A reference arrow with its force in the top-right corner: the one scale."""
    if view.scale <= 0:
        return
    w, h = view.size
    per_m = view.rect[2] * w / (view.hi[0] - view.lo[0])        # [in per m] of the drawing
    f_shown = d.value(anim.force_ref, "force")
    bar = _nice(f_shown)                   # 0.5 to 1 times the longest arrow
    length = bar / d.value(1.0, "force") * view.scale * per_m      # [in]
    x1 = 1 - 0.06 / w
    x0 = x1 - length / w
    y = 1 - 0.14 / h
    fig.add_artist(_arrow(fig, (x0, y), (x1, y), "k"))
    fig.text(x0 - 0.05 / w, y, f"{_fmt(bar)} {d.unit('force')} =", ha="right", va="center",
             fontsize=7)


def _fmt(x: float) -> str:
    return f"{x:g}" if x < 1e5 else f"{x:.0e}"


def _arrow(fig, a, b, color):
    from matplotlib.patches import FancyArrowPatch
    return FancyArrowPatch(a, b, transform=fig.transFigure, arrowstyle="-|>", color=color,
                           lw=1.2, mutation_scale=8, shrinkA=0, shrinkB=0)


def _away_range(anim) -> tuple[float, float]:
    """(low, high) of the driver's effort away from near-singular angles, 0 included."""
    e = anim.effort[~anim.near] if (~anim.near).any() else anim.effort
    e = e[np.isfinite(e)]
    lo, hi = (float(e.min()), float(e.max())) if e.size else (0.0, 0.0)
    lo, hi = min(lo, 0.0), max(hi, 0.0)
    if hi - lo <= 0:
        hi = lo + 1.0
    return lo, hi


def _rgba(fig) -> np.ndarray:
    """``fig`` rendered at DPI: (h, w, 4) uint8, straight alpha."""
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    canvas = fig.canvas if isinstance(fig.canvas, FigureCanvasAgg) else FigureCanvasAgg(fig)
    canvas.draw()
    return np.asarray(canvas.buffer_rgba())


@styled
def gif_bytes(anim, d) -> bytes:
    """``animation.gif`` of ``anim``: one frame per :class:`Frame`, every frame the same
    size, looping, ``anim.seconds`` each.

    What all frames share (the scale, the gauge's frame, the sweep strip) is rendered once;
    each frame draws its scene and its own marks into one reused transparent figure (the
    artists of a frame are removed after it), laid over that background."""
    from matplotlib.figure import Figure
    from PIL import Image
    view = view_of(anim)
    back = Figure(figsize=view.size, dpi=DPI)
    _static_decor(back, anim, view, d)
    _key(back, anim, view, d)
    bg = Image.fromarray(_rgba(back).copy())
    fig = Figure(figsize=view.size, dpi=DPI)
    fig.patch.set_alpha(0.0)
    ax = view_axes(fig, view)
    bare = replace(view, labels=False)
    images, palette = [], None
    draw = draw_scene.__wrapped__            # already in the report's style: not again
    for f in anim.frames:
        kept = (set(ax.get_children()), set(fig.get_children()))
        draw(f.scene, d, f.title, view=bare, ax=ax)
        _frame_decor(fig, anim, f, view, d)
        img = Image.alpha_composite(bg, Image.fromarray(_rgba(fig).copy())).convert("RGB")
        if palette is None:                  # the first frame's colours serve every frame
            palette = img.quantize(COLORS, method=Image.Quantize.FASTOCTREE, dither=0)
        images.append(img.quantize(palette=palette, dither=Image.Dither.NONE))
        for art in set(ax.get_children()) - kept[0]:
            art.remove()
        for art in set(fig.get_children()) - kept[1]:
            art.remove()
    buf = io.BytesIO()
    images[0].save(buf, format="GIF", save_all=True, append_images=images[1:], loop=0,
                   duration=round(anim.seconds * 1000), disposal=1)
    return buf.getvalue()


def write_animation(model, outdir: Path) -> list[Path]:
    """``animation.gif`` in ``outdir`` and the filmstrip's frames ``figures/frame_*.svg``
    (nothing when the model has no animation)."""
    anim = model.animation
    if anim is None:
        return []
    outdir = Path(outdir)
    out = [atomic_write_bytes(outdir / "animation.gif", gif_bytes(anim, model.display))]
    view = view_of(anim)
    for f, stem in zip(anim.strip, anim.strip_stems):
        out += save(draw_frame(anim, f, view, model.display), outdir / "figures", stem)
    return out
