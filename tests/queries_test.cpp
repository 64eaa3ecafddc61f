// Queries on replay (issue 20 item 3): every call that returns a value or writes an output runs
// with its side effects, and --queries logs what it returned. The expected values are worked
// out by hand from the spec (the state set just before, Table 4.7's conversions, §3.6.5's
// histogram bins, §2.5's error codes).
#include <gtest/gtest.h>

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "trace_io/query_log.hpp"
#include "trace_io/trace.hpp"

using namespace passim;

namespace {
const char* kHeader = "passim-trace 1\n@framebuffer 4x4 color=8 depth=16 stencil=8 double=no\n";

nlohmann::json replay_queries(const std::string& calls, QueryLog& log) {
  ReplayOptions options;
  options.queries = &log;
  (void)replay_trace_text(std::string(kHeader) + calls, "q.pass", std::filesystem::temp_directory_path(), options);
  return log.json()["queries"];
}

std::filesystem::path fresh_dir(const std::string& name) {
  const std::filesystem::path dir = std::filesystem::temp_directory_path() / name;
  std::filesystem::remove_all(dir);
  return dir;
}
}  // namespace

TEST(Queries, StateQueriesReturnWhatWasSet) {
  QueryLog log;
  const nlohmann::json q = replay_queries(
      "glViewport(1, 2, 3, 2)\n"
      "glGetIntegerv(GL_VIEWPORT, {})\n"
      "glEnable(GL_DEPTH_TEST)\n"
      "glIsEnabled(GL_DEPTH_TEST)\n"
      "glIsEnabled(GL_BLEND)\n"
      "glColor4f(0.25, 0.5, 0.75, 1)\n"
      "glGetFloatv(GL_CURRENT_COLOR, {})\n",
      log);
  ASSERT_EQ(q.size(), 4u);
  EXPECT_EQ(q[0]["at"], "q.pass:4");
  EXPECT_EQ(q[0]["call"], "glGetIntegerv(GL_VIEWPORT, {})");
  EXPECT_EQ(q[0]["outputs"]["params"], nlohmann::json({1, 2, 3, 2}));  // x, y, width, height (Table 6.6)
  EXPECT_EQ(q[1]["returned"], 1);  // GL_TRUE
  EXPECT_EQ(q[2]["returned"], 0);
  EXPECT_EQ(q[3]["outputs"]["params"], nlohmann::json({0.25, 0.5, 0.75, 1.0}));  // exact in float
}

TEST(Queries, GetErrorReturnsAndClearsTheFlag) {
  // §2.5: the first error is kept until glGetError returns it; the next call returns NO_ERROR.
  // A query that raises an error writes nothing: its entry names the error instead.
  QueryLog log;
  const nlohmann::json q = replay_queries(
      "glEnable(GL_FLOAT)\n"
      "glGetError()\n"
      "glGetError()\n"
      "glGetIntegerv(GL_FLOAT, {})\n",
      log);
  ASSERT_EQ(q.size(), 3u);
  EXPECT_EQ(q[0]["returned"], 0x0500);  // GL_INVALID_ENUM
  EXPECT_EQ(q[1]["returned"], 0);
  EXPECT_EQ(q[2]["error"], "GL_INVALID_ENUM");
  EXPECT_FALSE(q[2].contains("outputs"));
}

TEST(Queries, ReadPixelsReturnsTheClearedCodes) {
  // Clear colour (0.25, 0.5, 1, 0) at 8 bits: 0.25·255 = 63.75 -> 64, 0.5·255 = 127.5 (A1's
  // round half up) -> 128, 255, 0; read back as UNSIGNED_BYTE unchanged (Table 4.7).
  QueryLog log;
  const nlohmann::json q = replay_queries(
      "glClearColor(0.25, 0.5, 1, 0)\n"
      "glClear(GL_COLOR_BUFFER_BIT)\n"
      "glReadPixels(1, 1, 2, 1, GL_RGBA, GL_UNSIGNED_BYTE, {})\n"
      "glPixelStorei(GL_PACK_SKIP_PIXELS, 1)\n"
      "glReadPixels(0, 0, 1, 1, GL_RED, GL_UNSIGNED_BYTE, {})\n",
      log);
  ASSERT_EQ(q.size(), 2u);
  EXPECT_EQ(q[0]["outputs"]["pixels"], nlohmann::json({64, 128, 255, 0, 64, 128, 255, 0}));
  // SKIP_PIXELS 1 of one-byte groups: the value lands in the second byte, the first is untouched.
  EXPECT_EQ(q[1]["outputs"]["pixels"], nlohmann::json({0, 64}));
}

