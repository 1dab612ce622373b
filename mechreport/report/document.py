"""The one document model of every human-readable output: the report, the solution and
problem sheets, the batch index and the study report are each a :class:`Doc` (a title and a
list of blocks) built in Python from their models (:mod:`.report_doc`, :mod:`.sheet.solution_doc`,
:mod:`.sheet.problem_doc`, :mod:`.index_doc`, :mod:`mechreport.study.report`) and written out
by one writer per format (:mod:`.write_markdown`, :mod:`.write_typst`), so the formats say the
same thing. The model holds text as given: each writer escapes it with its format's one
escaper. A writer is a function of a document to a string that dispatches on the classes below.

Inline text is a string (plain text), a run, or a list of strings and runs. Runs:
:class:`Code`, :class:`Strong`, :class:`Emph`, :class:`Link`, :class:`Ref` (to a heading),
:class:`Math` (a sheet's atom, expression or equation: TeX in Markdown, Typst math in print),
:class:`Number`, :class:`Key` (a spec's quantity name), :class:`Aside` (a cell's secondary
line), :class:`Verdict` (a PASS / FAIL badge), :class:`NewLine`, :class:`Wording` (the
program's own words, written as they stand in Markdown).

Blocks: :class:`Heading`, :class:`Paragraph`, :class:`Items` (with :class:`Item`),
:class:`Table` (cells inline, :class:`Cell` spanning, :class:`Blank`), :class:`Figure`,
:class:`Figures`, :class:`Equation`, :class:`Found`, :class:`Columns`, :class:`Box`,
:class:`Pairs`, :class:`Description` (the user's Markdown), :class:`Space` and :class:`Gap`
(vertical space in print, an empty line in Markdown). No PDF needs a forced page break.

Print-only hints (page setup, table rules and widths) are in :class:`Layout` and
:class:`Print`: the text formats ignore them. Where a PDF and a Markdown file say a thing
differently on purpose, :class:`Either` (inline) and :class:`Only` (blocks) hold both."""
from __future__ import annotations

import re
from dataclasses import dataclass, field

# ----------------------------------------------------------------------------- inline runs


@dataclass(frozen=True)
class Code:
    """Monospace text (a file name, a key)."""
    text: str


@dataclass(frozen=True)
class Strong:
    text: str


@dataclass(frozen=True)
class Emph:
    text: str


@dataclass(frozen=True)
class Link:
    """``text`` linking to the relative file ``target``."""
    text: str
    target: str


@dataclass(frozen=True)
class Math:
    """Inline math: an atom, expression or equation of :mod:`.sheet.expr`, or a list of them."""
    value: object


@dataclass(frozen=True)
class Aside:
    """A table cell's secondary text (a name's file): after it in parentheses where lines
    cannot break, on a small line of its own in print."""
    text: str


@dataclass(frozen=True)
class Verdict:
    """A check's verdict (``PASS`` or ``FAIL``) as a badge, and what it says (may be empty):
    ``PASS``, ``FAIL: detail``."""
    status: str
    detail: str = ""

    @property
    def passed(self) -> bool:
        return self.status == "PASS"


@dataclass(frozen=True)
class Wording:
    """The program's own wording (never user text) written as it stands in Markdown, where
    the escaper would add backslashes it does not need (``points [m]``), and escaped in print
    but for its apostrophes (set as typographic ones, ``report’s``)."""
    text: str


@dataclass(frozen=True)
class Number:
    """A number as the program wrote it (``-15925.1``, ``3.4 N``): print sets its leading
    minus as a minus sign."""
    text: str


@dataclass(frozen=True)
class NewLine:
    """A line break inside a paragraph (a soft one in Markdown, a forced one in print, or a
    soft one there too where not ``hard``)."""
    hard: bool = True


@dataclass(frozen=True)
class Key:
    """A name to write in a spec (``cycle.torque.rms``) beside what it means: code, small
    and grey in print."""
    text: str


@dataclass(frozen=True)
class Ref:
    """``text`` linking to a heading of this document (its Markdown ``anchor``); plain text
    in print, which numbers its headings instead."""
    text: str
    anchor: str


def heading_id(text: str) -> str:
    """The anchor GitHub gives a heading of ``text`` (a :class:`Ref`'s ``anchor``; report.md's
    and report.html's ids)."""
    return re.sub(r"[^a-z0-9 _-]", "", text.lower()).replace(" ", "-")


