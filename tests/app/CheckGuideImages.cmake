# Runs a picture script of docs/scripts with the built cloudvis at a small size into a scratch
# folder and checks that every picture its document refers to (images/NAME.png) was made: a
# document and its script cannot drift apart unnoticed. By default the script is
# make-guide-images.sh (-s 64x48 -g 64x36 -a 1 -d 24) and the document docs/user-guide.md.
#
# Called as: cmake -DCLOUDVIS=<binary> -DSOURCE_DIR=<repository> -DWORK_DIR=<dir>
#   [-DSCRIPT=make-viewer-images.sh -DSCRIPT_ARGS=-s|320x280 -DDOC=viewer.md -DMINIMUM=4]
#   -P CheckGuideImages.cmake
if(NOT DEFINED SCRIPT)
  set(SCRIPT make-guide-images.sh)
  set(SCRIPT_ARGS -s 64x48 -g 64x36 -a 1 -d 24)
  set(DOC user-guide.md)
  set(MINIMUM 5)
endif()
string(REPLACE "|" ";" SCRIPT_ARGS "${SCRIPT_ARGS}")
file(REMOVE_RECURSE "${WORK_DIR}")
file(MAKE_DIRECTORY "${WORK_DIR}")
execute_process(
  COMMAND bash "${SOURCE_DIR}/docs/scripts/${SCRIPT}" ${SCRIPT_ARGS} "${CLOUDVIS}" "${WORK_DIR}"
  RESULT_VARIABLE status
  OUTPUT_VARIABLE out
  ERROR_VARIABLE err)
if(NOT status EQUAL 0)
  message(FATAL_ERROR "${SCRIPT} failed (${status})\n--- stdout:\n${out}\n--- stderr:\n${err}")
endif()
file(READ "${SOURCE_DIR}/docs/${DOC}" guide)
string(REGEX MATCHALL "images/[A-Za-z0-9_-]+\\.png" referenced "${guide}")
list(REMOVE_DUPLICATES referenced)
list(LENGTH referenced count)
if(count LESS MINIMUM)
  message(FATAL_ERROR "docs/${DOC} refers to only ${count} images: ${referenced}")
endif()
set(missing "")
foreach(image IN LISTS referenced)
  get_filename_component(name "${image}" NAME)
  if(NOT EXISTS "${WORK_DIR}/${name}")
    list(APPEND missing "${name}")
  endif()
  if(NOT EXISTS "${SOURCE_DIR}/docs/${image}")
    list(APPEND missing "docs/${image} (committed copy)")
  endif()
endforeach()
if(missing)
  message(FATAL_ERROR "pictures docs/${DOC} shows were not made: ${missing}\n--- stdout:\n${out}")
endif()
