#include "stages/clear.hpp"

#include <algorithm>
#include <cstring>

#include "pipeline/fixed_point.hpp"

namespace passim {

std::int32_t accum_code(double value, int bits) {
  const double scale = static_cast<double>((std::int64_t{1} << (bits - 1)) - 1);
  return static_cast<std::int32_t>(round_half_up(clamp_nan_low(value, -1.0, 1.0) * scale));
}

void clear_buffers(GLbitfield mask, const FramebufferControlState& ctl, const FragmentOpsState& ops,
                   const std::vector<ColorBufferId>& draw_buffers, Framebuffer& fb, Counters& counters) {
  const FramebufferConfig& cfg = fb.config;
  const PixelBox box = scissored_window(ops, cfg.width, cfg.height);
  const int x0 = box.x0, y0 = box.y0, x1 = box.x1, y1 = box.y1;  // plain ints: lambdas capture them
  const std::uint64_t pixels = static_cast<std::uint64_t>(x1 - x0) * static_cast<std::uint64_t>(y1 - y0);
  ++counters.clears;
  if (pixels == 0) return;

  auto for_each_pixel = [&](auto&& f) {
    for (int y = y0; y < y1; ++y)
      for (int x = x0; x < x1; ++x) f(fb.pixel_index(x, y));
  };

  if (mask & GL_COLOR_BUFFER_BIT) {
    std::uint16_t code[4];
    int bits = 0;
    for (int k = 0; k < 4; ++k) {
      code[k] = static_cast<std::uint16_t>(float_to_fixed(ctl.clear_color[k], cfg.color_bits[k]));
      if (ctl.color_mask[k]) bits += cfg.color_bits[k];
    }
    const bool all_channels = ctl.color_mask[0] && ctl.color_mask[1] && ctl.color_mask[2] && ctl.color_mask[3];
    for (ColorBufferId id : draw_buffers) {
      std::uint16_t* rgba = fb.color[static_cast<int>(id)].rgba.data();
      if (all_channels) {
        // Whole pixels: build one row of the clear pattern, then copy it into every row.
        const std::size_t row_values = 4 * static_cast<std::size_t>(x1 - x0);
        std::uint16_t* first = rgba + 4 * fb.pixel_index(x0, y0);
        for (std::size_t x = 0; x < row_values; x += 4) std::memcpy(first + x, code, sizeof(code));
        for (int y = y0 + 1; y < y1; ++y)
          std::memcpy(rgba + 4 * fb.pixel_index(x0, y), first, row_values * sizeof(std::uint16_t));
      } else {
        for_each_pixel([&](std::size_t p) {
          for (int k = 0; k < 4; ++k)
            if (ctl.color_mask[k] && cfg.color_bits[k] > 0) rgba[4 * p + k] = code[k];
        });
      }
      counters.clear_pixels += pixels;
      counters.color_bits_written += pixels * static_cast<std::uint64_t>(bits);
    }
  }
  if ((mask & GL_DEPTH_BUFFER_BIT) && cfg.depth_bits > 0 && ctl.depth_mask) {
    const std::uint32_t code = float_to_fixed(ctl.clear_depth, cfg.depth_bits);
    for (int y = y0; y < y1; ++y) std::fill_n(fb.depth.begin() + static_cast<std::ptrdiff_t>(fb.pixel_index(x0, y)), x1 - x0, code);
    counters.clear_pixels += pixels;
    counters.depth_bits_written += pixels * static_cast<std::uint64_t>(cfg.depth_bits);
  }
  if ((mask & GL_STENCIL_BUFFER_BIT) && cfg.stencil_bits > 0) {
    const std::uint32_t smax = max_code(cfg.stencil_bits);
    const std::uint32_t write = ctl.stencil_writemask & smax;
    const std::uint32_t value = static_cast<std::uint32_t>(ctl.clear_stencil) & smax;
    if (write) {
      for_each_pixel([&](std::size_t p) {
        fb.stencil[p] = static_cast<std::uint8_t>((fb.stencil[p] & ~write) | (value & write));
      });
      counters.clear_pixels += pixels;
      counters.stencil_bits_written += pixels * static_cast<std::uint64_t>(cfg.stencil_bits);
    }
  }
  if ((mask & GL_ACCUM_BUFFER_BIT) && cfg.accum_bits > 0) {
    std::int32_t code[4];
    for (int k = 0; k < 4; ++k) code[k] = accum_code(ctl.clear_accum[k], cfg.accum_bits);
    for_each_pixel([&](std::size_t p) {
      for (int k = 0; k < 4; ++k) fb.accum[4 * p + k] = code[k];
    });
    counters.clear_pixels += pixels;
    counters.accum_bits_written += pixels * 4u * static_cast<std::uint64_t>(cfg.accum_bits);
  }
}

}  // namespace passim
