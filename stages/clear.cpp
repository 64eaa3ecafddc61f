#include "stages/clear.hpp"

#include <algorithm>
#include <cstring>
#include <functional>

#include "pipeline/fixed_point.hpp"

namespace passim {

std::int32_t accum_code(double value, int bits) {
  const double scale = static_cast<double>((std::int64_t{1} << (bits - 1)) - 1);
  return static_cast<std::int32_t>(round_half_up(clamp_nan_low(value, -1.0, 1.0) * scale));
}

void clear_buffers(GLbitfield mask, const FramebufferControlState& ctl, const FragmentOpsState& ops,
                   const std::vector<ColorBufferId>& draw_buffers, Framebuffer& fb, Counters& counters,
                   const RowSplitter* split) {
  const FramebufferConfig& cfg = fb.config;
  const PixelBox box = scissored_window(ops, cfg.width, cfg.height);
  const int x0 = box.x0, y0 = box.y0, x1 = box.x1, y1 = box.y1;  // plain ints: lambdas capture them
  const std::uint64_t pixels = static_cast<std::uint64_t>(x1 - x0) * static_cast<std::uint64_t>(y1 - y0);
  ++counters.clears;
  if (pixels == 0) return;

  // What each plane is cleared to, and what is counted (once, here; the rows below write).
  const bool color = (mask & GL_COLOR_BUFFER_BIT) != 0;
  std::uint16_t color_code[4];
  int color_bits = 0;
  for (int k = 0; k < 4; ++k) {
    color_code[k] = static_cast<std::uint16_t>(float_to_fixed(ctl.clear_color[k], cfg.color_bits[k]));
    if (ctl.color_mask[k]) color_bits += cfg.color_bits[k];
  }
  // A pixel's four codes as one 64-bit word: the channels the colour mask opens from
  // `pattern` (a channel without bits gets its only code, 0), the others kept.
  std::uint16_t kept_channels[4];
  for (int k = 0; k < 4; ++k) kept_channels[k] = ctl.color_mask[k] ? 0 : 0xFFFF;
  std::uint64_t pattern = 0, keep = 0;
  std::memcpy(&pattern, color_code, sizeof pattern);
  std::memcpy(&keep, kept_channels, sizeof keep);
  pattern &= ~keep;
  if (color) {  // for each draw buffer
    counters.clear_pixels += pixels * draw_buffers.size();
    counters.color_bits_written += pixels * draw_buffers.size() * static_cast<std::uint64_t>(color_bits);
  }
  const bool depth = (mask & GL_DEPTH_BUFFER_BIT) && cfg.depth_bits > 0 && ctl.depth_mask;
  const std::uint32_t depth_code = depth ? float_to_fixed(ctl.clear_depth, cfg.depth_bits) : 0;
  if (depth) {
    counters.clear_pixels += pixels;
    counters.depth_bits_written += pixels * static_cast<std::uint64_t>(cfg.depth_bits);
  }
  const std::uint32_t stencil_write =
      (mask & GL_STENCIL_BUFFER_BIT) && cfg.stencil_bits > 0 ? ctl.stencil_writemask & max_code(cfg.stencil_bits) : 0;
  const std::uint32_t stencil_value =
      cfg.stencil_bits > 0 ? static_cast<std::uint32_t>(ctl.clear_stencil) & max_code(cfg.stencil_bits) : 0;
  if (stencil_write) {
    counters.clear_pixels += pixels;
    counters.stencil_bits_written += pixels * static_cast<std::uint64_t>(cfg.stencil_bits);
  }
  const bool accum = (mask & GL_ACCUM_BUFFER_BIT) && cfg.accum_bits > 0;
  std::int32_t accum_codes[4] = {};
  if (accum) {
    for (int k = 0; k < 4; ++k) accum_codes[k] = accum_code(ctl.clear_accum[k], cfg.accum_bits);
    counters.clear_pixels += pixels;
    counters.accum_bits_written += pixels * 4u * static_cast<std::uint64_t>(cfg.accum_bits);
  }

  // Rows y0 + first to y0 + end − 1 of every plane cleared.
  const std::function<void(int, int)> clear_rows = [&](int first, int end) {
    for (int y = y0 + first; y < y0 + end; ++y) {
      const std::size_t row = fb.pixel_index(x0, y), n = static_cast<std::size_t>(x1 - x0);
      if (color)
        for (ColorBufferId id : draw_buffers) {
          std::uint16_t* rgba = fb.color[static_cast<int>(id)].rgba.data() + 4 * row;
          for (std::size_t x = 0; x < n; ++x) {
            std::uint64_t codes = pattern;
            if (keep) {
              std::memcpy(&codes, rgba + 4 * x, sizeof codes);
              codes = (codes & keep) | pattern;
            }
            std::memcpy(rgba + 4 * x, &codes, sizeof codes);
          }
        }
      if (depth) std::fill_n(fb.depth.begin() + static_cast<std::ptrdiff_t>(row), n, depth_code);
      if (stencil_write)
        for (std::size_t x = row; x < row + n; ++x)
          fb.stencil[x] = static_cast<std::uint8_t>((fb.stencil[x] & ~stencil_write) | (stencil_value & stencil_write));
      if (accum)
        for (std::size_t x = row; x < row + n; ++x)
          for (int k = 0; k < 4; ++k) fb.accum[4 * x + k] = accum_codes[k];
    }
  };
  if (split) (*split)(y1 - y0, clear_rows);
  else clear_rows(0, y1 - y0);
}

}  // namespace passim
