#include "stages/texture_sample.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>

#include "pipeline/fixed_point.hpp"
#include "stages/texture_wrap.hpp"

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
    std::array<double, 4> v;
    level.decode(static_cast<std::size_t>(j + bj) * static_cast<std::size_t>(level.width) + static_cast<std::size_t>(i + b),
                 v.data());
    return v;
  }
};


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


bool compares(const TextureObject& tex, const TextureLevel& level) {
  return level.format.base == GL_DEPTH_COMPONENT && (tex.compare_sgix || tex.compare_mode == GL_COMPARE_R_TO_TEXTURE);
}

void nearest_ij(const TextureObject& tex, const TextureLevel& level, int dims, double s, double t, int& i, int& j) {
  const int w = level.width - 2 * level.border, h = dims == 2 ? level.height - 2 * level.border : 1;
  i = nearest_index(s, tex.wrap_s, edge_of(w), w);
  j = dims == 2 ? nearest_index(t, tex.wrap_t, edge_of(h), h) : 0;
}

// A29 (ArithmeticOptions::texture_filter_8_8): whether llvmpipe's AoS sampler would filter this
// level — every component 8 bits (util_format_fits_8unorm for the formats GL 1.2 has), no
// border, the "simple" wraps (REPEAT, CLAMP_TO_EDGE), no comparison.
bool filters_in_8_8(const TextureObject& tex, const TextureLevel& level, int dims) {
  const InternalFormat& f = level.format;
  for (int bits : {f.red, f.green, f.blue, f.alpha, f.luminance, f.intensity})
    if (bits != 0 && bits != 8) return false;
  auto simple = [](GLenum wrap) { return wrap == GL_REPEAT || wrap == GL_CLAMP_TO_EDGE; };
  return f.base != GL_DEPTH_COMPONENT && level.border == 0 && simple(tex.wrap_s) && (dims == 1 || simple(tex.wrap_t));
}

// A29: the coordinate s of a level `size` texels wide in 8.8 fixed point, less half a texel:
// the float32 product s·(size·256) rounded to the nearest integer (ties to even, CVTPS2DQ;
// out of range: the "integer indefinite" 0x80000000), minus 128, in 32-bit wrapping arithmetic.
std::int32_t fixed_8_8(double s, int size) {
  const float f = static_cast<float>(s) * static_cast<float>(size * 256);
  const std::uint32_t rounded = f >= -2147483648.0f && f < 2147483648.0f
                                    ? static_cast<std::uint32_t>(static_cast<std::int32_t>(std::nearbyint(f)))
                                    : 0x80000000u;
  return static_cast<std::int32_t>(rounded - 128u);
}

// A29: the texel index pair of a fixed-point coordinate (REPEAT: modulo the power-of-two size;
// CLAMP_TO_EDGE: each index clamped) and its weight in 1/256.
void indices_8_8(std::int32_t fixed, GLenum wrap, int size, int& i0, int& i1, int& weight) {
  const int i = fixed >> 8;  // floor (arithmetic shift, C++20)
  weight = fixed & 255;
  if (wrap == GL_REPEAT) {
    i0 = i & (size - 1);
    i1 = (i + 1) & (size - 1);
  } else {
    i0 = std::clamp(i, 0, size - 1);
    i1 = std::clamp(i + 1, 0, size - 1);
  }
}

// A29: one lerp of 8-bit codes with a weight in 1/256, rounded as PMULHRSW rounds:
// a + ⌊(w·(b − a) + 128)/256⌋ (which lies between a and b).
inline int lerp_8_8(int weight, int a, int b) { return a + ((weight * (b - a) + 128) >> 8); }

