"""Picture of a SPHERIC Test 2 run (cases/spheric2_dam_break_box.case): the
fluid coloured by pressure (0-6 kPa, about rho0 g H), the box's wall
particles grey, the tank's walls and lid left out (they would hide the
water), the tank outlined; a camera above the near corner behind the box.

    xvfb-run -a pvpython --disable-xdisplay-test paraview/spheric2_picture.py RUN_DIR TIME OUTPUT.png

(paraview/spheric2_dam_break_box.pvsm is the interactive view, cut open like
dam_break_3d.pvsm; there the box is grey against the grey back wall.)
"""
import glob, os, sys
import paraview.simple
from paraview.simple import *
run, t, out = sys.argv[1], float(sys.argv[2]), sys.argv[3]
paraview.simple._DisableFirstRenderCameraReset()
pvd = glob.glob(os.path.join(run, "*.pvd"))[0]
r = PVDReader(FileName=pvd)
r.UpdatePipelineInformation()
times = r.TimestepValues
t = min(times, key=lambda s: abs(s - t))
fluid = Threshold(Input=r, Scalars=["POINTS", "kind"], LowerThreshold=-0.5, UpperThreshold=0.5)
box = Clip(Input=Threshold(Input=r, Scalars=["POINTS", "kind"], LowerThreshold=0.5, UpperThreshold=1.5),
           ClipType="Box", Crinkleclip=1, Exact=1)
box.ClipType.Position = [0.6, 0.25, -0.001]   # around the box, inside the tank's walls
box.ClipType.Length = [0.3, 0.5, 0.2]
box.Invert = 1
v = CreateRenderView()
v.ViewSize = [960, 480]
v.Background = [1, 1, 1]
try:
    v.UseColorPaletteForBackground = 0
except AttributeError:
    pass
v.OrientationAxesVisibility = 0
v.ViewTime = t
fd = Show(fluid, v)
fd.SetRepresentationType("Point Gaussian")
fd.GaussianRadius = 0.025
fd.ShaderPreset = "Sphere"
ColorBy(fd, ("POINTS", "pressure"))
lut = GetColorTransferFunction("pressure")
lut.ApplyPreset("Turbo", True)
lut.AutomaticRescaleRangeMode = "Never"
lut.RescaleTransferFunction(0, 6000)
bar = GetScalarBar(lut, v)
bar.Title = "pressure [Pa]"
bar.ComponentTitle = ""
bar.TitleColor = bar.LabelColor = [0, 0, 0]
bar.Visibility = 1
bd = Show(box, v)
bd.SetRepresentationType("Point Gaussian")
bd.GaussianRadius = 0.025
bd.ShaderPreset = "Sphere"
ColorBy(bd, None)
bd.AmbientColor = bd.DiffuseColor = [0.6, 0.6, 0.6]
lo, hi = [0.0, 0.0, 0.0], [3.25, 1.0, 1.0]
outline = Box(XLength=hi[0] - lo[0], YLength=hi[1] - lo[1], ZLength=hi[2] - lo[2],
              Center=[(a + b) / 2 for a, b in zip(lo, hi)])
od = Show(outline, v)
od.SetRepresentationType("Outline")
od.AmbientColor = od.DiffuseColor = [0.3, 0.3, 0.3]
txt = Text(Text="SPHERIC Test 2, t = %.2f s" % t)
td = Show(txt, v)
td.Color = [0, 0, 0]
td.FontSize = 14
td.WindowLocation = "Upper Left Corner"
cam = v.GetActiveCamera()
cam.SetFocalPoint(1.55, 0.5, 0.3)
cam.SetPosition(0.2, -2.9, 2.3)
cam.SetViewUp(0, 0, 1)
v.CameraParallelProjection = 0
cam.SetViewAngle(30)
Render(v)
SaveScreenshot(out, v, ImageResolution=[960, 480])
print("wrote", out, "t =", t)
