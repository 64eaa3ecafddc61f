// The .pass format: parse errors name file and line; recording then replaying gives the
// same bits and counters; floats survive the text round trip exactly.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "reports/report.hpp"
#include "trace_io/trace.hpp"
#include "test_util.hpp"

using namespace passim;

namespace {

ReplayResult replay(const std::string& text, const ReplayOptions& options = {}) {
  return replay_trace_text(text, "t.pass", PASSIM_SOURCE_DIR "/traces", options);
}

// Expects the text to fail at `line` with a message containing `fragment`.
void expect_error(const std::string& text, int line, const std::string& fragment) {
  try {
    replay(text);
    ADD_FAILURE() << "no error for:\n" << text;
  } catch (const TraceError& e) {
    EXPECT_EQ(e.line, line) << e.what();
    EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos) << e.what();
    EXPECT_EQ(std::string(e.what()).rfind("t.pass:" + std::to_string(line) + ": ", 0), 0u) << e.what();
  }
}

const char* kHeader = "passim-trace 1\n@framebuffer 8x8 color=8 double=no\n";

}  // namespace

TEST(TraceParse, ErrorsNameTheLine) {
  expect_error("", 1, "first line");
  expect_error("passim-trace 2\n", 1, "version 2 is not supported");
  expect_error("glClear(GL_COLOR_BUFFER_BIT)\n", 1, "passim-trace 1");
  const std::string h = kHeader;  // lines 1-2
  expect_error(h + "glFrobnicate(1)\n", 3, "unknown call 'glFrobnicate'");
  expect_error(h + "\n# comment\nglClear(GL_COLOUR_BUFFER_BIT)\n", 5, "unknown enum 'GL_COLOUR_BUFFER_BIT'");
  expect_error(h + "glClearColor(0, 0, 0)\n", 3, "takes 4 arguments, the trace gives 3");
  expect_error(h + "glClearColor(0, 0, zero, 1)\n", 3, "'zero' is not a number");
  expect_error(h + "glViewport(0, 0, 1.5, 4)\n", 3, "not a whole number");
  expect_error(h + "glViewport(0, 0, 99999999999, 4)\n", 3, "out of range");
  expect_error(h + "glLoadMatrixf({1, 0, 0})\n", 3, "needs 16 values, the trace gives 3");
  expect_error(h + "glLightfv(GL_LIGHT0, GL_POSITION, {1, 2})\n", 3, "needs 4 values");
  expect_error(h + "glClear(GL_COLOR_BUFFER_BIT\n\n", 3, "not closed");
  expect_error(h + "glClear(GL_COLOR_BUFFER_BIT))\n", 3, "unbalanced");
  expect_error(h + "glPushGroupMarkerEXT(0, \"open)\n", 3, "unterminated string");
  expect_error(h + "glClear(GL_COLOR_BUFFER_BIT) extra\n", 3, "unexpected text");
  expect_error(h + "glVertexPointer(3, GL_FLOAT, 0, file(\"missing.f32\"))\n", 3, "cannot read side file");
  expect_error(h + "@output a color\n@output a color\n", 4, "already used");
  expect_error(h + "@output ../evil color\n", 3, "may hold only");
  expect_error(h + "@frobnicate\n", 3, "unknown directive");
  expect_error("passim-trace 1\n@framebuffer 5000x10\n", 2, "outside 1..4096");
  expect_error("passim-trace 1\n@framebuffer 8x8 color=17\n", 2, "colour width 17");
  expect_error("passim-trace 1\n@framebuffer 8x8 depth=40\n", 2, "depth width 40");
  expect_error("passim-trace 1\n@profile octane\n", 2, "unknown machine profile 'octane'");
  expect_error(h + "glClear(GL_COLOR_BUFFER_BIT)\n@framebuffer 4x4\n", 4, "must come before the first GL call");
  // Found by fuzzing: an enabled array that was never given a pointer (read through null).
  expect_error(h + "glEnableClientState(GL_VERTEX_ARRAY)\nglEnableClientState(GL_COLOR_ARRAY)\n"
                   "glVertexPointer(2, GL_FLOAT, 0, {0, 0, 1, 0, 0, 1})\nglDrawArrays(GL_TRIANGLES, 0, 3)\n",
               6, "color array enabled but no color pointer given");
  expect_error(h + "glEnableClientState(GL_VERTEX_ARRAY)\nglVertexPointer(2, GL_FLOAT, 0, {0, 0, 1, 0})\n"
                   "glDrawArrays(GL_TRIANGLES, 0, 3)\n",
               5, "reads element 2 of the vertex array, but only 16 bytes were given");
  expect_error(h + "glDrawElements(GL_TRIANGLES, 3, GL_UNSIGNED_BYTE, {0, 1})\n", 3, "(indices) needs 3 values, the trace gives 2");
  expect_error(h + "glColor4ub(256, 0, 0, 0)\n", 3, "argument 1 (256) is out of range");
  // Each integer type's own range (GLbyte, GLshort, GLushort), in scalars and arrays.
  expect_error(h + "glColor3b(0, 128, 0)\n", 3, "argument 2 (128) is out of range");
  expect_error(h + "glColor3b(-129, 0, 0)\n", 3, "argument 1 (-129) is out of range");
  expect_error(h + "glVertex2s(0, 32768)\n", 3, "argument 2 (32768) is out of range");
  expect_error(h + "glColor3us(65536, 0, 0)\n", 3, "argument 1 (65536) is out of range");
  expect_error(h + "glColor3us(-1, 0, 0)\n", 3, "argument 1 (-1) is out of range");
  expect_error(h + "glNormal3bv({0, 0, 200})\n", 3, "array element 3 '200' is not a valid GL_BYTE");
  expect_error(h + "glVertex3sv({0, -40000, 0})\n", 3, "array element 2 '-40000' is not a valid GL_SHORT");
  expect_error(h + "glTexCoord4sv({1, 2, 3})\n", 3, "needs 4 values, the trace gives 3");
  expect_error(h + "glRectsv({0, 0}, {1})\n", 3, "(v2) needs 2 values, the trace gives 1");
  expect_error(h + "glInterleavedArrays(GL_V2F, 0, {0, 0})\nglDrawArrays(GL_POINTS, 0, 1)\n", 4,
               "reads element 0 of the vertex array, but only 2 bytes were given");
}

