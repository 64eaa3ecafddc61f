// Texture sampling, OpenGL 1.2.1 §3.8.5-3.8.8 with SGIX_shadow / ARB_shadow depth
// comparison: wrap modes, NEAREST and LINEAR filtering, mipmap selection, border texels.
#pragma once
#include <cstdint>

#include "pipeline/counters.hpp"
#include "pipeline/texture.hpp"

namespace passim {

// A filtered texture value in the base format's components (Table 3.18 sources):
// LUMINANCE fills r = g = b = L; INTENSITY fills all four; absent components are unused.
struct TexelValue {
  double r = 0.0, g = 0.0, b = 0.0, a = 1.0;
};

// Base levels and mipmap completeness (§3.8.10): the highest level index that must be
// defined; -1 when the texture is incomplete (texturing is then disabled).
int texture_complete_levels(const TextureObject& tex, int dims);

// Whether the result depends on λ (min and mag filters differ, or mipmapping): when it
// does not, λ need not be computed.
bool texture_needs_lod(const TextureObject& tex);

// NEAREST on one level (§3.8.5): the storage index (texel number, border included) of the
// texel (s, t) selects after wrapping, or −1 when it is the border colour.
std::int64_t nearest_texel_index(const TextureObject& tex, const TextureLevel& level, int dims, double s, double t);

// Samples the texture at (s, t) (already divided by q) with level-of-detail λ; `r` is the
// fragment's r/q for depth comparison. `dims` is 1 or 2.
// The fast path's LINEAR (TextureStage): the level filtered at (s, t) with the arithmetic of
// sample_texture, when the coordinates are finite and the footprint is stored texels (no
// border colour); counts the texels read. False: nothing counted, use sample_texture.
// LinearLevel holds what is the same for every fragment of a span.
struct LinearLevel {
  const double* values = nullptr;  // TextureLevel::values()
  int dims = 1, width = 0, border = 0, row_border = 0, w = 0, h = 1, bits_per_texel = 0;
  GLenum wrap_s = 0, wrap_t = 0;
};
LinearLevel linear_level(const TextureObject& tex, const TextureLevel& level, int dims);
bool linear_stored_footprint(const LinearLevel& level, double s, double t, TexelValue& out, Counters& counters);

TexelValue sample_texture(const TextureObject& tex, int dims, double s, double t, double r, double lambda,
                          int last_level, Counters& counters);

}  // namespace passim
