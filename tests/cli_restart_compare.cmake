# `rigidflex restart` end to end: copies the directory of a finished run that wrote restart
# dumps (as if it had been interrupted after writing everything), restarts the copy from one of
# its dumps and requires the listed files to come out byte-identical to the uninterrupted run's.
# -D variables: RIGIDFLEX (executable), SOURCE (the run's directory), WORK (scratch directory),
# DUMP (dump file name), FILES (comma-separated names to compare), ARGS (extra restart arguments,
# comma-separated, optional).
file(REMOVE_RECURSE "${WORK}")
file(COPY "${SOURCE}/" DESTINATION "${WORK}")
string(REPLACE "," ";" extra "${ARGS}")
execute_process(COMMAND "${RIGIDFLEX}" restart "${WORK}/${DUMP}" --quiet ${extra}
                RESULT_VARIABLE status OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT status EQUAL 0)
  message(FATAL_ERROR "restart failed (${status}): ${out}${err}")
endif()
string(REPLACE "," ";" files "${FILES}")
foreach(name IN LISTS files)
  execute_process(COMMAND "${CMAKE_COMMAND}" -E compare_files "${SOURCE}/${name}" "${WORK}/${name}"
                  RESULT_VARIABLE differ)
  if(differ)
    message(FATAL_ERROR "${name} after the restart differs from the uninterrupted run's")
  endif()
  message(STATUS "${name}: identical")
endforeach()
