#include "stages/texture_sample.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>

#include "pipeline/fixed_point.hpp"
#include "stages/avx2.hpp"
#include "stages/kernel_paths.hpp"

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

// §3.8.4 wrap applied to a coordinate before scaling; `edge` = 1/(2·size), CLAMP_TO_EDGE's limit.
inline double wrap_coordinate(double s, GLenum mode, double edge) {
  switch (mode) {
    case GL_REPEAT: return s - floor_exact(s);
    case GL_CLAMP_TO_EDGE: return std::clamp(s, edge, 1.0 - edge);
    default: return std::clamp(s, 0.0, 1.0);  // GL_CLAMP
  }
}
inline double edge_of(int size) { return 1.0 / (2.0 * size); }
double wrap_coordinate(double s, GLenum mode, int size) { return wrap_coordinate(s, mode, edge_of(size)); }

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
inline int nearest_index(double s, GLenum mode, double edge, int size) {
  const double u = wrap_coordinate(s, mode, edge) * size;
  return wrap_index(std::min(static_cast<int>(floor_exact(u)), size - 1), mode, size);
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

LevelGeometry level_geometry(const TextureObject& tex, const TextureLevel& level, int dims, bool with_values) {
  LevelGeometry l;
  l.values = with_values ? level.values().data() : nullptr;
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

namespace {

// The footprint of (s, t) on a LevelGeometry, as filter_level finds it: wrap, scale, the lower
// texel, the fractions; false when the coordinates are not finite or a texel lies beyond the
// stored ones (the border colour: the general path). 1D: t01 = t00, t11 = t10, beta = 0.
struct Footprint {
  const double *t00, *t10, *t01, *t11;
  double alpha, beta;
};
inline bool linear_footprint(const LevelGeometry& l, double s, double t, Footprint& f) {
  if (!std::isfinite(s) || !std::isfinite(t)) return false;
  const int b = l.border, w = l.w, h = l.h, dims = l.dims;
  const double uu = wrap_coordinate(s, l.wrap_s, l.edge_s) * w - 0.5;
  const double vv = dims == 2 ? wrap_coordinate(t, l.wrap_t, l.edge_t) * h - 0.5 : 0.0;
  const double fu = floor_exact(uu), fv = dims == 2 ? floor_exact(vv) : 0.0;
  const int i0 = static_cast<int>(fu), j0 = static_cast<int>(fv);
  f.alpha = uu - fu;
  f.beta = vv - fv;
  const int i[2] = {wrap_index(i0, l.wrap_s, w), wrap_index(i0 + 1, l.wrap_s, w)};
  const int j[2] = {dims == 2 ? wrap_index(j0, l.wrap_t, h) : 0, dims == 2 ? wrap_index(j0 + 1, l.wrap_t, h) : 0};
  if (i[0] < -b || i[1] >= w + b || i[1] < -b || i[0] >= w + b) return false;
  if (dims == 2 && (j[0] < -b || j[1] >= h + b || j[1] < -b || j[0] >= h + b)) return false;
  auto at = [&](int x, int y) {
    return l.values + 4 * (static_cast<std::size_t>(y + l.row_border) * static_cast<std::size_t>(l.width) +
                           static_cast<std::size_t>(x + b));
  };
  f.t00 = at(i[0], j[0]);
  f.t10 = at(i[1], j[0]);
  f.t01 = dims == 2 ? at(i[0], j[1]) : f.t00;
  f.t11 = dims == 2 ? at(i[1], j[1]) : f.t10;
  return true;
}

void count_footprint(const LevelGeometry& l, Counters& counters) {
  const std::uint64_t texels = l.dims == 2 ? 4 : 2;
  counters.texels_fetched += texels;
  counters.texture_bits_read += texels * static_cast<std::uint64_t>(l.bits_per_texel);
}

// The scalar reference's span loop (the AVX2 kernel does the same four fragments at a time):
// each fragment's footprint, or general[i] = 1; `filter` writes the codes of one fragment
// from its footprint.
template <class Filter>
[[gnu::always_inline]] inline std::uint64_t for_each_footprint(const LevelGeometry& l, const FragmentSpan& span,
                                                               std::uint8_t* general, Counters& counters,
                                                               Filter&& filter) {
  std::uint64_t filtered = 0;
  for (int i = 0; i < span.count; ++i) {
    Footprint f;
    general[i] = !linear_footprint(l, span.s[i], span.t[i], f);
    if (general[i]) continue;
    ++filtered;
    count_footprint(l, counters);
    filter(f, span.rgba + 4 * i);
  }
  return filtered;
}

}  // namespace

std::uint64_t linear_replace_span_scalar(const LevelGeometry& l, const FragmentSpan& span,
                                         const std::array<int, 4>& bits, const std::array<bool, 4>& replace,
                                         std::uint8_t* general, Counters& counters) {
  return for_each_footprint(l, span, general, counters, [&](const Footprint& f, std::uint16_t* c) {
    for (int k = 0; k < 4; ++k) {
      const double r = l.dims == 2 ? lerp_2d(f.alpha, f.beta, f.t00[k], f.t10[k], f.t01[k], f.t11[k])
                                   : lerp_1d(f.alpha, f.t00[k], f.t10[k]);
      if (replace[static_cast<std::size_t>(k)]) c[k] = static_cast<std::uint16_t>(float_to_fixed(r, bits[static_cast<std::size_t>(k)]));
    }
  });
}

#if defined(PASSIM_HAVE_AVX2_KERNEL)
namespace {

// wrap_coordinate on four finite coordinates: REPEAT's s − floor(s) (ROUNDPD's floor is
// floor_exact's value), CLAMP's and CLAMP_TO_EDGE's std::clamp as MAXPD/MINPD (equal for
// finite values).
__attribute__((target("avx2"))) inline __m256d wrap_coordinate_4(__m256d s, GLenum mode, double edge) {
  if (mode == GL_REPEAT) return _mm256_sub_pd(s, _mm256_floor_pd(s));
  const double lo = mode == GL_CLAMP_TO_EDGE ? edge : 0.0;
  return _mm256_min_pd(_mm256_max_pd(s, _mm256_set1_pd(lo)), _mm256_set1_pd(1.0 - lo));
}

// wrap_index on four lower indices i0 and their i0 + 1. Under REPEAT the wrapped coordinate
// lies in [0, 1], so i0 = floor(u − 1/2) lies in [−1, size − 1] and one conditional add or
// subtract of `size` is i mod size; the clamping modes leave indices alone.
__attribute__((target("avx2"))) inline void wrap_index_4(__m128i i0, GLenum mode, int size, __m128i& lo,
                                                         __m128i& hi) {
  const __m128i i1 = _mm_add_epi32(i0, _mm_set1_epi32(1));
  if (mode != GL_REPEAT) {
    lo = i0;
    hi = i1;
    return;
  }
  const __m128i n = _mm_set1_epi32(size);
  lo = _mm_add_epi32(i0, _mm_and_si128(_mm_cmplt_epi32(i0, _mm_setzero_si128()), n));
  hi = _mm_sub_epi32(i1, _mm_andnot_si128(_mm_cmplt_epi32(i1, n), n));
}

// The bits of a fragment's four 16-bit codes (as one 64-bit word) that REPLACE leaves alone.
std::uint64_t kept_bits(const std::array<bool, 4>& replace) {
  std::uint64_t keep = 0;
  for (std::size_t k = 0; k < 4; ++k)
    if (!replace[k]) keep |= std::uint64_t{0xffff} << (16 * k);
  return keep;
}
// The fragment's codes `c` take `codes` where `keep` is clear.
inline void merge_codes(std::uint16_t* c, std::uint64_t codes, std::uint64_t keep) {
  std::uint64_t old = 0;
  std::memcpy(&old, c, sizeof old);
  const std::uint64_t now = (old & keep) | (codes & ~keep);
  std::memcpy(c, &now, sizeof now);
}

// Four coordinates from a span, the lanes past its end (n < 4) at 0.
__attribute__((target("avx2"))) inline __m256d load_4(const double* x, int n) {
  if (n == 4) return _mm256_loadu_pd(x);
  alignas(32) double padded[4] = {0, 0, 0, 0};
  std::copy(x, x + n, padded);
  return _mm256_load_pd(padded);
}

// Lanes whose two indices both lie in [−border, size + border): linear_footprint's test.
__attribute__((target("avx2"))) inline __m128i stored_4(__m128i lo, __m128i hi, int border, int size) {
  const __m128i first = _mm_set1_epi32(-border - 1), end = _mm_set1_epi32(size + border);
  const __m128i lo_in = _mm_and_si128(_mm_cmpgt_epi32(lo, first), _mm_cmplt_epi32(lo, end));
  const __m128i hi_in = _mm_and_si128(_mm_cmpgt_epi32(hi, first), _mm_cmplt_epi32(hi, end));
  return _mm_and_si128(lo_in, hi_in);
}

}  // namespace

// linear_footprint and the filter on four fragments at a time: wrap, scale, floor, fractions,
// indices and weights in lanes (the same IEEE operations as the scalar reference, in the same
// order: no FMA under -ffp-contract=off and with mul/add intrinsics); then per fragment the
// four components at once — each weight times its texel, summed left to right — and
// float_to_fixed (clamp_nan_low to [0, 1], times 2^bits − 1, + 0.5, truncated). The codes
// `replace` selects are merged into the fragment's four with one mask.
__attribute__((target("avx2"))) std::uint64_t linear_replace_span_avx2(const LevelGeometry& l, const FragmentSpan& span,
                                                                       const std::array<int, 4>& bits,
                                                                       const std::array<bool, 4>& replace,
                                                                       std::uint8_t* general, Counters& counters) {
  const __m256d zero = _mm256_setzero_pd(), one = _mm256_set1_pd(1.0), half = _mm256_set1_pd(0.5);
  const __m256d scale = _mm256_setr_pd(static_cast<double>(max_code(bits[0])), static_cast<double>(max_code(bits[1])),
                                       static_cast<double>(max_code(bits[2])), static_cast<double>(max_code(bits[3])));
  const std::uint64_t keep = kept_bits(replace);
  const bool two = l.dims == 2;
  const __m256d w_size = _mm256_set1_pd(static_cast<double>(l.w)), h_size = _mm256_set1_pd(static_cast<double>(l.h));
  const std::size_t row = static_cast<std::size_t>(l.width);
  const double* origin = l.values + 4 * (static_cast<std::size_t>(l.row_border) * row + static_cast<std::size_t>(l.border));
  std::uint64_t filtered = 0;
  for (int i0 = 0; i0 < span.count; i0 += 4) {
    const int n = std::min(4, span.count - i0);
    __m256d s = load_4(span.s + i0, n), t = load_4(span.t + i0, n);
    // Finite lanes: x − x is 0 exactly for finite x, NaN for NaN and ±inf. The others take
    // 0 here (their results are discarded) so that no conversion sees a NaN.
    const __m256d finite = _mm256_and_pd(_mm256_cmp_pd(_mm256_sub_pd(s, s), zero, _CMP_EQ_OQ),
                                         _mm256_cmp_pd(_mm256_sub_pd(t, t), zero, _CMP_EQ_OQ));
    s = _mm256_and_pd(s, finite);
    t = _mm256_and_pd(t, finite);
    const __m256d uu = _mm256_sub_pd(_mm256_mul_pd(wrap_coordinate_4(s, l.wrap_s, l.edge_s), w_size), half);
    const __m256d fu = _mm256_floor_pd(uu);
    const __m256d alpha = _mm256_sub_pd(uu, fu);
    __m128i ilo, ihi;
    wrap_index_4(_mm256_cvttpd_epi32(fu), l.wrap_s, l.w, ilo, ihi);
    __m128i stored = stored_4(ilo, ihi, l.border, l.w);
    __m128i jlo = _mm_setzero_si128(), jhi = _mm_setzero_si128();
    __m256d beta = zero;
    if (two) {
      const __m256d vv = _mm256_sub_pd(_mm256_mul_pd(wrap_coordinate_4(t, l.wrap_t, l.edge_t), h_size), half);
      const __m256d fv = _mm256_floor_pd(vv);
      beta = _mm256_sub_pd(vv, fv);
      wrap_index_4(_mm256_cvttpd_epi32(fv), l.wrap_t, l.h, jlo, jhi);
      stored = _mm_and_si128(stored, stored_4(jlo, jhi, l.border, l.h));
    }
    const int lanes = _mm_movemask_ps(_mm_castsi128_ps(stored)) & _mm256_movemask_pd(finite) & ((1 << n) - 1);
    // The weights as lerp_1d / lerp_2d form them.
    const __m256d not_alpha = _mm256_sub_pd(one, alpha), not_beta = _mm256_sub_pd(one, beta);
    alignas(32) double w00[4], w10[4], w01[4], w11[4];
    if (two) {
      _mm256_store_pd(w00, _mm256_mul_pd(not_alpha, not_beta));
      _mm256_store_pd(w10, _mm256_mul_pd(alpha, not_beta));
      _mm256_store_pd(w01, _mm256_mul_pd(not_alpha, beta));
      _mm256_store_pd(w11, _mm256_mul_pd(alpha, beta));
    } else {
      _mm256_store_pd(w00, not_alpha);
      _mm256_store_pd(w10, alpha);
    }
    // Byte offsets from `origin` of the four texels, (j·row + i)·32, in 64 bits (VPMULDQ: the
    // signed 32-bit j times the row length).
    const __m256i row64 = _mm256_set1_epi64x(static_cast<long long>(row));
    const __m256i j0 = _mm256_mul_epi32(_mm256_cvtepi32_epi64(jlo), row64);
    const __m256i j1 = _mm256_mul_epi32(_mm256_cvtepi32_epi64(jhi), row64);
    const __m256i il = _mm256_cvtepi32_epi64(ilo), ih = _mm256_cvtepi32_epi64(ihi);
    alignas(32) std::int64_t o00[4], o10[4], o01[4], o11[4];
    _mm256_store_si256(reinterpret_cast<__m256i*>(o00), _mm256_slli_epi64(_mm256_add_epi64(j0, il), 5));
    _mm256_store_si256(reinterpret_cast<__m256i*>(o10), _mm256_slli_epi64(_mm256_add_epi64(j0, ih), 5));
    _mm256_store_si256(reinterpret_cast<__m256i*>(o01), _mm256_slli_epi64(_mm256_add_epi64(j1, il), 5));
    _mm256_store_si256(reinterpret_cast<__m256i*>(o11), _mm256_slli_epi64(_mm256_add_epi64(j1, ih), 5));
    const char* base = reinterpret_cast<const char*>(origin);
    for (int k = 0; k < n; ++k) {
      const bool ok = (lanes >> k) & 1;
      general[i0 + k] = !ok;
      if (!ok) continue;
      auto at = [&](const std::int64_t* o) { return reinterpret_cast<const double*>(base + o[k]); };
      __m256d r;
      if (two) {
        r = _mm256_mul_pd(_mm256_broadcast_sd(w00 + k), _mm256_loadu_pd(at(o00)));
        r = _mm256_add_pd(r, _mm256_mul_pd(_mm256_broadcast_sd(w10 + k), _mm256_loadu_pd(at(o10))));
        r = _mm256_add_pd(r, _mm256_mul_pd(_mm256_broadcast_sd(w01 + k), _mm256_loadu_pd(at(o01))));
        r = _mm256_add_pd(r, _mm256_mul_pd(_mm256_broadcast_sd(w11 + k), _mm256_loadu_pd(at(o11))));
      } else {
        r = _mm256_add_pd(_mm256_mul_pd(_mm256_broadcast_sd(w00 + k), _mm256_loadu_pd(at(o00))),
                          _mm256_mul_pd(_mm256_broadcast_sd(w10 + k), _mm256_loadu_pd(at(o10))));
      }
      const __m256d x = _mm256_add_pd(_mm256_mul_pd(clamp_nan_low_4(r, zero, one), scale), half);
      // Codes are at most 65535: PACKUSDW keeps them exactly.
      const __m128i codes = _mm_packus_epi32(_mm256_cvttpd_epi32(x), _mm_setzero_si128());
      merge_codes(span.rgba + 4 * (i0 + k), static_cast<std::uint64_t>(_mm_cvtsi128_si64(codes)), keep);
    }
    filtered += static_cast<std::uint64_t>(__builtin_popcount(static_cast<unsigned>(lanes)));
  }
  const std::uint64_t texels = two ? 4 : 2;
  counters.texels_fetched += filtered * texels;
  counters.texture_bits_read += filtered * texels * static_cast<std::uint64_t>(l.bits_per_texel);
  return filtered;
}
#endif

std::uint64_t linear_replace_span(const LevelGeometry& l, const FragmentSpan& span, const std::array<int, 4>& bits,
                                  const std::array<bool, 4>& replace, std::uint8_t* general, Counters& counters) {
#if defined(PASSIM_HAVE_AVX2_KERNEL)
  if (use_avx2()) return linear_replace_span_avx2(l, span, bits, replace, general, counters);
#endif
  return linear_replace_span_scalar(l, span, bits, replace, general, counters);
}

void nearest_replace_span_scalar(const LevelGeometry& l, const std::uint16_t* codes, const FragmentSpan& span,
                                 const std::array<bool, 4>& replace) {
  for (int n = 0; n < span.count; ++n) {
    const double s = std::isfinite(span.s[n]) ? span.s[n] : 0.0;  // as sample_texture
    const double t = std::isfinite(span.t[n]) ? span.t[n] : 0.0;
    // Every wrap mode puts the coordinate in [0, 1], so nearest_index lies in [0, size − 1]:
    // a stored texel, never the border or the border colour.
    const int i = nearest_index(s, l.wrap_s, l.edge_s, l.w);
    const int j = l.dims == 2 ? nearest_index(t, l.wrap_t, l.edge_t, l.h) : 0;
    const std::uint16_t* texel = codes + 4 * (static_cast<std::size_t>(j + l.row_border) * static_cast<std::size_t>(l.width) +
                                              static_cast<std::size_t>(i + l.border));
    std::uint16_t* c = span.rgba + 4 * n;
    for (int k = 0; k < 4; ++k)
      if (replace[static_cast<std::size_t>(k)]) c[k] = texel[k];
  }
}

#if defined(PASSIM_HAVE_AVX2_KERNEL)
// NEAREST on four fragments at a time: the wrapped coordinate lies in [0, 1] under every wrap
// mode, so floor(u) clamped to size − 1 is a stored texel's index (wrap_index leaves it alone).
__attribute__((target("avx2"))) void nearest_replace_span_avx2(const LevelGeometry& l, const std::uint16_t* codes,
                                                               const FragmentSpan& span,
                                                               const std::array<bool, 4>& replace) {
  const std::uint64_t keep = kept_bits(replace);
  const bool two = l.dims == 2;
  const __m256d zero = _mm256_setzero_pd();
  const __m256d w_size = _mm256_set1_pd(static_cast<double>(l.w)), h_size = _mm256_set1_pd(static_cast<double>(l.h));
  const __m128i w_last = _mm_set1_epi32(l.w - 1), h_last = _mm_set1_epi32(l.h - 1);
  const __m256i row64 = _mm256_set1_epi64x(static_cast<long long>(l.width));
  const std::uint16_t* origin =
      codes + 4 * (static_cast<std::size_t>(l.row_border) * static_cast<std::size_t>(l.width) +
                   static_cast<std::size_t>(l.border));
  for (int i0 = 0; i0 < span.count; i0 += 4) {
    const int n = std::min(4, span.count - i0);
    __m256d s = load_4(span.s + i0, n), t = load_4(span.t + i0, n);
    // Non-finite coordinates sample at 0 (x − x is NaN exactly for NaN and ±inf).
    s = _mm256_and_pd(s, _mm256_cmp_pd(_mm256_sub_pd(s, s), zero, _CMP_EQ_OQ));
    t = _mm256_and_pd(t, _mm256_cmp_pd(_mm256_sub_pd(t, t), zero, _CMP_EQ_OQ));
    const __m128i i = _mm_min_epi32(
        _mm256_cvttpd_epi32(_mm256_floor_pd(_mm256_mul_pd(wrap_coordinate_4(s, l.wrap_s, l.edge_s), w_size))), w_last);
    __m128i j = _mm_setzero_si128();
    if (two)
      j = _mm_min_epi32(
          _mm256_cvttpd_epi32(_mm256_floor_pd(_mm256_mul_pd(wrap_coordinate_4(t, l.wrap_t, l.edge_t), h_size))),
          h_last);
    // Element offsets (j·width + i)·4 of the texels' codes, in 64 bits.
    alignas(32) std::int64_t offset[4];
    _mm256_store_si256(reinterpret_cast<__m256i*>(offset),
                       _mm256_slli_epi64(_mm256_add_epi64(_mm256_mul_epi32(_mm256_cvtepi32_epi64(j), row64),
                                                          _mm256_cvtepi32_epi64(i)),
                                         2));
    for (int k = 0; k < n; ++k) {
      std::uint64_t texel = 0;
      std::memcpy(&texel, origin + offset[k], sizeof texel);
      merge_codes(span.rgba + 4 * (i0 + k), texel, keep);
    }
  }
}
#endif

void nearest_replace_span(const LevelGeometry& l, const std::uint16_t* codes, const FragmentSpan& span,
                          const std::array<bool, 4>& replace) {
#if defined(PASSIM_HAVE_AVX2_KERNEL)
  if (use_avx2()) return nearest_replace_span_avx2(l, codes, span, replace);
#endif
  nearest_replace_span_scalar(l, codes, span, replace);
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
