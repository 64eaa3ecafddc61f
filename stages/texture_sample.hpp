// Texture sampling, OpenGL 1.2.1 §3.8.5-3.8.8 with SGIX_shadow / ARB_shadow depth
// comparison: wrap modes, NEAREST and LINEAR filtering, mipmap selection, border texels.
#pragma once
#include <array>
#include <cstdint>

#include "pipeline/counters.hpp"
#include "pipeline/texture.hpp"
#include "stages/fragment_span.hpp"

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

// What the fast paths (TextureStage) need of one level, the same for every fragment of a
// span: its sizes and border, the wrap modes with CLAMP_TO_EDGE's limits, its codes and the
// tables that decode them.
struct LevelGeometry {
  const std::uint16_t* texels = nullptr;     // TextureLevel::texels
  const TexelDecoding* decoding = nullptr;   // texel_decoding (the fast paths need one)
  int dims = 1, width = 0, border = 0, row_border = 0, w = 0, h = 1, bits_per_texel = 0;
  double edge_s = 0.0, edge_t = 0.0;  // CLAMP_TO_EDGE's 1/(2w), 1/(2h)
  GLenum wrap_s = 0, wrap_t = 0;
};
LevelGeometry level_geometry(const TextureObject& tex, const TextureLevel& level, int dims);
// NEAREST over a span (§3.8.5, the fast path): each fragment's texel after wrapping
// (non-finite coordinates at 0, as sample_texture) — always a stored texel, as every wrap mode
// puts the coordinate in [0, 1] — and of its REPLACE codes (`codes`: the decoding's
// replace_codes at the fragment widths) those `replace` selects are copied into the fragment. The AVX2
// kernel (run-time choice) and the scalar reference give the same codes
// (`TextureKernels.NearestReplaceAvx2EqualsScalar`).
void nearest_replace_span(const LevelGeometry& level, const std::uint16_t* codes, const FragmentSpan& span,
                          const std::array<bool, 4>& replace);
void nearest_replace_span_scalar(const LevelGeometry& level, const std::uint16_t* codes, const FragmentSpan& span,
                                 const std::array<bool, 4>& replace);
// Over a span: where the footprint is stored texels, the filtered components `replace`
// selects become float_to_fixed at `bits` (REPLACE with A4's rounding) and general[i] = 0;
// elsewhere general[i] = 1 and nothing is written or counted. Returns the fragments filtered.
// The AVX2 kernel (chosen at run time) and the scalar reference give the same bits
// (`TextureKernels.LinearReplaceAvx2EqualsScalar`).
std::uint64_t linear_replace_span(const LevelGeometry& level, const FragmentSpan& span, const std::array<int, 4>& bits,
                                  const std::array<bool, 4>& replace, std::uint8_t* general, Counters& counters);
std::uint64_t linear_replace_span_scalar(const LevelGeometry& level, const FragmentSpan& span,
                                         const std::array<int, 4>& bits, const std::array<bool, 4>& replace,
                                         std::uint8_t* general, Counters& counters);

// Samples the texture at (s, t) (already divided by q) with level-of-detail λ; `r` is the
// fragment's r/q for depth comparison. `dims` is 1 or 2.
// `filter_8_8`: ArithmeticOptions::texture_filter_8_8 (LINEAR on 8-bit levels in 8.8 fixed point).
TexelValue sample_texture(const TextureObject& tex, int dims, double s, double t, double r, double lambda,
                          int last_level, Counters& counters, bool filter_8_8 = false);

}  // namespace passim
