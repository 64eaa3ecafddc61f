#include "pipeline/framebuffer.hpp"

#include <fmt/format.h>

#include "pipeline/checked_size.hpp"

#include <algorithm>

namespace passim {

std::string FramebufferConfig::validate(int max_size) const {
  if (width < 1 || height < 1 || width > max_size || height > max_size)
    return fmt::format("framebuffer size {}x{} is outside 1..{} (the machine profile's limit)", width, height,
                       max_size);
  for (int c = 0; c < 4; ++c) {
    int lo = c == 3 ? 0 : 1;
    if (color_bits[c] < lo || color_bits[c] > 16)
      return fmt::format("colour width {} of channel {} is outside {}..16", color_bits[c], "RGBA"[c], lo);
  }
  if (depth_bits < 0 || depth_bits > 32) return fmt::format("depth width {} is outside 0..32", depth_bits);
  if (stencil_bits < 0 || stencil_bits > 8) return fmt::format("stencil width {} is outside 0..8", stencil_bits);
  if (accum_bits < 0 || accum_bits > 32) return fmt::format("accumulation width {} is outside 0..32", accum_bits);
  if (accum_bits != 0 && accum_bits < 2) return "accumulation width must be 0 (none) or at least 2";
  return {};
}

std::uint64_t FramebufferConfig::plane_bytes() const {
  const CheckedSize pixels = CheckedSize(width) * height;
  CheckedSize per_pixel = CheckedSize(4 * sizeof(std::uint16_t)) * (double_buffer ? 2 : 1);
  if (depth_bits > 0) per_pixel += sizeof(std::uint32_t);
  if (stencil_bits > 0) per_pixel += sizeof(std::uint8_t);
  if (accum_bits > 0) per_pixel += 4 * sizeof(std::int32_t);
  return (pixels * per_pixel).value();
}

int FramebufferConfig::default_accum_bits(const std::array<int, 4>& color_bits) {
  return std::min(32, 2 * *std::max_element(color_bits.begin(), color_bits.end()));
}

Framebuffer::Framebuffer(const FramebufferConfig& c) : config(c) {
  const std::size_t n = static_cast<std::size_t>(c.width) * static_cast<std::size_t>(c.height);
  color[0].rgba.assign(4 * n, 0);
  if (c.double_buffer) color[1].rgba.assign(4 * n, 0);
  if (c.depth_bits > 0) depth.assign(n, 0);
  if (c.stencil_bits > 0) stencil.assign(n, 0);
  if (c.accum_bits > 0) accum.assign(4 * n, 0);
}

}  // namespace passim
