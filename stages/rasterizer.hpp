// Polygon and point rasterization, OpenGL 1.2.1 §3.3 and §3.5, with the choices
// of docs/arithmetic.md: vertices snapped to 1/2^subpixel_bits of a pixel, a
// fragment for each pixel centre inside the triangle, centres on left or bottom
// edges inside (A5), depth screen-linear (eq. 3.4 with w = 1), colours
// perspective-correct (A6), polygon offset in the max form (A7).
#pragma once
#include <array>
#include <cmath>

#include "pipeline/counters.hpp"
#include "pipeline/state.hpp"
#include "stages/fragment_span.hpp"

namespace passim {

struct RasterVertex {
  double x = 0.0, y = 0.0, z = 0.0;  // window coordinates, z in [0, 1]
  double w = 1.0;                    // clip w, for perspective correction
  Vec4 color{};                      // clamped, quantised colour
  Vec4 tex{0.0, 0.0, 0.0, 1.0};      // texture coordinates (s, t, r, q)
  double eye_z = 0.0;                // eye-coordinate z, for fog

  // False for w = 0 on the clip boundary (0/0): such a vertex cannot be placed in the window.
  bool finite_position() const { return std::isfinite(x) && std::isfinite(y) && std::isfinite(z); }
};

// Table 6.6 (the current raster position, its validity and colour).
struct RasterPosState {
  bool valid = true;
  RasterVertex window{};
  Vec4 color{1.0, 1.0, 1.0, 1.0};
};

struct RasterTarget {
  int width = 0, height = 0;  // the window: fragments outside are not produced (pixel ownership)
  int subpixel_bits = 4;
  int depth_bits = 24;
  std::array<int, 4> color_bits{8, 8, 8, 8};  // fragment colour widths
  // Row bands (pipeline/raster_lanes): rows are grouped in bands of band_rows and the bands
  // in cycles of band_cycle; only the rows of bands [band_first, band_first + band_count) of
  // each cycle are produced, and the per-primitive counters are counted by the owner of
  // band 0 alone. The default owns every row.
  int band_rows = 8, band_cycle = 1, band_first = 0, band_count = 1;
  bool owns_row(std::int64_t row) const {
    return band_cycle <= 1 || static_cast<std::uint64_t>((row / band_rows) % band_cycle - band_first) <
                                  static_cast<std::uint64_t>(band_count);
  }
  // For rows in [0, 2^31). Three 32-bit divisions, whatever the number of bands (it runs for
  // every queued triangle in every row group).
  bool owns_any_row(std::int64_t first_row, std::int64_t last_row) const {
    if (band_cycle <= 1) return true;
    const auto rows = static_cast<std::uint32_t>(band_rows), cycle = static_cast<std::uint32_t>(band_cycle);
    const std::uint32_t first_band = static_cast<std::uint32_t>(first_row) / rows;
    const std::uint32_t bands = static_cast<std::uint32_t>(last_row) / rows - first_band + 1;
    if (bands > cycle) return true;  // more than a whole cycle: every owner
    for (std::uint32_t k = 0, in_cycle = first_band % cycle; k < bands; ++k) {
      if (in_cycle - static_cast<std::uint32_t>(band_first) < static_cast<std::uint32_t>(band_count)) return true;
      if (++in_cycle == cycle) in_cycle = 0;
    }
    return false;
  }
  bool counts_primitives() const { return band_first == 0; }
  bool operator==(const RasterTarget&) const = default;
};

// owns_row for consecutive rows from `row` (>= 0) upwards, with two divisions in all rather
// than two per row (64-bit divisions were a tenth of a triangle's set-up and row walking).
class RowOwnership {
 public:
  RowOwnership(const RasterTarget& target, std::int64_t row)
      : target_(target), every_row_(target.band_cycle <= 1) {
    if (every_row_) return;
    row_in_band_ = row % target.band_rows;
    band_in_cycle_ = (row / target.band_rows) % target.band_cycle;
  }
  bool owned() const {
    return every_row_ ||
           static_cast<std::uint64_t>(band_in_cycle_ - target_.band_first) < static_cast<std::uint64_t>(target_.band_count);
  }
  void next_row() {
    if (every_row_ || ++row_in_band_ < target_.band_rows) return;
    row_in_band_ = 0;
    if (++band_in_cycle_ == target_.band_cycle) band_in_cycle_ = 0;
  }

 private:
  const RasterTarget& target_;
  bool every_row_;
  std::int64_t row_in_band_ = 0, band_in_cycle_ = 0;
};

struct TriangleOptions {
  bool flat = false;  // one colour for the whole triangle: flat_color
  Vec4 flat_color{};
  bool offset = false;
  double offset_factor = 0.0, offset_units = 0.0;
  bool texcoords = false;  // interpolate s/q, t/q, r/q (eq. 3.4 with α = q)
  int texcoords_used = 3;  // of s/q, t/q, r/q the first this many, those the texture stage reads (the others 0)
  bool lod = false;        // also compute λ (§3.8.5, eq. 3.15) for a base level of lod_width x lod_height
  double lod_width = 1.0, lod_height = 1.0;
  double min_lod = -1000.0, max_lod = 1000.0;
  bool fog = false;  // compute the fog coordinate |z_eye| (perspective-correct)
};

// The fixed-point coordinate of a window coordinate: round(x · 2^subpixel_bits), doubled so
// that pixel centres (x + 1/2) are integers too.
std::int64_t snap_coordinate(double window_coordinate, int subpixel_bits);

// The window rows whose pixel centres a triangle's bounding box (of its snapped vertices)
// can hold; empty (first > last) when there are none.
struct TriangleRows {
  std::int32_t first = 0, last = -1;
};
TriangleRows triangle_rows(const RasterVertex& v0, const RasterVertex& v1, const RasterVertex& v2, int subpixel_bits,
                           int window_height);
// True when `target` owns none of `rows`: the triangle is then passed over, counted as
// rasterize_triangle counts it, without its vertices being read.
inline bool pass_over_triangle(const TriangleRows& rows, const RasterTarget& target, Counters& counters) {
  if (rows.first <= rows.last && target.owns_any_row(rows.first, rows.last)) return false;
  if (target.counts_primitives()) ++counters.triangles_rasterized;
  return true;
}

// `rows`, when given, is triangle_rows of the same vertices on the same target: a triangle
// none of whose rows the target owns is then passed over without being set up (raster
// lanes compute it once per triangle, not once per row group).
void rasterize_triangle(const RasterVertex& v0, const RasterVertex& v1, const RasterVertex& v2,
                        const TriangleOptions& options, const RasterTarget& target, SpanBuffers& buffers,
                        FragmentSink& sink, Counters& counters, const TriangleRows* rows = nullptr);

// Non-antialiased point of the given size (§3.3.1), at most kMaxPointSize wide (the
// implementation's largest aliased point, A34).
constexpr double kMaxPointSize = 64.0;
// Point fragments take the vertex's s/q, t/q, r/q and λ = 0 (ρ = 1).
void rasterize_point(const RasterVertex& v, double size, const RasterTarget& target, SpanBuffers& buffers,
                     FragmentSink& sink, Counters& counters);

}  // namespace passim
