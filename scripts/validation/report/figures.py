"""The figures of the report (docs/figures/validation/): comparison plots made here, and the
figures of scripts/plot_collapse.py copied in; each PNG kept under 200 kB."""
import io
import os
import shutil

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from .runs import FIG_REL  # noqa: E402 (puts scripts/ on sys.path)
import figstyle  # noqa: E402
import plot_collapse as pc  # noqa: E402

MAX_PNG = 200 * 1024


def save_png(fig, path):
    fig.tight_layout()
    for dpi in (110, 90, 72, 60):
        fig.savefig(path, dpi=dpi)
        if os.path.getsize(path) <= MAX_PNG:
            break
    plt.close(fig)
    shrink_png(path)


def shrink_png(path):
    """Keep a PNG under 200 kB: palette quantisation, then downscaling."""
    if os.path.getsize(path) <= MAX_PNG:
        return
    from PIL import Image
    im = Image.open(path).convert("RGB")
    scale = 1.0
    while True:
        w, h = int(im.width * scale), int(im.height * scale)
        q = im.resize((w, h), Image.LANCZOS) if scale < 1 else im
        q = q.quantize(colors=128, method=Image.Quantize.MEDIANCUT)
        buf = io.BytesIO()
        q.save(buf, format="PNG", optimize=True)
        if buf.tell() <= MAX_PNG or scale < 0.3:
            open(path, "wb").write(buf.getvalue())
            return
        scale *= 0.8


def compare_plot(runs, labels, path, title, ref_lines, equal=False, xmax=None):
    """Front against t and final profiles of several runs, with reference runouts."""
    runs = [(r, lab) for r, lab in zip(runs, labels) if r.ok]
    if not runs:
        return False
    fig, axs = plt.subplots(2, 1, figsize=(9, 8.5))
    for r, lab in runs:
        d = r.diag
        axs[0].plot(d["t"], d["front_x"], lw=1.4, label=lab)
        x, h = r.final_profile()
        axs[1].plot(x, h, lw=1.4, label=f"{lab}, t = {r.prof['t'].max():.3g} s")
    for val, lab, col, *ls in ref_lines:
        ls = ls[0] if ls else "--"
        axs[0].axhline(val, color=col, ls=ls, lw=1.0, label=lab)
        axs[1].axvline(val, color=col, ls=ls, lw=1.0, label=lab)
    axs[0].set(xlabel="t (s)", ylabel="front x (m)")
    axs[1].set(xlabel="x (m)", ylabel="h (m), final")
    if xmax:
        axs[1].set_xlim(0, xmax)
    axs[1].set_ylim(bottom=0)
    if equal:
        axs[1].set_aspect("equal")
    for ax in axs:
        ax.grid(alpha=0.3)
        ax.legend(fontsize=7)
    fig.suptitle(title, fontsize=10)
    save_png(fig, path)
    return True


def lh_plot(run, fits, path):
    if not fits:
        return False
    fig, ax = plt.subplots(figsize=(6.5, 5))
    for c, f in fits.items():
        line, = ax.plot(f["Xall"], f["Yall"], "-", lw=0.6, alpha=0.5)
        ax.plot(f["X"], f["Y"], ".", ms=4, color=line.get_color(),
                label=f"cut-off {100 * c:g} % (dots: the decreasing branch, fitted)")
        xx = np.array([f["X"].min(), f["X"].max()])
        ax.plot(xx, f["slope"] * xx + f["intercept"], "-", color=line.get_color(), lw=1,
                label=f"fit: {f['slope']:.3f} x + {f['intercept']:.3f}, R² = {f['r2']:.3f}")
    ax.set(xlabel="L_d / L_f", ylabel="L_h / L_f")
    ax.grid(alpha=0.3)
    ax.legend(fontsize=7)
    ax.set_title(f"{run.name} ({run.grid}): sliding head against basal deposit, "
                 f"L_f = {fits[next(iter(fits))]['Lf']:.3f} m", fontsize=9)
    save_png(fig, path)
    return True


def collapse_figures(run, figs_dir, names):
    """The figures of scripts/plot_collapse.py for a run, drawn into runs/validation/_figures/<run>/
    (not into the run's folder, which may be someone else's: A128_DIR), the chosen ones copied
    to docs/figures/validation/<run>_<name>.png."""
    if not run.ok:
        return []
    src = os.path.join(os.path.dirname(run.dir), "_figures", run.name)
    stamp = os.path.join(src, "collapse_front.png")
    if not os.path.exists(stamp) or os.path.getmtime(stamp) < os.path.getmtime(
            os.path.join(run.dir, "summary.json")):
        os.makedirs(src, exist_ok=True)
        # 110 dpi, as the report's own figures: the copies stay under 200 kB.
        pc.draw_all(pc.Run(run.dir), figstyle.Output(src, dpi=110))
    out = []
    for n in names:
        p = os.path.join(src, f"collapse_{n}.png")
        if os.path.exists(p):
            dst = os.path.join(figs_dir, f"{run.name}_{n}.png")
            shutil.copyfile(p, dst)
            shrink_png(dst)
            out.append((n, f"{FIG_REL}/{run.name}_{n}.png"))
    return out
