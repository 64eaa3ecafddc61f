#include "reports/cost.hpp"

#include <algorithm>
#include <cmath>

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

PassCost pass_cost(const Pass& pass, const MachineProfile& profile) {
  const Counters& c = pass.counters;
  const CostRates& r = profile.rates;
  PassCost p;
  p.label = pass.label;
  auto set = [&](CostStage s, double work, double seconds) {
    p.work[static_cast<int>(s)] = work;
    p.seconds[static_cast<int>(s)] = seconds;
  };
  const double vertices = static_cast<double>(c.vertices);
  set(CostStage::Geometry, vertices, per(vertices, r.vertices));
  const double triangles = static_cast<double>(c.triangles_rasterized);
  set(CostStage::Setup, triangles, per(triangles, r.triangles));
  const double fragments = static_cast<double>(c.fragments_generated);
  set(CostStage::Fill, fragments, per(fragments, r.fragments));
  const double lookups = static_cast<double>(c.texture_lookups);
  set(CostStage::Texture, lookups, per(lookups, r.texture_lookups));
  const double fb_bytes = static_cast<double>(c.color_bits_read + c.color_bits_written + c.depth_bits_read +
                                              c.depth_bits_written + c.stencil_bits_read + c.stencil_bits_written) /
                          8.0;
  set(CostStage::Framebuffer, fb_bytes, per(fb_bytes, r.framebuffer_bytes));
  // The pixel path is as slow as its slowest operation in use.
  const double pixels = static_cast<double>(c.pixels_transferred);
  const double tables =
      static_cast<double>(c.color_table_lookups + c.post_convolution_table_lookups + c.post_color_matrix_table_lookups);
  set(CostStage::PixelPath, pixels,
      std::max({per(pixels, r.pixels), per(static_cast<double>(c.pixels_scale_bias), r.scale_bias),
                per(tables, r.color_table), per(static_cast<double>(c.pixels_color_matrix), r.color_matrix)}));
  const double convolved = static_cast<double>(c.pixels_convolved);
  set(CostStage::Convolution, convolved,
      convolved > 0.0 ? per(convolved, convolution_rate(r, static_cast<double>(c.convolution_taps) / convolved)) : 0.0);
  const double accum = static_cast<double>(c.accum_accum_pixels + c.accum_load_pixels + c.accum_add_pixels +
                                           c.accum_mult_pixels + c.accum_return_pixels);
  set(CostStage::Accumulation, accum, per(accum, r.accumulation));
  const double cleared = static_cast<double>(c.clear_pixels);
  set(CostStage::Clear, cleared, per(cleared, r.clear));
  const double tex_bytes = static_cast<double>(c.texture_bits_written) / 8.0;
  set(CostStage::TextureLoad, tex_bytes, per(tex_bytes, r.texture_load_bytes));
  int bound = 0;
  for (int s = 0; s < kCostStages; ++s) {
    if (p.work[static_cast<std::size_t>(s)] > 0.0) p.idle = false;
    if (p.seconds[static_cast<std::size_t>(s)] > p.seconds[static_cast<std::size_t>(bound)]) bound = s;
  }
  p.bound = static_cast<CostStage>(bound);
  p.overhead = p.idle ? 0.0 : r.pass_overhead;
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

}  // namespace passim
