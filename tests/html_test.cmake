# The HTML report opened in headless Chromium at 1200 px: it renders without console errors;
# its first figure is the 8-against-12-bit headline; every chart has its axes titled and more
# than two tick labels on each axis; no table is wider than the page and the page does not
# scroll sideways; the cost and the held-out check against the paper are there. A screenshot
# is kept (html-work/report.png).
file(REMOVE_RECURSE ${WORK})
file(MAKE_DIRECTORY ${WORK})
execute_process(COMMAND ${PASSIM} study precision --program pcf --filter 2x2 --scene edges --size 160x120
                        --bits 6,8,12 --bias 0,0.5,1 --figures none -q --out ${WORK}/study RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "the study failed")
endif()
execute_process(COMMAND ${PASSIM} report html ${WORK}/study --cost octane-vpro8,o2 -q RESULT_VARIABLE rc
                ERROR_VARIABLE err)
if(NOT rc EQUAL 0 OR NOT EXISTS ${WORK}/study/report.html)
  message(FATAL_ERROR "passim report html failed:\n${err}")
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

# The measurements, by a script run in a copy of the page (the report itself has none): the
# laid-out page at 1200 px, as a reader's browser lays it out.
file(READ ${WORK}/study/report.html page)
string(REPLACE "</body>" "<script>
const problems = [];
const charts = [...document.querySelectorAll('svg.chart')];
if (charts.length < 5) problems.push('only ' + charts.length + ' charts');
const first = document.querySelector('figure');
if (!first || first.id !== '8_vs_12_bits') problems.push('the first figure is ' + (first && first.id));
for (const svg of charts) {
  const name = svg.closest('figure').id;
  const axes = [...svg.querySelectorAll('g[id^=axes_]')];
  if (axes.length === 0) problems.push(name + ': no axes');
  axes.forEach((ax, k) => {
    const text = sel => [...ax.querySelectorAll(sel)].map(t => t.textContent.trim()).filter(t => t.length > 0);
    const xt = text('[id=x-title] text'), yt = text('[id=y-title] text');
    const xticks = text('g[id^=xtick_] text'), yticks = text('g[id^=ytick_] text');
    if (xt.length === 0 || yt.length === 0) problems.push(name + ' axes ' + k + ': an axis without a title');
    if (xticks.length <= 2 || yticks.length <= 2)
      problems.push(name + ' axes ' + k + ': ' + xticks.length + ' x and ' + yticks.length + ' y tick labels');
    const box = ax.getBoundingClientRect();
    if (box.width < 100) problems.push(name + ' axes ' + k + ': drawn ' + Math.round(box.width) + ' px wide');
  });
}
const page = document.documentElement.clientWidth;
if (document.documentElement.scrollWidth > page) problems.push('the page scrolls sideways: ' + document.documentElement.scrollWidth + ' > ' + page);
document.querySelectorAll('table').forEach((t, k) => {
  const r = t.getBoundingClientRect().right;
  if (r > page) problems.push('table ' + k + ' (' + t.className + ') ends at ' + Math.round(r) + ' px, past ' + page);
});
const out = document.createElement('pre');
out.id = 'check';
out.textContent = problems.length ? 'PROBLEMS: ' + problems.join('; ') : 'CHECK OK ' + charts.length + ' charts';
document.body.appendChild(out);
</script></body>" page "${page}")
file(WRITE ${WORK}/measured.html "${page}")
execute_process(COMMAND ${CHROMIUM} ${FLAGS} --virtual-time-budget=5000 --dump-dom file://${WORK}/measured.html
                RESULT_VARIABLE rc OUTPUT_VARIABLE dom ERROR_QUIET TIMEOUT 120)
string(REGEX MATCH "<pre id=\"check\">[^<]*</pre>" check "${dom}")
if(NOT check MATCHES "CHECK OK")
  message(FATAL_ERROR "the report as laid out at 1200 px: ${check}")
endif()
foreach(needed "frames per second" "held out" "Fig. 8 shadow map" "8 against 12 bits" "bias_<wbr>8bit_<wbr>steps")
  string(FIND "${dom}" "${needed}" at)
  if(at EQUAL -1)
    message(FATAL_ERROR "the rendered page lacks '${needed}'")
  endif()
endforeach()
file(SIZE ${WORK}/report.png shot_size)
message(STATUS "report rendered: ${check}, screenshot ${WORK}/report.png (${shot_size} bytes)")
