#!/usr/bin/env pvpython
"""rigidflex-render: a PNG of a run's last frame coloured by effective (von Mises) stress.

    pvpython scripts/rigidflex-render.py DIR [-o PNG]     (or: xvfb-run -a pvpython ...)

Opens DIR/frames.pvd (the frame collection; DIR/d3plot.pvd, its older name, when that is all
there is), goes to the last frame and renders the mesh as it is in the file (the points are the
deformed positions: no warp), cells coloured by `effective_stress`, with a colour bar, into
DIR/plot_stress.png (or PNG). Runs headless: ParaView renders off screen where its build allows,
otherwise it needs an X display, which `xvfb-run -a` provides. Needs Debian's
python3-paraview (scripts/install-deps.sh).
"""

import argparse
import os
import sys


def main():
    parser = argparse.ArgumentParser(description="render the last frame of a RigidFlex run")
    parser.add_argument("directory")
    parser.add_argument("-o", "--output", help="PNG to write (default DIR/plot_stress.png)")
    parser.add_argument("--size", default="1200x800", help="image size WxH (default 1200x800)")
    args = parser.parse_args()
    collection = None
    for name in ("frames.pvd", "d3plot.pvd"):
        path = os.path.join(args.directory, name)
        if os.path.isfile(path):
            collection = path
            break
    if collection is None:
        print(f"rigidflex-render: no frames.pvd or d3plot.pvd in {args.directory}", file=sys.stderr)
        return 2
    output = args.output or os.path.join(args.directory, "plot_stress.png")
    width, height = (int(v) for v in args.size.lower().split("x"))

    from paraview import simple as pv  # imported late: --help works without ParaView

    reader = pv.PVDReader(FileName=collection)
    times = list(reader.TimestepValues) if reader.TimestepValues else [0.0]
    last = times[-1]
    view = pv.CreateView("RenderView")
    view.ViewSize = [width, height]
    view.OrientationAxesVisibility = 1
    view.Background = [1.0, 1.0, 1.0]
    try:  # ParaView 5.10+: the background colour is used only when asked for
        view.UseColorPaletteForBackground = 0
    except AttributeError:
        pass
    view.ViewTime = last
    reader.UpdatePipeline(last)
    display = pv.Show(reader, view)
    pv.ColorBy(display, ("CELLS", "effective_stress"))
    display.RescaleTransferFunctionToDataRange(False, True)
    display.SetScalarBarVisibility(view, True)
    bar = pv.GetScalarBar(pv.GetColorTransferFunction("effective_stress"), view)
    bar.Title = "effective stress"
    bar.ComponentTitle = ""
    bar.TitleColor = [0.0, 0.0, 0.0]
    bar.LabelColor = [0.0, 0.0, 0.0]
    view.ResetCamera()
    camera = view.GetActiveCamera()
    camera.Elevation(25.0)
    camera.Azimuth(35.0)
    view.ResetCamera()
    pv.Render(view)
    pv.SaveScreenshot(output, view, ImageResolution=[width, height])
    print(output)
    print(f"last frame: t = {last:g} of {os.path.abspath(collection)}")
    return 0


if __name__ == "__main__":
    status = main()
    # Leave without ParaView's teardown: under Xvfb (no GLX context sharing) it fails with
    # "GLXBadContext" after the picture is written and would turn success into status 1.
    sys.stdout.flush()
    sys.stderr.flush()
    os._exit(status)
