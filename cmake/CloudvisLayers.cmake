# The application's layers (app/CMakeLists.txt says what each is). Each layer's folder defines its
# library with cloudvis_add_layer in its own CMakeLists.txt, so the application and the ParaView
# plugin (paraview/CMakeLists.txt, built against ParaView's VTK) build the same targets from the
# same lists.
include("${CMAKE_CURRENT_LIST_DIR}/CloudvisWarnings.cmake")

# The source tree's root, whichever project includes this (the data the layers read: presets,
# scenes).
get_filename_component(CLOUDVIS_SOURCE_DIR "${CMAKE_CURRENT_LIST_DIR}/.." ABSOLUTE)

# cloudvis_add_layer(NAME SOURCES ... [PUBLIC_DEPENDS ...] [PRIVATE_DEPENDS ...]), called from the
# layer's folder: the static library cloudvis<NAME> (alias cloudvis::<NAME>) of its sources, with
# its public/ headers for the layers that link it and its private/ headers for itself alone.
function(cloudvis_add_layer name)
  cmake_parse_arguments(PARSE_ARGV 1 L "" "" "SOURCES;PUBLIC_DEPENDS;PRIVATE_DEPENDS")
  set(dir "${CMAKE_CURRENT_SOURCE_DIR}")
  add_library(cloudvis${name} STATIC ${L_SOURCES})
  add_library(cloudvis::${name} ALIAS cloudvis${name})
  target_include_directories(cloudvis${name} PUBLIC "${dir}/public")
  if(EXISTS "${dir}/private")
    target_include_directories(cloudvis${name} PRIVATE "${dir}/private")
  endif()
  target_link_libraries(cloudvis${name} PUBLIC ${L_PUBLIC_DEPENDS} PRIVATE ${L_PRIVATE_DEPENDS})
  cloudvis_enable_warnings(cloudvis${name})
endfunction()