// The variants added for §2.7 (byte, short, unsigned short and unsigned int components, every
// size, scalar and vector) parse, draw what their float forms draw, and record as they were
// written (the recorder's text replays to the same image).
TEST(TraceParse, EveryIntegerTypeAndSizeParsesAndRecords) {
  const std::string h = std::string("passim-trace 1\n@framebuffer 8x8 color=8 depth=0 stencil=0 accum=0 double=no\n") +
                        "glMatrixMode(GL_PROJECTION)\nglOrtho(0, 8, 0, 8, -1, 1)\nglMatrixMode(GL_MODELVIEW)\n";
  const std::string floats = h +
      "glBegin(GL_TRIANGLES)\nglColor3f(1, 0, 1)\nglNormal3f(0, 0, 1)\nglTexCoord2f(1, 2)\nglVertex2f(0, 0)\n"
      "glColor4f(0, 1, 1, 1)\nglVertex3f(8, 0, 0)\nglColor3f(1, 1, 0)\nglVertex4f(0, 8, 0, 1)\nglEnd()\n"
      "glRectf(6, 6, 8, 8)\nglRasterPos2f(1, 1)\n@output img color\n";
  const std::string integers = h +
      "glBegin(GL_TRIANGLES)\nglColor3b(127, -128, 127)\nglNormal3s(0, 0, 32767)\nglTexCoord2s(1, 2)\nglVertex2s(0, 0)\n"
      "glColor4usv({0, 65535, 65535, 65535})\nglVertex3sv({8, 0, 0})\nglColor3ui(4294967295, 4294967295, 0)\n"
      "glVertex4i(0, 8, 0, 1)\nglEnd()\nglRectsv({6, 6}, {8, 8})\nglRasterPos2s(1, 1)\n@output img color\n";
  const ReplayResult a = replay(floats), b = replay(integers);
  ASSERT_EQ(a.images.size(), 1u);
  ASSERT_EQ(b.images.size(), 1u);
  EXPECT_EQ(a.images[0].codes, b.images[0].codes);
  EXPECT_TRUE(b.context->error_log().empty());
  ReplayOptions options;
  std::ostringstream text;
  TraceWriter writer(text);
  options.record = &writer;
  const ReplayResult c = replay(integers, options);
  const std::string recorded = text.str();
  for (const char* line : {"glColor3b(127, -128, 127)", "glNormal3s(0, 0, 32767)", "glTexCoord2s(1, 2)",
                           "glColor4usv({0, 65535, 65535, 65535})", "glVertex3sv({8, 0, 0})",
                           "glColor3ui(4294967295, 4294967295, 0)", "glRectsv({6, 6}, {8, 8})", "glRasterPos2s(1, 1)"})
    EXPECT_NE(recorded.find(line), std::string::npos) << line << " in\n" << recorded;
  EXPECT_EQ(replay(recorded).images[0].codes, a.images[0].codes);
}