Inline = object   # str | run | list[str | run]


def rich(segments) -> list:
    """A sheet's rich text (strings and math atoms) as inline runs."""
    return [s if isinstance(s, str) else Math(s) for s in segments]


def runs(inline) -> list:
    """``inline`` as a list of strings and runs."""
    if isinstance(inline, (list, tuple)) and not isinstance(inline, Math):
        return list(inline)
    return [inline]


# ---------------------------------------------------------------------------------- blocks


@dataclass(frozen=True)
class Print:
    """How print lays a table out (the text formats ignore it). ``widths``: the columns'
    relative widths (``None``: as wide as their content); ``max_columns``: a wider table is
    split into parts of that many columns that repeat the leading ``lead`` ones; ``wrap``:
    header cells may break after dots and underscores (long key paths); ``inset``: the
    cells' padding (pt: vertical in a ruled table; all round in a grid), ``inset_x`` across
    in a ruled table; ``grid``: ruled cells (a data sheet's table) rather than rules above
    and below and shaded rows; ``size``: its text size (pt); ``right``: the right-aligned
    columns in print where they differ from the table's; ``keep``: a table of up to 30 rows
    is never split across pages (a longer one breaks between rows and repeats its header)."""
    widths: tuple | None = None
    max_columns: int | None = None
    lead: int = 1
    wrap: bool = False
    inset: float = 2.5
    grid: bool = False
    size: float | None = None
    right: frozenset | None = None
    keep: bool = False
    inset_x: float = 4


@dataclass
class Blank:
    """An empty cell of a total row (one blank between the bars in Markdown)."""


@dataclass
class Cell:
    """A table cell that spans ``span`` columns in print; where cells cannot span, ``span - 1``
    cells of ``fill`` come first. ``small``: in small print (a long message)."""
    text: object
    span: int = 1
    fill: str = "—"
    small: bool = False


@dataclass
class Heading:
    text: object
    level: int = 2


@dataclass
class Paragraph:
    """A paragraph of inline text; ``small``: in small print (a side note: ``True``, or its
    size in pt)."""
    text: object
    small: object = False
    tight: bool = False     # Markdown: no empty line after it (as the report has had)


@dataclass
class Items:
    """A bullet list (or a numbered one) of inline texts (or :class:`Item`); ``intro``: the
    line that introduces it (``Loads:``), kept close above it in print."""
    items: list
    ordered: bool = False
    intro: object = None
    small: bool = False


@dataclass
class Item:
    """A list item with a list of its own (``sub``: inline texts)."""
    text: object
    sub: list = field(default_factory=list)


@dataclass
class Table:
    """A table of inline cells (or :class:`Cell`) with a header; ``right``: the indices of the
    right-aligned columns; ``note``: small text under it."""
    header: list
    rows: list
    right: set = field(default_factory=set)
    note: object = ""
    print: Print = field(default_factory=Print)
    header_blank: bool = False    # Markdown: the header row ends with a blank (as it has)


@dataclass
class Figure:
    """An image file (relative to the document) and its caption. ``alt``: the image's text
    where it differs from the caption; ``caption_below``: the text formats, whose images show
    no caption, repeat it under the image; ``width`` (a fraction of the line) or ``height``
    (inches): its size in print."""
    path: str
    caption: object
    alt: object = None
    caption_below: bool = False
    width: float = 1.0
    height: float | None = None


@dataclass
class Only:
    """Blocks for print only (``print``) or for the text formats only: where a PDF and a
    Markdown file serve their readers differently (a contents list of links, an animation
    shown as frames)."""
    blocks: list
    print: bool


@dataclass
class Space:
    """Vertical space before a block in print (em); nothing in the text formats."""
    em: float = 1


@dataclass
class Box:
    """Blocks set off in a box in print, tinted by ``tone`` (``PASS``: green, else red); as
    they are in the text formats."""
    blocks: list
    tone: str = "PASS"


@dataclass
class Pairs:
    """Label and value rows (traceability): a table without a header in Markdown, a compact
    grid in print; ``text_rows``: rows only the text formats show (links to sibling files)."""
    rows: list
    text_rows: list = field(default_factory=list)


@dataclass
class Figures:
    """Figures side by side (``columns`` to a row in print; one line of images in Markdown)."""
    figures: list
    columns: int = 3


