# make bench-check's logic (bench/check.py), without timing anything: fake benches print fixed
# ratios. Recording writes them; the same ratios compare as no worse (exit 0); a derivative that
# costs 1.5x none against 1.2x recorded, and a generation speed-up of 8 against 10, are reported
# as worse by more than 15% (exit 1), while a 10% loss is not; a bench that prints no ratio is
# exit 2, naming it.
# Called as: cmake -DPYTHON=<python3> -DCHECK=<bench/check.py> -DWORK_DIR=<dir> -P BenchCheck.cmake
cmake_minimum_required(VERSION 3.16)
file(REMOVE_RECURSE "${WORK_DIR}")
file(MAKE_DIRECTORY "${WORK_DIR}/bin")

# fake(DERIVATIVE GENERATION): benches that print what the real ones print, with these ratios.
function(fake derivative generation)
  file(WRITE "${WORK_DIR}/bin/cloudvis-bench-rendering" "#!/bin/sh
cat <<'OUT'
  sparse speed-up ratio: 2.80
  dense speed-up ratio: 1.00
  none                                                     20.9 ms/frame  (1.00 x none)
  derivative                                               24.1 ms/frame  (${derivative} x none)
  march (light volumes, multiple-scattering volume)       102.3 ms/frame  (4.91 x none)
  march (light volumes) vs VTK shaded speed-up ratio: 2.49
  march (light volumes, octaves)                           96.6 ms/frame  (4.63 x none)
OUT
")
  file(WRITE "${WORK_DIR}/bin/cloudvis-bench-generation" "#!/bin/sh
echo 'generation speed-up ratio: ${generation} (target >= 10: met)'
")
  file(CHMOD "${WORK_DIR}/bin/cloudvis-bench-rendering" "${WORK_DIR}/bin/cloudvis-bench-generation"
    PERMISSIONS OWNER_READ OWNER_WRITE OWNER_EXECUTE)
endfunction()

function(check expected_status)
  execute_process(COMMAND "${PYTHON}" "${CHECK}" --build "${WORK_DIR}" --rounds 1
      --figures "${WORK_DIR}/figures.json" ${ARGN}
    RESULT_VARIABLE status OUTPUT_VARIABLE out ERROR_VARIABLE err TIMEOUT 60)
  if(NOT "${status}" STREQUAL "${expected_status}")
    message(FATAL_ERROR "check.py ${ARGN} exited with '${status}', expected ${expected_status}\n"
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

fake(1.20 10.0)
check(0 --record)
file(READ "${WORK_DIR}/figures.json" figures)
expect("${figures}" "\"derivative vs none\": 1\\.2,")
expect("${figures}" "\"generation vs vtkSampleFunction\": 10\\.0")
check(0)
expect("${out}" "no ratio worse by more than 15%")

fake(1.50 8.0)
check(1)
expect("${out}" "derivative vs none +1\\.50 +recorded +1\\.20 +25\\.0% worse")
expect("${out}" "worse by more than 15%:\n  derivative vs none: 1\\.50 against 1\\.20 recorded \\(25% worse\\)\n  generation vs vtkSampleFunction: 8\\.00 against 10\\.00 recorded \\(25% worse\\)\n")

fake(1.32 9.2)
check(0)
expect("${out}" "derivative vs none +1\\.32 +recorded +1\\.20 +10\\.0% worse")

file(WRITE "${WORK_DIR}/bin/cloudvis-bench-generation" "#!/bin/sh\necho 'nothing'\n")
check(2)
expect("${err}" "cloudvis-bench-generation printed no \"generation vs vtkSampleFunction\"")
