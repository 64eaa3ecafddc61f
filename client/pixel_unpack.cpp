#include "client/pixel_unpack.hpp"

#include <cstdint>
#include <cstring>

#include "pipeline/calls.hpp"
#include "pipeline/checked_size.hpp"

namespace passim {

int format_components(GLenum format) {
  switch (format) {
    case GL_RED: case GL_GREEN: case GL_BLUE: case GL_ALPHA: case GL_LUMINANCE: case GL_DEPTH_COMPONENT:
    case GL_STENCIL_INDEX: case GL_COLOR_INDEX:
      return 1;
    case GL_LUMINANCE_ALPHA: return 2;
    case GL_RGB: case GL_BGR: return 3;
    case GL_RGBA: case GL_BGRA: return 4;
    default: return 0;
  }
}

bool is_color_pixel_format(GLenum format) {
  switch (format) {
    case GL_RED: case GL_GREEN: case GL_BLUE: case GL_ALPHA: case GL_RGB: case GL_RGBA: case GL_BGR: case GL_BGRA:
    case GL_LUMINANCE: case GL_LUMINANCE_ALPHA:
      return true;
    default: return false;
  }
}

bool is_pixel_type(GLenum type) {
  switch (type) {
    case GL_UNSIGNED_BYTE: case GL_BYTE: case GL_UNSIGNED_SHORT: case GL_SHORT: case GL_UNSIGNED_INT: case GL_INT:
    case GL_FLOAT:
      return true;
    default: return false;
  }
}

CheckedSize pixel_row_stride(int width, int components, int size, const PixelStore& s) {
  const CheckedSize row = CheckedSize(components) * CheckedSize(s.row_length > 0 ? s.row_length : width) * size;
  if (size >= s.alignment) return row;
  return CheckedSize::round_up(row, s.alignment);
}

namespace {

double element(const std::byte* p, GLenum type, bool swap, bool normalise) {
  std::byte b[8] = {};
  const int size = type_size(type);
  std::memcpy(b, p, static_cast<std::size_t>(size));
  if (swap)
    for (int i = 0; i < size / 2; ++i) std::swap(b[i], b[size - 1 - i]);
  // Table 2.6: unsigned c/(2^b - 1), signed (2c + 1)/(2^b - 1), floats unchanged.
  switch (type) {
    case GL_UNSIGNED_BYTE: { std::uint8_t v; std::memcpy(&v, b, 1); return normalise ? v / 255.0 : v; }
    case GL_BYTE: { std::int8_t v; std::memcpy(&v, b, 1); return normalise ? (2.0 * v + 1.0) / 255.0 : v; }
    case GL_UNSIGNED_SHORT: { std::uint16_t v; std::memcpy(&v, b, 2); return normalise ? v / 65535.0 : v; }
    case GL_SHORT: { std::int16_t v; std::memcpy(&v, b, 2); return normalise ? (2.0 * v + 1.0) / 65535.0 : v; }
    case GL_UNSIGNED_INT: { std::uint32_t v; std::memcpy(&v, b, 4); return normalise ? v / 4294967295.0 : v; }
    case GL_INT: { std::int32_t v; std::memcpy(&v, b, 4); return normalise ? (2.0 * v + 1.0) / 4294967295.0 : v; }
    case GL_FLOAT: { float v; std::memcpy(&v, b, 4); return v; }
    default: return 0.0;
  }
}

template <class F>
void for_each_group(const void* data, int width, int height, GLenum format, GLenum type, const PixelStore& s, F&& f) {
  // Callers have checked that the data holds image_bytes(...), so these offsets fit.
  const int n = format_components(format), size = type_size(type);
  const std::size_t stride = pixel_row_stride(width, n, size, s).as_size();
  const std::size_t group = static_cast<std::size_t>(n) * static_cast<std::size_t>(size);
  const std::byte* base = static_cast<const std::byte*>(data) + static_cast<std::size_t>(s.skip_rows) * stride +
                          static_cast<std::size_t>(s.skip_pixels) * group;
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x)
      f(x, y, base + static_cast<std::size_t>(y) * stride + static_cast<std::size_t>(x) * group, n, size);
}

}  // namespace

namespace {
// ⌈l / 8⌉ bytes padded to the alignment (§3.6.4, type BITMAP).
CheckedSize bitmap_row_bytes(int width, const PixelStore& s) {
  const CheckedSize bits = s.row_length > 0 ? s.row_length : width;
  return CheckedSize::round_up(CheckedSize((bits.value() + 7) / 8), s.alignment);
}
}  // namespace

