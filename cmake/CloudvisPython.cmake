# `import cloudvis`: cloudvis::Filters and cloudvis::Rendering wrapped for Python with VTK's own
# wrapping (vtk_module_wrap_python), against Debian's python3-vtk9, so that the wrapped classes
# are ordinary vtkmodules classes (they import vtkmodules.vtkCommonCore... of Debian, not a second
# VTK). The package lands in the build tree, laid out like Debian's dist-packages:
#   <build>/lib/python3/dist-packages/cloudvis/{__init__.py, cloudvisFilters*.so, cloudvisRendering*.so}
# and is found with PYTHONPATH=<build>/lib/python3/dist-packages (`make python-path` prints it).
vtk_module_python_default_destination(cloudvis_python_destination)
vtk_module_wrap_python(
  MODULES ${cloudvis_modules}
  TARGET cloudvis::Python
  WRAPPED_MODULES cloudvis_python_modules
  PYTHON_PACKAGE cloudvis
  MODULE_DESTINATION "${cloudvis_python_destination}"
  LIBRARY_DESTINATION lib
  INSTALL_HEADERS OFF
  BUILD_STATIC OFF)
set(CLOUDVIS_PYTHONPATH "${CMAKE_BINARY_DIR}/${cloudvis_python_destination}"
  CACHE INTERNAL "Where `import cloudvis` finds the package in the build tree")
foreach(file IN ITEMS __init__.py fields.py render.py)
  configure_file("${CMAKE_SOURCE_DIR}/app/python/${file}" "${CLOUDVIS_PYTHONPATH}/cloudvis/${file}"
    COPYONLY)
endforeach()
# Where cloudvis.render finds the program it runs (render.py), in the build tree.
file(GENERATE OUTPUT "${CLOUDVIS_PYTHONPATH}/cloudvis/_build.py"
  CONTENT "# Written by cmake/CloudvisPython.cmake: the cloudvis program of this build.\nCLOUDVIS_EXECUTABLE = \"$<TARGET_FILE:cloudvis>\"\n")
# One name for the whole package (`make python`): the demo builds the cloudvis binary alone, so
# the wrapping, a few minutes of the first build, never stands between a new user and a picture.
add_custom_target(cloudvis-python)
add_dependencies(cloudvis-python cloudvisFiltersPython cloudvisRenderingPython cloudvis)
