# The reference tables of docs/scene-format.md are generated from the scene schema: each sits
# between "<!-- schema:NAME -->" and "<!-- /schema -->" and must be what `cloudvis schema` prints
# for NAME. This script checks that (the test app.scene_docs) or, with -DUPDATE=ON, writes the
# tables into the document (make docs); the prose around them is left as it is.
#
#   cmake -DCLOUDVIS=build/bin/cloudvis -DDOC=docs/scene-format.md [-DUPDATE=ON] [-DWORK_DIR=dir]
#         -P cmake/SceneDocs.cmake
#
# The text is handled with string(FIND) and string(SUBSTRING) only: the tables hold semicolons,
# which CMake lists would split.
cmake_minimum_required(VERSION 3.16)

execute_process(COMMAND "${CLOUDVIS}" schema OUTPUT_VARIABLE tables RESULT_VARIABLE status)
if(NOT status EQUAL 0)
  message(FATAL_ERROR "${CLOUDVIS} schema failed with status ${status}")
endif()
file(READ "${DOC}" doc)

set(begin_mark "<!-- schema:")
set(end_mark "<!-- /schema -->\n")
string(LENGTH "${begin_mark}" begin_length)
string(LENGTH "${end_mark}" end_length)

# The block NAME of `text` (from its begin marker through its end marker) in `block`, or "".
function(find_block text name block)
  string(FIND "${text}" "${begin_mark}${name} -->\n" start)
  if(start EQUAL -1)
    set(${block} "" PARENT_SCOPE)
    return()
  endif()
  string(SUBSTRING "${text}" ${start} -1 from)
  string(FIND "${from}" "${end_mark}" stop)
  math(EXPR stop "${stop} + ${end_length}")
  string(SUBSTRING "${from}" 0 ${stop} found)
  set(${block} "${found}" PARENT_SCOPE)
endfunction()

# The names of the blocks of `text`, in order.
function(block_names text names)
  set(found "")
  set(rest "${text}")
  while(TRUE)
    string(FIND "${rest}" "${begin_mark}" start)
    if(start EQUAL -1)
      break()
    endif()
    math(EXPR start "${start} + ${begin_length}")
    string(SUBSTRING "${rest}" ${start} -1 rest)
    string(FIND "${rest}" " -->" stop)
    string(SUBSTRING "${rest}" 0 ${stop} name)
    list(APPEND found "${name}")
  endwhile()
  set(${names} "${found}" PARENT_SCOPE)
endfunction()

block_names("${tables}" generated_names)
block_names("${doc}" doc_names)
set(problems "")
foreach(name IN LISTS generated_names)
  if(NOT name IN_LIST doc_names)
    string(APPEND problems "  ${DOC} has no table ${name} (add the two marker lines where it goes)\n")
  endif()
endforeach()
foreach(name IN LISTS doc_names)
  if(NOT name IN_LIST generated_names)
    string(APPEND problems "  ${DOC} has a table ${name} that `cloudvis schema` does not print\n")
  endif()
endforeach()
if(problems)
  message(FATAL_ERROR "the scene reference tables do not match:\n${problems}")
endif()

# The document with each of its blocks replaced by the generated one.
set(updated "${doc}")
foreach(name IN LISTS doc_names)
  find_block("${updated}" "${name}" old)
  find_block("${tables}" "${name}" new)
  string(REPLACE "${old}" "${new}" updated "${updated}")
endforeach()

if(UPDATE)
  if(NOT updated STREQUAL doc)
    file(WRITE "${DOC}" "${updated}")
    message(STATUS "wrote the scene reference tables into ${DOC}")
  endif()
elseif(NOT updated STREQUAL doc)
  if(NOT WORK_DIR)
    set(WORK_DIR "${CMAKE_CURRENT_BINARY_DIR}")
  endif()
  file(MAKE_DIRECTORY "${WORK_DIR}")
  file(WRITE "${WORK_DIR}/scene-format.md" "${updated}")
  execute_process(COMMAND diff -u "${DOC}" "${WORK_DIR}/scene-format.md" OUTPUT_VARIABLE difference)
  message(FATAL_ERROR "the reference tables of ${DOC} differ from the scene schema "
    "(`cloudvis schema`); `make docs` writes them in. The difference:\n${difference}")
endif()
