// Work counters, kept per pass (group marker) and in total. Counters follow the
// modelled machine's stage order; see docs/counters.md for each field.
#pragma once
#include <cstddef>
#include <cstdint>
#include <nlohmann/json_fwd.hpp>
#include <string>
#include <vector>

namespace passim {

// The counter fields, listed once: the struct, every sum, comparison and serialisation
// are made from this list (X(name) per field, in the modelled machine's stage order).
#define PASSIM_COUNTER_FIELDS(X) \
  /* geometry */ \
  X(vertices) \
  X(primitives_in) /* GL primitives: points, line segments, triangles, quads, polygons */ \
  X(primitives_clipped) /* cut by a clip plane (partly inside) */ \
  X(primitives_clipped_out) /* wholly outside the clip volume */ \
  X(primitives_culled) \
  X(triangles_rasterized) /* after clipping and fan decomposition */ \
  X(lighting_evaluations) /* vertex x face colour computations */ \
  /* texturing */ \
  X(texgen_evaluations) /* per vertex and generated coordinate */ \
  X(texture_lookups) /* per fragment (per level for *_MIPMAP_LINEAR: see texels) */ \
  X(texels_fetched) /* texels read from texture memory (border colours excluded) */ \
  X(texture_bits_read) /* at the internal format's widths */ \
  X(texture_bits_written) \
  X(fog_operations) \
  /* fragments */ \
  X(fragments_generated) \
  X(killed_scissor) \
  X(killed_alpha) \
  X(killed_stencil) \
  X(killed_depth) \
  X(fragments_written) /* passed every test (masks may still discard bits) */ \
  X(blend_operations) /* per fragment and draw buffer */ \
  X(logic_operations) \
  /* planes: bits read and written at their configured widths */ \
  X(color_bits_read) \
  X(color_bits_written) \
  X(depth_bits_read) \
  X(depth_bits_written) \
  X(stencil_bits_read) \
  X(stencil_bits_written) \
  X(accum_bits_read) \
  X(accum_bits_written) \
  /* pixel rectangles and transfer */ \
  X(pixels_transferred) /* groups through the pixel-transfer chain */ \
  X(pixels_scale_bias) \
  X(pixels_color_matrix) \
  X(pixels_mapped) /* groups through MAP_COLOR or MAP_STENCIL */ \
  X(pixels_convolved) \
  X(convolution_taps) /* multiply-adds (per pixel and tap) */ \
  X(color_table_lookups) /* pixels through COLOR_TABLE */ \
  X(post_convolution_table_lookups) \
  X(post_color_matrix_table_lookups) \
  X(histogram_updates) /* pixels counted */ \
  X(minmax_updates) \
  X(pixels_drawn) /* groups drawn by DrawPixels / CopyPixels (before zoom) */ \
  X(pixels_read) /* groups read by ReadPixels / CopyPixels / texture copies */ \
  /* accumulation buffer: pixels per operation */ \
  X(accum_accum_pixels) \
  X(accum_load_pixels) \
  X(accum_add_pixels) \
  X(accum_mult_pixels) \
  X(accum_return_pixels) \
  /* clears */ \
  X(clears) \
  X(clear_pixels) /* pixels x buffers cleared */

struct Counters {
#define PASSIM_COUNTER_MEMBER(name) std::uint64_t name = 0;
  PASSIM_COUNTER_FIELDS(PASSIM_COUNTER_MEMBER)
#undef PASSIM_COUNTER_MEMBER

  // f(name, member pointer) for every field, in the list's order.
  template <class F>
  static void for_each_field(F&& f) {
#define PASSIM_COUNTER_VISIT(name) f(#name, &Counters::name);
    PASSIM_COUNTER_FIELDS(PASSIM_COUNTER_VISIT)
#undef PASSIM_COUNTER_VISIT
  }
  static constexpr std::size_t field_count() {
#define PASSIM_COUNTER_ONE(name) +1
    return 0 PASSIM_COUNTER_FIELDS(PASSIM_COUNTER_ONE);
#undef PASSIM_COUNTER_ONE
  }

  Counters& operator+=(const Counters& o);
  bool operator==(const Counters& o) const;
  std::uint64_t fragments_killed() const { return killed_scissor + killed_alpha + killed_stencil + killed_depth; }
  // Conservation: generated = written + sum of kills. Empty when it holds.
  std::string balance_error() const;
  nlohmann::json to_json() const;
};

// Nothing but the listed fields: a member added outside the list would be missed by every sum.
static_assert(sizeof(Counters) == Counters::field_count() * sizeof(std::uint64_t));

struct Pass {
  std::string label;  // group-marker label; "(unmarked)" for work outside any marker
  int depth = 0;      // nesting depth of the marker
  Counters counters;
};

struct GlErrorRecord {
  std::string call;
  std::uint32_t error = 0;
  std::string where;  // "file:line" when replaying a trace
};

}  // namespace passim
