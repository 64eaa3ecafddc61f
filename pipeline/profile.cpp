#include "pipeline/profile.hpp"

namespace passim {

const std::vector<MachineProfile>& machine_profiles() {
  static const std::vector<MachineProfile> profiles = [] {
    std::vector<MachineProfile> p;
    {
      MachineProfile m;
      m.name = "ideal";
      m.description = "Reference machine: 8-bit RGBA, 24-bit depth, 8-bit stencil, 16-bit accumulation; generous limits.";
      m.limits.max_convolution_width = m.limits.max_convolution_height = 11;
      m.limits.max_color_table_width = 65536;
      m.limits.max_histogram_width = 65536;
      m.limits.max_pixel_map_table = 65536;
      m.limits.max_texture_size = 65536;  // a 16-bit depth ramp is a 65536-texel 1D texture
      m.sources = "assumed (a machine without the period's limits)";
      p.push_back(m);
    }
    {
      MachineProfile m;
      m.name = "octane-vpro8";
      m.description = "SGI Octane VPro/8 (V8): 12-bit RGBA path, 96-bit accumulation, ARB_imaging in hardware.";
      m.color_bits = {12, 12, 12, 12};
      m.accum_bits = 24;
      m.limits.max_color_table_width = 4096;  // assumed: one entry per 12-bit code
      m.limits.max_histogram_width = 4096;    // assumed
      m.limits.max_convolution_width = m.limits.max_convolution_height = 7;  // assumed
      m.limits.max_texture_size = 4096;  // assumed (a 12-bit depth ramp needs 4096 texels)
      m.sources =
          "12-bit colour and 96-bit accumulation: SGI VPro product text (gl12-semantics §9); limits assumed";
      // Cost rates (docs/cost-model.md). Fitted by tools/fit_vpro_rates.py to the paper's
      // Figure 7 frame rates (the largest margin inside all four ranges): triangles, pixel path, scale/bias, colour
      // table / matrix, clears, texture load, pass overhead. Assumed: the rest.
      CostRates& r = m.rates;
      r.vertices = 10.0e6;
      r.triangles = 0.745e6;  // fitted: an effective rate, host and set-up included
      r.fragments = 200.0e6;
      r.texture_lookups = 150.0e6;
      r.framebuffer_bytes = 2.0e9;
      r.pixels = 228.0e6;                      // fitted
      r.scale_bias = 278.0e6;                  // fitted
      r.color_table = r.color_matrix = 20.7e6;  // fitted
      r.convolution[0] = 40.0e6, r.convolution[1] = 20.0e6, r.convolution[2] = 10.0e6;
      r.accumulation = 400.0e6;
      r.clear = 1.07e9;                        // fitted
      r.texture_load_bytes = 221.0e6;          // fitted
      r.pass_overhead = 47.9e-6;               // fitted
      r.sources = "fitted to Brabec & Seidel Figure 7 (triangles, pixel path, scale/bias, colour table/matrix, "
                  "clears, texture load, pass overhead); every other rate assumed";
      p.push_back(m);
    }
    {
      MachineProfile m;
      m.name = "o2";
      m.description = "SGI O2 (CRM): 8-bit RGBA, imaging through glCopyPixels.";
      m.limits.max_convolution_width = m.limits.max_convolution_height = 7;  // the published 7x7 rate exists
      m.limits.max_texture_size = 1024;                                      // assumed
      m.sources = "8-bit colour assumed; 7x7 convolution from the published O2 CopyPixels rates";
      CostRates& r = m.rates;
      // Published O2 glCopyPixels rates (M pixels/s): scale/bias 7.8, colour matrix 7.7,
      // convolution 3x3 4.3, 5x5 2.1, 7x7 1.2 (separable 4.6, 3.9, 2.3: not used, the
      // counters do not say whether a filter was separable). The rest assumed.
      r.scale_bias = 7.8e6;
      r.color_matrix = 7.7e6;
      r.color_table = 7.7e6;  // assumed: as the colour matrix
      r.convolution[0] = 4.3e6, r.convolution[1] = 2.1e6, r.convolution[2] = 1.2e6;
      r.pixels = 10.0e6;
      r.vertices = 2.0e6;
      r.triangles = 0.3e6;
      r.fragments = 60.0e6;
      r.texture_lookups = 30.0e6;
      r.framebuffer_bytes = 0.5e9;
      r.accumulation = 10.0e6;
      r.clear = 100.0e6;
      r.texture_load_bytes = 50.0e6;
      r.pass_overhead = 100.0e-6;
      r.sources = "pixel path: published O2 glCopyPixels rates; every other rate assumed";
      p.push_back(m);
    }
    {
      MachineProfile m;
      m.name = "infinite-reality";
      m.description = "SGI Onyx InfiniteReality: 12-bit RGBA visuals, 24-bit accumulation per component.";
      m.color_bits = {12, 12, 12, 12};
      m.accum_bits = 24;
      m.limits.max_color_table_width = 4096;  // assumed
      m.limits.max_histogram_width = 4096;    // assumed
      m.sources = "widths assumed (not found in public sources, gl12-semantics §9)";
      CostRates& r = m.rates;  // all assumed: a multi-pipe machine several times the VPro
      r.vertices = 30.0e6;
      r.triangles = 3.0e6;
      r.fragments = 800.0e6;
      r.texture_lookups = 600.0e6;
      r.framebuffer_bytes = 8.0e9;
      r.pixels = 200.0e6;
      r.scale_bias = 200.0e6;
      r.color_table = r.color_matrix = 100.0e6;
      r.convolution[0] = 100.0e6, r.convolution[1] = 50.0e6, r.convolution[2] = 25.0e6;
      r.accumulation = 800.0e6;
      r.clear = 2.0e9;
      r.texture_load_bytes = 800.0e6;
      r.pass_overhead = 20.0e-6;
      r.sources = "every rate assumed";
      p.push_back(m);
    }
    {
      MachineProfile m;
      m.name = "mesa-llvmpipe";
      m.description = "Debian 12 Mesa llvmpipe's open choices, for the outside check: 8 sub-pixel bits, "
                      "vertex colours interpolated unrounded, immediate-mode quads split into triangles (0,1,3), "
                      "(1,2,3), blend products rounded one by one.";
      m.limits.subpixel_bits = 8;
      m.arithmetic.quantise_vertex_colors = false;
      m.arithmetic.immediate_quads_as_triangle_pairs = true;
      m.arithmetic.blend_products_rounded = true;
      m.arithmetic.texture_filter_8_8 = true;
      m.limits.max_convolution_width = m.limits.max_convolution_height = 9;  // Mesa 6.x; llvmpipe has none
      m.sources = "measured against OSMesa 22.3.6 (tests/osmesa_check.cpp, docs/arithmetic.md)";
      p.push_back(m);
    }
    return p;
  }();
  return profiles;
}

const MachineProfile* find_profile(const std::string& name) {
  for (const auto& p : machine_profiles())
    if (p.name == name) return &p;
  return nullptr;
}

}  // namespace passim