TEST(Queries, GetHistogramWithResetEmptiesTheHistogram) {
  // A 2x2 copy of the cleared colour (1, 0.5, 0, 1) through a 4-entry histogram (sink: nothing
  // drawn). §3.6.5: bin = round(c·(4 − 1)): R 1 -> 3, G 128/255·3 = 1.506 -> 2, B 0 -> 0,
  // A 1 -> 3; four pixels each. With reset = TRUE the next query finds every count 0.
  QueryLog log;
  const nlohmann::json q = replay_queries(
      "glClearColor(1, 0.5, 0, 1)\n"
      "glClear(GL_COLOR_BUFFER_BIT)\n"
      "glHistogram(GL_HISTOGRAM, 4, GL_RGBA, GL_TRUE)\n"
      "glEnable(GL_HISTOGRAM)\n"
      "glCopyPixels(0, 0, 2, 2, GL_COLOR)\n"
      "glGetHistogram(GL_HISTOGRAM, GL_TRUE, GL_RGBA, GL_UNSIGNED_INT, {})\n"
      "glGetHistogram(GL_HISTOGRAM, GL_FALSE, GL_RGBA, GL_UNSIGNED_INT, {})\n",
      log);
  ASSERT_EQ(q.size(), 2u);
  EXPECT_EQ(q[0]["outputs"]["values"], nlohmann::json({0, 0, 4, 0, 0, 0, 0, 0, 0, 4, 0, 0, 4, 0, 0, 4}));
  EXPECT_EQ(q[1]["outputs"]["values"], nlohmann::json(std::vector<int>(16, 0)));
}

TEST(Queries, MinmaxAndTexImageAreSizedByTheState) {
  // glGetMinmax: the minimum group, then the maximum. glGetTexImage of a 2x1 LUMINANCE level
  // as RGBA (§6.1.4: L in R, G = B = 0, A = 1).
  QueryLog log;
  const nlohmann::json q = replay_queries(
      "glClearColor(0.25, 0.5, 0, 1)\n"
      "glClear(GL_COLOR_BUFFER_BIT)\n"
      "glMinmax(GL_MINMAX, GL_RGBA, GL_TRUE)\n"
      "glEnable(GL_MINMAX)\n"
      "glCopyPixels(0, 0, 1, 1, GL_COLOR)\n"
      "glGetMinmax(GL_MINMAX, GL_FALSE, GL_RGBA, GL_UNSIGNED_BYTE, {})\n"
      "glDisable(GL_MINMAX)\n"
      "glTexImage2D(GL_TEXTURE_2D, 0, GL_LUMINANCE, 2, 1, 0, GL_LUMINANCE, GL_UNSIGNED_BYTE, {0, 255})\n"
      "glGetTexImage(GL_TEXTURE_2D, 0, GL_RGBA, GL_UNSIGNED_BYTE, {})\n",
      log);
  ASSERT_EQ(q.size(), 2u);
  EXPECT_EQ(q[0]["outputs"]["values"], nlohmann::json({64, 128, 0, 255, 64, 128, 0, 255}));
  EXPECT_EQ(q[1]["outputs"]["pixels"], nlohmann::json({0, 0, 0, 255, 255, 0, 0, 255}));
}

