# Runs one ParaView test script: cmake -DPVBATCH=... -DMPIRUN=... -DRANKS=<n, 0: no mpirun>
#   -DSCRIPT=<file.py> -DARGS=<a|b|...> -DWORK_DIR=<dir> [-DEXPECT_OUTPUT=<regex>]
#   -P RunPvbatch.cmake
# With EXPECT_OUTPUT, the output must also match it (a message ParaView prints, such as the
# mapper's refusal, which the script itself cannot read).
# The script runs in WORK_DIR (emptied first) and fails the test by exiting non-zero. pvbatch
# runs with a timeout, so a rank left waiting for another shows as a failure, not a hang.
cmake_minimum_required(VERSION 3.16)
file(REMOVE_RECURSE "${WORK_DIR}")
file(MAKE_DIRECTORY "${WORK_DIR}")
include("${CMAKE_CURRENT_LIST_DIR}/../../cmake/OpenMpiOnOneMachine.cmake")
string(REPLACE "|" ";" args "${ARGS}")
set(command "${PVBATCH}" --force-offscreen-rendering "${SCRIPT}" ${args})
if(RANKS GREATER 0)
  set(command "${MPIRUN}" --oversubscribe -np ${RANKS} ${command})
endif()
execute_process(COMMAND ${command} WORKING_DIRECTORY "${WORK_DIR}" TIMEOUT 500
  RESULT_VARIABLE status OUTPUT_VARIABLE out ERROR_VARIABLE err)
message("${out}${err}")
if(NOT status EQUAL 0)
  message(FATAL_ERROR "${SCRIPT} exited with '${status}'")
endif()
if(EXPECT_OUTPUT AND NOT "${out}${err}" MATCHES "${EXPECT_OUTPUT}")
  message(FATAL_ERROR "${SCRIPT}: the output does not say '${EXPECT_OUTPUT}'")
endif()
