# Runs docs/scripts/make-guide-images.sh with the built cloudvis at a tiny size into a scratch
# folder and checks that every picture docs/user-guide.md refers to (images/NAME.png) was made:
# the guide and its script cannot drift apart unnoticed.
#
# Called as: cmake -DCLOUDVIS=<binary> -DSOURCE_DIR=<repository> -DWORK_DIR=<dir> -P CheckGuideImages.cmake
file(REMOVE_RECURSE "${WORK_DIR}")
file(MAKE_DIRECTORY "${WORK_DIR}")
execute_process(
  COMMAND bash "${SOURCE_DIR}/docs/scripts/make-guide-images.sh" -s 64x48 -a 1 -d 24
    "${CLOUDVIS}" "${WORK_DIR}"
  RESULT_VARIABLE status
  OUTPUT_VARIABLE out
  ERROR_VARIABLE err)
if(NOT status EQUAL 0)
  message(FATAL_ERROR "make-guide-images.sh failed (${status})\n--- stdout:\n${out}\n--- stderr:\n${err}")
endif()
file(READ "${SOURCE_DIR}/docs/user-guide.md" guide)
string(REGEX MATCHALL "images/[A-Za-z0-9_-]+\\.png" referenced "${guide}")
list(REMOVE_DUPLICATES referenced)
list(LENGTH referenced count)
if(count LESS 5)
  message(FATAL_ERROR "docs/user-guide.md refers to only ${count} images: ${referenced}")
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
  message(FATAL_ERROR "pictures the guide shows were not made: ${missing}\n--- stdout:\n${out}")
endif()