// Item 3 of issue 20: a .pass trace's queries run (with their side effects; --queries logs
// their results), so a .pass replay skips nothing and has nothing to summarise.
TEST(TraceParse, QueriesRunRatherThanBeingSkipped) {
  const std::string text = std::string(kHeader) + "glGetIntegerv(GL_VIEWPORT, {})\nglClear(GL_COLOR_BUFFER_BIT)\n"
                                                  "glGetIntegerv(GL_VIEWPORT, {})\nglGetFloatv(GL_CURRENT_COLOR, {})\n";
  ReplayOptions options;
  std::ostringstream diagnostics;
  options.diagnostics = &diagnostics;
  const ReplayResult r = replay(text, options);
  EXPECT_EQ(diagnostics.str(), "");
  EXPECT_TRUE(r.skipped.empty());
  EXPECT_TRUE(run_report(r, "t.pass", {})["skipped_calls"].empty());
}

TEST(TraceParse, AcceptsApitraceDumpShapes) {
  // Leading call numbers, "name = value" arguments, recorded return values, hex floats.
  const std::string text = std::string(kHeader) +
                           "12 glClearColor(red = 0x1p-1, green = 0.25, blue = 0, alpha = 1)\n"
                           "13 glClear(mask = GL_COLOR_BUFFER_BIT)\n"
                           "14 glGetError() = GL_NO_ERROR\n"
                           "@output c color GL_FRONT\n";
  ReplayResult r = replay(text);
  EXPECT_EQ(test::pixel(*r.context, 3, 3), (std::array<std::uint32_t, 4>{128, 64, 0, 255}));
}

TEST(TraceParse, GlErrorsAreReportedNotFatalUnlessStrict) {
  const std::string text = std::string(kHeader) + "glEnable(GL_TRIANGLES)\nglClear(GL_COLOR_BUFFER_BIT)\n";
  std::ostringstream diag;
  ReplayOptions opt;
  opt.diagnostics = &diag;
  ReplayResult r = replay(text, opt);
  EXPECT_EQ(r.context->error_log().size(), 1u);
  EXPECT_NE(diag.str().find("t.pass:3: GL_INVALID_ENUM raised by glEnable"), std::string::npos) << diag.str();
  opt.strict = true;
  opt.diagnostics = nullptr;
  try {
    replay(text, opt);
    ADD_FAILURE() << "strict replay did not fail";
  } catch (const TraceError& e) {
    EXPECT_EQ(e.line, 3);
  }
}

