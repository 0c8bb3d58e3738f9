# `mpirun -np 2 cloudvis generate ... -o m.pvti` with Debian's Open MPI: each rank generates and
# writes its own piece, rank 0 the .pvti; the pieces are byte for byte those of a serial run with
# the same number of pieces (which ParallelFiles.GeneratedPiecesEqualTheWholeFieldBitForBit in
# FieldFormatTests.cxx assembles into the field generated whole, bit for bit). Also: a failing
# rank fails the job without hanging, and commands other than generate refuse to run on 2 ranks.
# Called as: cmake -DCLOUDVIS=<binary> -DMPIRUN=<mpirun> -DWORK_DIR=<dir> -P MpiGeneration.cmake
cmake_minimum_required(VERSION 3.16)
file(REMOVE_RECURSE "${WORK_DIR}")
file(MAKE_DIRECTORY "${WORK_DIR}")
# Open MPI in a container, as root, on one machine: no ssh launcher, shared memory and loopback
# only, no single-copy mechanism that needs ptrace, more ranks than cores allowed.
set(ENV{OMPI_MCA_plm_rsh_agent} "")
set(ENV{OMPI_MCA_btl} "self,vader")
set(ENV{OMPI_MCA_btl_vader_single_copy_mechanism} "none")
set(ENV{OMPI_MCA_oob_tcp_if_include} "lo")
set(ENV{OMPI_MCA_rmaps_base_oversubscribe} "1")
set(ENV{OMPI_ALLOW_RUN_AS_ROOT} "1")
set(ENV{OMPI_ALLOW_RUN_AS_ROOT_CONFIRM} "1")
set(mpirun "${MPIRUN}" --oversubscribe -np 2)
set(field --set field.dimensions=33,29,17 --set field.noise=perlin)

function(run expected_status)
  execute_process(COMMAND ${ARGN} WORKING_DIRECTORY "${WORK_DIR}" TIMEOUT 120
    RESULT_VARIABLE status OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT "${status}" STREQUAL "${expected_status}")
    message(FATAL_ERROR "${ARGN}\nexited with '${status}', expected ${expected_status}\n"
      "stdout: ${out}\nstderr: ${err}")
  endif()
  set(out "${out}" PARENT_SCOPE)
  set(err "${err}" PARENT_SCOPE)
endfunction()

function(expect text regex)
  if(NOT text MATCHES "${regex}")
    message(FATAL_ERROR "expected /${regex}/ in:\n${text}")
  endif()
endfunction()

run(0 ${mpirun} "${CLOUDVIS}" generate ${field} -o m.pvti)
expect("${out}" "wrote m\\.pvti \\(33 x 29 x 17 voxels in 2 pieces, m_0\\.vti \\.\\. m_1\\.vti, written by 2 MPI processes\\)")
run(0 "${CLOUDVIS}" generate ${field} -o s.pvti --pieces 2)
foreach(piece 0 1)
  execute_process(COMMAND ${CMAKE_COMMAND} -E compare_files
    "${WORK_DIR}/m_${piece}.vti" "${WORK_DIR}/s_${piece}.vti" RESULT_VARIABLE different)
  if(different)
    message(FATAL_ERROR "piece ${piece} of the MPI run differs from the serial run's")
  endif()
endforeach()
file(READ "${WORK_DIR}/m.pvti" parallel)
expect("${parallel}" "<Piece Extent=\"[0-9 ]+\" Source=\"m_1\\.vti\"/>")

# One rank cannot write its piece (a directory stands where x_1.vti goes): every rank fails,
# nothing hangs, and no .pvti names a piece that is not there.
file(MAKE_DIRECTORY "${WORK_DIR}/x_1.vti")
run(1 ${mpirun} "${CLOUDVIS}" generate ${field} -o x.pvti)
expect("${err}" "x_1\\.vti: ")
# (The other rank's own message, "another process could not write its pieces", may be cut
# short: mpirun ends the whole job at the first non-zero exit.)
if(EXISTS "${WORK_DIR}/x.pvti")
  message(FATAL_ERROR "x.pvti was written although a piece failed")
endif()
# Only generate, and only to .pvti, runs in several processes.
run(2 ${mpirun} "${CLOUDVIS}" info m.pvti)
expect("${err}" "info: only generate runs in several MPI processes")
run(2 ${mpirun} "${CLOUDVIS}" generate ${field} -o m.vti)
expect("${err}" "generate: under mpirun the output is written in pieces: give it a \\.pvti name")
message(STATUS "MPI generation: 2 ranks, pieces identical to the serial run's")