std::uint64_t bitmap_bytes(int width, int height, const PixelStore& s) {
  if (width <= 0 || height <= 0) return 0;
  const CheckedSize last_bit = CheckedSize(s.skip_pixels) + width - 1;
  return ((CheckedSize(s.skip_rows) + height - 1) * bitmap_row_bytes(width, s) + last_bit.value() / 8 + 1).value();
}

bool bitmap_bit(const void* data, int width, int x, int y, const PixelStore& s) {
  // Callers have checked that the data holds bitmap_bytes(...), so these offsets fit.
  const std::size_t bit = static_cast<std::size_t>(s.skip_pixels) + static_cast<std::size_t>(x);
  const auto* row = static_cast<const std::uint8_t*>(data) +
                    (static_cast<std::size_t>(s.skip_rows) + static_cast<std::size_t>(y)) *
                        bitmap_row_bytes(width, s).as_size();
  const std::uint8_t byte = row[bit / 8];
  const unsigned shift = s.lsb_first ? static_cast<unsigned>(bit % 8) : 7u - static_cast<unsigned>(bit % 8);
  return (byte >> shift) & 1u;
}

std::uint64_t image_bytes(int width, int height, GLenum format, GLenum type, const PixelStore& s) {
  if (width <= 0 || height <= 0) return 0;
  const int n = format_components(format), size = type_size(type);
  // The last row's start, then the groups up to the end of its last pixel.
  return ((CheckedSize(s.skip_rows) + height - 1) * pixel_row_stride(width, n, size, s) +
          (CheckedSize(s.skip_pixels) + width) * n * size)
      .value();
}

void unpack_rgba(const void* data, int width, int height, GLenum format, GLenum type, const PixelStore& s,
                 std::vector<Rgba>& out) {
  out.assign(static_cast<std::size_t>(width) * static_cast<std::size_t>(height), Rgba{0.0, 0.0, 0.0, 1.0});
  for_each_group(data, width, height, format, type, s, [&](int x, int y, const std::byte* p, int n, int size) {
    double c[4];
    for (int k = 0; k < n; ++k) c[k] = element(p + k * size, type, s.swap_bytes, true);
    Rgba& o = out[static_cast<std::size_t>(y) * static_cast<std::size_t>(width) + static_cast<std::size_t>(x)];
    switch (format) {
      case GL_RED: o[0] = c[0]; break;
      case GL_GREEN: o[1] = c[0]; break;
      case GL_BLUE: o[2] = c[0]; break;
      case GL_ALPHA: o[3] = c[0]; break;
      case GL_LUMINANCE: o[0] = o[1] = o[2] = c[0]; break;
      case GL_LUMINANCE_ALPHA: o[0] = o[1] = o[2] = c[0]; o[3] = c[1]; break;
      case GL_RGB: o[0] = c[0]; o[1] = c[1]; o[2] = c[2]; break;
      case GL_BGR: o[0] = c[2]; o[1] = c[1]; o[2] = c[0]; break;
      case GL_RGBA: o = {c[0], c[1], c[2], c[3]}; break;
      case GL_BGRA: o = {c[2], c[1], c[0], c[3]}; break;
      default: break;
    }
  });
}

void unpack_elements(const void* data, int width, int height, GLenum format, GLenum type, const PixelStore& s,
                     std::vector<double>& out) {
  const std::size_t n = static_cast<std::size_t>(format_components(format));
  out.assign(static_cast<std::size_t>(width) * static_cast<std::size_t>(height) * n, 0.0);
  for_each_group(data, width, height, format, type, s, [&](int x, int y, const std::byte* p, int, int size) {
    const std::size_t at = (static_cast<std::size_t>(y) * static_cast<std::size_t>(width) + static_cast<std::size_t>(x)) * n;
    for (std::size_t k = 0; k < n; ++k) out[at + k] = element(p + k * static_cast<std::size_t>(size), type, s.swap_bytes, false);
  });
}

void unpack_indices(const void* data, int width, int height, GLenum format, GLenum type, const PixelStore& s,
                    std::vector<double>& out) {
  unpack_elements(data, width, height, format, type, s, out);  // one element per group
}

void unpack_depth(const void* data, int width, int height, GLenum type, const PixelStore& s, std::vector<double>& out) {
  out.assign(static_cast<std::size_t>(width) * static_cast<std::size_t>(height), 0.0);
  for_each_group(data, width, height, GL_DEPTH_COMPONENT, type, s, [&](int x, int y, const std::byte* p, int, int) {
    out[static_cast<std::size_t>(y) * static_cast<std::size_t>(width) + static_cast<std::size_t>(x)] =
        element(p, type, s.swap_bytes, true);
  });
}

}  // namespace passim