@dataclass
class Equation:
    """Display math (an equation of :mod:`.sheet.expr`); with a ``number``, and with
    ``numeric``, the same equation with the numbers put in, under it."""
    value: object
    number: int | None = None
    numeric: object = None


@dataclass
class Found:
    """What a derivation found, set off as a result: ``label`` (``(1)–(3) give``; in print
    only where ``print_label``), the ``items`` (inline texts, separated by commas) and
    ``more`` (further statements, separated by semicolons); ``gap``: the space print adds
    after each comma (em)."""
    label: object
    items: list
    more: list = field(default_factory=list)
    print_label: bool = True
    gap: float = 0.5


@dataclass
class Columns:
    """Columns side by side in print, one after the other in the text formats: each a block
    or a list of blocks; ``widths``: their relative widths (``None``: as wide as their
    content); ``gutter``: the space between them (pt)."""
    blocks: list
    widths: tuple | None = None
    gutter: float = 10


@dataclass
class Gap:
    """An empty line in the text formats (kept where the Markdown has always had one)."""


@dataclass
class Description:
    """Markdown written by the user (a spec's description: its text, or a list of its
    paragraphs), kept as Markdown in Markdown and interpreted in print; never raw HTML."""
    markdown: object

    @property
    def paragraphs(self) -> list[str]:
        m = self.markdown
        return [m] if isinstance(m, str) else list(m)

    @property
    def text(self) -> str:
        return "\n\n".join(self.paragraphs)


@dataclass(frozen=True)
class Layout:
    """The page in print (the text formats ignore it): A4, ``landscape`` or not, ``margin``
    (cm: all sides; x and y; or x, top and bottom), the body ``size`` (pt), the
    ``title_size`` (pt), ``heading_sizes`` ((level, pt) pairs), the spacing around headings
    (em, ``None``: Typst's own), the ``leading`` of paragraphs and the ``spacing`` between
    them (em, ``None``: Typst's own); ``title_heading``: the title is a level-1 heading (a
    sheet's) rather than a line of large bold text; ``equations_left``: display equations
    flush left, tight and breakable (a sheet's derivations); ``justify``: justified
    paragraphs; ``numbered``: numbered headings (1.1); ``heading_shift``: print's heading
    levels are Markdown's less this (a report's title is no heading in print);
    ``level_spaces``: (print level, above, below) em; ``figures_whole``: figures never
    split, small captions; ``title_center``: a centred title block (with the document's
    subtitle and byline); ``header``: (left, right) text of the page header from page 2 on."""
    landscape: bool = False
    margin: tuple = (1.8, 1.8)
    justify: bool = False
    numbered: bool = False
    heading_shift: int = 0
    level_spaces: tuple = ()
    figures_whole: bool = False
    title_center: bool = False
    header: tuple | None = None
    size: float = 9
    title_size: float = 16
    heading_sizes: tuple = ((2, 11.5),)
    heading_space: tuple | None = (1.3, 0.7)
    leading: float | None = None
    spacing: float | None = None
    title_heading: bool = False
    equations_left: bool = False


@dataclass
class Doc:
    """A document: its title and its blocks, built in order by the methods below."""
    title: str
    blocks: list = field(default_factory=list)
    layout: Layout = field(default_factory=Layout)
    end_blank: bool = False     # Markdown: end with an empty line (the sheets always have)
    subtitle: str = ""          # under the title (bold in Markdown)
    byline: object = None       # print only: a line under the title (what and from where)
    author: str = ""            # the PDF's metadata

    def add(self, block) -> None:
        self.blocks.append(block)

    def h(self, text, level: int = 2) -> None:
        self.add(Heading(text, level))

    def p(self, *parts) -> None:
        self.add(Paragraph(list(parts)))

    def items(self, items: list, ordered: bool = False, intro=None) -> None:
        self.add(Items(items, ordered, intro))

    def table(self, header: list, rows: list, right=frozenset(), note="",
              print: Print | None = None) -> None:
        self.add(Table(header, rows, set(right), note, print or Print()))

    def image(self, path: str, caption, height: float | None = None, **how) -> None:
        self.add(Figure(path, caption, height=height, **how))


@dataclass(frozen=True)
class Either:
    """Where the formats say a thing differently on purpose: ``text`` in the text formats
    (Markdown, HTML), ``print`` in print (the PDF); each an inline text (may be empty). Kept
    for the few places a PDF leaves out what only a file browser can use (links to Markdown
    and CSV files)."""
    text: object
    print: object
