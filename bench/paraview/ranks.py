"""One rank count's figures for bench/paraview-ranks.sh: pvbatch --symmetric runs this on every
rank. It draws FIELD as a Cloud Volume with the march, turns the camera FRAMES times (each frame
marched anew: no accumulation) and prints, on rank 0, the mean milliseconds per frame, the first
frame's (which uploads the pieces and exchanges the optical depth), and every rank's peak resident
memory.

Usage: pvbatch --symmetric ranks.py FIELD.vti SCENE.json FRAMES, with the plugin's path in
CLOUDVIS_PARAVIEW_PLUGIN and tests/paraview on PYTHONPATH (bench/paraview-ranks.sh sets them)."""
import sys
import time

from paraview import simple
from paraview.modules.vtkRemotingCore import vtkProcessModule
from vtkmodules.vtkCommonCore import vtkIntArray

import cloudvis_paraview_testing as testing  # tests/paraview: the scene's view and display

field, scene_path, frames = sys.argv[1], sys.argv[2], int(sys.argv[3])
testing.load_plugin()
scene = testing.read_scene(scene_path)
controller = vtkProcessModule.GetProcessModule().GetGlobalController()
rank, ranks = controller.GetLocalProcessId(), controller.GetNumberOfProcesses()

reader = simple.XMLImageDataReader(FileName=[field])
view = testing.render_view(scene)
display = testing.show_cloud(reader, view, scene, "march")
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
mine, all_ranks = vtkIntArray(), vtkIntArray()
mine.InsertNextValue(peak // 1024)
controller.AllGather(mine, all_ranks)
if rank == 0:
    print("ranks %d: %.1f ms/frame, first frame %.1f ms, peak memory per rank %s MiB"
          % (ranks, per_frame * 1000.0, first * 1000.0,
             " ".join(str(all_ranks.GetValue(r)) for r in range(ranks))))
