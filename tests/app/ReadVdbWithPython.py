"""Reads a .vdb that cloudvis wrote with OpenVDB's own Python module (pyopenvdb, Debian's
python3-openvdb), as Blender's and Houdini's Python would, and checks it against the same field
written as .vti: one fog-volume FloatGrid "density", background 0, exactly the non-empty voxels
stored, the same largest value, the creator and the scene recorded.
Usage: ReadVdbWithPython.py CLOUDVIS WORK_DIRECTORY"""
import json
import os
import subprocess
import sys

import pyopenvdb

cloudvis, work = sys.argv[1], sys.argv[2]
os.makedirs(work, exist_ok=True)
field = ["--set", "field.dimensions=20,18,16", "--set", "field.noise=perlin"]
vdb, vti = os.path.join(work, "py.vdb"), os.path.join(work, "py.vti")
for output in (vdb, vti):
    subprocess.run([cloudvis, "generate", *field, "-o", output], check=True, capture_output=True)
statistics = json.loads(subprocess.run([cloudvis, "info", vti, "--json"], check=True,
                                       capture_output=True, text=True).stdout)

grids, metadata = pyopenvdb.readAll(vdb)
assert len(grids) == 1, f"{len(grids)} grids"
grid = grids[0]
assert grid.name == "density", grid.name
assert grid.gridClass == "fog volume", grid.gridClass
assert grid.background == 0.0, grid.background
assert grid.activeVoxelCount() == statistics["non_empty_voxels"], \
    (grid.activeVoxelCount(), statistics["non_empty_voxels"])
low, high = grid.evalMinMax()
assert high == statistics["range"][1], (high, statistics["range"])
assert metadata["creator"].startswith("cloudvis "), metadata
assert '"field"' in metadata["cloudvis_scene"]
print(f"pyopenvdb read {vdb}: grid density, {grid.activeVoxelCount()} active voxels, "
      f"max {high}, creator {metadata['creator']}")
