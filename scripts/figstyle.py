"""What the figures of plot_run.py, plot_collapse.py and animate_run.py share: the output
resolution and formats, and titles wrapped to the figure's width so that none is cut.

PNG at 200 dpi, always; with `formats` ("pdf", "svg") a vector copy of each figure beside it,
with its text kept as text (TrueType in PDF, <text> in SVG) so that a journal's editor or
Inkscape can change a label without redrawing.
"""
import os
import textwrap

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

DPI = 200
VECTOR_FORMATS = ("pdf", "svg")
matplotlib.rcParams.update({"pdf.fonttype": 42, "ps.fonttype": 42, "svg.fonttype": "none"})


class Output:
    """Where the figures go (folder), at what resolution (dpi) and in which extra formats."""

    def __init__(self, folder, dpi=DPI, formats=()):
        bad = [f for f in formats if f not in VECTOR_FORMATS]
        if bad:
            raise ValueError(f"unknown figure format(s) {bad}: {', '.join(VECTOR_FORMATS)}")
        self.folder, self.dpi, self.formats = folder, dpi, tuple(formats)

    def path(self, name):
        return os.path.join(self.folder, name)

    def save(self, fig, name, tight=True):
        """Writes NAME (a .png name) and its vector copies, and closes the figure."""
        os.makedirs(self.folder, exist_ok=True)
        if tight:
            fig.tight_layout()
        fig.savefig(self.path(name), dpi=self.dpi)
        stem = os.path.splitext(name)[0]
        for ext in self.formats:
            fig.savefig(self.path(f"{stem}.{ext}"))
        plt.close(fig)


def parser(doc):
    """The command line of a figure script, its help from the script's docstring: the first
    line as description, what follows the usage paragraph as epilog."""
    import argparse
    return argparse.ArgumentParser(description=doc.split("\n")[0],
                                   epilog=doc.split("\n\n", 2)[2],
                                   formatter_class=argparse.RawDescriptionHelpFormatter)


def formats_arg(text):
    """argparse type of --format: "pdf", "svg" or "pdf,svg"."""
    import argparse
    out = [f.strip().lower() for f in text.split(",") if f.strip()]
    bad = [f for f in out if f not in VECTOR_FORMATS]
    if bad or not out:
        raise argparse.ArgumentTypeError(f"{text!r}: the vector formats are "
                                         f"{', '.join(VECTOR_FORMATS)} (PNG is always written)")
    return out


def add_arguments(ap):
    """The options of the figure scripts: --format, --dpi."""
    ap.add_argument("--format", type=formats_arg, default=[], metavar="pdf|svg|pdf,svg",
                    help="also write each figure as PDF and/or SVG (text kept as text)")
    ap.add_argument("--dpi", type=int, default=DPI, help=f"PNG resolution ({DPI})")


def check_arguments(ap, a):
    if a.dpi <= 0:
        ap.error("--dpi must be positive")


def wrap(text, width_in, fontsize):
    """`text` broken into lines that fit `width_in` inches at `fontsize` points (a character
    of DejaVu Sans is about half the font size wide on average)."""
    chars = max(20, int(width_in * 72 / (0.5 * fontsize)))
    return "\n".join(textwrap.fill(part, chars) for part in text.split("\n"))


def suptitle(fig, text, fontsize=9):
    """A figure title wrapped to the figure's width."""
    fig.suptitle(wrap(text, 0.95 * fig.get_figwidth(), fontsize), fontsize=fontsize)


def title(ax, text, fontsize=9):
    """An axes title wrapped to the axes' width."""
    w = ax.get_position().width * ax.figure.get_figwidth()
    ax.set_title(wrap(text, w, fontsize), fontsize=fontsize)
