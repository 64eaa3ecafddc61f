// Framebuffer planes (§4.2): RGBA colour buffers of 1-16 bits per channel,
// depth 0-32, stencil 0-8, signed accumulation 0-32 bits per component.
// Every plane stores integer codes exactly at its width.
#pragma once
#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace passim {

struct FramebufferConfig {
  int width = 800;
  int height = 600;
  std::array<int, 4> color_bits{8, 8, 8, 8};  // R, G, B, A (alpha may be 0)
  int depth_bits = 24;
  int stencil_bits = 8;
  int accum_bits = 16;  // per component; 0 = no accumulation buffer
  bool double_buffer = true;

  // The bytes the planes take (as Framebuffer stores them), in checked arithmetic.
  std::uint64_t plane_bytes() const;
  // Empty when valid, else a message naming the offending setting.
  std::string validate(int max_size) const;
  // A21: 16-bit accumulation for <=8-bit colour, 24 for 12-bit: twice the widest channel.
  static int default_accum_bits(const std::array<int, 4>& color_bits);
};

enum class ColorBufferId : int { FrontLeft = 0, BackLeft = 1 };

struct ColorPlane {
  std::vector<std::uint16_t> rgba;  // 4 codes per pixel, row 0 at the bottom
};

struct Framebuffer {
  explicit Framebuffer(const FramebufferConfig& config);

  FramebufferConfig config;
  std::array<ColorPlane, 2> color;  // [FrontLeft, BackLeft]; BackLeft empty when single-buffered
  std::vector<std::uint32_t> depth;
  std::vector<std::uint8_t> stencil;
  std::vector<std::int32_t> accum;  // 4 per pixel

  int width() const { return config.width; }
  int height() const { return config.height; }
  bool has_buffer(ColorBufferId id) const { return !color[static_cast<int>(id)].rgba.empty(); }
  std::size_t pixel_index(int x, int y) const {
    return static_cast<std::size_t>(y) * static_cast<std::size_t>(config.width) + static_cast<std::size_t>(x);
  }
};

}  // namespace passim
