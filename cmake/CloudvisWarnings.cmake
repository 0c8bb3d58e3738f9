# Warnings for our own code only: VTK's headers come in as system headers through their targets.
set(CLOUDVIS_WARNING_FLAGS "")
if(CMAKE_CXX_COMPILER_ID MATCHES "GNU|Clang")
  set(CLOUDVIS_WARNING_FLAGS -Wall -Wextra -Wshadow -Wnon-virtual-dtor)
endif()

function(cloudvis_enable_warnings target)
  target_compile_options(${target} PRIVATE ${CLOUDVIS_WARNING_FLAGS})
endfunction()
