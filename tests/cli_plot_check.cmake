# rigidflex-plot end to end: runs a deck, plots its output directory and requires each expected
# PNG to exist, to be a PNG and to be non-trivial (a blank figure of that size compresses to a few
# kB; curves, labels and legends make it several times larger). Skips (status 77) when matplotlib
# is missing. -D variables: RIGIDFLEX, PYTHON, SCRIPT (scripts/rigidflex-plot.py), DECK, WORK,
# PLOTS (comma-separated PNG names expected).
file(REMOVE_RECURSE "${WORK}")
execute_process(COMMAND "${RIGIDFLEX}" run "${DECK}" -o "${WORK}" --threads 1 --quiet
                RESULT_VARIABLE status OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT status EQUAL 0)
  message(FATAL_ERROR "run failed (${status}): ${out}${err}")
endif()
execute_process(COMMAND "${PYTHON}" "${SCRIPT}" "${WORK}"
                RESULT_VARIABLE status OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(status EQUAL 77)
  message("SKIPPED: ${err}")
  # ctest's SKIP_REGULAR_EXPRESSION sees this line.
  return()
endif()
if(NOT status EQUAL 0)
  message(FATAL_ERROR "rigidflex-plot failed (${status}): ${out}${err}")
endif()
string(REPLACE "," ";" plots "${PLOTS}")
foreach(name IN LISTS plots)
  set(path "${WORK}/${name}")
  if(NOT EXISTS "${path}")
    message(FATAL_ERROR "${name} was not written (script said: ${out})")
  endif()
  file(SIZE "${path}" size)
  file(READ "${path}" signature LIMIT 4 HEX)
  if(NOT signature STREQUAL "89504e47")
    message(FATAL_ERROR "${name} is not a PNG (starts with ${signature})")
  endif()
  if(size LESS 20000)
    message(FATAL_ERROR "${name} is only ${size} bytes: an empty figure?")
  endif()
  message(STATUS "${name}: ${size} bytes")
endforeach()
