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

struct TextureLevel {
  int width = 0, height = 0, border = 0;  // width and height include the border
  InternalFormat format;
  // 4 codes per texel: R, G, B, A for colour bases; L in [0] (and A in [3]) for
  // LUMINANCE(_ALPHA); I in [0] for INTENSITY; D in [0] for DEPTH_COMPONENT.
  std::vector<std::uint32_t, UnsetOnGrowth<std::uint32_t>> texels;
  bool defined() const { return width > 0 && height > 0; }
  // The texels as the reals k/(2^bits − 1) sampling reads, R G B A per texel with L and I
  // replicated (Table 3.18 sources): made on first sampling, dropped when texels change.
  mutable std::vector<double> decoded;
  const std::vector<double>& values() const;
  // The fragment codes each texel's R G B A become at `bits` (float_to_fixed of values()):
  // what REPLACE writes, for the NEAREST fast path. Made on first use, dropped with decoded.
  // `split`: the texels converted by ranges of rows as it chooses (every texel alone).
  using ReplaceCodes = std::vector<std::uint16_t, UnsetOnGrowth<std::uint16_t>>;
  mutable ReplaceCodes replace_codes;
  mutable std::array<int, 4> replace_codes_bits{};
  const ReplaceCodes& codes_at(const std::array<int, 4>& bits, const RowSplitter* split = nullptr) const;
  void texels_changed() {
    decoded.clear();
    replace_codes.clear();
  }
  int bits_per_texel() const;
  // What a level of width x height texels holds for the memory budget: its codes (16 bytes a
  // texel) and the reals and replace codes made from them when it is sampled (32 + 8).
  static std::uint64_t bytes_for(std::int64_t width, std::int64_t height) {
    return static_cast<std::uint64_t>(width) * static_cast<std::uint64_t>(height) * 56u;
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
