// Texture objects and images (OpenGL 1.2.1 §3.8, SGIX_depth_texture, SGIX_shadow /
// ARB_shadow). Texels are stored as integer codes at exactly the widths of the internal
// format (Table 3.16), so a 12-bit value stored in RGBA8 loses its low bits as on hardware.
#pragma once
#include <array>
#include <cstdint>
#include <map>
#include <optional>
#include <memory>
#include <utility>
#include <vector>

#include "pipeline/gl.hpp"
#include "pipeline/state.hpp"
#include "stages/row_splitter.hpp"

namespace passim {

// std::allocator, but growing a vector leaves the new elements unset rather than zeroing them:
// a level that a copy is about to fill wholly (tex_image's `overwritten`) is not written twice
// (zeroing a 512² RGBA level a frame was 2 % of a frame's time). Every other definition of a
// level sets every texel explicitly.
template <class T>
struct UnsetOnGrowth : std::allocator<T> {
  template <class U>
  struct rebind {
    using other = UnsetOnGrowth<U>;
  };
  UnsetOnGrowth() = default;
  template <class U>
  UnsetOnGrowth(const UnsetOnGrowth<U>&) noexcept {}
  template <class U, class... Args>
  void construct(U* p, Args&&... args) {
    if constexpr (sizeof...(Args) == 0) ::new (static_cast<void*>(p)) U;  // default-initialised: unset
    else ::new (static_cast<void*>(p)) U(std::forward<Args>(args)...);
  }
};

// Table 3.15-3.16: base format and component widths of an internal format.
struct InternalFormat {
  GLenum requested = 0;  // as given to TexImage
  GLenum base = 0;       // ALPHA, LUMINANCE, LUMINANCE_ALPHA, INTENSITY, RGB, RGBA, DEPTH_COMPONENT
  // Widths of R, G, B, A, L, I, D (0 when absent).
  int red = 0, green = 0, blue = 0, alpha = 0, luminance = 0, intensity = 0, depth = 0;
};

// Widths for an internal format; nullopt for a value TexImage does not accept.
// Unsized formats get `unsized_bits` per component (A10: 8).
std::optional<InternalFormat> internal_format(GLint internalformat, int unsized_bits = 8);

// How a level's stored codes become the values sampling reads, for one internal format whose
// components are at most 16 bits wide (every colour format; DEPTH_COMPONENT16): output
// component k (R, G, B, A with L and I replicated, Table 3.18's sources) is
// values[k << code_bits | code] of the code in slot source[k]. Built once per format and
// shared by every level of it, so its size does not grow with the textures a trace defines.
struct TexelDecoding {
  int code_bits = 0;                    // the widest stored component
  std::array<std::uint8_t, 4> source{};  // slot of the code output k reads
  std::vector<double> values;           // 4 << code_bits reals: fixed_to_float of each code
  // When each output component is a constant or exactly code / (2^w − 1) (IEEE division; checked
  // against `values` for every code), the fast samplers divide rather than read the table: a
  // gather from it costs more than the division on CPUs with the gather-data-sampling fix.
  bool by_division = false;
  std::array<double, 4> divisor{1.0, 1.0, 1.0, 1.0};  // 2^w − 1; 1 for a constant component
  std::array<double, 4> constant{};                   // a constant component's value
  std::array<bool, 4> is_constant{};
  // REPLACE's codes (Table 3.18 with A4's rounding: float_to_fixed of the value) at the
  // fragment widths `bits`, laid out as `values`; made on first use per widths.
  const std::vector<std::uint16_t>& replace_codes(const std::array<int, 4>& bits) const;

