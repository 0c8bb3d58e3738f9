# `mpirun -np 2 cloudvis generate ... -o m.pvti` with Debian's Open MPI: each rank generates and
# writes its own piece, rank 0 the .pvti; the pieces are byte for byte those of a serial run with
# the same number of pieces, apart from the run each records (which
# ParallelFiles.GeneratedPiecesEqualTheWholeFieldBitForBit in FieldFormatTests.cxx assembles into
# the field generated whole, bit for bit). Also: a failure on one rank only, before the pieces
# (a field file it cannot read) or while making them (memory), ends every rank promptly with
# that rank's message and leaves the previous output byte for byte as it was, no temporary; and
# commands other than generate refuse to run on 2 ranks. Every mpirun has a timeout, so a rank
# left waiting for another shows as a failure. (Interrupted runs: tests/faults.)
# Called as: cmake -DCLOUDVIS=<binary> -DMPIRUN=<mpirun> -DWORK_DIR=<dir> [-DSANITIZED=ON]
#   -P MpiGeneration.cmake
cmake_minimum_required(VERSION 3.16)
file(REMOVE_RECURSE "${WORK_DIR}")
file(MAKE_DIRECTORY "${WORK_DIR}")
include("${CMAKE_CURRENT_LIST_DIR}/../../cmake/OpenMpiOnOneMachine.cmake")
# Under LeakSanitizer (make test-asan): Open MPI keeps what MPI_Init allocates until the process
# exits, and unloads its components (dlclose) in MPI_Finalize, so those allocations would be
# reported from "<unknown module>" that no suppression can name. The components stay loaded, and
# allocations are unwound in full (Debian's libraries have no frame pointers), so that
# tests/sanitizers/lsan.supp can name Open MPI's own libraries, and only them.
set(ENV{OMPI_MCA_mca_base_component_disable_dlclose} "1")
if(DEFINED ENV{ASAN_OPTIONS})
  set(ENV{ASAN_OPTIONS} "$ENV{ASAN_OPTIONS}:fast_unwind_on_malloc=0")
endif()
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
# A file's bytes as hexadecimal, with the run it records (CloudvisRun="<32 hex digits>") blanked.
set(hex_digit "[36][0-9a-f]") # a digit or a to f, in hexadecimal
string(REPEAT "${hex_digit}" 32 run_id)
function(bytes_without_run file variable)
  file(READ "${file}" hex HEX)
  # ' CloudvisRun="' in hexadecimal, the id, '"'.
  string(REGEX REPLACE "20436c6f756476697352756e3d22${run_id}22" "RUN" hex "${hex}")
  set(${variable} "${hex}" PARENT_SCOPE)
endfunction()
file(READ "${WORK_DIR}/m.pvti" parallel)
expect("${parallel}" "<Piece Extent=\"[0-9 ]+\" Source=\"m_1\\.vti\"/>")
string(REGEX MATCH "CloudvisRun=\"([0-9a-f]+)\"" found "${parallel}")
set(run "${CMAKE_MATCH_1}")
foreach(piece 0 1)
  bytes_without_run("${WORK_DIR}/m_${piece}.vti" mpi)
  bytes_without_run("${WORK_DIR}/s_${piece}.vti" serial)
  if(NOT mpi STREQUAL serial)
    message(FATAL_ERROR "piece ${piece} of the MPI run differs from the serial run's")
  endif()
  file(READ "${WORK_DIR}/m_${piece}.vti" header LIMIT 1000)
  expect("${header}" "<ImageData [^>]*CloudvisRun=\"${run}\"")
endforeach()

# field.dimensions "auto" (chosen from the camera when the scene is read): every rank chooses the
# same lattice, and the pieces are the serial run's.
set(auto_field --set field.dimensions=auto --set camera.position=[0,0,9] --set field.max_voxels=9000
  --set field.noise=perlin)
run(0 ${mpirun} "${CLOUDVIS}" generate ${auto_field} -o ma.pvti)
expect("${out}" "wrote ma\\.pvti \\(20 x 20 x 20 voxels in 2 pieces")
run(0 "${CLOUDVIS}" generate ${auto_field} -o sa.pvti --pieces 2)
foreach(piece 0 1)
  bytes_without_run("${WORK_DIR}/ma_${piece}.vti" mpi)
  bytes_without_run("${WORK_DIR}/sa_${piece}.vti" serial)
  if(NOT mpi STREQUAL serial)
    message(FATAL_ERROR "piece ${piece} of the MPI run with auto dimensions differs from the serial run's")
  endif()
