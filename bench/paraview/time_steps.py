"""ParaView's side of cloudvis-bench-viewer --time-steps: pvbatch opens FIELD.nc with ParaView's
own NetCDF (CF) reader as image data, draws its first variable `ql` as a volume (ParaView's
default volume mapper) in an 800 x 800 view, the size of `cloudvis view`'s 3D view, and prints,
for each of STEPS steps, the milliseconds of GoToNext() and the render after it: the time from
asking for the next step to seeing it.

Usage: pvbatch --force-offscreen-rendering time_steps.py FIELD.nc STEPS [LAST.png]
(LAST.png: the last step's picture, to look at)"""
import sys
import time

from paraview import simple

field, steps = sys.argv[1], int(sys.argv[2])
reader = simple.NetCDFReader(FileName=[field])
reader.Dimensions = "(zt, yt, xt)"
reader.SphericalCoordinates = 0
reader.OutputType = "Image"
view = simple.CreateView("RenderView")
view.ViewSize = [800, 800]
display = simple.Show(reader, view)
display.Representation = "Volume"
simple.ColorBy(display, ("POINTS", "ql"))
display.RescaleTransferFunctionToDataRange(True, False)
scene = simple.GetAnimationScene()
scene.UpdateAnimationUsingDataTimeSteps()
view.ResetCamera()
simple.Render(view)
for step in range(1, steps + 1):
    start = time.perf_counter()
    scene.AnimationTime = reader.TimestepValues[step]
    simple.Render(view)
    print("step %d: %.1f ms" % (step, 1000.0 * (time.perf_counter() - start)), flush=True)
if len(sys.argv) > 3:
    simple.SaveScreenshot(sys.argv[3], view)
