"""ParaView view of a granflow run: the granular phase alone, coloured by |u| on a fixed range.

    pvpython scripts/paraview_granular.py OUTDIR [--field speed] [--vmax V] [--time T]
                                         [--screenshot FILE.png] [--size 1600x600]
    xvfb-run -a pvpython scripts/paraview_granular.py OUTDIR --screenshot a.png   (no display)
    GRANFLOW_RUN=OUTDIR paraview --script=scripts/paraview_granular.py    (in the ParaView GUI)

Opens OUTDIR/fields.pvd (the VTK series of `granflow run`), keeps the cells with phi < 0
(Threshold on the cell array phi between -1e30 and 0: the air, phi > 0, is dropped: its vortices
move faster than the grains and would own the colour scale), colours them by |u| (cell array
`speed`, or --field) with the Viridis map on a range fixed for the whole run, 0 to the largest
granular speed of diagnostics.csv (max_speed_granular, the granular cells outside the smeared
band) unless --vmax is given, and draws the interface phi = 0 as a black line (Contour of phi
after Cell Data to Point Data). The time slider then plays the run. With --screenshot it
renders the time nearest --time (default the last snapshot) into a PNG and exits. Debian's
ParaView renders through X (its `pvpython --force-offscreen-rendering` has no offscreen back-end
and crashes without a display): on a machine without one, run it under xvfb-run (package xvfb).

The same in the GUI by hand: open fields.pvd, Apply; Filters > Threshold, Scalars phi, lower
threshold -1e30, upper 0 (method "Between"), Apply; colour by speed; Edit color map >
"Rescale to custom range" 0 .. the run's max_speed_granular and untick automatic rescaling.
"""
import argparse
import os
import sys

from paraview.simple import (CellDatatoPointData, ColorBy, Contour, GetActiveViewOrCreate,
                             GetAnimationScene, GetColorTransferFunction, GetScalarBar, PVDReader,
                             Render, ResetCamera, SaveScreenshot, Show, Threshold)

HERE = os.path.dirname(os.path.abspath(__file__))


def run_vmax(folder, field):
    """The top of the colour scale: the run's largest granular speed (diagnostics.csv), read
    through granflow_run when numpy is there; None otherwise (then the data's own range)."""
    if field != "speed":
        return None
    try:
        sys.path.insert(0, HERE)
        import granflow_run as gr
        d = gr.Run(folder).diagnostics
        v = float(d["max_speed_granular"].max()) if d and "max_speed_granular" in d else 0.0
        return v if v > 0 else None
    except ImportError:
        return None


def parse_args():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("out", nargs="?", default=os.environ.get("GRANFLOW_RUN", "."),
                    metavar="OUTDIR", help="a granflow run folder (default $GRANFLOW_RUN or .)")
    ap.add_argument("--field", default="speed", help="cell array to colour by (speed)")
    ap.add_argument("--vmax", type=float, help="top of the colour scale")
    ap.add_argument("--time", type=float, help="time shown (s); default the last snapshot")
    ap.add_argument("--screenshot", metavar="FILE", help="render into FILE (PNG) and exit")
    ap.add_argument("--size", default="1600x600", help="screenshot size in pixels (WxH)")
    # Under `paraview --script` sys.argv holds ParaView's own arguments, not ours.
    a = ap.parse_args(sys.argv[1:] if os.path.basename(sys.argv[0]) != "paraview" else [])
    pvd = os.path.join(a.out, "fields.pvd")
    if not os.path.isfile(pvd):
        ap.error(f"{a.out}: no fields.pvd (not a granflow run folder, or output.vtk_interval = 0)")
    return a, pvd


def main():
    a, pvd = parse_args()
    reader = PVDReader(FileName=pvd)
    scene = GetAnimationScene()
    scene.UpdateAnimationUsingDataTimeSteps()
    times = list(reader.TimestepValues) or [0.0]

    granular = Threshold(Input=reader)
    granular.Scalars = ["CELLS", "phi"]
    if "ThresholdMethod" in granular.ListProperties():  # ParaView 5.10 and later
        granular.LowerThreshold, granular.UpperThreshold = -1e30, 0.0
        granular.ThresholdMethod = "Between"
    else:
        granular.ThresholdRange = [-1e30, 0.0]

    view = GetActiveViewOrCreate("RenderView")
    view.InteractionMode = "2D"
    view.OrientationAxesVisibility = 0
    shown = Show(granular, view)
    ColorBy(shown, ("CELLS", a.field))
    lut = GetColorTransferFunction(a.field)
    lut.ApplyPreset("Viridis (matplotlib)", True)
    vmax = a.vmax or run_vmax(a.out, a.field)
    if vmax is None:  # the data's range over every snapshot
        hi = 0.0
        for t in times:
            granular.UpdatePipeline(t)
            arr = granular.CellData[a.field]
            if arr is not None:
                hi = max(hi, arr.GetRange()[1])
        vmax = hi or 1.0
    lut.AutomaticRescaleRangeMode = "Never"  # fixed over the run: frames compare
    lut.RescaleTransferFunction(0.0, vmax)
    shown.SetScalarBarVisibility(view, True)
    bar = GetScalarBar(lut, view)
    bar.Title = "|u| (m/s)" if a.field == "speed" else a.field
    bar.ComponentTitle = ""
    bar.RangeLabelFormat = "%-#.3g"
    box = Show(reader, view)  # the domain's outline, for scale
    box.SetRepresentationType("Outline")
    ColorBy(box, None)
    box.AmbientColor = box.DiffuseColor = [0.6, 0.6, 0.6]

    points = CellDatatoPointData(Input=reader)
    interface = Contour(Input=points)
    interface.ContourBy = ["POINTS", "phi"]
    interface.Isosurfaces = [0.0]
    line = Show(interface, view)
    ColorBy(line, None)
    line.AmbientColor = line.DiffuseColor = [0.0, 0.0, 0.0]
    line.LineWidth = 2.0

    w, h = (int(x) for x in a.size.lower().split("x"))
    view.ViewSize = [w, h]  # a screenshot larger than the view would scale the fonts up
    t = times[-1] if a.time is None else min(times, key=lambda x: abs(x - a.time))
    scene.AnimationTime = t
    view.ViewTime = t
    ResetCamera(view)
    Render(view)
    if a.screenshot:
        SaveScreenshot(a.screenshot, view, ImageResolution=[w, h])
        print(f"paraview_granular: t = {t:g} s, {a.field} on [0, {vmax:.4g}], wrote {a.screenshot}")


if __name__ in ("__main__", "__vtkconsole__"):
    main()
