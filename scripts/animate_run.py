#!/usr/bin/python3
"""Animation of |u| in the granular phase of a granflow run, with the interface phi = 0.

usage: animate_run.py OUTDIR [--out FILE] [--format {mp4,gif}] [--fps N] [--vmax V] [--dpi N]

Reads the run's VTK series (fields.pvd, fields_*.vtr: one frame per snapshot, so
output.vtk_interval sets the smoothness; case A's 0.1 s gives 12 frames, 0.02 s a fluid
film) and draws the speed |u| where phi < 0 (the air, phi >= 0, is left white: its vortices
would own the colour scale), the zero level of phi in black, on a colour scale fixed over the
whole run (0 to the largest granular speed of all snapshots, or --vmax) so that frames compare.
Writes OUTDIR/figures/speed.mp4 with ffmpeg (Debian's ffmpeg package) when it is installed,
else OUTDIR/figures/speed.gif through Pillow (python3-pil, which matplotlib brings); --format
chooses, --out names the file (its extension is replaced by the format's).

Also `plot_run.py --animate OUTDIR`.
"""
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from matplotlib import animation  # noqa: E402
import numpy as np  # noqa: E402

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import figstyle  # noqa: E402
import granflow_run as gr  # noqa: E402


def region(run, first):
    """(xmax, ymax) shown, m: where the mass goes for a collapse, else the whole domain."""
    if run.profiles and "front_x" in run.diagnostics:
        import plot_collapse
        return plot_collapse.shown_region(run)
    return first.xn[-1], first.yn[-1]


def writer_for(fmt, fps):
    """(matplotlib writer, file extension): MP4 through ffmpeg if asked for or available,
    else a GIF through Pillow."""
    has_ffmpeg = animation.FFMpegWriter.isAvailable()
    if fmt == "mp4" and not has_ffmpeg:
        raise RuntimeError("--format mp4 needs ffmpeg (apt-get install ffmpeg); --format gif "
                           "needs nothing more")
    if fmt == "mp4" or (fmt is None and has_ffmpeg):
        return animation.FFMpegWriter(fps=fps, codec="libx264", extra_args=["-pix_fmt",
                                                                            "yuv420p"]), "mp4"
    return animation.PillowWriter(fps=fps), "gif"


def main(folder, out=None, fmt=None, fps=None, vmax=None, dpi=120):
    """Writes the animation of run `folder`; returns its path."""
    run = gr.Run(folder)
    snaps = run.snapshots
    if len(snaps) < 2:
        raise LookupError(f"{folder}: {len(snaps)} VTK snapshot(s) in fields.pvd, an animation "
                          "needs two or more (set output.vtk_interval)")
    first = run.fields(index=0)
    if vmax is None:  # one scale for the whole run: the largest granular speed of any frame
        vmax = max(float(run.fields(index=k).granular("speed").max() or 0.0)
                   for k in range(len(snaps)))
    vmax = vmax if vmax > 0 else 1.0
    norm = matplotlib.colors.Normalize(0.0, vmax)
    xmax, ymax = region(run, first)
    fps = fps or max(2, min(12, round(len(snaps) / 5)))
    writer, ext = writer_for(fmt, fps)
    path = os.path.splitext(out or os.path.join(run.path("figures"), "speed"))[0] + "." + ext
    os.makedirs(os.path.dirname(os.path.abspath(path)), exist_ok=True)

    width = 8.0
    fig, ax = plt.subplots(figsize=(width, max(2.5, width * ymax / xmax + 1.3)),
                           layout="constrained")
    fig.colorbar(matplotlib.cm.ScalarMappable(norm=norm, cmap="viridis"), ax=ax, shrink=0.85,
                 label="|u| (m/s) where phi < 0 (the granular phase)")
    title = figstyle.wrap(f"{run.title} ({run.grid})", width * 0.8, 9)

    def frame(k):
        f = run.fields(index=k)
        ax.clear()
        ax.pcolormesh(f.xn, f.yn, f.granular("speed"), norm=norm, cmap="viridis",
                      shading="flat")
        if np.nanmin(f["phi"]) < 0 < np.nanmax(f["phi"]):
            ax.contour(f.xc, f.yc, f["phi"], levels=[0], colors="k", linewidths=0.8)
        ax.set_xlim(0, xmax)
        ax.set_ylim(0, ymax)
        ax.set_aspect("equal")
        ax.set_xlabel("x (m)")
        ax.set_ylabel("y (m)")
        ax.set_title(f"{title}\nt = {f.t:.3f} s", fontsize=9)

    anim = animation.FuncAnimation(fig, frame, frames=len(snaps), interval=1000 / fps)
    anim.save(path, writer=writer, dpi=dpi)
    plt.close(fig)
    return path


def parse_args(argv=None):
    ap = figstyle.parser(__doc__)
    ap.add_argument("out_dir", metavar="OUTDIR", help="a granflow run folder with a VTK series")
    ap.add_argument("--out", metavar="FILE", help="the animation (OUTDIR/figures/speed.EXT)")
    ap.add_argument("--format", choices=("mp4", "gif"),
                    help="mp4 (needs ffmpeg) or gif; default mp4 if ffmpeg is there, else gif")
    ap.add_argument("--fps", type=int, help="frames per second (default: about 5 s in all)")
    ap.add_argument("--vmax", type=float, help="top of the colour scale (m/s)")
    ap.add_argument("--dpi", type=int, default=120, help="resolution of the frames (120)")
    a = ap.parse_args(argv)
    if not os.path.isfile(os.path.join(a.out_dir, "fields.pvd")):
        ap.error(f"{a.out_dir}: no fields.pvd (not a granflow run folder, or a run made with "
                 "output.vtk_interval = 0)")
    for name in ("fps", "dpi"):
        if getattr(a, name) is not None and getattr(a, name) <= 0:
            ap.error(f"--{name} must be positive")
    return a


if __name__ == "__main__":
    a = parse_args()
    try:
        print(f"animate_run: wrote {main(a.out_dir, a.out, a.format, a.fps, a.vmax, a.dpi)}")
    except (RuntimeError, LookupError, gr.RunFileError, OSError) as e:
        sys.exit(f"animate_run.py: {e}")
