"""A NetCDF file with a time axis opens in ParaView as a time-varying dataset: the plugin's reader
offers the time coordinate's values as the time steps (TimestepValues, which the animation steps
through), and a time asked of the pipeline reads that step, the last at or before the time, as
cloudvis reads it with field.time_step.

The file (made here by ncgen, with the netCDF library's own dimension order (time, z, y, x))
holds three steps at t = 0, 60 and 120 s of a blob whose density is 0.25, 0.5 and 0.75: each
step's maximum says which was read.

A numbered series of one-step files (step_*.nc4) is one dataset the same way, a step per file.

Usage: pvbatch ReadTimeSeries.py"""
import os
import subprocess

import numpy
from paraview import servermanager, simple
from vtkmodules.util.numpy_support import vtk_to_numpy

import cloudvis_paraview_testing as testing

testing.load_plugin()
STEPS = [0.0, 60.0, 120.0]
PEAKS = [0.25, 0.5, 0.75]
blob = numpy.zeros((4, 5, 6))
blob[1:3, 1:4, 2:4] = 1.0
values = ", ".join("%g" % v for peak in PEAKS for v in (blob * peak).ravel())
cdl = """netcdf series {
dimensions:
  time = UNLIMITED ; z = 4 ; y = 5 ; x = 6 ;
variables:
  double time(time) ; time:units = "seconds since 2020-06-01 12:00:00" ;
  double z(z) ; z:units = "m" ; z:axis = "Z" ;
  double y(y) ; y:units = "m" ;
  double x(x) ; x:units = "m" ;
  float density(time, z, y, x) ;
data:
  time = %s ;
  z = 0, 40, 80, 120 ; y = 0, 40, 80, 120, 160 ; x = 0, 40, 80, 120, 160, 200 ;
  density = %s ;
}
""" % (", ".join("%g" % t for t in STEPS), values)
with open("series.cdl", "w") as f:
    f.write(cdl)
path = os.path.abspath("series.nc4")
result = subprocess.run(["ncgen", "-k", "3", "-o", path, "series.cdl"], capture_output=True, text=True)
testing.check(result.returncode == 0, "ncgen failed: %s" % result.stderr)

reader = simple.OpenDataFile(path)
testing.check(reader is not None and reader.GetXMLName() == "CloudFieldReader",
              "ParaView opens %s with %s, not the plugin's reader" % (
                  path, reader.GetXMLName() if reader else "nothing"))
reader.UpdatePipelineInformation()
times = list(reader.TimestepValues)
print("time steps:", times)
testing.check(times == STEPS, "TimestepValues %s, the file's times %s" % (times, STEPS))


def peak_at(time):
    reader.UpdatePipeline(time)
    output = servermanager.Fetch(reader)
    got = vtk_to_numpy(output.GetPointData().GetArray("density"))
    data_time = output.GetInformation().Get(output.DATA_TIME_STEP())
    return float(got.max()), data_time


# Each step's time reads that step; a time between steps the one before; before the first, the
# first; after the last, the last.
for time, step in ((0.0, 0), (60.0, 1), (120.0, 2), (100.0, 1), (-5.0, 0), (500.0, 2)):
    peak, data_time = peak_at(time)
    print("t = %g: peak %g, data time %s" % (time, peak, data_time))
    testing.check(abs(peak - PEAKS[step]) < 1e-6,
                  "t = %g read a peak of %g, step %d holds %g" % (time, peak, step, PEAKS[step]))
    testing.check(data_time == STEPS[step],
                  "t = %g: the output's time is %s, step %d's is %g" % (time, data_time, step, STEPS[step]))

# ParaView's animation takes the reader's steps: its last frame is the last step.
scene = simple.GetAnimationScene()
scene.UpdateAnimationUsingDataTimeSteps()
keeper = simple.GetTimeKeeper()
testing.check(list(keeper.TimestepValues) == STEPS,
              "the animation's time steps %s, the file's %s" % (list(keeper.TimestepValues), STEPS))
scene.AnimationTime = STEPS[-1]
output = servermanager.Fetch(reader)
peak = float(vtk_to_numpy(output.GetPointData().GetArray("density")).max())
testing.check(abs(peak - PEAKS[-1]) < 1e-6, "the animation's last frame shows a peak of %g" % peak)

# A file without a time axis has no time steps.
single = os.path.abspath("single.nc4")
with open("single.cdl", "w") as f:
    f.write(cdl.replace("time = UNLIMITED ; ", "").replace("(time, z, y, x)", "(z, y, x)")
            .replace('  double time(time) ; time:units = "seconds since 2020-06-01 12:00:00" ;\n', "")
            .replace("  time = %s ;\n" % ", ".join("%g" % t for t in STEPS), "")
            .replace(values, ", ".join("%g" % v for v in (blob * 0.5).ravel())))
result = subprocess.run(["ncgen", "-k", "3", "-o", single, "single.cdl"], capture_output=True, text=True)
testing.check(result.returncode == 0, "ncgen failed: %s" % result.stderr)
reader.FileName = single
reader.UpdatePipelineInformation()
testing.check(list(reader.TimestepValues) == [], "a file of one step offers %s" % list(reader.TimestepValues))

# A numbered file series (field.file with a *, docs/data.md) is one dataset with a step per file,
# as ParaView groups such files: step_1.nc4 .. step_3.nc4, one step each, at steps 0, 1, 2.
single_cdl = open("single.cdl").read()
for number, peak in enumerate(PEAKS, start=1):
    with open("step_%d.cdl" % number, "w") as f:
        f.write(single_cdl.replace(", ".join("%g" % v for v in (blob * 0.5).ravel()),
                                   ", ".join("%g" % v for v in (blob * peak).ravel())))
    result = subprocess.run(["ncgen", "-k", "3", "-o", "step_%d.nc4" % number, "step_%d.cdl" % number],
                            capture_output=True, text=True)
    testing.check(result.returncode == 0, "ncgen failed: %s" % result.stderr)
reader.FileName = os.path.abspath("step_*.nc4")
reader.UpdatePipelineInformation()
times = list(reader.TimestepValues)
testing.check(times == [0.0, 1.0, 2.0], "the series offers the steps %s, not 0, 1, 2" % times)
for time, step in ((0.0, 0), (1.0, 1), (2.0, 2), (1.5, 1)):
    peak, data_time = peak_at(time)
    testing.check(abs(peak - PEAKS[step]) < 1e-6,
                  "t = %g of the series read a peak of %g, file %d holds %g" % (
                      time, peak, step + 1, PEAKS[step]))
print("OK")