TEST(TraceFormat, FloatsRoundTripExactly) {
  // Awkward floats (shortest round-trip text) survive writing and parsing bit for bit.
  const float values[] = {0.1f, 1.0f / 3.0f, 16777217.0f, 1e-38f, 3.4028235e38f, -0.0f, 1.17549435e-38f,
                          std::nextafter(1.0f, 2.0f)};
  Context ctx(test::small_config(4, 4));
  std::ostringstream out;
  TraceWriter w(out);
  TraceSettings s;
  s.framebuffer = ctx.config();
  w.write_header(s);
  ctx.set_call_sink(&w);
  for (float v : values) ctx.glClearColor(v, v, v, v);
  std::istringstream in(out.str());
  std::string line;
  std::size_t k = 0;
  while (std::getline(in, line)) {
    if (line.rfind("glClearColor(", 0) != 0) continue;
    const std::string first = line.substr(13, line.find(',') - 13);
    float parsed = std::strtof(first.c_str(), nullptr);
    ASSERT_LT(k, std::size(values));
    EXPECT_EQ(std::memcmp(&parsed, &values[k], 4), 0) << line;
    ++k;
  }
  EXPECT_EQ(k, std::size(values));
}

namespace {
// A program that uses the spine's features, for the record -> replay identity.
void program(Context& c) {
  const float verts[] = {1, 1, 0, 30, 2, 0, 16, 28, 0, 4, 20, 0.5f};
  const float colors[] = {1, 0, 0, 0, 1, 0, 0, 0, 1, 1, 1, 0};
  c.glPushGroupMarkerEXT(0, "setup");
  c.glMatrixMode(GL_PROJECTION);
  c.glLoadIdentity();
  c.glOrtho(0, 32, 0, 32, -1, 1);
  c.glMatrixMode(GL_MODELVIEW);
  c.glLoadIdentity();
  c.glClearColor(0.2f, 0.1f, 0.3f, 1);
  c.glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  c.glPopGroupMarkerEXT();
  c.glPushGroupMarkerEXT(0, "arrays");
  c.glEnable(GL_DEPTH_TEST);
  c.glEnableClientState(GL_VERTEX_ARRAY);
  c.glEnableClientState(GL_COLOR_ARRAY);
  c.glVertexPointer(3, GL_FLOAT, 0, verts);
  c.glColorPointer(3, GL_FLOAT, 0, colors);
  c.glDrawArrays(GL_TRIANGLE_FAN, 0, 4);
  const GLuint idx[] = {0, 2, 3};
  c.glNewList(7, GL_COMPILE);
  c.glDrawElements(GL_TRIANGLES, 3, GL_UNSIGNED_INT, idx);
  c.glEndList();
  c.glDisableClientState(GL_COLOR_ARRAY);
  c.glPopGroupMarkerEXT();
  c.glPushGroupMarkerEXT(0, "lit list");
  c.glEnable(GL_LIGHTING);
  c.glEnable(GL_LIGHT0);
  c.glTranslatef(0.5f, 0.25f, 0);
  c.glDepthFunc(GL_LEQUAL);
  c.glCallList(7);
  c.glEnable(GL_BLEND);
  c.glBlendFunc(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA);
  c.glDisable(GL_LIGHTING);
  c.glColor4f(1, 1, 1, 0.3f);
  c.glRotatef(10, 0, 0, 1);
  c.glBegin(GL_QUAD_STRIP);
  for (int k = 0; k < 5; ++k) {
    c.glVertex3f(4.0f + 5.5f * k, 10, -0.25f);
    c.glVertex3f(4.0f + 5.5f * k, 22, -0.25f);
  }
  c.glEnd();
  c.glEnable(GL_POLYGON_OFFSET_FILL);
  c.glPolygonOffset(1.5f, 2);
  c.glBegin(GL_POLYGON);
  c.glVertex2f(3, 3);
  c.glVertex2f(12, 4);
  c.glVertex2f(14, 11);
  c.glVertex2f(6, 13);
  c.glVertex2f(2, 8);
  c.glEnd();
  c.glPopGroupMarkerEXT();
}
}  // namespace

