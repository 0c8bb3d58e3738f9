"""The pvpython example of docs/paraview.md (docs/examples/paraview_cloud.py) runs as the docs say
and writes its screenshot: a cloud over the sky-blue background, not a blank image.

Usage: pvbatch ExampleScript.py PVPYTHON"""
import os
import subprocess
import sys

import cloudvis_paraview_testing as testing

pvpython = sys.argv[1]
example = os.path.join(testing.SOURCE_DIR, "docs", "examples", "paraview_cloud.py")
result = subprocess.run([pvpython, "--force-offscreen-rendering", example, testing.PLUGIN, "example.png"],
                        capture_output=True, text=True, timeout=300)
print(result.stdout + result.stderr)
testing.check(result.returncode == 0, "pvpython %s exited %d" % (example, result.returncode))
image = testing.read_png("example.png")
cloud = testing.cloud_pixels(image, [0.32, 0.45, 0.65])
print("the example's cloud covers %d of %d pixels" % (cloud.sum(), cloud.size))
testing.check(cloud.sum() > 0.1 * cloud.size, "the example's image shows no cloud")
