// Line segment rasterization, OpenGL 1.2.1 §3.4, non-antialiased, with the choices of
// docs/arithmetic.md (A30-A34): end points snapped to 1/2^subpixel_bits of a pixel like polygon
// vertices, the diamond-exit rule (§3.4.1) decided exactly on the snapped points with the
// spec's perturbation (ε, ε²) taken symbolically, wide lines as columns (rows) of fragments
// (§3.4.2), the line stipple (§3.4.2), attributes interpolated by eq. 3.5-3.7 at the pixel
// centre with t clamped to [0, 1].
#pragma once
#include <cstdint>

#include "stages/rasterizer.hpp"

namespace passim {

// What a segment adds to the attributes' options (a TriangleOptions: shading, texture
// coordinates, λ and fog as for triangles; its offset fields are not read).
struct LineOptions {
  int width = 1;  // the rounded width, >= 1 (§3.4.2)
  // Line stipple (§3.4.2): a fragment is kept when bit floor(s / factor) mod 16 of the
  // pattern is 1, s counting the segment's width-one fragments from stipple_counter on.
  bool stipple = false;
  std::uint16_t stipple_pattern = 0xFFFF;
  int stipple_factor = 1;
  std::uint64_t stipple_counter = 0;
  double depth_offset = 0.0;  // added to z before the depth code (polygon offset, §3.5.5)
  // The end b was made by clipping (A31): the fragment whose diamond holds it is not excepted.
  bool open_end = false;
};

// The rounded width of §3.4.2 (w = round(width), 0 read as 1), at most kMaxLineWidth (A34).
constexpr int kMaxLineWidth = 64;
int line_width_of(double width);

// The number of width-one fragments the segment a → b of `width` produces by the diamond-exit
// rule, inside the window or not (how far it moves the stipple counter).
std::uint64_t line_fragment_count(const RasterVertex& a, const RasterVertex& b, int width, bool open_end,
                                  int subpixel_bits);

// Rasterizes the segment from a to b (a is its start: the diamond-exit rule is not symmetric)
// and hands its fragments inside the window to `sink`.
void rasterize_line(const RasterVertex& a, const RasterVertex& b, const TriangleOptions& attributes,
                    const LineOptions& options,
                    const RasterTarget& target, SpanBuffers& buffers, FragmentSink& sink, Counters& counters);

}  // namespace passim
