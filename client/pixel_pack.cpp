#include "client/pixel_pack.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>

#include "pipeline/calls.hpp"
#include "pipeline/checked_size.hpp"
#include "pipeline/fixed_point.hpp"

namespace passim {
namespace {

// One element of `size` bytes to client memory, its bytes reversed under SWAP_BYTES.
void write_element(std::byte* p, std::byte* b, int size, bool swap) {
  if (swap)
    for (int i = 0; i < size / 2; ++i) std::swap(b[i], b[size - 1 - i]);
  std::memcpy(p, b, static_cast<std::size_t>(size));
}

void store(std::byte* p, GLenum type, double f, bool swap) {
  f = clamp_nan_low(f, 0.0, 1.0);
  std::byte b[8] = {};
  auto put = [&](auto v) { std::memcpy(b, &v, sizeof(v)); };
  switch (type) {
    case GL_UNSIGNED_BYTE: put(static_cast<std::uint8_t>(round_half_up(255.0 * f))); break;
    case GL_BYTE: put(static_cast<std::int8_t>(round_half_up((255.0 * f - 1.0) / 2.0))); break;
    case GL_UNSIGNED_SHORT: put(static_cast<std::uint16_t>(round_half_up(65535.0 * f))); break;
    case GL_SHORT: put(static_cast<std::int16_t>(round_half_up((65535.0 * f - 1.0) / 2.0))); break;
    case GL_UNSIGNED_INT: put(static_cast<std::uint32_t>(round_half_up(4294967295.0 * f))); break;
    case GL_INT: put(static_cast<std::int32_t>(round_half_up((4294967295.0 * f - 1.0) / 2.0))); break;
    case GL_FLOAT: put(static_cast<float>(f)); break;
    default: return;
  }
  write_element(p, b, type_size(type), swap);
}

}  // namespace

namespace {

// §4.3.2: group (x, y) of a width x height image of n components of `size` bytes, placed by
// the pack modes (as §3.6.4 places unpacked groups).
template <class F>
void for_each_packed_group(void* out, int width, int height, int n, int size, const PixelStore& s, F&& f) {
  // The caller's buffer holds image_bytes(...) under the pack modes, so these offsets fit.
  const std::size_t stride = pixel_row_stride(width, n, size, s).as_size();
  const std::size_t group = static_cast<std::size_t>(n) * static_cast<std::size_t>(size);
  std::byte* base = static_cast<std::byte*>(out) + static_cast<std::size_t>(s.skip_rows) * stride +
                    static_cast<std::size_t>(s.skip_pixels) * group;
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x)
      f(static_cast<std::size_t>(y) * static_cast<std::size_t>(width) + static_cast<std::size_t>(x),
        base + static_cast<std::size_t>(y) * stride + static_cast<std::size_t>(x) * group);
}

}  // namespace

void pack_rgba(const std::vector<Rgba>& pixels, int width, int height, GLenum format, GLenum type,
               const PixelStore& s, void* out) {
  const int n = format_components(format), size = type_size(type);
  for_each_packed_group(out, width, height, n, size, s, [&](std::size_t i, std::byte* p) {
    const Rgba& c = pixels[i];
    double v[4] = {0, 0, 0, 0};
    switch (format) {
      case GL_RED: case GL_LUMINANCE: case GL_DEPTH_COMPONENT: v[0] = c[0]; break;
      case GL_GREEN: v[0] = c[1]; break;
      case GL_BLUE: v[0] = c[2]; break;
      case GL_ALPHA: v[0] = c[3]; break;
      case GL_LUMINANCE_ALPHA: v[0] = c[0]; v[1] = c[3]; break;
      case GL_RGB: v[0] = c[0]; v[1] = c[1]; v[2] = c[2]; break;
      case GL_BGR: v[0] = c[2]; v[1] = c[1]; v[2] = c[0]; break;
      case GL_BGRA: v[0] = c[2]; v[1] = c[1]; v[2] = c[0]; v[3] = c[3]; break;
      default: v[0] = c[0]; v[1] = c[1]; v[2] = c[2]; v[3] = c[3]; break;
    }
    for (int m = 0; m < n; ++m) store(p + m * size, type, v[m], s.swap_bytes);
  });
}

void pack_indices(const std::vector<double>& indices, int width, int height, GLenum type, const PixelStore& s,
                  void* out) {
  const int size = type_size(type);
  for_each_packed_group(out, width, height, 1, size, s, [&](std::size_t i, std::byte* p) {
    std::byte b[4] = {};
    auto put = [&](auto v) { std::memcpy(b, &v, sizeof(v)); };
    const double index = indices[i];
    switch (type) {
      case GL_UNSIGNED_BYTE: put(static_cast<std::uint8_t>(index_low_bits(index, 8))); break;
      case GL_BYTE: put(static_cast<std::int8_t>(index_low_bits(index, 7))); break;
      case GL_UNSIGNED_SHORT: put(static_cast<std::uint16_t>(index_low_bits(index, 16))); break;
      case GL_SHORT: put(static_cast<std::int16_t>(index_low_bits(index, 15))); break;
      case GL_UNSIGNED_INT: put(static_cast<std::uint32_t>(index_low_bits(index, 32))); break;
      case GL_INT: put(static_cast<std::int32_t>(index_low_bits(index, 31))); break;
      default: put(static_cast<float>(std::isfinite(index) ? std::floor(index) : 0.0)); break;  // FLOAT
    }
    write_element(p, b, size, s.swap_bytes);
  });
}

std::uint64_t packed_image_elements(int width, int height, GLenum format, GLenum type, const PixelStore& store) {
  if (width <= 0 || height <= 0 || format_components(format) == 0 || !is_pixel_type(type)) return 0;
  return image_bytes(width, height, format, type, store) / static_cast<std::uint64_t>(type_size(type));
}

}  // namespace passim
