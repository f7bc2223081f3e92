# One verification case (called by CTest through CMakeLists.txt, cmake -P):
# runs APP on DECK into OUTPUT, then compares REFERENCE with OUTPUT.
# Fails when the run fails (exit code != 0) or when compare finds a difference.
# Inputs: APP, DECK, REFERENCE, OUTPUT, RTOL, ATOL.
foreach(var APP DECK REFERENCE OUTPUT RTOL ATOL)
  if(NOT DEFINED ${var} OR "${${var}}" STREQUAL "")
    message(FATAL_ERROR "run_case.cmake: ${var} is not set")
  endif()
endforeach()
if(NOT EXISTS "${REFERENCE}")
  message(FATAL_ERROR "no reference ${REFERENCE}: create it with scripts/bless.sh")
endif()

get_filename_component(output_dir "${OUTPUT}" DIRECTORY)
file(MAKE_DIRECTORY "${output_dir}")
file(REMOVE "${OUTPUT}")

execute_process(COMMAND "${APP}" "${DECK}" -q -o "${OUTPUT}" RESULT_VARIABLE run_status)
if(NOT run_status EQUAL 0)
  message(FATAL_ERROR "igacontact ${DECK} failed (exit code ${run_status})")
endif()

execute_process(COMMAND "${APP}" compare "${REFERENCE}" "${OUTPUT}" --rtol ${RTOL} --atol ${ATOL}
                RESULT_VARIABLE compare_status)
if(NOT compare_status EQUAL 0)
  message(FATAL_ERROR "results differ from ${REFERENCE} beyond rtol ${RTOL}, atol ${ATOL} "
                      "(exit code ${compare_status}); if the change is intended: scripts/bless.sh")
endif()
