"""Formatting of the report: numbers, relative differences, table cells, markdown tables."""
import math

def isnan(x):
    return x is None or (isinstance(x, float) and math.isnan(x))


def f3(x, nd=3):
    return "–" if isnan(x) else f"{x:.{nd}g}"


def on_ranks(r):
    """' on N ranks' for a run made on more than one MPI rank, else ''."""
    nr = int(r.s.get("ranks", 1) or 1)
    return f" on {nr} ranks" if nr > 1 else ""


def rel(x, ref):
    if isnan(x) or isnan(ref) or ref == 0:
        return float("nan")
    return 100.0 * (x / ref - 1.0)


def pct(x, nd=1):
    return "–" if isnan(x) else f"{x:+.{nd}f} %"


def cell(x, paper=None, exp=None, nd=3):
    """value (Δ paper, Δ experiment)."""
    if isnan(x):
        return "–"
    parts = []
    if paper is not None and not isnan(paper):
        parts.append(f"{pct(rel(x, paper))} p")
    if exp is not None and not isnan(exp):
        parts.append(f"{pct(rel(x, exp))} e")
    return f"{x:.{nd}g}" + (f" ({', '.join(parts)})" if parts else "")


def table(header, rows):
    out = ["| " + " | ".join(header) + " |", "|" + "---|" * len(header)]
    out += ["| " + " | ".join(str(c) for c in r) + " |" for r in rows]
    return "\n".join(out)


def mins(s):
    return "–" if isnan(s) else (f"{s:.0f} s" if s < 120 else f"{s / 60:.1f} min")



def img(rel_path, alt):
    return f"![{alt}]({rel_path})"
