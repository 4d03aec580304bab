"""The pieces of docs/reproduction.md (scripts/reproduction_report.py): numbers with error
bars, tables that render to Markdown and to results.json from the same cells, sections that
wrap the hand-written text around the generated parts, and the figures' files."""
import math
import os

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from PIL import Image  # noqa: E402  (python3-pil, a dependency of python3-matplotlib)

from campaign_data import Measured, finite_or_none  # noqa: E402

FIGURE_DPI = 100
PALETTE_COLOURS = 128
VERDICT_MARKERS = ("Verdict:", "**Verdict")


# ---- Numbers ---------------------------------------------------------------------------------
def format_number(x, digits=4):
    if x is None or not math.isfinite(x):
        return "–"
    return f"{x:.{digits}g}"


def format_measured(m):
    """'v ± e' (e to two significant digits); '–' for the error of a single seed."""
    if not math.isfinite(m.value):
        return "–"
    return f"{format_number(m.value)} ± {format_number(m.error, 2)}"


def escape(text):
    """Markdown-safe: '*' (mu*, eta*) would start emphasis and '|' would split a table cell."""
    return text.replace("*", "\\*").replace("|", "\\|")


def cell_markdown(cell):
    if isinstance(cell, Measured):
        return format_measured(cell)
    if isinstance(cell, float):
        return format_number(cell)
    return "–" if cell is None else escape(str(cell))


def cell_json(cell):
    if isinstance(cell, Measured):
        return cell.json()
    if isinstance(cell, float):
        return finite_or_none(cell)
    return cell


class Table:
    """Rows of cells (Measured, float, int, str) under named columns."""

    def __init__(self, name, columns, caption=""):
        self.name, self.columns, self.caption = name, list(columns), caption
        self.rows = []

    def add(self, *cells):
        assert len(cells) == len(self.columns), (self.name, cells)
        self.rows.append(list(cells))

    def markdown(self):
        lines = [f"*{escape(self.caption)}*", ""] if self.caption else []
        lines.append("| " + " | ".join(escape(c) for c in self.columns) + " |")
        lines.append("|" + "---|" * len(self.columns))
        lines += ["| " + " | ".join(cell_markdown(c) for c in row) + " |" for row in self.rows]
        return "\n".join(lines)

    def json(self):
        return [{col: cell_json(c) for col, c in zip(self.columns, row)} for row in self.rows]


# ---- Hand-written text -----------------------------------------------------------------------
def read_text(text_dir, name):
    """The text file <name>.md split at its verdict line: (before, from the verdict on). A
    missing file gives a placeholder that says where to write it."""
    path = os.path.join(text_dir, f"{name}.md")
    if not os.path.isfile(path):
        return f"*(No text yet: write `docs/reproduction/text/{name}.md`.)*", ""
    with open(path, encoding="utf-8") as f:
        lines = f.read().rstrip("\n").split("\n")
    for k, line in enumerate(lines):
        if line.lstrip().startswith(VERDICT_MARKERS):
            return "\n".join(lines[:k]).rstrip(), "\n".join(lines[k:])
    return "\n".join(lines), ""


def verdict_line(after_text):
    """The verdict's first paragraph on one line, for the closing summary."""
    if not after_text:
        return "Verdict: (none written)"
    return " ".join(after_text.split("\n\n", 1)[0].split())


# ---- Sections --------------------------------------------------------------------------------
class Section:
    """One result id: the text before the verdict, what was run, figures, tables and generated
    comparison lines, then the verdict and what follows it in the text file."""

    def __init__(self, result_id, title, text_dir):
        self.id, self.title = result_id, title
        self.before, self.after = read_text(text_dir, result_id)
        self.blocks = []
        self.results = {}

    def add(self, markdown):
        self.blocks.append(markdown)

    def add_table(self, table):
        self.blocks.append(table.markdown())
        self.results.setdefault("tables", {})[table.name] = table.json()

    def add_figure(self, relative_path, caption):
        self.blocks.append(f"![{self.id}: {escape(caption)}]({relative_path})\n\n"
                           f"*{escape(caption)}*")

    def compare(self, text):
        """A generated comparison line (numbers the verdict rests on)."""
        self.blocks.append(f"Generated comparison: {escape(text)}")

    def markdown(self):
        parts = [f"## {self.id}: {escape(self.title)}", self.before, *self.blocks]
        if self.after:
            parts.append(self.after)
        return "\n\n".join(p for p in parts if p)


# ---- Figures ---------------------------------------------------------------------------------
class Figures:
    """Saves figures as DOCS_DIR/reproduction/<name>.png; returns the path relative to DOCS_DIR
    for the Markdown link."""

    def __init__(self, docs_dir):
        self.docs_dir = docs_dir
        self.directory = os.path.join(docs_dir, "reproduction")
        os.makedirs(self.directory, exist_ok=True)
        self.written = set()

    def remove_stale(self):
        """Deletes the PNGs of an earlier report that this one did not draw (a section that
        lost its data), so the directory holds exactly the figures the report links."""
        for name in sorted(os.listdir(self.directory)):
            if name.endswith(".png") and name not in self.written:
                os.remove(os.path.join(self.directory, name))

    def save(self, fig, name):
        fig.tight_layout()
        fig.set_dpi(FIGURE_DPI)
        fig.canvas.draw()
        image = Image.fromarray(np.asarray(fig.canvas.buffer_rgba())).convert("RGB")
        plt.close(fig)
        # A palette of 128 colours: line plots need no more, and the PNG shrinks about 3x.
        small = image.quantize(colors=PALETTE_COLOURS, method=Image.Quantize.MEDIANCUT)
        path = os.path.join(self.directory, f"{name}.png")
        small.save(path, optimize=True)
        self.written.add(os.path.basename(path))
        return os.path.relpath(path, self.docs_dir)
