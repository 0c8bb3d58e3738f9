# The headers each part of cloudvis shows the others are the ones it declares public (issue 20):
#   - every header of filters/ is a class header (vtk*.h) or in exactly one of the lists
#     PUBLIC and PRIVATE (filters/CMakeLists.txt);
#   - the application's layers (app/common, fields, statistics, scene, export, viewer, cli,
#     main.cxx) include no private header of filters/ and none of app/rendering's
#     (RENDERING_PRIVATE): those are the transport code and the mapper's insides, which only
#     filters/ and app/rendering include;
#   - no public header (filters/' PUBLIC and classes, app/rendering's classes, app/*/public/)
#     includes a private one, so a public header never drags a private one along;
#   - a layer's public/ headers include no header of any layer's private/ folder;
#   - the clients of the libraries, paraview/ (the plugin's modules) and bench/, include public
#     headers only, as the layers do, but for the benches named in WHITE_BOX (paths relative to
#     the source), which measure the CPU transport's own code as tests/unit tests it.
#   cmake -DSOURCE_DIR=... -DPUBLIC="a.h;b.h" -DPRIVATE="c.h" -DRENDERING_PRIVATE="d.h"
#         -DWHITE_BOX="bench/e.cxx" -P PublicHeaders.cmake
cmake_minimum_required(VERSION 3.13)
set(failures "")

# The quoted includes of a file, as a list of file names.
function(quoted_includes file out)
  file(STRINGS "${file}" lines REGEX "^[ \t]*#[ \t]*include[ \t]*\"")
  set(names "")
  foreach(line IN LISTS lines)
    string(REGEX REPLACE "^[ \t]*#[ \t]*include[ \t]*\"([^\"]*)\".*" "\\1" name "${line}")
    get_filename_component(name "${name}" NAME)
    list(APPEND names "${name}")
  endforeach()
  set(${out} "${names}" PARENT_SCOPE)
endfunction()

# Appends to `failures` each include of `file` that is in the list `forbidden`.
function(check_includes file forbidden why)
  quoted_includes("${file}" names)
  foreach(name IN LISTS names)
    if(name IN_LIST forbidden)
      file(RELATIVE_PATH relative "${SOURCE_DIR}" "${file}")
      string(APPEND failures "  ${relative} includes ${name} (${why})\n")
    endif()
  endforeach()
  set(failures "${failures}" PARENT_SCOPE)
endfunction()

# Every filters/ header is declared once.
file(GLOB filters_headers RELATIVE "${SOURCE_DIR}/filters" "${SOURCE_DIR}/filters/*.h")
foreach(header IN LISTS filters_headers)
  if(header MATCHES "^vtk")
    continue()
  endif()
  set(count 0)
  if(header IN_LIST PUBLIC)
    math(EXPR count "${count} + 1")
  endif()
  if(header IN_LIST PRIVATE)
    math(EXPR count "${count} + 1")
  endif()
  if(NOT count EQUAL 1)
    string(APPEND failures "  filters/${header} is in ${count} of the public and private lists "
      "(filters/CMakeLists.txt): it belongs in exactly one\n")
  endif()
endforeach()

set(private_everywhere ${PRIVATE} ${RENDERING_PRIVATE})

# The application's layers see public headers only.
file(GLOB_RECURSE layer_files
  "${SOURCE_DIR}/app/common/*.h" "${SOURCE_DIR}/app/common/*.cxx"
  "${SOURCE_DIR}/app/fields/*.h" "${SOURCE_DIR}/app/fields/*.cxx"
  "${SOURCE_DIR}/app/statistics/*.h" "${SOURCE_DIR}/app/statistics/*.cxx"
  "${SOURCE_DIR}/app/scene/*.h" "${SOURCE_DIR}/app/scene/*.cxx"
  "${SOURCE_DIR}/app/export/*.h" "${SOURCE_DIR}/app/export/*.cxx"
  "${SOURCE_DIR}/app/viewer/*.h" "${SOURCE_DIR}/app/viewer/*.cxx"
  "${SOURCE_DIR}/app/cli/*.h" "${SOURCE_DIR}/app/cli/*.cxx"
  "${SOURCE_DIR}/app/main.cxx")
foreach(file IN LISTS layer_files)
  check_includes("${file}" "${private_everywhere}"
    "a private header of filters/ or app/rendering")
endforeach()

# The clients of the libraries see public headers only.
file(GLOB_RECURSE client_files RELATIVE "${SOURCE_DIR}"
  "${SOURCE_DIR}/paraview/*.h" "${SOURCE_DIR}/paraview/*.cxx"
  "${SOURCE_DIR}/bench/*.h" "${SOURCE_DIR}/bench/*.cxx")
foreach(white_box IN LISTS WHITE_BOX)
  if(NOT EXISTS "${SOURCE_DIR}/${white_box}")
    string(APPEND failures "  ${white_box} is named a white-box bench but does not exist\n")
  endif()
endforeach()
file(GLOB all_layer_private_headers "${SOURCE_DIR}/app/*/private/*.h")
set(all_layer_private_names "")
foreach(header IN LISTS all_layer_private_headers)
  get_filename_component(name "${header}" NAME)
  list(APPEND all_layer_private_names "${name}")
endforeach()
foreach(file IN LISTS client_files)
  if(file IN_LIST WHITE_BOX)
    continue()
  endif()
  check_includes("${SOURCE_DIR}/${file}" "${private_everywhere};${all_layer_private_names}"
    "paraview/ and bench/ include public headers, but for bench/CMakeLists.txt's white-box benches")
endforeach()

# Public headers include no private one.
set(public_files "")
foreach(header IN LISTS PUBLIC)
  list(APPEND public_files "${SOURCE_DIR}/filters/${header}")
endforeach()
file(GLOB class_headers "${SOURCE_DIR}/filters/vtk*.h" "${SOURCE_DIR}/app/rendering/vtk*.h")
file(GLOB layer_public_headers "${SOURCE_DIR}/app/*/public/*.h")
list(APPEND public_files ${class_headers} ${layer_public_headers})
file(GLOB layer_private_headers RELATIVE "${SOURCE_DIR}" "${SOURCE_DIR}/app/*/private/*.h")
set(layer_private_names "")
foreach(header IN LISTS layer_private_headers)
  get_filename_component(name "${header}" NAME)
  list(APPEND layer_private_names "${name}")
endforeach()
foreach(file IN LISTS public_files)
  check_includes("${file}" "${private_everywhere};${layer_private_names}"
    "a public header may include public headers only")
endforeach()

if(failures)
  message(FATAL_ERROR "private headers reached from outside their part:\n${failures}")
endif()
list(LENGTH filters_headers count)
list(LENGTH client_files clients)
message(STATUS "${count} filters/ headers declared; the layers, the public headers and ${clients} "
  "files of paraview/ and bench/ include public headers only")
