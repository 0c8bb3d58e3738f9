# Runs the real cloudvis binary once for one ctest case and checks everything a user would see:
# the exit status, stdout and stderr against regular expressions (every one must match), that a
# failure prints exactly one "cloudvis: error:" line (plus the usage hint for status 2), and that
# the working directory holds exactly the files expected afterwards: the setup files, unchanged,
# plus the declared outputs on success, and nothing else (no partial output, no temporary).
#
# Called as: cmake -DCLOUDVIS=<binary> -DSPEC=<spec file> -DWORK_DIR=<dir> -P RunCloudvis.cmake
# The spec file (written by cloudvis_app_test in CMakeLists.txt) sets ARGS, STATUS, STDOUT,
# STDERR, OUTPUTS, SETUP (pairs of file name and content), PREPARE (shell commands run in the
# working directory before cloudvis, for what file(WRITE) cannot make: FIFOs, sockets, large
# sparse files, copies; what they make counts as setup) and ENV (changes to the environment in
# the form of `cmake -E env`: NAME=VALUE or --unset=NAME). In ARGS, SETUP and PREPARE, \xNN
# stands for the byte NN, for names that are not UTF-8.
cmake_minimum_required(VERSION 3.16)
include("${SPEC}")

# \xNN -> the byte NN in each element of the list variable `name`.
function(decode_bytes name)
  set(decoded "")
  foreach(item IN LISTS ${name})
    string(REGEX MATCHALL "\\\\x[0-9A-Fa-f][0-9A-Fa-f]" escapes "${item}")
    list(REMOVE_DUPLICATES escapes)
    foreach(escape IN LISTS escapes)
      string(SUBSTRING "${escape}" 2 2 hex)
      math(EXPR code "0x${hex}")
      string(ASCII ${code} byte)
      string(REPLACE "${escape}" "${byte}" item "${item}")
    endforeach()
    list(APPEND decoded "${item}")
  endforeach()
  set(${name} "${decoded}" PARENT_SCOPE)
endfunction()
decode_bytes(ARGS)
decode_bytes(SETUP)
decode_bytes(PREPARE)

set(failures "")
macro(fail what)
  string(APPEND failures "  - ${what}\n")
endmacro()

file(REMOVE_RECURSE "${WORK_DIR}")
file(MAKE_DIRECTORY "${WORK_DIR}")
set(setup_names "")
list(LENGTH SETUP setup_length)
if(setup_length GREATER 0)
  math(EXPR last "${setup_length} - 1")
  foreach(i RANGE 0 ${last} 2)
    math(EXPR j "${i} + 1")
    list(GET SETUP ${i} name)
    list(GET SETUP ${j} content)
    file(WRITE "${WORK_DIR}/${name}" "${content}")
    list(APPEND setup_names "${name}")
  endforeach()
endif()

foreach(command IN LISTS PREPARE)
  execute_process(COMMAND sh -c "${command}" WORKING_DIRECTORY "${WORK_DIR}"
    RESULT_VARIABLE prepared ERROR_VARIABLE prepare_error)
  if(NOT prepared EQUAL 0)
    message(FATAL_ERROR "PREPARE failed: ${command}\n${prepare_error}")
  endif()
endforeach()
# Everything present now is setup, expected to be left in place (FIFOs and sockets included).
file(GLOB_RECURSE prepared_names LIST_DIRECTORIES false RELATIVE "${WORK_DIR}" "${WORK_DIR}/*")
list(APPEND setup_names ${prepared_names})
list(REMOVE_DUPLICATES setup_names)

execute_process(
  COMMAND "${CMAKE_COMMAND}" -E env ${ENV} "${CLOUDVIS}" ${ARGS}
  WORKING_DIRECTORY "${WORK_DIR}"
  RESULT_VARIABLE status
  OUTPUT_VARIABLE out
  ERROR_VARIABLE err)

if(NOT "${status}" STREQUAL "${STATUS}")
  fail("exit status ${status}, expected ${STATUS}")
endif()
foreach(re IN LISTS STDOUT)
  if(NOT out MATCHES "${re}")
    fail("stdout does not match: ${re}")
  endif()
endforeach()
foreach(re IN LISTS STDERR)
  if(NOT err MATCHES "${re}")
    fail("stderr does not match: ${re}")
  endif()
endforeach()
if(STATUS STREQUAL "0")
  if(NOT err STREQUAL "")
    fail("stderr is not empty on success")
  endif()
else()
  # One clean message: no VTK log dump, no second error.
  string(REGEX MATCHALL "\n" newlines "${err}")
  list(LENGTH newlines lines)
  set(expected_lines 1)
  if(STATUS STREQUAL "2")
    set(expected_lines 2)
  endif()
  if(NOT err MATCHES "^cloudvis: error: " OR NOT lines EQUAL expected_lines)
    fail("stderr is not exactly ${expected_lines} line(s) starting with 'cloudvis: error: '")
  endif()
endif()

# Files left behind; CMake's * also matches hidden names, which is how temporaries are named.
file(GLOB_RECURSE left LIST_DIRECTORIES false RELATIVE "${WORK_DIR}" "${WORK_DIR}/*")
set(expected ${setup_names})
if(STATUS STREQUAL "0")
  list(APPEND expected ${OUTPUTS})
  foreach(output IN LISTS OUTPUTS)
    if(NOT output IN_LIST left)
      fail("output ${output} was not written")
    endif()
  endforeach()
endif()
foreach(file IN LISTS left)
  if(NOT file IN_LIST expected)
    fail("unexpected file left in the working directory: ${file}")
  endif()
endforeach()
if(setup_length GREATER 0)
  foreach(i RANGE 0 ${last} 2)
    math(EXPR j "${i} + 1")
    list(GET SETUP ${i} name)
    list(GET SETUP ${j} content)
    if(EXISTS "${WORK_DIR}/${name}")
      file(READ "${WORK_DIR}/${name}" now)
      if(NOT now STREQUAL content)
        fail("setup file ${name} was modified")
      endif()
    endif()
  endforeach()
endif()

if(NOT failures STREQUAL "")
  list(JOIN ARGS " " command_line)
  message(FATAL_ERROR "cloudvis ${command_line}\n${failures}--- status: ${status}\n"
    "--- stdout:\n${out}\n--- stderr:\n${err}")
endif()
