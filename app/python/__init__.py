"""cloudvis for Python: procedural cloud density fields, their GPU volume mapper and the CPU
renderers of the same equations, as ordinary VTK classes; fields from numpy and xarray, and
pictures of them as numpy images.

The classes come from cloudvis's two VTK modules, wrapped with VTK's own Python wrapping
(cmake/CloudvisPython.cmake); they mix with Debian's `vtk` / `vtkmodules` in one pipeline.
field_from_numpy, field_from_xarray (fields.py) and render (render.py) are Python.
See docs/python.md.
"""

# The mapper draws through VTK's OpenGL render window: make sure its implementations are
# registered (what `import vtk` does too), so a vtkRenderWindow made after `import cloudvis`
# alone is an OpenGL one.
import vtkmodules.vtkRenderingOpenGL2  # noqa: F401
import vtkmodules.vtkRenderingVolumeOpenGL2  # noqa: F401

del vtkmodules  # imported for its side effect only: keep the package's names cloudvis's own

from .cloudvisFilters import *  # noqa: F401,F403
from .cloudvisRendering import *  # noqa: F401,F403

from .fields import field_from_numpy, field_from_xarray  # noqa: E402,F401
from .render import Image, RenderError, render  # noqa: E402,F401