TEST(Queries, LargeArraysAreHashedAndWrittenOnlyWhenTheRunSucceeds) {
  // 4x4 RGBA = 64 values: inline; a 16-value row more (the 4x4 with ROW_LENGTH 5 addresses
  // 4·(5·3 + 4) = 76 bytes) is logged by size and hash, and its bytes written to the folder.
  const std::filesystem::path dir = fresh_dir("passim-queries-arrays");
  std::vector<std::uint8_t> expected(76, 0);
  for (int row = 0; row < 4; ++row)
    for (int px = 0; px < 4; ++px)
      for (int k = 0; k < 4; ++k) expected[static_cast<std::size_t>(4 * (5 * row + px) + k)] = k == 3 ? 255 : 0;
  {
    QueryLog log(dir);
    const nlohmann::json q = replay_queries(
        "glClearColor(0, 0, 0, 1)\n"
        "glClear(GL_COLOR_BUFFER_BIT)\n"
        "glReadPixels(0, 0, 4, 4, GL_RGBA, GL_UNSIGNED_BYTE, {})\n"
        "glPixelStorei(GL_PACK_ROW_LENGTH, 5)\n"
        "glReadPixels(0, 0, 4, 4, GL_RGBA, GL_UNSIGNED_BYTE, {})\n",
        log);
    ASSERT_EQ(q.size(), 2u);
    EXPECT_EQ(q[0]["outputs"]["pixels"].size(), 64u);
    const nlohmann::json& large = q[1]["outputs"]["pixels"];
    EXPECT_EQ(large["elements"], 76);
    EXPECT_EQ(large["type"], "GL_UNSIGNED_BYTE");
    const std::string name = large["file"];
    // Not yet committed: nothing under its final name.
    EXPECT_FALSE(std::filesystem::exists(dir / name));
    log.commit();
    std::ifstream file(dir / name, std::ios::binary);
    const std::vector<std::uint8_t> bytes{std::istreambuf_iterator<char>(file), std::istreambuf_iterator<char>()};
    EXPECT_EQ(bytes, expected);
    // FNV-1a 64 of those bytes, computed here (offset basis and prime of the FNV definition).
    std::uint64_t h = 0xcbf29ce484222325ull;
    for (std::uint8_t b : expected) h = (h ^ b) * 0x100000001b3ull;
    char hex[17];
    std::snprintf(hex, sizeof hex, "%016llx", static_cast<unsigned long long>(h));
    EXPECT_EQ(large["fnv1a"], hex);
  }
  // A run that fails (no commit) leaves no array behind.
  const std::filesystem::path failed = fresh_dir("passim-queries-failed");
  {
    QueryLog log(failed);
    EXPECT_THROW(replay_queries("glPixelStorei(GL_PACK_ROW_LENGTH, 100)\n"
                                "glReadPixels(0, 0, 4, 4, GL_RGBA, GL_UNSIGNED_BYTE, {})\n"
                                "glNoSuchCall()\n",
                                log),
                 TraceError);
  }
  EXPECT_TRUE(!std::filesystem::exists(failed) || std::filesystem::is_empty(failed));
  std::filesystem::remove_all(dir);
  std::filesystem::remove_all(failed);
}

TEST(Queries, FnvMatchesThePublishedVectors) {
  // FNV-1a 64-bit test vectors of the FNV reference (Noll): "" and "a" and "foobar".
  auto of = [](const std::string& s) { return fnv1a(std::as_bytes(std::span(s.data(), s.size()))); };
  EXPECT_EQ(of(""), 0xcbf29ce484222325ull);
  EXPECT_EQ(of("a"), 0xaf63dc4c8601ec8cull);
  EXPECT_EQ(of("foobar"), 0x85944171f73967e8ull);
}

TEST(Queries, OutputPastTheBudgetStopsTheReplayNamingTheLine) {
  QueryLog log;
  try {
    replay_queries("glReadPixels(0, 0, 2147483647, 1, GL_RGBA, GL_FLOAT, {})\n", log);
    FAIL() << "no error";
  } catch (const TraceError& e) {
    EXPECT_NE(std::string(e.what()).find("q.pass:3"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("more than the memory budget leaves room for"), std::string::npos) << e.what();
  }
}
