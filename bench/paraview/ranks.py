"""One rank count's figures for bench/paraview-ranks.sh: pvbatch --symmetric runs this on every
rank. It draws FIELD as a Cloud Volume with the march, turns the camera FRAMES times (each frame
marched anew: no accumulation) and prints, on rank 0, the mean milliseconds per frame, the first
frame's (which uploads the pieces and exchanges the optical depth), and every rank's peak resident
memory.

Usage: pvbatch --symmetric ranks.py PLUGIN FIELD.vti SCENE.json FRAMES"""
import json
import sys
import time

from paraview import servermanager, simple
from paraview.modules.vtkRemotingCore import vtkProcessModule

plugin, field, scene_path, frames = sys.argv[1], sys.argv[2], sys.argv[3], int(sys.argv[4])
simple.LoadPlugin(plugin, remote=False, ns=vars(simple))
with open(scene_path) as f:
    scene = json.load(f)
controller = vtkProcessModule.GetProcessModule().GetGlobalController()
rank, ranks = controller.GetLocalProcessId(), controller.GetNumberOfProcesses()

reader = simple.XMLImageDataReader(FileName=[field])
view = simple.CreateView("RenderView")
view.ViewSize = scene["render"]["size"]
view.OrientationAxesVisibility = 0
display = simple.Show(reader, view)
display.SetRepresentationType("Cloud Volume")
simple.ColorBy(display, ("POINTS", "density"))
transfer = scene["transfer_function"]
lut = simple.GetColorTransferFunction("density")
lut.AutomaticRescaleRangeMode = "Never"
lut.RGBPoints = [value for point in transfer["color"] for value in point]
simple.GetOpacityTransferFunction("density").Points = [
    value for x, a in transfer["opacity"] for value in (x, a, 0.5, 0.0)]
display.ScalarOpacityUnitDistance = transfer["unit_distance"]
display.CloudLighting = "march"
display.CloudSunDirection = scene["lights"][0]["position"]
display.CloudJitter = 0
display.CloudAccumulatedFrames = 1

camera = view.GetActiveCamera()
controller.Barrier()
start = time.perf_counter()
simple.Render(view)
controller.Barrier()
first = time.perf_counter() - start
start = time.perf_counter()
for _ in range(frames):
    camera.Azimuth(360.0 / frames)
    simple.Render(view)
controller.Barrier()
per_frame = (time.perf_counter() - start) / frames

with open("/proc/self/status") as f:
    peak = next(int(line.split()[1]) for line in f if line.startswith("VmHWM:"))
peaks = [0] * ranks
from vtkmodules.vtkCommonCore import vtkIntArray
mine, all_ranks = vtkIntArray(), vtkIntArray()
mine.InsertNextValue(peak // 1024)
controller.AllGather(mine, all_ranks)
if rank == 0:
    print("ranks %d: %.1f ms/frame, first frame %.1f ms, peak memory per rank %s MiB"
          % (ranks, per_frame * 1000.0, first * 1000.0,
             " ".join(str(all_ranks.GetValue(r)) for r in range(ranks))))
