#include "stages/rasterizer.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <utility>

#include "pipeline/fixed_point.hpp"
#include "stages/span_kernels.hpp"

namespace passim {
namespace {

// Floor and ceiling of n / d for d > 0.
std::int64_t floor_div(std::int64_t n, std::int64_t d) {
  std::int64_t q = n / d;
  if ((n % d) != 0 && n < 0) --q;
  return q;
}
std::int64_t ceil_div(std::int64_t n, std::int64_t d) { return -floor_div(-n, d); }

// A plane f(x, y) = f0 + dfdx·(x - x0) + dfdy·(y - y0) through three attribute values at
// the snapped vertex positions (the eq. 3.4 interpolation written as a plane).
struct Plane {
  double f0 = 0.0, dfdx = 0.0, dfdy = 0.0;
  double at_row(double cy, double y0) const { return f0 + dfdy * (cy - y0); }
};

struct PlaneSetup {
  double x0, y0, ex1, ey1, ex2, ey2, det;  // edges from vertex 0 and the determinant
  Plane plane(double f0, double f1, double f2) const {
    Plane p;
    p.f0 = f0;
    p.dfdx = ((f1 - f0) * ey2 - (f2 - f0) * ey1) / det;
    p.dfdy = ((f2 - f0) * ex1 - (f1 - f0) * ex2) / det;
    return p;
  }
};

std::uint32_t depth_code(double z, int depth_bits) {
  if (depth_bits == 0) return 0;
  return float_to_fixed(z, depth_bits);  // clamps to [0, 1] (A7: clamp after offset), rounds (A8)
}

void constant_color_codes(const Vec4& c, const RasterTarget& t, std::uint16_t out[4]) {
  for (int k = 0; k < 4; ++k) out[k] = static_cast<std::uint16_t>(float_to_fixed(c[k], t.color_bits[k]));
}

}  // namespace

std::int64_t snap_coordinate(double window_coordinate, int subpixel_bits) {
  // Guard band: a vertex of a primitive that can touch a window (at most 4096 wide, viewports
  // at most as large) lies well inside ±2^17. Beyond it only the clipper's rounding on
  // degenerate input reaches (found by fuzzing, −2.5e30); clamping keeps the edge products
  // of snapped coordinates (2^31 · 2^31 at 12 sub-pixel bits) inside 64 bits.
  constexpr double kGuard = 131072.0;
  const double x = std::isnan(window_coordinate) ? 0.0 : std::clamp(window_coordinate, -kGuard, kGuard);
  const double scale = static_cast<double>(std::int64_t{1} << subpixel_bits);  // 2^bits, exact
  return 2 * static_cast<std::int64_t>(round_half_up(x * scale));
}

namespace {

// s/q, t/q, r/q (the span kernel) and, when λ is needed, λ (eq. 3.4, eq. 3.15).
void texture_coordinates(const Plane tex[4], const PlaneSetup& setup, double cy, int x0, int n,
                         const TriangleOptions& o, FragmentSpan& span) {
  SpanPlane stq[4];
  for (int k = 0; k < 4; ++k) stq[k] = SpanPlane{tex[k].at_row(cy, setup.y0), tex[k].dfdx};
  texture_coordinates(stq, x0, setup.x0, n, o.texcoords_used, span.s, span.t, span.r);
  if (!o.lod) return;  // λ = 0, written for the span's rows together (rasterize_triangle)
  for (int i = 0; i < n; ++i) {
    // ∂(a/q)/∂x = (a_x·q − a·q_x)/q², likewise for y; u = W·s, v = H·t;
    // ρ = max(‖(∂u/∂x, ∂v/∂x)‖, ‖(∂u/∂y, ∂v/∂y)‖), λ = log2 ρ clamped to [MIN_LOD, MAX_LOD].
    const double dx = (static_cast<double>(x0 + i) + 0.5) - setup.x0;
    double a[4];
    for (int k = 0; k < 4; ++k) a[k] = stq[k].row + tex[k].dfdx * dx;
    const double q = a[3], q2 = q * q;
    const double dudx = o.lod_width * (tex[0].dfdx * q - a[0] * tex[3].dfdx) / q2;
    const double dvdx = o.lod_height * (tex[1].dfdx * q - a[1] * tex[3].dfdx) / q2;
    const double dudy = o.lod_width * (tex[0].dfdy * q - a[0] * tex[3].dfdy) / q2;
    const double dvdy = o.lod_height * (tex[1].dfdy * q - a[1] * tex[3].dfdy) / q2;
    const double rho = std::max(std::sqrt(dudx * dudx + dvdx * dvdx), std::sqrt(dudy * dudy + dvdy * dvdy));
    span.lambda[i] = std::clamp(std::log2(rho), o.min_lod, o.max_lod);
  }
}

// The pixels, 0 to size − 1, whose centres (2p + 1)·S lie in [lo, hi] (snapped units, S half
// a pixel).
std::pair<std::int64_t, std::int64_t> centres_between(std::int64_t lo, std::int64_t hi, std::int64_t S, int size) {
  return {std::max<std::int64_t>(0, ceil_div(lo - S, 2 * S)), std::min<std::int64_t>(size - 1, floor_div(hi - S, 2 * S))};
}

}  // namespace

TriangleRows triangle_rows(const RasterVertex& a, const RasterVertex& b, const RasterVertex& c, int subpixel_bits,
                           int window_height) {
  const std::int64_t Y[3] = {snap_coordinate(a.y, subpixel_bits), snap_coordinate(b.y, subpixel_bits),
                             snap_coordinate(c.y, subpixel_bits)};
  const auto [first, last] = centres_between(std::min({Y[0], Y[1], Y[2]}), std::max({Y[0], Y[1], Y[2]}),
                                             std::int64_t{1} << subpixel_bits, window_height);
  if (first > last) return TriangleRows{};
  return TriangleRows{static_cast<std::int32_t>(first), static_cast<std::int32_t>(last)};
}

void rasterize_triangle(const RasterVertex& a, const RasterVertex& b, const RasterVertex& c,
                        const TriangleOptions& options, const RasterTarget& target, SpanBuffers& buffers,
                        FragmentSink& sink, Counters& counters, const TriangleRows* rows) {
  if (rows && pass_over_triangle(*rows, target, counters)) return;
  if (target.counts_primitives()) ++counters.triangles_rasterized;
  const std::int64_t S = std::int64_t{1} << target.subpixel_bits;  // half a pixel in doubled units
  const std::int64_t pixel = 2 * S;
  const RasterVertex* v[3] = {&a, &b, &c};
  std::int64_t X[3], Y[3];
  for (int i = 0; i < 3; ++i) {
    X[i] = snap_coordinate(v[i]->x, target.subpixel_bits);
    Y[i] = snap_coordinate(v[i]->y, target.subpixel_bits);
  }
  std::int64_t area = (X[1] - X[0]) * (Y[2] - Y[0]) - (X[2] - X[0]) * (Y[1] - Y[0]);
  if (area == 0) return;  // degenerate after snapping: no pixel centre is strictly inside
  if (area < 0) {         // make the vertex order counter-clockwise (y up)
    std::swap(v[1], v[2]);
    std::swap(X[1], X[2]);
    std::swap(Y[1], Y[2]);
    area = -area;
  }

  // Rows and columns whose centres (2x+1)·S can lie inside the bounding box.
  const std::int64_t min_x = std::min({X[0], X[1], X[2]}), max_x = std::max({X[0], X[1], X[2]});
  const std::int64_t min_y = std::min({Y[0], Y[1], Y[2]}), max_y = std::max({Y[0], Y[1], Y[2]});
  const auto [col_lo, col_hi] = centres_between(min_x, max_x, S, target.width);
  const auto [row_lo, row_hi] = centres_between(min_y, max_y, S, target.height);
  if (col_lo > col_hi || row_lo > row_hi) return;
  if (!rows && !target.owns_any_row(row_lo, row_hi)) return;  // another raster lane's rows only

  // Edge k runs from vertex k+1 to vertex k+2; E_k(P) = dx·(Py - ay) - dy·(Px - ax) > 0 inside.
  // A5: a centre exactly on an edge is inside when the edge is a left edge (dy < 0) or a
  // bottom edge (dy == 0, dx > 0), so an edge shared by two triangles is drawn once.
  struct Edge {
    std::int64_t ax, ay, dx, dy, threshold;
  } edges[3];
  for (int k = 0; k < 3; ++k) {
    const int i = (k + 1) % 3, j = (k + 2) % 3;
    Edge& e = edges[k];
    e.ax = X[i];
    e.ay = Y[i];
    e.dx = X[j] - X[i];
    e.dy = Y[j] - Y[i];
    e.threshold = (e.dy < 0 || (e.dy == 0 && e.dx > 0)) ? 0 : 1;
  }

  // Planes in window coordinates of the snapped vertices (exact: divisions by powers of two).
  const double unit = static_cast<double>(pixel);
  PlaneSetup setup;
  setup.x0 = static_cast<double>(X[0]) / unit;
  setup.y0 = static_cast<double>(Y[0]) / unit;
  setup.ex1 = static_cast<double>(X[1] - X[0]) / unit;
  setup.ey1 = static_cast<double>(Y[1] - Y[0]) / unit;
  setup.ex2 = static_cast<double>(X[2] - X[0]) / unit;
  setup.ey2 = static_cast<double>(Y[2] - Y[0]) / unit;
  setup.det = static_cast<double>(area) / (unit * unit);

  const Plane z_plane = setup.plane(v[0]->z, v[1]->z, v[2]->z);
  double offset = 0.0;
  if (options.offset) {
    // §3.5.5, eq. 3.6 (max form), r = one step of the depth plane (A7).
    const double m = std::max(std::fabs(z_plane.dfdx), std::fabs(z_plane.dfdy));
    const double r = target.depth_bits > 0 ? 1.0 / static_cast<double>(max_code(target.depth_bits)) : 0.0;
    offset = m * options.offset_factor + r * options.offset_units;
  }

  // Colour: constant (flat shading, or three equal quantised colours) or perspective-correct
  // (eq. 3.4: planes of c/w and 1/w; per fragment c = (c/w plane) · (1 / (1/w plane))).
  std::uint16_t constant_codes[4];
  bool constant = options.flat || (v[0]->color == v[1]->color && v[1]->color == v[2]->color);
  if (constant) constant_color_codes(options.flat ? options.flat_color : v[0]->color, target, constant_codes);
  Plane q_plane, c_plane[4];
  if (!constant) {
    const double q0 = 1.0 / v[0]->w, q1 = 1.0 / v[1]->w, q2 = 1.0 / v[2]->w;
    q_plane = setup.plane(q0, q1, q2);
    for (int k = 0; k < 4; ++k)
      c_plane[k] = setup.plane(v[0]->color[k] * q0, v[1]->color[k] * q1, v[2]->color[k] * q2);
  }

  // Texture coordinates: planes of s/w, t/w, r/w and q/w; the fragment's s/q is their ratio.
  Plane tex_plane[4];
  if (options.texcoords) {
    for (int k = 0; k < 4; ++k) {
      const double w0 = 1.0 / v[0]->w, w1 = 1.0 / v[1]->w, w2 = 1.0 / v[2]->w;
      tex_plane[k] = setup.plane(v[0]->tex[k] * w0, v[1]->tex[k] * w1, v[2]->tex[k] * w2);
    }
  }
  // Fog coordinate: planes of z_eye/w and 1/w.
  Plane fog_plane, fog_q;
  if (options.fog) {
    const double w0 = 1.0 / v[0]->w, w1 = 1.0 / v[1]->w, w2 = 1.0 / v[2]->w;
    fog_plane = setup.plane(v[0]->eye_z * w0, v[1]->eye_z * w1, v[2]->eye_z * w2);
    fog_q = setup.plane(w0, w1, w2);
  }
  const double depth_scale = static_cast<double>(max_code(target.depth_bits));
  double color_scale[4];
  for (int k = 0; k < 4; ++k) color_scale[k] = static_cast<double>(max_code(target.color_bits[k]));
  // The rows go to the stages together, as one span of several rows, as many as the span
  // buffers hold: the texture stage then takes a triangle's fragments in one run.
  int stored = 0, stored_rows = 0;
  const auto hand_over = [&] {
    if (stored_rows == 0) return;
    FragmentSpan rows = buffers.span(0, 0, stored);
    if (options.texcoords && !options.lod) std::fill(rows.lambda, rows.lambda + stored, 0.0);
    if (stored_rows == 1) {
      rows.y = buffers.rows[0].y;
      rows.x0 = buffers.rows[0].x0;
    } else {
      rows.rows = buffers.rows.data();
      rows.row_count = stored_rows;
    }
    sink.process(rows);
    stored = stored_rows = 0;
  };
  RowOwnership ownership(target, row_lo);
  for (std::int64_t row = row_lo; row <= row_hi; ++row, ownership.next_row()) {
    if (!ownership.owned()) continue;
    const std::int64_t py = (2 * row + 1) * S;
    std::int64_t lo = col_lo, hi = col_hi;
    for (const Edge& e : edges) {
      // E(x) = e0 + x·step at the centre of column x.
      const std::int64_t e0 = e.dx * (py - e.ay) - e.dy * (S - e.ax);
      const std::int64_t step = -e.dy * pixel;
      if (step > 0) {
        lo = std::max(lo, ceil_div(e.threshold - e0, step));
      } else if (step < 0) {
        hi = std::min(hi, floor_div(e0 - e.threshold, -step));
      } else if (e0 < e.threshold) {
        lo = hi + 1;
      }
      if (lo > hi) break;
    }
    if (lo > hi) continue;
    const int x0 = static_cast<int>(lo), n = static_cast<int>(hi - lo + 1);
    if (stored + n > buffers.capacity()) hand_over();
    FragmentSpan span = buffers.span_at(stored, static_cast<int>(row), x0, n);
    buffers.rows[static_cast<std::size_t>(stored_rows++)] = SpanRow{static_cast<int>(row), x0, n, stored};
    stored += n;
    counters.fragments_generated += static_cast<std::uint64_t>(n);

    const double cy = static_cast<double>(row) + 0.5;
    if (target.depth_bits == 0) {
      std::fill(span.depth, span.depth + n, 0u);
    } else {
      depth_codes_padded(SpanPlane{z_plane.at_row(cy, setup.y0), z_plane.dfdx}, offset, x0, setup.x0, n, depth_scale,
                         span.depth);
    }
    if (constant) {
      for (int i = 0; i < n; ++i) std::memcpy(span.rgba + 4 * i, constant_codes, sizeof(constant_codes));
    } else {
      SpanPlane c[4];
      for (int k = 0; k < 4; ++k) c[k] = SpanPlane{c_plane[k].at_row(cy, setup.y0), c_plane[k].dfdx};
      color_codes_padded(SpanPlane{q_plane.at_row(cy, setup.y0), q_plane.dfdx}, c, color_scale, x0, setup.x0, n,
                         span.rgba);
    }
    if (options.texcoords) texture_coordinates(tex_plane, setup, cy, x0, n, options, span);
    if (options.fog) {
      const double f_row = fog_plane.at_row(cy, setup.y0), q_row = fog_q.at_row(cy, setup.y0);
      for (int i = 0; i < n; ++i) {
        const double dx = (static_cast<double>(x0 + i) + 0.5) - setup.x0;
        span.fog[i] = std::fabs((f_row + fog_plane.dfdx * dx) / (q_row + fog_q.dfdx * dx));
      }
    }
  }
  hand_over();
}

void rasterize_point(const RasterVertex& v, double size, const RasterTarget& target, SpanBuffers& buffers,
                     FragmentSink& sink, Counters& counters) {
  // §3.3.1: width w = max(1, round(size)); odd w is centred on the pixel holding the point,
  // even w on the nearest pixel corner.
  // Sizes above kMaxPointSize draw as that size (A34).
  const int w = std::max(1, static_cast<int>(round_half_up(std::min(size, kMaxPointSize))));
  std::int64_t x_lo, y_lo;
  if (w % 2 == 1) {
    x_lo = static_cast<std::int64_t>(std::floor(v.x)) - (w - 1) / 2;
    y_lo = static_cast<std::int64_t>(std::floor(v.y)) - (w - 1) / 2;
  } else {
    x_lo = static_cast<std::int64_t>(std::floor(v.x + 0.5)) - w / 2;
    y_lo = static_cast<std::int64_t>(std::floor(v.y + 0.5)) - w / 2;
  }
  const std::int64_t x_a = std::max<std::int64_t>(0, x_lo), x_b = std::min<std::int64_t>(target.width - 1, x_lo + w - 1);
  const std::int64_t y_a = std::max<std::int64_t>(0, y_lo), y_b = std::min<std::int64_t>(target.height - 1, y_lo + w - 1);
  if (x_a > x_b || y_a > y_b) return;
  std::uint16_t codes[4];
  constant_color_codes(v.color, target, codes);
  const std::uint32_t z = depth_code(v.z, target.depth_bits);
  for (std::int64_t row = y_a; row <= y_b; ++row) {
    if (!target.owns_row(row)) continue;
    const int n = static_cast<int>(x_b - x_a + 1);
    FragmentSpan span = buffers.span(static_cast<int>(row), static_cast<int>(x_a), n);
    counters.fragments_generated += static_cast<std::uint64_t>(n);
    for (int i = 0; i < n; ++i) {
      span.depth[i] = z;
      for (int k = 0; k < 4; ++k) span.rgba[4 * i + k] = codes[k];
      span.s[i] = v.tex[0] / v.tex[3];
      span.t[i] = v.tex[1] / v.tex[3];
      span.r[i] = v.tex[2] / v.tex[3];
      span.lambda[i] = 0.0;
      span.fog[i] = std::fabs(v.eye_z);
    }
    sink.process(span);
  }
}

}  // namespace passim
