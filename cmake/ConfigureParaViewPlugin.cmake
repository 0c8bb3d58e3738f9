# The first half of the ParaView plugin's build step (cmake/ParaViewPlugin.cmake): configures
# paraview/ into BINARY_DIR unless it is configured already, so that a deleted build/paraview is
# made again by the next build (ExternalProject's own configure step runs once per stamp, and a
# build after `rm -rf build/paraview` would find no makefile). The second half, the build, is
# the external project's $(MAKE), which shares make's job slots.
#   cmake -DSOURCE_DIR=... -DBINARY_DIR=... -DPARAVIEW_DIR=... -DBUILD_TYPE=...
#         [-DLAUNCHER=ccache] -P ConfigureParaViewPlugin.cmake
cmake_minimum_required(VERSION 3.16)
if(EXISTS "${BINARY_DIR}/CMakeCache.txt")
  return()
endif()
set(args "-DParaView_DIR=${PARAVIEW_DIR}" "-DCMAKE_BUILD_TYPE=${BUILD_TYPE}")
if(LAUNCHER)
  list(APPEND args "-DCMAKE_CXX_COMPILER_LAUNCHER=${LAUNCHER}" "-DCMAKE_C_COMPILER_LAUNCHER=${LAUNCHER}")
endif()
execute_process(COMMAND "${CMAKE_COMMAND}" -S "${SOURCE_DIR}" -B "${BINARY_DIR}" ${args}
  RESULT_VARIABLE status)
if(NOT status EQUAL 0)
  file(REMOVE "${BINARY_DIR}/CMakeCache.txt")
  message(FATAL_ERROR "configuring the ParaView plugin (${SOURCE_DIR}) failed")
endif()
