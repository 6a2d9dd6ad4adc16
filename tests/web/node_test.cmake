# Runs `NODE --test DIR` (cmake -P): prints "SKIPPED: …" and succeeds when REQUIRE (a path, e.g.
# web/node_modules) is missing, otherwise fails when the tests fail.
if(NOT EXISTS "${REQUIRE}")
  message("SKIPPED: ${REQUIRE} missing (run `npm ci` in web/)")
  return()
endif()
execute_process(COMMAND "${NODE}" --test "${DIR}" RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "node --test ${DIR} failed (${rc})")
endif()
