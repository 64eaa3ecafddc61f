// Unpacking client pixel data (OpenGL 1.2.1 §3.6.4): addressing by the pixel-store
// modes, Table 2.6 conversion to floating point, conversion to RGBA.
#pragma once
#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "pipeline/checked_size.hpp"
#include "pipeline/gl.hpp"

namespace passim {

// Table 3.1 (PixelStore) for one direction (pack or unpack).
struct PixelStore {
  bool swap_bytes = false;
  bool lsb_first = false;
  int row_length = 0;
  int skip_rows = 0;
  int skip_pixels = 0;
  int alignment = 4;
};

// Table 6.20 (pixel storage): the modes for packing and for unpacking.
struct PixelStoreState {
  PixelStore pack, unpack;
};

using Rgba = std::array<double, 4>;

// A bitmap (§3.6.4, type BITMAP: one bit per pixel; rows of ⌈row length / 8⌉ bytes padded to
// the alignment; SKIP_PIXELS counts bits; UNPACK_LSB_FIRST picks the bit order in a byte).
// The byte counts are computed in checked 64-bit arithmetic (SizeOverflow when they overflow).
std::uint64_t bitmap_bytes(int width, int height, const PixelStore& s);
bool bitmap_bit(const void* data, int width, int x, int y, const PixelStore& s);

// Components of a pixel format (Table 3.5); 0 for a name that is not one.
int format_components(GLenum format);
// The colour formats of Table 3.5 (not DEPTH, STENCIL or COLOR_INDEX).
bool is_color_pixel_format(GLenum format);
// The non-packed pixel types of Table 3.4 (BITMAP and the packed types are not modelled).
bool is_pixel_type(GLenum type);
// §3.6.4: the distance in bytes between the starts of consecutive rows of groups of
// `components` elements of `size` bytes, k·⌈n·l·s / k⌉ (n·l·s when s ≥ k), l the row length
// or width. Checked 64-bit arithmetic (SizeOverflow): the modes come from input.
CheckedSize pixel_row_stride(int width, int components, int size, const PixelStore& store);
// The bytes an image of width x height reads, counting from the data pointer (§3.6.4).
std::uint64_t image_bytes(int width, int height, GLenum format, GLenum type, const PixelStore& store);

// Unpacks width x height groups into RGBA (§3.6.4): Table 2.6 conversion (integers to
// [0,1] or [-1,1]); LUMINANCE to R = G = B = L; missing R, G, B are 0 and A is 1.
// Rows bottom first, as GL images. Colour formats only (not DEPTH or STENCIL or INDEX).
void unpack_rgba(const void* data, int width, int height, GLenum format, GLenum type, const PixelStore& store,
                 std::vector<Rgba>& out);
// The elements of width x height groups as stored (no Table 2.6 conversion; FLOAT as its
// value), format_components(format) per group, rows bottom first.
void unpack_elements(const void* data, int width, int height, GLenum format, GLenum type, const PixelStore& store,
                     std::vector<double>& out);
// Unpacks STENCIL_INDEX or COLOR_INDEX data into one index per pixel (§3.6.4): integer types
// keep their integer value, FLOAT its value (a fixed-point index with a fraction).
void unpack_indices(const void* data, int width, int height, GLenum format, GLenum type, const PixelStore& store,
                    std::vector<double>& out);
// Unpacks DEPTH_COMPONENT data into one value per pixel, Table 2.6 (unsigned types to [0,1]).
void unpack_depth(const void* data, int width, int height, GLenum type, const PixelStore& store,
                  std::vector<double>& out);

}  // namespace passim
