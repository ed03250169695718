"""Draw the last frame of a granmpm run in ParaView, points coloured by pressure.

    pvpython pressure.py RUNDIR OUT.png
    xvfb-run -a pvpython pressure.py RUNDIR OUT.png     (without a display)

Opens RUNDIR/run.xdmf (docs/output.md), goes to its last time, shows the
points coloured by the point array p with a colour bar and the time, and
saves a PNG: a plane run seen along z, a 3D run from an oblique angle.
A run with rigid bodies shows them too, from RUNDIR/bodies.xdmf: their
outlines in the plane, their surfaces half transparent in 3D.
Prints one line: the time, the number of points and their pressure range.
"""
import os
import sys

from paraview.simple import (ColorBy, CreateView, GetColorTransferFunction, GetScalarBar,
                             Render, SaveScreenshot, Show, Text, Xdmf3ReaderS)

run, png = sys.argv[1], sys.argv[2]
reader = Xdmf3ReaderS(FileName=[run + "/run.xdmf"])
times = reader.TimestepValues                   # one time per frame with points
t = times[-1] if hasattr(times, "__len__") else times

view = CreateView("RenderView")
view.ViewSize = [1200, 700]
view.ViewTime = t
view.OrientationAxesVisibility = 1
view.Background = [1, 1, 1]
view.UseColorPaletteForBackground = 0

points = Show(reader, view)
points.SetRepresentationType("Points")
points.PointSize = 4
ColorBy(points, ("POINTS", "p"))
points.RescaleTransferFunctionToDataRange(True, False)
lut = GetColorTransferFunction("p")
lut.ApplyPreset("Viridis (matplotlib)", True)
bar = GetScalarBar(lut, view)
bar.Title = "pressure p (Pa)"
bar.ComponentTitle = ""
bar.TitleColor = bar.LabelColor = [0, 0, 0]
points.SetScalarBarVisibility(view, True)

if os.path.exists(run + "/bodies.xdmf"):
    bodies = Show(Xdmf3ReaderS(FileName=[run + "/bodies.xdmf"]), view)
    bodies.SetRepresentationType("Surface")
    ColorBy(bodies, None)
    bodies.AmbientColor = bodies.DiffuseColor = [0.15, 0.15, 0.15]
    bodies.LineWidth = 3

label = Text(Text="%s: t = %.4g s" % (os.path.basename(os.path.abspath(run)), t))
shown = Show(label, view)
shown.Color = [0, 0, 0]
shown.WindowLocation = "Upper Center"

Render(view)                          # the first render resets the camera: set it after
info = reader.GetDataInformation()
x0, x1, y0, y1, z0, z1 = info.GetBounds()
cx, cy, cz = (x0 + x1) / 2, (y0 + y1) / 2, (z0 + z1) / 2
view.CameraViewUp = [0, 1, 0]
view.CameraParallelProjection = 1
if z1 > z0:      # 3D: from the front, right and above, the whole cloud in view
    view.CameraFocalPoint = [cx, cy, cz]
    view.CameraPosition = [cx + 0.6, cy + 0.5, cz + 1.0]
    view.ResetCamera()
    points.PointSize = 6
    if os.path.exists(run + "/bodies.xdmf"):
        bodies.Opacity = 0.4          # the material behind a body stays in view
else:            # plane: along z, the points on 75 % of the width, left of the colour bar
    scale = max(0.6 * (y1 - y0), (x1 - x0) / 0.75 / 2 * 700 / 1200)
    cx += 0.06 * 2 * scale * 1200 / 700
    view.CameraFocalPoint = [cx, cy, 0]
    view.CameraPosition = [cx, cy, 1]
    view.CameraParallelScale = scale
    if os.path.exists(run + "/bodies.xdmf"):
        bodies.Position = [0, 0, 1e-3 * scale]   # drawn over the points at a wall
Render(view)
SaveScreenshot(png, view, ImageResolution=[1200, 700])

p = info.GetPointDataInformation().GetArrayInformation("p").GetComponentRange(0)
print("t %.17g s: %d points, p %.17g to %.17g Pa" % (t, info.GetNumberOfPoints(), p[0], p[1]))
