# OpenVDB through Debian's own FindOpenVDB.cmake (libopenvdb-dev), for the application and for the
# ParaView plugin's build (paraview/), which compiles the field readers again. It is found inside a
# function: the module sets BUILD_SHARED_LIBS, and its folder holds a FindOpenEXR.cmake that must
# not shadow an OpenEXR config found before.
function(cloudvis_find_openvdb)
  list(APPEND CMAKE_MODULE_PATH "/usr/lib/${CMAKE_LIBRARY_ARCHITECTURE}/cmake/OpenVDB")
  find_package(OpenVDB REQUIRED)
endfunction()
