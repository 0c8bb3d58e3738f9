# Sanitized and fuzzing builds of cloudvis' own code (filters/, app/, tests/, bench/).
#
#   CLOUDVIS_SANITIZE  a list of sanitizers, separated by ',' or ';': address, undefined.
#                      Empty (the default): an ordinary build.
#   CLOUDVIS_FUZZ      builds the libFuzzer targets of tests/fuzz (clang only). Implies address,
#                      and instruments our code for coverage (-fsanitize=fuzzer-no-link); only the
#                      fuzz executables link libFuzzer's main (-fsanitize=fuzzer).
#
# The flags are added with add_compile_options/add_link_options before any of our targets is
# created, so every target of this project gets them and no imported target (VTK, GTest) does:
# the Debian libraries stay uninstrumented, which ASan and UBSan support. UBSan aborts on the
# first report (-fno-sanitize-recover), so undefined behaviour fails the test that hit it instead
# of scrolling past in its output. docs/reliability.md says how the runs are made.

set(CLOUDVIS_SANITIZE "" CACHE STRING
  "Sanitizers for cloudvis' own code: a list of address, undefined (empty: none)")
option(CLOUDVIS_FUZZ "Build the libFuzzer targets in tests/fuzz (clang only)" OFF)

string(REPLACE "," ";" cloudvis_sanitizers "${CLOUDVIS_SANITIZE}")
if(CLOUDVIS_FUZZ)
  if(NOT CMAKE_CXX_COMPILER_ID STREQUAL "Clang")
    message(FATAL_ERROR "CLOUDVIS_FUZZ needs clang (libFuzzer): configure with "
      "-DCMAKE_CXX_COMPILER=clang++ -DCMAKE_C_COMPILER=clang")
  endif()
  list(APPEND cloudvis_sanitizers address)
endif()
list(REMOVE_DUPLICATES cloudvis_sanitizers)
foreach(sanitizer IN LISTS cloudvis_sanitizers)
  if(NOT sanitizer MATCHES "^(address|undefined)$")
    message(FATAL_ERROR "CLOUDVIS_SANITIZE: unknown sanitizer \"${sanitizer}\"; "
      "supported: address, undefined")
  endif()
endforeach()

if(cloudvis_sanitizers)
  if(NOT CMAKE_CXX_COMPILER_ID MATCHES "GNU|Clang")
    message(FATAL_ERROR "CLOUDVIS_SANITIZE needs GCC or clang")
  endif()
  list(JOIN cloudvis_sanitizers "," cloudvis_sanitizer_list)
  add_compile_options(-fsanitize=${cloudvis_sanitizer_list} -fno-omit-frame-pointer)
  add_link_options(-fsanitize=${cloudvis_sanitizer_list})
  if("undefined" IN_LIST cloudvis_sanitizers)
    add_compile_options(-fno-sanitize-recover=undefined)
    add_link_options(-fno-sanitize-recover=undefined)
  endif()
  message(STATUS "cloudvis: sanitizers ${cloudvis_sanitizer_list}")
endif()
if(CLOUDVIS_FUZZ)
  add_compile_options(-fsanitize=fuzzer-no-link)
  # Code that runs in a forked child (app/fields/private/IsolatedRead.h) adds no coverage to the
  # fuzzer's counters; such code reruns its accepted work in the parent under this definition.
  add_compile_definitions(CLOUDVIS_FUZZING_BUILD)
endif()
