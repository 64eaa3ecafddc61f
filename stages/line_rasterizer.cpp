// Line segment rasterization, OpenGL 1.2.1 §3.4 (A30-A34 of docs/arithmetic.md).
#include "stages/line_rasterizer.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstring>

#include "pipeline/fixed_point.hpp"

namespace passim {
namespace {

__extension__ using Wide = __int128;  // products of two snapped coordinates, with room

// Floor of n / d for d > 0.
std::int64_t floor_div(std::int64_t n, std::int64_t d) {
  std::int64_t q = n / d;
  if ((n % d) != 0 && n < 0) --q;
  return q;
}

// a + b·ε + c·ε² for an infinitesimal ε > 0 (the perturbation of §3.4.1), ordered
// lexicographically.
struct Perturbed {
  Wide a = 0, b = 0, c = 0;
  int sign() const {
    if (a != 0) return a > 0 ? 1 : -1;
    if (b != 0) return b > 0 ? 1 : -1;
    if (c != 0) return c > 0 ? 1 : -1;
    return 0;
  }
  Perturbed times(Wide k) const { return Perturbed{a * k, b * k, c * k}; }
  Perturbed minus(const Perturbed& o) const { return Perturbed{a - o.a, b - o.b, c - o.c}; }
};

// p/dp < q/dq for dp, dq != 0.
bool ratio_less(const Perturbed& p, Wide dp, const Perturbed& q, Wide dq) {
  const int s = p.times(dq).minus(q.times(dp)).sign();
  return (dp > 0) == (dq > 0) ? s < 0 : s > 0;
}

// §3.4.1, A30: whether the segment from A' = A − (ε, ε²) to B' = B − (ε, ε²) meets the open
// diamond |x − cx| + |y − cy| < S, and whether B' lies in it; every coordinate is an integer
// in snapped units (a pixel is 2S). The diamond is four open half-planes n·(P − C) < S,
// n = (±1, ±1); with P(t) = A' + t·(B − A) each is t·(n·D) < S − n·(A − C) + nx·ε + ny·ε²,
// a bound on t; the segment meets the diamond when the bounds and 0 <= t <= 1 leave a t.
struct DiamondTest {
  bool meets = false, holds_end = false;
};
DiamondTest diamond_test(std::int64_t ax, std::int64_t ay, std::int64_t bx, std::int64_t by, std::int64_t cx,
                         std::int64_t cy, std::int64_t S) {
  DiamondTest r;
  // The end point B': |bx − ε − cx| + |by − ε² − cy| < S. The ε part of the sum is −ε when
  // bx > cx and +ε otherwise, so on the boundary (sum of the integers = S) B' is inside exactly
  // when bx > cx.
  const std::int64_t ex = bx - cx, ey = by - cy;
  const std::int64_t end_sum = std::llabs(ex) + std::llabs(ey);
  r.holds_end = end_sum < S || (end_sum == S && ex > 0);
  const Wide dx = bx - ax, dy = by - ay;
  Perturbed lower[4], upper[4];
  Wide lower_d[4], upper_d[4];
  int lowers = 0, uppers = 0;
  for (int nx = -1; nx <= 1; nx += 2) {
    for (int ny = -1; ny <= 1; ny += 2) {
      const Wide d = nx * dx + ny * dy;
      const Perturbed rhs{Wide{S} - (Wide{nx} * (ax - cx) + Wide{ny} * (ay - cy)), nx, ny};
      if (d > 0) {
        upper[uppers] = rhs;
        upper_d[uppers++] = d;
      } else if (d < 0) {
        lower[lowers] = rhs;
        lower_d[lowers++] = d;
      } else if (rhs.sign() <= 0) {
        return r;  // 0 < rhs fails for every t
      }
    }
  }
  // Every open lower bound below 1 and below every open upper bound; every open upper bound
  // above 0.
  for (int i = 0; i < lowers; ++i)
    if (!ratio_less(lower[i], lower_d[i], Perturbed{1, 0, 0}, 1)) return r;
  for (int j = 0; j < uppers; ++j)
    if (!ratio_less(Perturbed{0, 0, 0}, 1, upper[j], upper_d[j])) return r;
  for (int i = 0; i < lowers; ++i)
    for (int j = 0; j < uppers; ++j)
      if (!ratio_less(lower[i], lower_d[i], upper[j], upper_d[j])) return r;
  r.meets = true;
  return r;
}

// The snapped end points of a segment of width w, shifted by −(w − 1)/2 in the minor
// direction (§3.4.2), and whether it is x-major (|Δx| >= |Δy| on the unshifted snapped points).
struct SnappedLine {
  std::int64_t ax, ay, bx, by, S;
  bool x_major;
};
SnappedLine snap_line(const RasterVertex& a, const RasterVertex& b, int width, int subpixel_bits) {
  SnappedLine l;
  l.S = std::int64_t{1} << subpixel_bits;
  l.ax = snap_coordinate(a.x, subpixel_bits);
  l.ay = snap_coordinate(a.y, subpixel_bits);
  l.bx = snap_coordinate(b.x, subpixel_bits);
  l.by = snap_coordinate(b.y, subpixel_bits);
  l.x_major = std::llabs(l.bx - l.ax) >= std::llabs(l.by - l.ay);
  // (w − 1)/2 pixels is (w − 1)·S snapped units: exact, so shifting after snapping is the same
  // as snapping the shifted coordinate.
  const std::int64_t shift = static_cast<std::int64_t>(width - 1) * l.S;
  if (l.x_major) {
    l.ay -= shift;
    l.by -= shift;
  } else {
    l.ax -= shift;
    l.bx -= shift;
  }
  return l;
}

// Calls f(column, row) for every fragment of the width-one segment l by the diamond-exit rule,
// in order from a to b. Candidates: along the major axis every pixel whose centre is within a
// pixel of the segment's extent, and across it the five pixels about the segment's position
// there (the diamond-meeting ones are among them: the segment moves at most a pixel across per
// pixel along).
template <class F>
void for_each_line_fragment(const SnappedLine& l, bool open_end, F&& f) {
  const std::int64_t S = l.S, pixel = 2 * S;
  if (l.ax == l.bx && l.ay == l.by) return;  // B' is in every diamond A' is in (nothing left by clipping either)
  // Major and minor coordinates.
  const std::int64_t ma = l.x_major ? l.ax : l.ay, mb = l.x_major ? l.bx : l.by;
  const std::int64_t na = l.x_major ? l.ay : l.ax, nb = l.x_major ? l.by : l.bx;
  const int step = mb >= ma ? 1 : -1;
  const std::int64_t first = floor_div(ma, pixel) - step, last = floor_div(mb, pixel) + step;
  const int minor_step = nb >= na ? 1 : -1;
  const double slope = static_cast<double>(nb - na) / static_cast<double>(mb - ma);
  for (std::int64_t m = first;; m += step) {
    const std::int64_t centre = (2 * m + 1) * S;
    const std::int64_t along = std::clamp(centre, std::min(ma, mb), std::max(ma, mb));
    const double across = static_cast<double>(na) + static_cast<double>(along - ma) * slope;
    const auto around = static_cast<std::int64_t>(std::floor(across / static_cast<double>(pixel)));
    for (int k = -2; k <= 2; ++k) {
      const std::int64_t n = around + minor_step * k;
      const std::int64_t col = l.x_major ? m : n, row = l.x_major ? n : m;
      const DiamondTest d = diamond_test(l.ax, l.ay, l.bx, l.by, (2 * col + 1) * S, (2 * row + 1) * S, S);
      if (d.meets && (open_end || !d.holds_end)) f(col, row);
    }
    if (m == last) break;
  }
}

// Eq. 3.5: t of the pixel centre's projection on the segment, clamped to [0, 1] (A32).
double line_parameter(const SnappedLine& l, std::int64_t col, std::int64_t row) {
  const Wide dx = l.bx - l.ax, dy = l.by - l.ay;
  const Wide px = (2 * col + 1) * l.S - l.ax, py = (2 * row + 1) * l.S - l.ay;
  const double t = static_cast<double>(px * dx + py * dy) / static_cast<double>(dx * dx + dy * dy);
  return std::clamp(t, 0.0, 1.0);
}

}  // namespace

int line_width_of(double width) {
  const double w = round_half_up(std::min(width, static_cast<double>(kMaxLineWidth)));
  return w < 1.0 ? 1 : static_cast<int>(w);
}

std::uint64_t line_fragment_count(const RasterVertex& a, const RasterVertex& b, int width, bool open_end,
                                  int subpixel_bits) {
  std::uint64_t n = 0;
  for_each_line_fragment(snap_line(a, b, width, subpixel_bits), open_end, [&](std::int64_t, std::int64_t) { ++n; });
  return n;
}

void rasterize_line(const RasterVertex& a, const RasterVertex& b, const TriangleOptions& attributes,
                    const LineOptions& options,
                    const RasterTarget& target, SpanBuffers& buffers, FragmentSink& sink, Counters& counters) {
  const SnappedLine l = snap_line(a, b, options.width, target.subpixel_bits);
  const TriangleOptions& o = attributes;
  const int w = options.width;
  // Eq. 3.6 weights: (1 − t)/wa and t/wb over their sum, for colours, texture coordinates and
  // the fog coordinate; depth is linear in t (eq. 3.7).
  const double qa = 1.0 / a.w, qb = 1.0 / b.w;
  std::uint16_t flat_codes[4];
  for (int k = 0; k < 4; ++k)
    flat_codes[k] = static_cast<std::uint16_t>(float_to_fixed(o.flat_color[k], target.color_bits[k]));
  // The segment's length in window units, for λ (§3.8.5: ρ along the segment).
  const double unit = static_cast<double>(2 * l.S);
  const double len_x = static_cast<double>(l.bx - l.ax) / unit, len_y = static_cast<double>(l.by - l.ay) / unit;
  const double length = std::sqrt(len_x * len_x + len_y * len_y);

  int stored = 0, stored_rows = 0;
  const auto hand_over = [&] {
    if (stored_rows == 0) return;
    FragmentSpan rows = buffers.span(0, 0, stored);
    if (o.texcoords && !o.lod) std::fill(rows.lambda, rows.lambda + stored, 0.0);
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
  // One fragment at (col, row) with the attributes of t; consecutive fragments of a row join
  // that row's run.
  const auto put = [&](std::int64_t col, std::int64_t row, double t) {
    if (col < 0 || row < 0 || col >= target.width || row >= target.height || !target.owns_row(row)) return;
    if (stored + 1 > buffers.capacity()) hand_over();
    SpanRow* last = stored_rows > 0 ? &buffers.rows[static_cast<std::size_t>(stored_rows - 1)] : nullptr;
    if (last && last->y == row && last->x0 + last->count == col) {
      ++last->count;
    } else {
      if (stored_rows == static_cast<int>(buffers.rows.size())) hand_over();
      buffers.rows[static_cast<std::size_t>(stored_rows++)] =
          SpanRow{static_cast<int>(row), static_cast<int>(col), 1, stored};
    }
    const int i = stored++;
    ++counters.fragments_generated;
    FragmentSpan f = buffers.span_at(i, static_cast<int>(row), static_cast<int>(col), 1);
    const double u = 1.0 - t;
    f.depth[0] = target.depth_bits == 0
                     ? 0u
                     : float_to_fixed(u * a.z + t * b.z + options.depth_offset, target.depth_bits);
    const double ua = u * qa, tb = t * qb, q = ua + tb;
    if (o.flat) {
      std::memcpy(f.rgba, flat_codes, sizeof(flat_codes));
    } else {
      for (int k = 0; k < 4; ++k)
        f.rgba[k] = static_cast<std::uint16_t>(
            float_to_fixed((ua * a.color[k] + tb * b.color[k]) / q, target.color_bits[k]));
    }
    if (o.texcoords) {
      double c[4];
      for (int k = 0; k < 4; ++k) c[k] = ua * a.tex[k] + tb * b.tex[k];  // (s, t, r, q)/w
      f.s[0] = c[0] / c[3];
      f.t[0] = o.texcoords_used >= 2 ? c[1] / c[3] : 0.0;
      f.r[0] = o.texcoords_used >= 3 ? c[2] / c[3] : 0.0;
      if (o.lod) {
        // d(a/q)/dt = (a'·q − a·q')/q² with a' = a_b/w_b − a_a/w_a along t; ρ = |(W·ds, H·dt)|/length.
        const double dq = b.tex[3] * qb - a.tex[3] * qa;
        const double ds = ((b.tex[0] * qb - a.tex[0] * qa) * c[3] - c[0] * dq) / (c[3] * c[3]);
        const double dt = ((b.tex[1] * qb - a.tex[1] * qa) * c[3] - c[1] * dq) / (c[3] * c[3]);
        const double du = o.lod_width * ds, dv = o.lod_height * dt;
        const double rho = std::sqrt(du * du + dv * dv) / length;
        f.lambda[0] = std::clamp(std::log2(rho), o.min_lod, o.max_lod);
      }
    }
    if (o.fog) f.fog[0] = std::fabs((ua * a.eye_z + tb * b.eye_z) / q);
  };
  std::uint64_t s = options.stipple_counter;
  for_each_line_fragment(l, options.open_end, [&](std::int64_t col, std::int64_t row) {
    // §3.4.2: the stipple bit floor(s / factor) mod 16, s counting width-one fragments.
    const bool kept = !options.stipple ||
                      ((options.stipple_pattern >> ((s / static_cast<std::uint64_t>(options.stipple_factor)) % 16)) & 1u);
    ++s;
    if (!kept) return;
    const double t = line_parameter(l, col, row);
    // §3.4.2: a column (x-major) or row (y-major) of w fragments from the width-one fragment
    // up, with its attributes.
    for (int k = 0; k < w; ++k) put(l.x_major ? col : col + k, l.x_major ? row + k : row, t);
  });
  hand_over();
}

}  // namespace passim
