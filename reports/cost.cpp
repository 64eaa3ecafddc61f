#include "reports/cost.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <stdexcept>

#include <fmt/format.h>

namespace passim {

const char* cost_stage_name(CostStage s) {
  static const char* const names[kCostStages] = {"geometry", "setup", "fill", "texture", "framebuffer",
                                                  "pixel path", "convolution", "accumulation", "clear",
                                                  "texture load"};
  return names[static_cast<int>(s)];
}

namespace {

double per(double work, double rate) { return rate > 0.0 ? work / rate : 0.0; }

// A convolution's rate from the filter size its taps per pixel give: the profile's 3x3,
// 5x5 and 7x7 rates, other sizes scaled from the nearest by their taps.
double convolution_rate(const CostRates& r, double taps_per_pixel) {
  const double sizes[3] = {9.0, 25.0, 49.0};
  int k = 0;
  for (int i = 1; i < 3; ++i)
    if (std::abs(taps_per_pixel - sizes[i]) < std::abs(taps_per_pixel - sizes[k])) k = i;
  return r.convolution[k] * sizes[k] / taps_per_pixel;
}

}  // namespace

const MachineProfile& timed_profile(const std::string& name) {
  const MachineProfile* p = find_profile(name);
  std::string timed;
  for (const MachineProfile& m : machine_profiles())
    if (m.rates.triangles > 0.0) timed += (timed.empty() ? "" : ", ") + m.name;
  if (!p) throw std::invalid_argument(fmt::format("unknown machine profile '{}' (passim info lists them)", name));
  if (p->rates.triangles <= 0.0)
    throw std::invalid_argument(fmt::format("profile '{}' has no cost rates ({} have)", name, timed));
  return *p;
}

namespace {

// A pass's work per stage, and the pixel path's operations its rate depends on.
struct Work {
  std::array<double, kCostStages> work{};
  double scale_bias = 0.0, tables = 0.0, color_matrix = 0.0, taps_per_pixel = 0.0;
  bool idle = true;
};

Work work_of(const Counters& c) {
  Work w;
  auto set = [&](CostStage s, double v) { w.work[static_cast<std::size_t>(s)] = v; };
  set(CostStage::Geometry, static_cast<double>(c.vertices));
  set(CostStage::Setup, static_cast<double>(c.triangles_rasterized));
  set(CostStage::Fill, static_cast<double>(c.fragments_generated));
  set(CostStage::Texture, static_cast<double>(c.texture_lookups));
  set(CostStage::Framebuffer, static_cast<double>(c.color_bits_read + c.color_bits_written + c.depth_bits_read +
                                                  c.depth_bits_written + c.stencil_bits_read + c.stencil_bits_written) /
                                  8.0);
  set(CostStage::PixelPath, static_cast<double>(c.pixels_transferred));
  w.scale_bias = static_cast<double>(c.pixels_scale_bias);
  w.tables =
      static_cast<double>(c.color_table_lookups + c.post_convolution_table_lookups + c.post_color_matrix_table_lookups);
  w.color_matrix = static_cast<double>(c.pixels_color_matrix);
  const double convolved = static_cast<double>(c.pixels_convolved);
  set(CostStage::Convolution, convolved);
  w.taps_per_pixel = convolved > 0.0 ? static_cast<double>(c.convolution_taps) / convolved : 0.0;
  set(CostStage::Accumulation, static_cast<double>(c.accum_accum_pixels + c.accum_load_pixels + c.accum_add_pixels +
                                                   c.accum_mult_pixels + c.accum_return_pixels));
  set(CostStage::Clear, static_cast<double>(c.clear_pixels));
  set(CostStage::TextureLoad, static_cast<double>(c.texture_bits_written) / 8.0);
  for (double v : w.work)
    if (v > 0.0) w.idle = false;
  return w;
}

std::array<double, kCostStages> seconds_of(const Work& w, const CostRates& r) {
  std::array<double, kCostStages> s{};
  auto at = [&](CostStage st) { return w.work[static_cast<std::size_t>(st)]; };
  auto put = [&](CostStage st, double v) { s[static_cast<std::size_t>(st)] = v; };
  put(CostStage::Geometry, per(at(CostStage::Geometry), r.vertices));
  put(CostStage::Setup, per(at(CostStage::Setup), r.triangles));
  put(CostStage::Fill, per(at(CostStage::Fill), r.fragments));
  put(CostStage::Texture, per(at(CostStage::Texture), r.texture_lookups));
  put(CostStage::Framebuffer, per(at(CostStage::Framebuffer), r.framebuffer_bytes));
  // The pixel path is as slow as its slowest operation in use.
  put(CostStage::PixelPath, std::max({per(at(CostStage::PixelPath), r.pixels), per(w.scale_bias, r.scale_bias),
                                      per(w.tables, r.color_table), per(w.color_matrix, r.color_matrix)}));
  const double convolved = at(CostStage::Convolution);
  put(CostStage::Convolution, convolved > 0.0 ? per(convolved, convolution_rate(r, w.taps_per_pixel)) : 0.0);
  put(CostStage::Accumulation, per(at(CostStage::Accumulation), r.accumulation));
  put(CostStage::Clear, per(at(CostStage::Clear), r.clear));
  put(CostStage::TextureLoad, per(at(CostStage::TextureLoad), r.texture_load_bytes));
  return s;
}

}  // namespace

PassCost pass_cost(const Pass& pass, const MachineProfile& profile) {
  const Work w = work_of(pass.counters);
  PassCost p;
  p.label = pass.label;
  p.work = w.work;
  p.seconds = seconds_of(w, profile.rates);
  p.idle = w.idle;
  int bound = 0;
  for (int s = 1; s < kCostStages; ++s)
    if (p.seconds[static_cast<std::size_t>(s)] > p.seconds[static_cast<std::size_t>(bound)]) bound = s;
  p.bound = static_cast<CostStage>(bound);
  p.overhead = p.idle ? 0.0 : profile.rates.pass_overhead;
  p.total = p.seconds[static_cast<std::size_t>(bound)] + p.overhead;
  return p;
}

FrameCost frame_cost(const std::vector<Pass>& passes, const MachineProfile& profile) {
  FrameCost f;
  f.profile = profile.name;
  for (const Pass& p : passes) {
    f.passes.push_back(pass_cost(p, profile));
    f.seconds += f.passes.back().total;
  }
  return f;
}

nlohmann::json cost_json(const FrameCost& f) {
  nlohmann::json passes = nlohmann::json::array();
  for (const PassCost& p : f.passes) {
    nlohmann::json stages;
    for (int s = 0; s < kCostStages; ++s)
      stages[cost_stage_name(static_cast<CostStage>(s))] = {{"work", p.work[static_cast<std::size_t>(s)]},
                                                            {"seconds", p.seconds[static_cast<std::size_t>(s)]}};
    passes.push_back({{"label", p.label},
                      {"bound", p.idle ? "" : cost_stage_name(p.bound)},
                      {"seconds", p.total},
                      {"overhead", p.overhead},
                      {"stages", stages}});
  }
  return {{"profile", f.profile}, {"passes", passes}, {"seconds", f.seconds}, {"fps", f.fps()}};
}

const std::vector<PublishedFrameRate>& published_frame_rates() {
  // Brabec & Seidel, "Hardware-accelerated rendering of antialiased shadows with shadow maps"
  // (2001), §5, on an SGI Octane VPro/8: "25–30", "about 10", "15–20", "about 5" frames per
  // second for Figure 7 (6,780 triangles, 512² map), "about 15" and "about 10" for Figure 8 with a
  // 1024² map. An "about" is taken as ±10 % (about 10: 9–11).
  static const std::vector<PublishedFrameRate> rates = {
      {"Fig. 7 shadow map", "shadow-map", 0, "paper", 25.0, 30.0},
      {"Fig. 7 PCF 2x2", "pcf", 2, "paper", 9.0, 11.0},
      {"Fig. 7 fast PCF 2x2", "fast-pcf", 2, "paper", 15.0, 20.0},
      {"Fig. 7 fast PCF 4x4", "fast-pcf", 4, "paper", 4.5, 5.5},
      {"Fig. 8 shadow map (1024² map)", "shadow-map", 0, "fig8", 13.5, 16.5},
      {"Fig. 8 fast PCF 2x2 (1024² map)", "fast-pcf", 2, "fig8", 9.0, 11.0}};
  return rates;
}

double range_miss(double fps, double low, double high) {
  return fps < low ? fps / low - 1.0 : fps > high ? fps / high - 1.0 : 0.0;
}

const std::vector<std::string>& fitted_rate_names() {
  static const std::vector<std::string> names = {"triangles", "pixels",        "scale_bias",   "color_table",
                                                 "clear",     "texture_load", "pass_overhead"};
  return names;
}

namespace {

double& free_rate(CostRates& r, std::size_t k) {
  double* const slots[] = {&r.triangles, &r.pixels, &r.scale_bias, &r.color_table, &r.clear, &r.texture_load_bytes,
                           &r.pass_overhead};
  return *slots[k];
}

// A normal deviate from two uniform ones (Box–Muller), from mt19937's raw output, whose
// sequence the standard fixes (the library's distributions are not the same everywhere).
double normal(std::mt19937& rng) {
  auto uniform = [&] { return (static_cast<double>(rng() >> 8) + 0.5) / 16777216.0; };
  const double u = uniform(), v = uniform();
  return std::sqrt(-2.0 * std::log(u)) * std::cos(6.283185307179586 * v);
}

}  // namespace

RateFit fit_rates(const std::vector<std::vector<Pass>>& runs, const std::vector<PublishedFrameRate>& published,
                  const std::vector<bool>& used, const CostRates& start, int iterations) {
  std::vector<std::vector<Work>> works;
  for (const std::vector<Pass>& run : runs) {
    works.emplace_back();
    for (const Pass& p : run) works.back().push_back(work_of(p.counters));
  }
  auto fps = [&](std::size_t k, const CostRates& r) {
    double seconds = 0.0;
    for (const Work& w : works[k]) {
      const auto s = seconds_of(w, r);
      seconds += *std::max_element(s.begin(), s.end()) + (w.idle ? 0.0 : r.pass_overhead);
    }
    return seconds > 0.0 ? 1.0 / seconds : 0.0;
  };
  // The least margin, in log units, inside the used ranges (negative outside one).
  auto margin = [&](const CostRates& r) {
    double m = std::numeric_limits<double>::infinity();
    for (std::size_t k = 0; k < published.size(); ++k)
      if (used[k]) {
        const double f = fps(k, r);
        m = std::min({m, std::log(f / published[k].low), std::log(published[k].high / f)});
      }
    return m;
  };
  RateFit best{start, margin(start)};
  best.rates.color_matrix = best.rates.color_table;
  std::mt19937 rng(6);
  for (int it = 0; it < iterations; ++it) {
    CostRates candidate = best.rates;
    // One to three rates moved by a factor of e^(0.15·N(0,1)) each.
    const int moves = 1 + static_cast<int>(rng() % 3);
    for (int m = 0; m < moves; ++m) {
      const std::size_t k = rng() % fitted_rate_names().size();
      free_rate(candidate, k) *= std::exp(0.15 * normal(rng));
    }
    candidate.color_matrix = candidate.color_table;  // one rate for both (docs/cost-model.md)
    const double m = margin(candidate);
    if (m > best.margin) best = {candidate, m};
  }
  return best;
}

RateFit fit_published(const MachineProfile& profile, const std::vector<std::vector<Pass>>& runs,
                      const std::vector<bool>& used, int iterations, const std::vector<PublishedFrameRate>& published) {
  // The search starts from round figures that owe nothing to the published rates (the
  // profile's own free rates were fitted to Figure 7, held-out points included), and keeps
  // the profile's other rates.
  CostRates start = profile.rates;
  const double neutral[] = {0.8e6, 100e6, 80e6, 20e6, 800e6, 240e6, 100e-6};
  for (std::size_t k = 0; k < std::size(neutral); ++k) free_rate(start, k) = neutral[k];
  return fit_rates(runs, published, used, start, iterations);
}

std::vector<PaperPrediction> paper_predictions(const MachineProfile& profile, const std::vector<std::vector<Pass>>& runs,
                                               int iterations, const std::vector<PublishedFrameRate>& published) {
  std::vector<PaperPrediction> out;
  for (std::size_t k = 0; k < published.size(); ++k) {
    std::vector<bool> used(published.size(), true);
    used[k] = false;  // held out: the rates are fitted to the other five
    const RateFit fit = fit_published(profile, runs, used, iterations, published);
    MachineProfile refit = profile;
    refit.rates = fit.rates;
    PaperPrediction p;
    p.published = published[k];
    p.with_profile = frame_cost(runs[k], profile).fps();
    p.held_out = frame_cost(runs[k], refit).fps();
    p.held_out_fit_margin = fit.margin;
    out.push_back(p);
  }
  return out;
}

}  // namespace passim