TEST(TraceRecord, RecordedProgramReplaysToIdenticalBitsAndCounters) {
  for (int bits : {8, 12}) {
    FramebufferConfig cfg = test::small_config(32, 32, bits);
    Context original(cfg);
    test::Recording recording(original);
    const std::ostringstream& text = recording.text;
    program(original);
    recording.writer.output("final", "color", "GL_FRONT");

    ReplayResult r = replay(text.str());
    EXPECT_EQ(r.context->framebuffer().color[0].rgba, original.framebuffer().color[0].rgba) << text.str();
    EXPECT_EQ(r.context->framebuffer().depth, original.framebuffer().depth);
    ASSERT_EQ(r.context->passes().size(), original.passes().size());
    for (std::size_t k = 0; k < original.passes().size(); ++k) {
      EXPECT_EQ(r.context->passes()[k].label, original.passes()[k].label);
      EXPECT_TRUE(r.context->passes()[k].counters == original.passes()[k].counters) << original.passes()[k].label;
    }
    // Recording the replay again gives the same text: the format is canonical.
    std::ostringstream again;
    TraceWriter writer2(again);
    ReplayOptions opt;
    opt.record = &writer2;
    replay(text.str(), opt);
    EXPECT_EQ(again.str(), text.str());
  }
}

TEST(TraceRecord, ExampleTracesReRecordToTheSameBits) {
  for (const char* name : {"masked-multipass.pass", "lit-scene.pass"}) {
    const std::filesystem::path path = std::filesystem::path(PASSIM_SOURCE_DIR) / "traces" / name;
    std::ostringstream text;
    TraceWriter writer(text);
    ReplayOptions opt;
    opt.record = &writer;
    ReplayResult first = replay_trace(path, opt);
    ReplayResult second = replay_trace_text(text.str(), "rerecorded.pass", path.parent_path());
    ASSERT_EQ(first.images.size(), second.images.size()) << name;
    for (std::size_t k = 0; k < first.images.size(); ++k) EXPECT_EQ(first.images[k].hash, second.images[k].hash) << name;
    EXPECT_TRUE(first.context->total_counters() == second.context->total_counters()) << name;
  }
}

// Found by fuzzing (an apitrace corpus input): a pointer call the GL rejects (size 5 is
// GL_INVALID_VALUE, §2.8) has no effect, so the array still reads the earlier data, which the
// replayer must keep. The earlier triangle covers the lower-left half of the 4x4 window:
// 6 pixel centres with x + y < 3 (as in MeshDirectiveDrawsAnObjFile).
TEST(TraceParse, RejectedPointerCallKeepsTheEarlierArray) {
  const std::string text = "passim-trace 1\n@framebuffer 4x4 color=8 double=no\n"
                           "glMatrixMode(GL_PROJECTION)\nglOrtho(0, 4, 0, 4, -1, 1)\n"
                           "glEnableClientState(GL_VERTEX_ARRAY)\n"
                           "glVertexPointer(2, GL_FLOAT, 0, {0, 0, 4, 0, 0, 4})\n"
                           "glVertexPointer(5, GL_FLOAT, 0, {9, 9, 9, 9, 9})\n"
                           "glDrawArrays(GL_TRIANGLES, 0, 3)\n";
  ReplayResult r = replay(text);
  ASSERT_EQ(r.context->error_log().size(), 1u);
  EXPECT_EQ(r.context->error_log()[0].error, static_cast<GLenum>(GL_INVALID_VALUE));
  EXPECT_EQ(r.context->total_counters().fragments_generated, 6u);
}

