# The headers VTK's Python wrapper parses stay light (issue 24: the first run). vtkWrapPython
# reads every header a wrapped class's header includes, as the preprocessor sees it with
# __VTK_WRAP__ defined, and a template-heavy include (glm, the per-path code of CloudPathTrace.h)
# once kept it busy for minutes on one header. This lists each wrapped header's includes the way
# the wrapper sees them and fails on glm or on any of the modules' private Cloud*.h headers.
#   cmake -DCXX=... -DINCLUDES="dir;dir" -DHEADERS="a.h;b.h" -P WrappedHeaders.cmake
set(flags -std=c++17 -D__VTK_WRAP__ -M)
foreach(dir IN LISTS INCLUDES)
  list(APPEND flags "-I${dir}")
endforeach()
set(failures "")
foreach(header IN LISTS HEADERS)
  execute_process(COMMAND "${CXX}" ${flags} -x c++ "${header}"
    RESULT_VARIABLE status OUTPUT_VARIABLE depends ERROR_VARIABLE errors)
  if(NOT status EQUAL 0)
    message(FATAL_ERROR "${header}: the preprocessor failed:\n${errors}")
  endif()
  string(REGEX MATCHALL "[^ \\\n]*(glm/[^ \\\n]*|/Cloud[A-Za-z]*\\.h)" heavy "${depends}")
  if(heavy)
    list(JOIN heavy "\n    " heavy)
    string(APPEND failures "  ${header} includes, as the wrapper parses it:\n    ${heavy}\n")
  endif()
endforeach()
if(failures)
  message(FATAL_ERROR "wrapped headers that include glm or a private header (guard them with "
    "#ifndef __VTK_WRAP__ or move them into the .cxx):\n${failures}")
endif()
list(LENGTH HEADERS count)
message(STATUS "${count} wrapped headers include neither glm nor a private header")