endforeach()

# What a failed run must leave: the previous output `stem` byte for byte, no temporary.
function(expect_unchanged stem)
  foreach(file ${stem}.pvti ${stem}_0.vti ${stem}_1.vti)
    file(SHA256 "${WORK_DIR}/${file}" now)
    if(NOT now STREQUAL "${before_${file}}")
      message(FATAL_ERROR "${file} changed although the run failed")
    endif()
  endforeach()
  file(GLOB left LIST_DIRECTORIES true "${WORK_DIR}/.${stem}*.tmp-*")
  if(left)
    message(FATAL_ERROR "temporaries left behind: ${left}")
  endif()
endfunction()
function(remember stem)
  foreach(file ${stem}.pvti ${stem}_0.vti ${stem}_1.vti)
    file(SHA256 "${WORK_DIR}/${file}" hash)
    set(before_${file} "${hash}" PARENT_SCOPE)
  endforeach()
endfunction()
remember(m)

# Rank 1 cannot read its field file (truncated), before the pieces: rank 0, which read its own,
# must not wait for it. (MPMD: each rank its own command line.)
run(0 "${CLOUDVIS}" generate ${field} -o whole.vti)
execute_process(COMMAND head -c 700 "${WORK_DIR}/whole.vti" OUTPUT_FILE "${WORK_DIR}/cut.vti")
run(1 "${MPIRUN}" --oversubscribe -np 1 "${CLOUDVIS}" generate whole.vti -o m.pvti
  : -np 1 "${CLOUDVIS}" generate cut.vti -o m.pvti)
expect("${err}" "cut\\.vti: cannot read VTK XML image data")
expect_unchanged(m)
# Rank 1 runs out of memory while making its piece (an address-space limit of 1.5 GB for a piece
# of 1.7 GB); rank 0 has made its own and waits at the agreement: both end, with that message.
# AddressSanitizer reserves terabytes of address space for its shadow, which no `ulimit -v`
# allows; under it the allocations are capped instead, with the same effect on the piece (the
# allocation fails, as it does under the limit).
if(SANITIZED)
  set(limited env
    "ASAN_OPTIONS=$ENV{ASAN_OPTIONS}:allocator_may_return_null=1:max_allocation_size_mb=1500")
else()
  set(limited bash -c "ulimit -v 1500000 && exec \"$@\"" bash)
endif()
run(1 "${MPIRUN}" --oversubscribe -np 1 "${CLOUDVIS}" generate ${field} -o m.pvti
  : -np 1 ${limited} "${CLOUDVIS}" generate --set field.dimensions=1024,1024,800 -o m.pvti)
expect("${err}" "m_1\\.vti: out of memory while making this piece \\(1024 x 513 x 800 voxels\\)")
expect_unchanged(m)

# One rank cannot write its piece (a directory stands where x_1.vti goes): every rank fails,
# nothing hangs, and nothing is written.
file(MAKE_DIRECTORY "${WORK_DIR}/x_1.vti")
run(1 ${mpirun} "${CLOUDVIS}" generate ${field} -o x.pvti)
expect("${err}" "x_1\\.vti: cannot write: it is a directory")
# (Rank 0's own message, "process 1 of 2 failed: ...", may be cut short: mpirun ends the whole
# job at the first non-zero exit.)
foreach(file x.pvti x_0.vti)
  if(EXISTS "${WORK_DIR}/${file}")
    message(FATAL_ERROR "${file} was written although a piece failed")
  endif()
endforeach()
# Only generate, and only to .pvti, runs in several processes.
run(2 ${mpirun} "${CLOUDVIS}" info m.pvti)
expect("${err}" "info: only generate runs in several MPI processes")
run(2 ${mpirun} "${CLOUDVIS}" generate ${field} -o m.vti)
expect("${err}" "generate: under mpirun the output is written in pieces: give it a \\.pvti name")
message(STATUS "MPI generation: 2 ranks, pieces identical to the serial run's; failures on "
  "one rank agreed, the previous output kept")
