#include "stages/texture_sample.hpp"

#include <algorithm>
#include <cmath>

#include "pipeline/fixed_point.hpp"

namespace passim {
namespace {

bool is_mipmap_filter(GLenum f) { return f != GL_NEAREST && f != GL_LINEAR; }

// The border rows of a level: a 1D texture (one row) has its border at the row's ends only.
int row_border(const TextureLevel& level) { return level.height == 1 ? 0 : level.border; }

// Base-format components of the level's texel (i, j), or the border colour when (i, j) lies
// beyond the specified border (§3.8.5); the texel is read as k / (2^bits − 1).
struct Fetch {
  const TextureObject& tex;
  const TextureLevel& level;
  Counters& counters;
  const std::vector<double>& values = level.values();
  const int bits = level.bits_per_texel();

  // The raw components R, G, B, A (L in r, I in r, D in r) as reals.
  std::array<double, 4> texel(int i, int j) const {
    const int b = level.border, bj = row_border(level);
    const int w = level.width - 2 * b, h = level.height - 2 * bj;
    if (i < -b || i >= w + b || j < -bj || j >= h + bj) {
      const Vec4& c = tex.border_color;
      const InternalFormat& f = level.format;
      // Table 3.15: the border colour is taken as an RGBA colour and mapped like a texel.
      switch (f.base) {
        case GL_LUMINANCE: case GL_INTENSITY: case GL_DEPTH_COMPONENT: return {c.r, c.r, c.r, c.r};
        case GL_LUMINANCE_ALPHA: return {c.r, c.r, c.r, c.a};
        default: return {c.r, c.g, c.b, c.a};
      }
    }
    ++counters.texels_fetched;
    counters.texture_bits_read += static_cast<std::uint64_t>(bits);
    const std::size_t p = 4 * (static_cast<std::size_t>(j + bj) * static_cast<std::size_t>(level.width) +
                               static_cast<std::size_t>(i + b));
    return {values[p], values[p + 1], values[p + 2], values[p + 3]};
  }
};

// §3.8.4 wrap applied to a coordinate before scaling.
double wrap_coordinate(double s, GLenum mode, int size) {
  switch (mode) {
    case GL_REPEAT: return s - floor_exact(s);
    case GL_CLAMP_TO_EDGE: {
      const double lo = 1.0 / (2.0 * size), hi = 1.0 - lo;
      return std::clamp(s, lo, hi);
    }
    default: return std::clamp(s, 0.0, 1.0);  // GL_CLAMP
  }
}

int wrap_index(int i, GLenum mode, int size) {
  if (mode == GL_REPEAT) {
    int m = i % size;
    return m < 0 ? m + size : m;
  }
  return i;  // CLAMP may reach the border (or border colour); CLAMP_TO_EDGE cannot leave [0, size)
}

// Depth comparison of one texel (A25: r rounded to the texel's depth width, codes compared).
double compare_depth(const TextureObject& tex, const TextureLevel& level, double texel, double r) {
  const int bits = level.format.depth;
  const std::uint32_t d = float_to_fixed(texel, bits), rr = float_to_fixed(r, bits);
  bool pass;
  if (tex.compare_sgix) {
    // SGIX_shadow: LEQUAL_R passes when texel <= r, GEQUAL_R when texel >= r.
    pass = tex.compare_operator_sgix == GL_TEXTURE_GEQUAL_R_SGIX ? d >= rr : d <= rr;
  } else {
    // ARB_shadow: the function compares r with the texel D: LEQUAL passes when r <= D.
    pass = tex.compare_func == GL_GEQUAL ? rr >= d : rr <= d;
  }
  return pass ? 1.0 : tex.shadow_ambient;
}

// eq. 3.17: (1−α)τ0 + ατ1; eq. 3.18: (1−α)(1−β)τ00 + α(1−β)τ10 + (1−α)βτ01 + αβτ11, with A11's exact
// real weights — one expression for the general and the fast path, so the same bits.
inline double lerp_1d(double alpha, double a, double b) { return (1.0 - alpha) * a + alpha * b; }
inline double lerp_2d(double alpha, double beta, double t00, double t10, double t01, double t11) {
  return (1.0 - alpha) * (1.0 - beta) * t00 + alpha * (1.0 - beta) * t10 + (1.0 - alpha) * beta * t01 +
         alpha * beta * t11;
}

bool compares(const TextureObject& tex, const TextureLevel& level) {
  return level.format.base == GL_DEPTH_COMPONENT && (tex.compare_sgix || tex.compare_mode == GL_COMPARE_R_TO_TEXTURE);
}

// §3.8.5: i = floor(u), with s = 1 giving W − 1.
void nearest_ij(const TextureObject& tex, const TextureLevel& level, int dims, double s, double t, int& i, int& j) {
  const int w = level.width - 2 * level.border, h = dims == 2 ? level.height - 2 * level.border : 1;
  const double u = wrap_coordinate(s, tex.wrap_s, w) * w;
  const double v = dims == 2 ? wrap_coordinate(t, tex.wrap_t, h) * h : 0.0;
  i = wrap_index(std::min(static_cast<int>(floor_exact(u)), w - 1), tex.wrap_s, w);
  j = dims == 2 ? wrap_index(std::min(static_cast<int>(floor_exact(v)), h - 1), tex.wrap_t, h) : 0;
}

TexelValue filter_level(const TextureObject& tex, const TextureLevel& level, int dims, GLenum filter, double s,
                        double t, double r, Counters& counters) {
  const Fetch fetch{tex, level, counters};
  const int w = level.width - 2 * level.border, h = dims == 2 ? level.height - 2 * level.border : 1;
  const double ws = wrap_coordinate(s, tex.wrap_s, w);
  const double wt = dims == 2 ? wrap_coordinate(t, tex.wrap_t, h) : 0.0;
  const double u = ws * w, v = wt * h;
  const bool cmp = compares(tex, level);
  auto value = [&](int i, int j) {
    std::array<double, 4> c = fetch.texel(wrap_index(i, tex.wrap_s, w), dims == 2 ? wrap_index(j, tex.wrap_t, h) : 0);
    if (cmp) {
      const double x = compare_depth(tex, level, c[0], r);
      c = {x, x, x, x};
    }
    return c;
  };
  std::array<double, 4> out;
  if (filter == GL_NEAREST) {
    int i = 0, j = 0;
    nearest_ij(tex, level, dims, s, t, i, j);
    std::array<double, 4> c = fetch.texel(i, j);
    if (cmp) {
      const double x = compare_depth(tex, level, c[0], r);
      c = {x, x, x, x};
    }
    out = c;
  } else {
    const double uu = u - 0.5, vv = v - 0.5;
    const int i0 = static_cast<int>(floor_exact(uu)), j0 = dims == 2 ? static_cast<int>(floor_exact(vv)) : 0;
    const double alpha = uu - floor_exact(uu), beta = dims == 2 ? vv - floor_exact(vv) : 0.0;
    if (dims == 1) {
      const auto a = value(i0, 0), b = value(i0 + 1, 0);
      for (int k = 0; k < 4; ++k) out[k] = lerp_1d(alpha, a[k], b[k]);
    } else {
      const auto t00 = value(i0, j0), t10 = value(i0 + 1, j0), t01 = value(i0, j0 + 1), t11 = value(i0 + 1, j0 + 1);
      for (int k = 0; k < 4; ++k) out[k] = lerp_2d(alpha, beta, t00[k], t10[k], t01[k], t11[k]);
    }
  }
  TexelValue tv{out[0], out[1], out[2], out[3]};
  if (cmp) {
    // The comparison result is a depth-texture value, returned per DEPTH_TEXTURE_MODE.
    const double x = out[0];
    if (tex.depth_texture_mode == GL_ALPHA) tv = {0, 0, 0, x};
    else tv = {x, x, x, x};
  }
  return tv;
}

}  // namespace

int texture_complete_levels(const TextureObject& tex, int dims) {
  const int b = tex.base_level;
  if (b < 0 || b >= static_cast<int>(tex.levels.size()) || !tex.levels[b].defined()) return -1;
  if (!is_mipmap_filter(tex.min_filter)) return b;
  const TextureLevel& base = tex.levels[b];
  int w = base.width - 2 * base.border, h = base.height - 2 * base.border;
  int last = b;
  // Levels b+1 .. q halve each size (1 stays 1) with the same internal format and border.
  while ((w > 1 || (dims == 2 && h > 1)) && last < tex.max_level) {
    w = std::max(1, w / 2);
    h = dims == 2 ? std::max(1, h / 2) : 1;
    ++last;
    if (last >= static_cast<int>(tex.levels.size())) return -1;
    const TextureLevel& l = tex.levels[last];
    if (!l.defined() || l.width - 2 * l.border != w || (dims == 2 && l.height - 2 * l.border != h) ||
        l.format.requested != base.format.requested || l.border != base.border)
      return -1;
  }
  return last;
}

bool texture_needs_lod(const TextureObject& tex) {
  return is_mipmap_filter(tex.min_filter) || tex.min_filter != tex.mag_filter;
}

LinearLevel linear_level(const TextureObject& tex, const TextureLevel& level, int dims) {
  LinearLevel l;
  l.values = level.values().data();
  l.dims = dims;
  l.width = level.width;
  l.border = level.border;
  l.row_border = row_border(level);
  l.w = level.width - 2 * level.border;
  l.h = dims == 2 ? level.height - 2 * level.border : 1;
  l.bits_per_texel = level.bits_per_texel();
  l.wrap_s = tex.wrap_s;
  l.wrap_t = tex.wrap_t;
  return l;
}

bool linear_stored_footprint(const LinearLevel& l, double s, double t, TexelValue& out, Counters& counters) {
  if (!std::isfinite(s) || !std::isfinite(t)) return false;
  const int b = l.border, w = l.w, h = l.h, dims = l.dims;
  // As filter_level: wrap, scale, the lower texel and the fractions.
  const double uu = wrap_coordinate(s, l.wrap_s, w) * w - 0.5;
  const double vv = dims == 2 ? wrap_coordinate(t, l.wrap_t, h) * h - 0.5 : 0.0;
  const double fu = floor_exact(uu), fv = dims == 2 ? floor_exact(vv) : 0.0;
  const int i0 = static_cast<int>(fu), j0 = static_cast<int>(fv);
  const double alpha = uu - fu, beta = vv - fv;
  const int i[2] = {wrap_index(i0, l.wrap_s, w), wrap_index(i0 + 1, l.wrap_s, w)};
  const int j[2] = {dims == 2 ? wrap_index(j0, l.wrap_t, h) : 0, dims == 2 ? wrap_index(j0 + 1, l.wrap_t, h) : 0};
  // Only stored texels (the border colour takes the general path).
  if (i[0] < -b || i[1] >= w + b || i[1] < -b || i[0] >= w + b) return false;
  if (dims == 2 && (j[0] < -b || j[1] >= h + b || j[1] < -b || j[0] >= h + b)) return false;
  auto at = [&](int x, int y) {
    return l.values + 4 * (static_cast<std::size_t>(y + l.row_border) * static_cast<std::size_t>(l.width) +
                           static_cast<std::size_t>(x + b));
  };
  double r[4];
  if (dims == 1) {
    const double *a = at(i[0], 0), *c = at(i[1], 0);
    for (int k = 0; k < 4; ++k) r[k] = lerp_1d(alpha, a[k], c[k]);
  } else {
    const double *t00 = at(i[0], j[0]), *t10 = at(i[1], j[0]), *t01 = at(i[0], j[1]), *t11 = at(i[1], j[1]);
    for (int k = 0; k < 4; ++k) r[k] = lerp_2d(alpha, beta, t00[k], t10[k], t01[k], t11[k]);
  }
  const std::uint64_t texels = dims == 2 ? 4 : 2;
  counters.texels_fetched += texels;
  counters.texture_bits_read += texels * static_cast<std::uint64_t>(l.bits_per_texel);
  out = {r[0], r[1], r[2], r[3]};
  return true;
}

std::int64_t nearest_texel_index(const TextureObject& tex, const TextureLevel& level, int dims, double s, double t) {
  if (!std::isfinite(s)) s = 0.0;  // as sample_texture
  if (!std::isfinite(t)) t = 0.0;
  int i = 0, j = 0;
  nearest_ij(tex, level, dims, s, t, i, j);
  const int b = level.border, bj = row_border(level), w = level.width - 2 * b, h = level.height - 2 * bj;
  if (i < -b || i >= w + b || j < -bj || j >= h + bj) return -1;
  return static_cast<std::int64_t>(j + bj) * level.width + (i + b);
}

TexelValue sample_texture(const TextureObject& tex, int dims, double s, double t, double r, double lambda,
                          int last_level, Counters& counters) {
  ++counters.texture_lookups;
  // Non-finite coordinates (q = 0, overflow) are undefined in GL; they sample at 0 here.
  if (!std::isfinite(s)) s = 0.0;
  if (!std::isfinite(t)) t = 0.0;
  if (!std::isfinite(r)) r = 0.0;
  if (std::isnan(lambda)) lambda = 0.0;
  const int b = tex.base_level;
  // §3.8.7: magnification when λ <= c.
  const double c = (tex.mag_filter == GL_LINEAR &&
                    (tex.min_filter == GL_NEAREST_MIPMAP_NEAREST || tex.min_filter == GL_NEAREST_MIPMAP_LINEAR))
                       ? 0.5
                       : 0.0;
  if (lambda <= c) return filter_level(tex, tex.levels[b], dims, tex.mag_filter, s, t, r, counters);
  switch (tex.min_filter) {
    case GL_NEAREST:
    case GL_LINEAR:
      return filter_level(tex, tex.levels[b], dims, tex.min_filter, s, t, r, counters);
    case GL_NEAREST_MIPMAP_NEAREST:
    case GL_LINEAR_MIPMAP_NEAREST: {
      // A9: d = b if λ <= 1/2, else ceil(b + λ + 1/2) − 1, at most q.
      // λ above 64 (or NaN, from NaN coordinates) is past every level: no int overflow.
      int d = lambda <= 0.5 ? b : !(lambda < 64.0) ? last_level : static_cast<int>(std::ceil(b + lambda + 0.5)) - 1;
      d = std::min(d, last_level);
      const GLenum f = tex.min_filter == GL_NEAREST_MIPMAP_NEAREST ? GL_NEAREST : GL_LINEAR;
      return filter_level(tex, tex.levels[d], dims, f, s, t, r, counters);
    }
    default: {
      // *_MIPMAP_LINEAR: d1 = floor(b + λ), d2 = d1 + 1 (both q when b + λ >= q).
      const GLenum f = tex.min_filter == GL_NEAREST_MIPMAP_LINEAR ? GL_NEAREST : GL_LINEAR;
      const double bl = b + lambda;
      if (bl >= last_level) return filter_level(tex, tex.levels[last_level], dims, f, s, t, r, counters);
      const int d1 = static_cast<int>(floor_exact(bl));
      const double frac = bl - floor_exact(bl);
      const TexelValue t1 = filter_level(tex, tex.levels[d1], dims, f, s, t, r, counters);
      const TexelValue t2 = filter_level(tex, tex.levels[d1 + 1], dims, f, s, t, r, counters);
      return {(1.0 - frac) * t1.r + frac * t2.r, (1.0 - frac) * t1.g + frac * t2.g, (1.0 - frac) * t1.b + frac * t2.b,
              (1.0 - frac) * t1.a + frac * t2.a};
    }
  }
}

}  // namespace passim
