# The ParaView plugin (paraview/, docs/paraview.md), when CLOUDVIS_PARAVIEW is on: the cloudvis
# VTK modules built a second time against ParaView 5.11's own VTK, by the CMake project in
# paraview/ (one project cannot find two VTKs), as an external project of this one: `cmake --build`
# builds it with everything else, into <build>/paraview. Its tests (tests/paraview) run in this
# project's ctest with pvbatch.
include(ExternalProject)

# The private prefix ParaView's CMake package and pvbatch need (paraview/make-prefix.sh says why):
# made once per ParaView version, at configure time.
set(CLOUDVIS_PARAVIEW_PREFIX "${CMAKE_BINARY_DIR}/paraview-prefix")
execute_process(
  COMMAND bash "${CMAKE_SOURCE_DIR}/paraview/make-prefix.sh" "${CLOUDVIS_PARAVIEW_PREFIX}"
  RESULT_VARIABLE prefix_status
  ERROR_VARIABLE prefix_error
  OUTPUT_QUIET)
if(prefix_status)
  message(FATAL_ERROR "The ParaView plugin cannot be built: ${prefix_error}"
    "Install what it needs with `bash cmake/install-deps.sh` (or `make deps`), or configure "
    "with -DCLOUDVIS_PARAVIEW=OFF to build cloudvis without it.")
endif()
set(arch "${CMAKE_LIBRARY_ARCHITECTURE}")
set(CLOUDVIS_PARAVIEW_DIR "${CLOUDVIS_PARAVIEW_PREFIX}/usr/lib/${arch}/cmake/paraview-5.11")
# pvbatch and pvpython find ParaView's Python modules here (docs/paraview.md).
set(CLOUDVIS_PARAVIEW_PYTHONPATH "${CLOUDVIS_PARAVIEW_PREFIX}/python/usr/lib/python3/dist-packages"
  CACHE INTERNAL "PYTHONPATH for pvbatch and pvpython")

set(CLOUDVIS_PARAVIEW_BINARY_DIR "${CMAKE_BINARY_DIR}/paraview")
ExternalProject_Add(cloudvis-paraview
  SOURCE_DIR "${CMAKE_SOURCE_DIR}/paraview"
  BINARY_DIR "${CLOUDVIS_PARAVIEW_BINARY_DIR}"
  # Configured by the build step itself whenever its folder has no cache (a deleted
  # build/paraview is remade), then built with make's own job slots.
  CONFIGURE_COMMAND ""
  BUILD_COMMAND "${CMAKE_COMMAND}"
    "-DSOURCE_DIR=${CMAKE_SOURCE_DIR}/paraview" "-DBINARY_DIR=${CLOUDVIS_PARAVIEW_BINARY_DIR}"
    "-DPARAVIEW_DIR=${CLOUDVIS_PARAVIEW_DIR}" "-DBUILD_TYPE=${CMAKE_BUILD_TYPE}"
    "-DLAUNCHER=${CMAKE_CXX_COMPILER_LAUNCHER}"
    -P "${CMAKE_SOURCE_DIR}/cmake/ConfigureParaViewPlugin.cmake"
    COMMAND $(MAKE)
  # The sources it compiles are this project's: always let its own build decide what changed.
  BUILD_ALWAYS ON
  INSTALL_COMMAND "")
# The build step runs in the plugin's folder: it must exist even after `rm -rf build/paraview`.
ExternalProject_Add_Step(cloudvis-paraview folder
  COMMAND "${CMAKE_COMMAND}" -E make_directory "${CLOUDVIS_PARAVIEW_BINARY_DIR}"
  WORKING_DIRECTORY "${CMAKE_BINARY_DIR}"
  DEPENDEES configure
  DEPENDERS build
  ALWAYS ON)
set(CLOUDVIS_PARAVIEW_PLUGIN
  "${CLOUDVIS_PARAVIEW_BINARY_DIR}/lib/paraview-5.11/plugins/CloudVis/CloudVis.so"
  CACHE INTERNAL "The plugin ParaView loads")
