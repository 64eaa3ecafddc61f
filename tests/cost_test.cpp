// The cost model (docs/cost-model.md): arithmetic by hand, and the VPro fit against the
// paper's published frame rates.
#include <gtest/gtest.h>

#include "reports/cost.hpp"
#include "programs/programs.hpp"
#include "reports/paper_check.hpp"

namespace passim {
namespace {

TEST(CostModel, APassTakesItsSlowestStagePlusTheOverhead) {
  MachineProfile m;
  m.rates.vertices = 1e6;
  m.rates.triangles = 5e5;
  m.rates.fragments = 1e8;
  m.rates.framebuffer_bytes = 1e9;
  m.rates.pixels = 1e7;
  m.rates.color_table = 2e6;
  m.rates.convolution[0] = 4e6;
  m.rates.convolution[1] = 1e6;
  m.rates.pass_overhead = 1e-4;
  Pass p;
  p.label = "test";
  p.counters.vertices = 3000;              // 3 ms
  p.counters.triangles_rasterized = 1000;  // 2 ms
  p.counters.fragments_generated = 100000;  // 1 ms
  p.counters.color_bits_written = 8u * 4000000u;  // 4 MB: 4 ms
  PassCost c = pass_cost(p, m);
  EXPECT_EQ(c.bound, CostStage::Framebuffer);
  EXPECT_DOUBLE_EQ(c.seconds[static_cast<int>(CostStage::Geometry)], 3e-3);
  EXPECT_DOUBLE_EQ(c.seconds[static_cast<int>(CostStage::Setup)], 2e-3);
  EXPECT_DOUBLE_EQ(c.total, 4e-3 + 1e-4);
  // The pixel path is as slow as its slowest operation: 10,000 pixels at 10 M/s is 1 ms,
  // through a colour table at 2 M/s 5 ms.
  Pass q;
  q.counters.pixels_transferred = 10000;
  q.counters.color_table_lookups = 10000;
  EXPECT_DOUBLE_EQ(pass_cost(q, m).total, 5e-3 + 1e-4);
  // A 5x5 convolution (25 taps per pixel) runs at the 5x5 rate; 4x4 (16 taps) is nearest
  // 3x3 (9) and scaled by taps: 4 M/s · 9/16.
  Pass r;
  r.counters.pixels_convolved = 1000;
  r.counters.convolution_taps = 25000;
  EXPECT_DOUBLE_EQ(pass_cost(r, m).seconds[static_cast<int>(CostStage::Convolution)], 1e-3);
  r.counters.convolution_taps = 16000;
  EXPECT_DOUBLE_EQ(pass_cost(r, m).seconds[static_cast<int>(CostStage::Convolution)], 1000.0 / (4e6 * 9.0 / 16.0));
  // A pass without work costs nothing, not even the overhead.
  EXPECT_EQ(pass_cost(Pass{}, m).total, 0.0);
}

// The six published frame rates' runs on the VPro, made once for the tests below.
const std::vector<std::vector<Pass>>& vpro_runs() {
  static const std::vector<std::vector<Pass>> runs = published_runs(*find_profile("octane-vpro8"));
  return runs;
}

TEST(CostModel, TheProfilesRatesReproduceFigure7ItWasFittedTo) {
  // A check of the fit, not of the model: octane-vpro8's free rates were fitted to Figure 7's
  // four published ranges (Brabec & Seidel §5: 25-30, about 10, 15-20, about 5 fps), so its
  // predictions lie inside them, in the paper's order.
  const MachineProfile& vpro = *find_profile("octane-vpro8");
  std::vector<double> fps;
  for (std::size_t k = 0; k < 4; ++k) {
    const PublishedFrameRate& r = published_frame_rates()[k];
    fps.push_back(frame_cost(vpro_runs()[k], vpro).fps());
    EXPECT_GE(fps.back(), r.low) << r.what;
    EXPECT_LE(fps.back(), r.high) << r.what;
  }
  EXPECT_GT(fps[0], fps[2]);  // shadow map > fast PCF 2x2 > PCF 2x2 > fast PCF 4x4
  EXPECT_GT(fps[2], fps[1]);
  EXPECT_GT(fps[1], fps[3]);
}

TEST(CostModel, HeldOutPredictionsMissAsMeasured) {
  // The model's quality (docs/cost-model.md, "Leave-one-out"): each published rate predicted by
  // rates fitted to the other five. The misses below are the measured ones (a regression
  // value, labelled as such: they changed only if the model, the runs or the fit changed), to
  // ±3 percentage points. They are poor for PCF 2x2 and Figure 8's shadow map: the model does
  // not predict the paper out of sample.
  const MachineProfile& vpro = *find_profile("octane-vpro8");
  const std::vector<PaperPrediction> p = paper_predictions(vpro, vpro_runs());
  const double measured[] = {-0.33, +0.48, -0.02, -0.08, +0.51, 0.00};
  ASSERT_EQ(p.size(), std::size(measured));
  for (std::size_t k = 0; k < p.size(); ++k)
    EXPECT_NEAR(range_miss(p[k].held_out, p[k].published.low, p[k].published.high), measured[k], 0.03)
        << p[k].published.what << ": " << p[k].held_out << " fps";
}

TEST(CostModel, AHeldOutPredictionDoesNotSeeItsOwnPublishedRate) {
  // Moving one published range far away changes nothing in that rate's held-out prediction
  // (its fit never sees it), while the fits that do see it move.
  const MachineProfile& vpro = *find_profile("octane-vpro8");
  const std::vector<PaperPrediction> base = paper_predictions(vpro, vpro_runs(), 3000);
  for (std::size_t k : {std::size_t{1}, std::size_t{4}}) {
    std::vector<PublishedFrameRate> moved = published_frame_rates();
    moved[k].low *= 3.0, moved[k].high *= 3.0;
    const std::vector<PaperPrediction> other = paper_predictions(vpro, vpro_runs(), 3000, moved);
    EXPECT_EQ(other[k].held_out, base[k].held_out) << moved[k].what;
    bool any_moved = false;
    for (std::size_t j = 0; j < base.size(); ++j)
      if (j != k && other[j].held_out != base[j].held_out) any_moved = true;
    EXPECT_TRUE(any_moved) << moved[k].what;
  }
}

}  // namespace
}  // namespace passim
