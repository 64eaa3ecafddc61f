# End-to-end checks of the passim command's exit codes, messages and outputs.
file(REMOVE_RECURSE ${WORK})
file(MAKE_DIRECTORY ${WORK})

function(expect_exit code)
  execute_process(COMMAND ${PASSIM} ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL code)
    message(FATAL_ERROR "passim ${ARGN}: exit ${rc}, expected ${code}\n${out}\n${err}")
  endif()
  set(LAST_ERR "${err}" PARENT_SCOPE)
  set(LAST_OUT "${out}" PARENT_SCOPE)
endfunction()

expect_exit(2 run)
expect_exit(2 frobnicate)
expect_exit(2 run a.pass --no-such-flag)
expect_exit(0 --help)
expect_exit(0 info)
if(NOT LAST_OUT MATCHES "octane-vpro8")
  message(FATAL_ERROR "passim info does not list octane-vpro8")
endif()

# A missing trace: exit 1, message names the file.
expect_exit(1 run ${WORK}/missing.pass --out ${WORK}/o1)
if(NOT LAST_ERR MATCHES "missing.pass")
  message(FATAL_ERROR "no file name in: ${LAST_ERR}")
endif()

# A malformed trace: exit 1, file:line, and nothing written.
file(WRITE ${WORK}/bad.pass "passim-trace 1\n@framebuffer 4x4\n@output early color\nglClear(GL_COLOR_BUFFER_BIT\n")
expect_exit(1 run ${WORK}/bad.pass --out ${WORK}/o2)
if(NOT LAST_ERR MATCHES "bad.pass:4: ")
  message(FATAL_ERROR "no file:line in: ${LAST_ERR}")
endif()
if(EXISTS ${WORK}/o2/early.png OR EXISTS ${WORK}/o2/counters.json)
  message(FATAL_ERROR "a failed run left output files behind")
endif()

# A GL error: reported with its line, not fatal; fatal with --strict.
file(WRITE ${WORK}/glerr.pass "passim-trace 1\n@framebuffer 4x4\nglEnable(GL_TRIANGLES)\n@output c\n")
expect_exit(0 run ${WORK}/glerr.pass --out ${WORK}/o3)
if(NOT LAST_ERR MATCHES "glerr.pass:3: GL_INVALID_ENUM raised by glEnable")
  message(FATAL_ERROR "GL error not reported: ${LAST_ERR}")
endif()
file(READ ${WORK}/o3/counters.json counters)
if(NOT counters MATCHES "GL_INVALID_ENUM")
  message(FATAL_ERROR "GL error not listed in counters.json")
endif()
expect_exit(1 run ${WORK}/glerr.pass --out ${WORK}/o4 --strict)

# --expect mismatch exits 3.
file(WRITE ${WORK}/wrong.json "{\"total\": {\"fragments_generated\": 1}}")
expect_exit(3 run ${SRC}/traces/masked-multipass.pass --out ${WORK}/o5 --expect ${WORK}/wrong.json)

# --record writes a canonical trace that replays to the same expectation.
expect_exit(0 run ${SRC}/traces/masked-multipass.pass --out ${WORK}/o6 --record ${WORK}/rec.pass)
expect_exit(0 run ${WORK}/rec.pass --out ${WORK}/o7 --expect ${SRC}/traces/masked-multipass.expected.json)
