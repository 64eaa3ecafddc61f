# The HTML report opened in headless Chromium: it renders without console errors, the
# charts and the image are there, and a screenshot is taken.
file(REMOVE_RECURSE ${WORK})
file(MAKE_DIRECTORY ${WORK})
execute_process(COMMAND ${PASSIM} study precision --program pcf --filter 2x2 --scene edges --size 160x120
                        --bits 6,8,12 -q --out ${WORK}/study RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "the study failed")
endif()
execute_process(COMMAND ${PASSIM} report html ${WORK}/study --cost octane-vpro8 RESULT_VARIABLE rc)
if(NOT rc EQUAL 0 OR NOT EXISTS ${WORK}/study/report.html)
  message(FATAL_ERROR "passim report html failed")
endif()
set(FLAGS --headless=new --no-sandbox --disable-gpu --hide-scrollbars --window-size=1200,2400)
execute_process(COMMAND ${CHROMIUM} ${FLAGS} --enable-logging=stderr --v=0 --screenshot=${WORK}/report.png
                        file://${WORK}/study/report.html
                RESULT_VARIABLE rc ERROR_VARIABLE err OUTPUT_QUIET TIMEOUT 120)
if(NOT rc EQUAL 0 OR NOT EXISTS ${WORK}/report.png)
  message(FATAL_ERROR "chromium could not render the report (exit ${rc}):\n${err}")
endif()
# Console messages appear as INFO:CONSOLE lines; any error or uncaught exception fails.
string(REGEX MATCH "CONSOLE[^\n]*([Ee]rror|Uncaught)[^\n]*" console "${err}")
if(console)
  message(FATAL_ERROR "console error in the report: ${console}")
endif()
execute_process(COMMAND ${CHROMIUM} ${FLAGS} --dump-dom file://${WORK}/study/report.html
                RESULT_VARIABLE rc OUTPUT_VARIABLE dom ERROR_QUIET TIMEOUT 120)
string(REGEX MATCHALL "<svg" charts "${dom}")
list(LENGTH charts chart_count)
if(chart_count LESS 4 OR NOT dom MATCHES "data:image/png;base64," OR NOT dom MATCHES "frames per second")
  message(FATAL_ERROR "the rendered page lacks its charts (${chart_count}), image or cost table")
endif()
file(SIZE ${WORK}/report.png shot_size)
message(STATUS "report rendered: ${chart_count} charts, screenshot ${WORK}/report.png (${shot_size} bytes)")
