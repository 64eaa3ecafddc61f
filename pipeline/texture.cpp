#include "pipeline/texture.hpp"

#include <algorithm>
#include <mutex>

#include "pipeline/fixed_point.hpp"

namespace passim {

std::optional<InternalFormat> internal_format(GLint f, int u) {
  InternalFormat r;
  r.requested = static_cast<GLenum>(f);
  auto rgba = [&](GLenum base, int R, int G, int B, int A) {
    r.base = base;
    r.red = R;
    r.green = G;
    r.blue = B;
    r.alpha = A;
    return r;
  };
  auto la = [&](GLenum base, int L, int A) {
    r.base = base;
    r.luminance = L;
    r.alpha = A;
    return r;
  };
  switch (static_cast<GLenum>(f)) {
    case 1: case GL_LUMINANCE: return la(GL_LUMINANCE, u, 0);
    case 2: case GL_LUMINANCE_ALPHA: return la(GL_LUMINANCE_ALPHA, u, u);
    case 3: case GL_RGB: return rgba(GL_RGB, u, u, u, 0);
    case 4: case GL_RGBA: return rgba(GL_RGBA, u, u, u, u);
    case GL_ALPHA: return la(GL_ALPHA, 0, u);
    case GL_INTENSITY: r.base = GL_INTENSITY; r.intensity = u; return r;
    case GL_ALPHA4: return la(GL_ALPHA, 0, 4);
    case GL_ALPHA8: return la(GL_ALPHA, 0, 8);
    case GL_ALPHA12: return la(GL_ALPHA, 0, 12);
    case GL_ALPHA16: return la(GL_ALPHA, 0, 16);
    case GL_LUMINANCE4: return la(GL_LUMINANCE, 4, 0);
    case GL_LUMINANCE8: return la(GL_LUMINANCE, 8, 0);
    case GL_LUMINANCE12: return la(GL_LUMINANCE, 12, 0);
    case GL_LUMINANCE16: return la(GL_LUMINANCE, 16, 0);
    case GL_LUMINANCE4_ALPHA4: return la(GL_LUMINANCE_ALPHA, 4, 4);
    case GL_LUMINANCE6_ALPHA2: return la(GL_LUMINANCE_ALPHA, 6, 2);
    case GL_LUMINANCE8_ALPHA8: return la(GL_LUMINANCE_ALPHA, 8, 8);
    case GL_LUMINANCE12_ALPHA4: return la(GL_LUMINANCE_ALPHA, 12, 4);
    case GL_LUMINANCE12_ALPHA12: return la(GL_LUMINANCE_ALPHA, 12, 12);
    case GL_LUMINANCE16_ALPHA16: return la(GL_LUMINANCE_ALPHA, 16, 16);
    case GL_INTENSITY4: r.base = GL_INTENSITY; r.intensity = 4; return r;
    case GL_INTENSITY8: r.base = GL_INTENSITY; r.intensity = 8; return r;
    case GL_INTENSITY12: r.base = GL_INTENSITY; r.intensity = 12; return r;
    case GL_INTENSITY16: r.base = GL_INTENSITY; r.intensity = 16; return r;
    case GL_R3_G3_B2: return rgba(GL_RGB, 3, 3, 2, 0);
    case GL_RGB4: return rgba(GL_RGB, 4, 4, 4, 0);
    case GL_RGB5: return rgba(GL_RGB, 5, 5, 5, 0);
    case GL_RGB8: return rgba(GL_RGB, 8, 8, 8, 0);
    case GL_RGB10: return rgba(GL_RGB, 10, 10, 10, 0);
    case GL_RGB12: return rgba(GL_RGB, 12, 12, 12, 0);
    case GL_RGB16: return rgba(GL_RGB, 16, 16, 16, 0);
    case GL_RGBA2: return rgba(GL_RGBA, 2, 2, 2, 2);
    case GL_RGBA4: return rgba(GL_RGBA, 4, 4, 4, 4);
    case GL_RGB5_A1: return rgba(GL_RGBA, 5, 5, 5, 1);
    case GL_RGBA8: return rgba(GL_RGBA, 8, 8, 8, 8);
    case GL_RGB10_A2: return rgba(GL_RGBA, 10, 10, 10, 2);
    case GL_RGBA12: return rgba(GL_RGBA, 12, 12, 12, 12);
    case GL_RGBA16: return rgba(GL_RGBA, 16, 16, 16, 16);
    case GL_DEPTH_COMPONENT: r.base = GL_DEPTH_COMPONENT; r.depth = 24; return r;
    case GL_DEPTH_COMPONENT16: r.base = GL_DEPTH_COMPONENT; r.depth = 16; return r;
    case GL_DEPTH_COMPONENT24: r.base = GL_DEPTH_COMPONENT; r.depth = 24; return r;
    case GL_DEPTH_COMPONENT32: r.base = GL_DEPTH_COMPONENT; r.depth = 32; return r;
    default: return std::nullopt;
  }
}

namespace {

// One texel's components as the reals k/(2^bits − 1) sampling reads (Table 3.18 sources).
void decode_texel(const InternalFormat& f, const std::uint32_t* t, double* o) {
  auto v = [](std::uint32_t k, int bits) { return fixed_to_float(k, bits); };
  switch (f.base) {
    case GL_ALPHA: o[0] = o[1] = o[2] = 0.0; o[3] = v(t[3], f.alpha); break;
    case GL_LUMINANCE: o[0] = o[1] = o[2] = v(t[0], f.luminance); o[3] = 1.0; break;
    case GL_LUMINANCE_ALPHA: o[0] = o[1] = o[2] = v(t[0], f.luminance); o[3] = v(t[3], f.alpha); break;
    case GL_INTENSITY: o[0] = o[1] = o[2] = o[3] = v(t[0], f.intensity); break;
    case GL_DEPTH_COMPONENT: o[0] = o[1] = o[2] = o[3] = v(t[0], f.depth); break;
    case GL_RGB: o[0] = v(t[0], f.red); o[1] = v(t[1], f.green); o[2] = v(t[2], f.blue); o[3] = 1.0; break;
    default: o[0] = v(t[0], f.red); o[1] = v(t[1], f.green); o[2] = v(t[2], f.blue); o[3] = v(t[3], f.alpha); break;
  }
}

std::mutex& decoding_mutex() {
  static std::mutex m;
  return m;
}

}  // namespace

void TextureLevel::decode(std::size_t index, double* out) const {
  const std::uint16_t* t = &texels[4 * index];
  const std::uint32_t codes[4] = {format.base == GL_DEPTH_COMPONENT ? depth_code(index) : t[0], t[1], t[2], t[3]};
  decode_texel(format, codes, out);
}

const TexelDecoding* texel_decoding(const InternalFormat& f) {
  const int widest = std::max({f.red, f.green, f.blue, f.alpha, f.luminance, f.intensity, f.depth});
  if (widest > 16) return nullptr;
  const std::array<int, 8> key{static_cast<int>(f.base), f.red, f.green, f.blue, f.alpha, f.luminance, f.intensity,
                               f.depth};
  static std::map<std::array<int, 8>, TexelDecoding> decodings;
  std::lock_guard<std::mutex> lock(decoding_mutex());
  auto [it, made] = decodings.try_emplace(key);
  TexelDecoding& d = it->second;
  if (!made) return &d;
  // Each output component is a function of one stored component (or a constant): found by
  // decoding texels with one component set; then its value for every code, tabulated.
  const std::uint32_t zero[4] = {0, 0, 0, 0};
  double at_zero[4];
  decode_texel(f, zero, at_zero);
  for (std::size_t m = 0; m < 4; ++m) {
    std::uint32_t one[4] = {0, 0, 0, 0};
    one[m] = 1;
    double o[4];
    decode_texel(f, one, o);
    for (std::size_t k = 0; k < 4; ++k)
      if (o[k] != at_zero[k]) d.source[k] = static_cast<std::uint8_t>(m);  // a constant reads any slot: all hold it
  }
  d.code_bits = widest;
  const std::size_t codes = std::size_t{1} << widest;
  d.values.resize(4 * codes);
  for (std::size_t k = 0; k < 4; ++k)
    for (std::size_t c = 0; c < codes; ++c) {
      std::uint32_t t[4] = {0, 0, 0, 0};
      t[d.source[k]] = static_cast<std::uint32_t>(c);
      double o[4];
      decode_texel(f, t, o);
      d.values[k * codes + c] = o[k];
    }
  // The division form, where it gives every value of the table to the bit.
  d.by_division = true;
  for (std::size_t k = 0; k < 4; ++k) {
    const double* v = &d.values[k * codes];
    d.is_constant[k] = std::all_of(v, v + codes, [&](double x) { return x == v[0]; });
    if (d.is_constant[k]) {
      d.constant[k] = v[0];
      continue;
    }
    int width = 1;
    while (width < widest && v[(std::size_t{1} << width) - 1] != 1.0) ++width;
    d.divisor[k] = static_cast<double>((std::uint32_t{1} << width) - 1);
    for (std::size_t c = 0; c < codes && d.by_division; ++c)
      d.by_division = v[c] == static_cast<double>(c) / d.divisor[k];
  }
  return &d;
}

const std::vector<std::uint16_t>& TexelDecoding::replace_codes(const std::array<int, 4>& bits) const {
  std::lock_guard<std::mutex> lock(decoding_mutex());
  auto [it, made] = replace_codes_.try_emplace(bits);
  if (made) {
    const std::size_t codes = std::size_t{1} << code_bits;
    it->second.resize(values.size());
    for (std::size_t k = 0; k < 4; ++k)
      for (std::size_t c = 0; c < codes; ++c)
        it->second[k * codes + c] = static_cast<std::uint16_t>(float_to_fixed(values[k * codes + c], bits[k]));
  }
  return it->second;
}

int TextureLevel::bits_per_texel() const {
  const InternalFormat& f = format;
  switch (f.base) {
    case GL_ALPHA: return f.alpha;
    case GL_LUMINANCE: case GL_LUMINANCE_ALPHA: return f.luminance + f.alpha;
    case GL_INTENSITY: return f.intensity;
    case GL_DEPTH_COMPONENT: return f.depth;
    default: return f.red + f.green + f.blue + f.alpha;
  }
}

}  // namespace passim
