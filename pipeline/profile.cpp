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
      p.push_back(m);
    }
    {
      MachineProfile m;
      m.name = "o2";
      m.description = "SGI O2 (CRM): 8-bit RGBA, imaging through glCopyPixels.";
      m.limits.max_convolution_width = m.limits.max_convolution_height = 7;  // the published 7x7 rate exists
      m.limits.max_texture_size = 1024;                                      // assumed
      m.sources = "8-bit colour assumed; 7x7 convolution from the published O2 CopyPixels rates";
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
      p.push_back(m);
    }
    {
      MachineProfile m;
      m.name = "mesa-llvmpipe";
      m.description = "Debian 12 Mesa llvmpipe's open choices, for the outside check: 8 sub-pixel bits, "
                      "vertex colours interpolated unrounded.";
      m.limits.subpixel_bits = 8;
      m.arithmetic.quantise_vertex_colors = false;
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
