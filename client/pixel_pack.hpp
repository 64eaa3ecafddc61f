// Packing pixels into client memory (OpenGL 1.2.1 §4.3.2, Table 4.7): clamp to [0,1]
// (1.2.1: for every type, FLOAT too, A17), convert (A18: round; signed types
// round(((2^b−1)·f − 1)/2)), addressed by the pack pixel-store modes.
#pragma once
#include <cstdint>
#include <vector>

#include "client/pixel_unpack.hpp"

namespace passim {

// Writes width x height RGBA groups (rows bottom first) as `format`/`type`. LUMINANCE is
// R (GetTexImage of a luminance texture returns L in R), LUMINANCE_ALPHA is R and A.
void pack_rgba(const std::vector<Rgba>& pixels, int width, int height, GLenum format, GLenum type,
               const PixelStore& store, void* out);
// Writes width x height indices (STENCIL_INDEX, COLOR_INDEX) as `type`: the integer part
// masked with Table 4.6 (2^8 − 1 for UNSIGNED_BYTE, 2^7 − 1 for BYTE, …), or for FLOAT the
// integer part as a float.
void pack_indices(const std::vector<double>& indices, int width, int height, GLenum type, const PixelStore& store,
                  void* out);
// The elements of `type` that packing a width x height image of `format` addresses under
// `store`, from the data pointer (the bytes image_bytes counts); 0 for an empty image or a
// format or type that is not a pixel one.
std::uint64_t packed_image_elements(int width, int height, GLenum format, GLenum type, const PixelStore& store);

}  // namespace passim