TexelValue filter_level(const TextureObject& tex, const TextureLevel& level, int dims, GLenum filter, double s,
                        double t, double r, Counters& counters, bool filter_8_8) {
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
  } else if (filter_8_8 && !cmp && filters_in_8_8(tex, level, dims)) {
    int i0, i1, j0 = 0, j1 = 0, ws8, wt8 = 0;
    indices_8_8(fixed_8_8(s, w), tex.wrap_s, w, i0, i1, ws8);
    if (dims == 2) indices_8_8(fixed_8_8(t, h), tex.wrap_t, h, j0, j1, wt8);
    // The codes: every component is 8 bits (absent ones read 0 or 1: codes 0 or 255).
    auto codes = [&](int i, int j) {
      const std::array<double, 4> c = fetch.texel(i, j);
      std::array<int, 4> k;
      for (std::size_t n = 0; n < 4; ++n) k[n] = static_cast<int>(std::lround(c[n] * 255.0));
      return k;
    };
    const auto c00 = codes(i0, j0), c10 = codes(i1, j0);
    const auto c01 = dims == 2 ? codes(i0, j1) : c00, c11 = dims == 2 ? codes(i1, j1) : c10;
    for (std::size_t k = 0; k < 4; ++k) {
      const int row0 = lerp_8_8(ws8, c00[k], c10[k]);
      const int code = dims == 2 ? lerp_8_8(wt8, row0, lerp_8_8(ws8, c01[k], c11[k])) : row0;
      out[k] = static_cast<double>(code) / 255.0;
    }
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

LevelGeometry level_geometry(const TextureObject& tex, const TextureLevel& level, int dims) {
  LevelGeometry l;
  l.texels = level.texels.data();
  l.decoding = texel_decoding(level.format);
  l.dims = dims;
  l.width = level.width;
  l.border = level.border;
  l.row_border = row_border(level);
  l.w = level.width - 2 * level.border;
  l.h = dims == 2 ? level.height - 2 * level.border : 1;
  l.edge_s = edge_of(l.w);
  l.edge_t = edge_of(l.h);
  l.bits_per_texel = level.bits_per_texel();
  l.wrap_s = tex.wrap_s;
  l.wrap_t = tex.wrap_t;
  return l;
}

TexelValue sample_texture(const TextureObject& tex, int dims, double s, double t, double r, double lambda,
                          int last_level, Counters& counters, bool filter_8_8) {
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
  if (lambda <= c) return filter_level(tex, tex.levels[b], dims, tex.mag_filter, s, t, r, counters, filter_8_8);
  switch (tex.min_filter) {
    case GL_NEAREST:
    case GL_LINEAR:
      return filter_level(tex, tex.levels[b], dims, tex.min_filter, s, t, r, counters, filter_8_8);
    case GL_NEAREST_MIPMAP_NEAREST:
    case GL_LINEAR_MIPMAP_NEAREST: {
      // A9: d = b if λ <= 1/2, else ceil(b + λ + 1/2) − 1, at most q.
      // λ above 64 (or NaN, from NaN coordinates) is past every level: no int overflow.
      int d = lambda <= 0.5 ? b : !(lambda < 64.0) ? last_level : static_cast<int>(std::ceil(b + lambda + 0.5)) - 1;
      d = std::min(d, last_level);
      const GLenum f = tex.min_filter == GL_NEAREST_MIPMAP_NEAREST ? GL_NEAREST : GL_LINEAR;
      return filter_level(tex, tex.levels[d], dims, f, s, t, r, counters, filter_8_8);
    }
    default: {
      // *_MIPMAP_LINEAR: d1 = floor(b + λ), d2 = d1 + 1 (both q when b + λ >= q).
      const GLenum f = tex.min_filter == GL_NEAREST_MIPMAP_LINEAR ? GL_NEAREST : GL_LINEAR;
      const double bl = b + lambda;
      if (bl >= last_level) return filter_level(tex, tex.levels[last_level], dims, f, s, t, r, counters, filter_8_8);
      const int d1 = static_cast<int>(floor_exact(bl));
      const double frac = bl - floor_exact(bl);
      const TexelValue t1 = filter_level(tex, tex.levels[d1], dims, f, s, t, r, counters, filter_8_8);
      const TexelValue t2 = filter_level(tex, tex.levels[d1 + 1], dims, f, s, t, r, counters, filter_8_8);
      return {(1.0 - frac) * t1.r + frac * t2.r, (1.0 - frac) * t1.g + frac * t2.g, (1.0 - frac) * t1.b + frac * t2.b,
              (1.0 - frac) * t1.a + frac * t2.a};
    }
  }
}

}  // namespace passim