TEST(TraceParse, MeshDirectiveDrawsAnObjFile) {
  // A one-triangle OBJ covering the lower-left half of a 4x4 window (ortho 0..4):
  // centres with x + y < 3 (x + y = 3 lies on the hypotenuse, a right/top edge): 6 fragments.
  const std::filesystem::path dir = std::filesystem::temp_directory_path() / "passim-mesh-test";
  std::filesystem::create_directories(dir);
  {
    std::ofstream obj(dir / "tri.obj");
    obj << "v 0 0 0\nv 4 0 0\nv 0 4 0\nvn 0 0 1\nf 1//1 2//1 3//1\n";
  }
  const std::string text = "passim-trace 1\n@framebuffer 4x4 color=8 double=no\n"
                           "glMatrixMode(GL_PROJECTION)\nglOrtho(0, 4, 0, 4, -1, 1)\n@mesh \"tri.obj\"\n";
  ReplayResult r = replay_trace_text(text, "mesh.pass", dir);
  EXPECT_EQ(r.context->total_counters().fragments_generated, 6u);
  EXPECT_EQ(r.context->total_counters().primitives_in, 1u);
  try {
    replay_trace_text("passim-trace 1\n@mesh \"missing.obj\"\n", "mesh.pass", dir);
    ADD_FAILURE() << "a missing mesh was accepted";
  } catch (const TraceError& e) {
    EXPECT_EQ(e.line, 2);
  }
}

// The vector and integer variants draw exactly what their scalar forms draw (Table 2.6 for
// unsigned bytes: c / 255).
TEST(TraceParse, VectorAndIntegerVariantsEqualTheirScalarForms) {
  const std::string h = std::string("passim-trace 1\n@framebuffer 8x8 color=8 depth=0 stencil=0 accum=0 double=no\n") +
                        "glMatrixMode(GL_PROJECTION)\nglOrtho(0, 8, 0, 8, -1, 1)\nglMatrixMode(GL_MODELVIEW)\n";
  const std::string scalar = h +
      "glBegin(GL_TRIANGLES)\nglColor3ub(51, 102, 153)\nglNormal3d(0, 0, 1)\nglTexCoord2d(0.5, 0.25)\n"
      "glVertex2d(0, 0)\nglColor4ub(10, 20, 30, 40)\nglVertex3d(8, 0, 0)\nglColor3d(0.5, 0.25, 1)\nglTexCoord2i(1, 2)\n"
      "glVertex2i(0, 8)\nglColor4d(1, 0.5, 0, 1)\nglTexCoord3f(1, 2, 3)\nglVertex2f(8, 8)\nglTexCoord4f(1, 2, 3, 4)\n"
      "glVertex3i(8, 0, 0)\nglVertex2f(0, 8)\nglEnd()\n@output img color\n";
  const std::string vector = h +
      "glBegin(GL_TRIANGLES)\nglColor3ubv({51, 102, 153})\nglNormal3dv({0, 0, 1})\nglTexCoord2dv({0.5, 0.25})\n"
      "glVertex2dv({0, 0})\nglColor4ubv({10, 20, 30, 40})\nglVertex3dv({8, 0, 0})\nglColor3dv({0.5, 0.25, 1})\n"
      "glTexCoord2i(1, 2)\nglVertex2iv({0, 8})\nglColor4dv({1, 0.5, 0, 1})\nglTexCoord3fv({1, 2, 3})\nglVertex2f(8, 8)\n"
      "glTexCoord4fv({1, 2, 3, 4})\nglVertex3iv({8, 0, 0})\nglVertex2f(0, 8)\nglEnd()\n@output img color\n";
  const ReplayResult a = replay_trace_text(scalar, "scalar.pass", "."), b = replay_trace_text(vector, "vector.pass", ".");
  ASSERT_EQ(a.images.size(), 1u);
  ASSERT_EQ(b.images.size(), 1u);
  EXPECT_EQ(a.images[0].codes, b.images[0].codes);
  EXPECT_TRUE(a.context->error_log().empty());
  // Pixel (0, 0), centre (0.5, 0.5), of the first triangle (0,0) (8,0) (0,8): weights 7/8,
  // 1/16, 1/16 of red codes 51, 10 and 128 (0.5 rounded up, A1 and A4):
  // 44.625 + 0.625 + 8 = 53.25 -> 53.
  EXPECT_EQ(a.images[0].codes[0], 53u);
}
