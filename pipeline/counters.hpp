// Work counters, kept per pass (group marker) and in total. Counters follow the
// modelled machine's stage order; see docs/counters.md for each field.
#pragma once
#include <cstdint>
#include <nlohmann/json_fwd.hpp>
#include <string>
#include <vector>

namespace passim {

// Every counter is a plain uint64 field listed once in for_each_field, so that
// adding, JSON output and comparison cannot drift apart.
struct Counters {
  // geometry
  std::uint64_t vertices = 0;
  std::uint64_t primitives_in = 0;         // GL primitives: points, triangles, quads, polygons
  std::uint64_t primitives_clipped = 0;    // cut by a clip plane (partly inside)
  std::uint64_t primitives_clipped_out = 0;  // wholly outside the clip volume
  std::uint64_t primitives_culled = 0;
  std::uint64_t triangles_rasterized = 0;  // after clipping and fan decomposition
  std::uint64_t lighting_evaluations = 0;  // vertex x face colour computations
  // texturing
  std::uint64_t texgen_evaluations = 0;  // per vertex and generated coordinate
  std::uint64_t texture_lookups = 0;     // per fragment (per level for *_MIPMAP_LINEAR: see texels)
  std::uint64_t texels_fetched = 0;      // texels read from texture memory (border colours excluded)
  std::uint64_t texture_bits_read = 0;   // at the internal format's widths
  std::uint64_t texture_bits_written = 0;
  std::uint64_t fog_operations = 0;
  // fragments
  std::uint64_t fragments_generated = 0;
  std::uint64_t killed_scissor = 0;
  std::uint64_t killed_alpha = 0;
  std::uint64_t killed_stencil = 0;
  std::uint64_t killed_depth = 0;
  std::uint64_t fragments_written = 0;  // passed every test (masks may still discard bits)
  std::uint64_t blend_operations = 0;   // per fragment and draw buffer
  std::uint64_t logic_operations = 0;
  // planes: bits read and written at their configured widths
  std::uint64_t color_bits_read = 0;
  std::uint64_t color_bits_written = 0;
  std::uint64_t depth_bits_read = 0;
  std::uint64_t depth_bits_written = 0;
  std::uint64_t stencil_bits_read = 0;
  std::uint64_t stencil_bits_written = 0;
  std::uint64_t accum_bits_read = 0;
  std::uint64_t accum_bits_written = 0;
  // pixel rectangles and transfer
  std::uint64_t pixels_transferred = 0;   // groups through the pixel-transfer chain
  std::uint64_t pixels_scale_bias = 0;
  std::uint64_t pixels_color_matrix = 0;
  std::uint64_t pixels_mapped = 0;  // groups through MAP_COLOR or MAP_STENCIL
  std::uint64_t pixels_convolved = 0;
  std::uint64_t convolution_taps = 0;               // multiply-adds (per pixel and tap)
  std::uint64_t color_table_lookups = 0;            // pixels through COLOR_TABLE
  std::uint64_t post_convolution_table_lookups = 0;
  std::uint64_t post_color_matrix_table_lookups = 0;
  std::uint64_t histogram_updates = 0;  // pixels counted
  std::uint64_t minmax_updates = 0;
  std::uint64_t pixels_drawn = 0;          // groups drawn by DrawPixels / CopyPixels (before zoom)
  std::uint64_t pixels_read = 0;           // groups read by ReadPixels / CopyPixels / texture copies
  // accumulation buffer: pixels per operation
  std::uint64_t accum_accum_pixels = 0;
  std::uint64_t accum_load_pixels = 0;
  std::uint64_t accum_add_pixels = 0;
  std::uint64_t accum_mult_pixels = 0;
  std::uint64_t accum_return_pixels = 0;
  // clears
  std::uint64_t clears = 0;
  std::uint64_t clear_pixels = 0;  // pixels x buffers cleared

  template <class F>
  static void for_each_field(F&& f) {
#define PASSIM_COUNTER(name) f(#name, &Counters::name);
    PASSIM_COUNTER(vertices)
    PASSIM_COUNTER(primitives_in)
    PASSIM_COUNTER(primitives_clipped)
    PASSIM_COUNTER(primitives_clipped_out)
    PASSIM_COUNTER(primitives_culled)
    PASSIM_COUNTER(triangles_rasterized)
    PASSIM_COUNTER(lighting_evaluations)
    PASSIM_COUNTER(texgen_evaluations)
    PASSIM_COUNTER(texture_lookups)
    PASSIM_COUNTER(texels_fetched)
    PASSIM_COUNTER(texture_bits_read)
    PASSIM_COUNTER(texture_bits_written)
    PASSIM_COUNTER(fog_operations)
    PASSIM_COUNTER(fragments_generated)
    PASSIM_COUNTER(killed_scissor)
    PASSIM_COUNTER(killed_alpha)
    PASSIM_COUNTER(killed_stencil)
    PASSIM_COUNTER(killed_depth)
    PASSIM_COUNTER(fragments_written)
    PASSIM_COUNTER(blend_operations)
    PASSIM_COUNTER(logic_operations)
    PASSIM_COUNTER(color_bits_read)
    PASSIM_COUNTER(color_bits_written)
    PASSIM_COUNTER(depth_bits_read)
    PASSIM_COUNTER(depth_bits_written)
    PASSIM_COUNTER(stencil_bits_read)
    PASSIM_COUNTER(stencil_bits_written)
    PASSIM_COUNTER(accum_bits_read)
    PASSIM_COUNTER(accum_bits_written)
    PASSIM_COUNTER(pixels_transferred)
    PASSIM_COUNTER(pixels_scale_bias)
    PASSIM_COUNTER(pixels_color_matrix)
    PASSIM_COUNTER(pixels_mapped)
    PASSIM_COUNTER(pixels_convolved)
    PASSIM_COUNTER(convolution_taps)
    PASSIM_COUNTER(color_table_lookups)
    PASSIM_COUNTER(post_convolution_table_lookups)
    PASSIM_COUNTER(post_color_matrix_table_lookups)
    PASSIM_COUNTER(histogram_updates)
    PASSIM_COUNTER(minmax_updates)
    PASSIM_COUNTER(pixels_drawn)
    PASSIM_COUNTER(pixels_read)
    PASSIM_COUNTER(accum_accum_pixels)
    PASSIM_COUNTER(accum_load_pixels)
    PASSIM_COUNTER(accum_add_pixels)
    PASSIM_COUNTER(accum_mult_pixels)
    PASSIM_COUNTER(accum_return_pixels)
    PASSIM_COUNTER(clears)
    PASSIM_COUNTER(clear_pixels)
#undef PASSIM_COUNTER
  }

  Counters& operator+=(const Counters& o);
  bool operator==(const Counters& o) const;
  std::uint64_t fragments_killed() const { return killed_scissor + killed_alpha + killed_stencil + killed_depth; }
  // Conservation: generated = written + sum of kills. Empty when it holds.
  std::string balance_error() const;
  nlohmann::json to_json() const;
};

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
