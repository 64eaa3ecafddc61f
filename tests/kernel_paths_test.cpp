// The reference and fast paths (stages/kernel_paths.hpp) and the cross-check that compares
// them (reports/cross_check.hpp).
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "reports/cross_check.hpp"
#include "reports/report.hpp"
#include "test_util.hpp"

namespace passim {
namespace {

namespace fs = std::filesystem;

// Every example trace replays to its golden hashes and counters on the SSE2 paths (no AVX2,
// whatever the processor has) and on the reference paths, as it does on the fastest ones
// (the trace.* ctests).
TEST(KernelPaths, TheExampleTracesMeetTheirGoldensOnSse2AndOnTheReference) {
  int traces = 0;
  for (const auto& entry : fs::directory_iterator(PASSIM_SOURCE_DIR "/traces")) {
    if (entry.path().extension() != ".pass") continue;
    fs::path expected_file = entry.path();
    expected_file.replace_extension(".expected.json");
    std::ifstream in(expected_file);
    ASSERT_TRUE(in) << expected_file;
    const nlohmann::json expected = nlohmann::json::parse(in);
    for (const KernelPaths paths : {KernelPaths{KernelPaths::Simd::Sse2, true}, KernelPaths::reference()}) {
      const ScopedKernelPaths scope(paths);
      const ReplayResult run = replay_trace(entry.path());
      const auto differences = check_expectation(run_report(run, entry.path().string(), {}), expected);
      EXPECT_TRUE(differences.empty()) << entry.path().filename() << (paths.specialised ? " on SSE2" : " on the reference")
                                       << ": " << (differences.empty() ? "" : differences.front());
    }
    ++traces;
  }
  EXPECT_GE(traces, 10);
}

// A run that draws one pixel differently on the fast paths: the cross-check names the pass,
// the plane and the pixel.
ReplayResult two_passes(const KernelPaths& paths, Context::PassEndObserver observer) {
  ReplayResult r;
  r.context = std::make_unique<Context>(test::small_config(8, 4, 8));
  Context& ctx = *r.context;
  ctx.set_pass_end_observer(std::move(observer));
  test::window_projection(ctx);
  ctx.glPushGroupMarkerEXT(0, "same");
  ctx.glRecti(0, 0, 8, 4);
  ctx.glPopGroupMarkerEXT();
  ctx.glPushGroupMarkerEXT(0, "differs");
  ctx.glColor3f(1.0f, 0.0f, 0.0f);
  ctx.glRecti(5, 2, 6, 3);  // pixel (5, 2)
  if (paths.specialised) ctx.glColor3f(0.0f, 1.0f, 0.0f), ctx.glRecti(5, 2, 6, 3);
  ctx.glPopGroupMarkerEXT();
  return r;
}

TEST(CrossCheck, NamesThePassThePlaneAndThePixelThatDiffer) {
  const CrossCheckReport report = cross_check(two_passes);
  EXPECT_FALSE(report.same);
  EXPECT_EQ(report.checkpoints, 2u);
  EXPECT_NE(report.difference.find("pass 1 'differs'"), std::string::npos) << report.difference;
  EXPECT_NE(report.difference.find("pixel (5, 2) channel R: reference 255, fast 0"), std::string::npos)
      << report.difference;
}

TEST(CrossCheck, NamesTheCounterThatDiffersWhenThePlanesAgree) {
  const CrossCheckReport report = cross_check([](const KernelPaths& paths, Context::PassEndObserver observer) {
    ReplayResult r;
    r.context = std::make_unique<Context>(test::small_config(4, 4, 8));
    r.context->set_pass_end_observer(std::move(observer));
    r.context->glPushGroupMarkerEXT(0, "clears");
    r.context->glClear(GL_COLOR_BUFFER_BIT);
    if (paths.specialised) r.context->glClear(GL_COLOR_BUFFER_BIT);  // the same planes, one clear more
    r.context->glPopGroupMarkerEXT();
    return r;
  });
  EXPECT_FALSE(report.same);
  // The first counter in the list's order that differs: 16 pixels x 4 channels x 8 bits per clear.
  EXPECT_NE(report.difference.find("pass 0 'clears': counter color_bits_written: reference 512, fast 1024"),
            std::string::npos)
      << report.difference;
}

TEST(CrossCheck, AgreesWhenBothPathsDrawTheSame) {
  const CrossCheckReport report = cross_check([](const KernelPaths& paths, Context::PassEndObserver observer) {
    return two_passes(KernelPaths{paths.simd, false}, std::move(observer));
  });
  EXPECT_TRUE(report.same) << report.difference;
  EXPECT_EQ(report.checkpoints, 2u);
}

}  // namespace
}  // namespace passim