 private:
  mutable std::map<std::array<int, 4>, std::vector<std::uint16_t>> replace_codes_;
};
// The decoding of a format; nullptr when a component is wider than 16 bits (DEPTH24/32),
// which only the general sampler reads. Thread-safe.
const TexelDecoding* texel_decoding(const InternalFormat& format);

struct TextureLevel {
  int width = 0, height = 0, border = 0;  // width and height include the border
  InternalFormat format;
  // 4 codes per texel, each at its component's width (16 bits hold every colour width):
  // R, G, B, A for colour bases; L in [0] (and A in [3]) for LUMINANCE(_ALPHA); I in [0] for
  // INTENSITY. A depth code D wider than 16 bits keeps its low 16 bits in [0] and its high
  // ones in [1] (depth_code). 8 bytes a texel, where llvmpipe's RGBA8 takes 4.
  std::vector<std::uint16_t, UnsetOnGrowth<std::uint16_t>> texels;
  bool defined() const { return width > 0 && height > 0; }
  // Stores one texel's codes (as texel_codes gives them, each below 2^width).
  void set_texel(std::size_t index, const std::uint32_t* codes) {
    std::uint16_t* t = &texels[4 * index];
    t[0] = static_cast<std::uint16_t>(codes[0] & 0xffffu);
    t[1] = static_cast<std::uint16_t>(format.base == GL_DEPTH_COMPONENT ? codes[0] >> 16 : codes[1]);
    t[2] = static_cast<std::uint16_t>(codes[2]);
    t[3] = static_cast<std::uint16_t>(codes[3]);
  }
  std::uint32_t depth_code(std::size_t index) const {
    return static_cast<std::uint32_t>(texels[4 * index]) | static_cast<std::uint32_t>(texels[4 * index + 1]) << 16;
  }
  // The texel's components as the reals k/(2^bits − 1) sampling reads, R G B A with L and I
  // replicated (Table 3.18 sources), by the spec's division: the reference the tables of
  // TexelDecoding must equal.
  void decode(std::size_t index, double* out) const;
  // Dropped caches when texels change (none today: the decoding tables depend on the format).
  void texels_changed() {}
  int bits_per_texel() const;
  // What a level of width x height texels holds for the memory budget: its codes, 8 bytes a
  // texel (the decoding tables are per format, at most 40 of them).
  static std::uint64_t bytes_for(std::int64_t width, std::int64_t height) {
    return static_cast<std::uint64_t>(width) * static_cast<std::uint64_t>(height) * 8u;
  }
  std::uint64_t bytes() const { return defined() ? bytes_for(width, height) : 0; }
};

// Table 6.18 (texture objects).
struct TextureObject {
  GLenum target = 0;  // GL_TEXTURE_1D or GL_TEXTURE_2D (0 until first bound)
  std::vector<TextureLevel> levels;
  GLenum min_filter = GL_NEAREST_MIPMAP_LINEAR;
  GLenum mag_filter = GL_LINEAR;
  GLenum wrap_s = GL_REPEAT, wrap_t = GL_REPEAT, wrap_r = GL_REPEAT;
  Vec4 border_color{0.0, 0.0, 0.0, 0.0};
  double min_lod = -1000.0, max_lod = 1000.0;
  int base_level = 0, max_level = 1000;
  double priority = 1.0;
  // Depth comparison: SGIX_shadow (compare, operator) and ARB_shadow (mode, func).
  bool compare_sgix = false;
  GLenum compare_operator_sgix = GL_TEXTURE_LEQUAL_R_SGIX;
  GLenum compare_mode = GL_NONE;
  GLenum compare_func = GL_LEQUAL;
  GLenum depth_texture_mode = GL_LUMINANCE;
  double shadow_ambient = 0.0;  // SGIX_shadow_ambient: the value of a failed comparison
};

// Table 6.14 (texture coordinate generation), one coordinate's.
struct TexGenState {
  bool enabled = false;
  GLenum mode = GL_EYE_LINEAR;
  Vec4 object_plane{0.0}, eye_plane{0.0};
};

// Tables 6.15-6.17 (texturing: the enables, bindings and objects) and 6.14 (texgen), with the
// texture environment (Table 6.18 of the 1.2.1 spec).
struct TextureState {
  bool enabled_1d = false, enabled_2d = false;
  GLuint bound_1d = 0, bound_2d = 0;
  TextureObject default_1d, default_2d;
  std::map<GLuint, TextureObject> objects;
  std::map<GLuint, bool> reserved;  // names handed out by glGenTextures
  GLenum env_mode = GL_MODULATE;
  Vec4 env_color{0.0, 0.0, 0.0, 0.0};
  std::array<TexGenState, 4> gen{};
};

}  // namespace passim
