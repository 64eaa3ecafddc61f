#include "stages/texture_env.hpp"

#include <algorithm>

namespace passim {

Vec4 apply_texture_env(GLenum mode, GLenum base, const Vec4& cf, const TexelValue& t, const Vec4& cc) {
  const bool has_color = base != GL_ALPHA;  // L, LA, I, RGB, RGBA
  const bool has_alpha = base == GL_ALPHA || base == GL_LUMINANCE_ALPHA || base == GL_RGBA || base == GL_INTENSITY;
  const Vec3 ct(t.r, t.g, t.b);
  const double at = t.a;
  Vec3 c(cf);
  double a = cf.a;
  switch (mode) {
    case GL_REPLACE:
      if (has_color) c = ct;
      if (has_alpha) a = at;
      break;
    case GL_MODULATE:
      if (has_color) c = Vec3(cf) * ct;
      if (has_alpha) a = cf.a * at;
      break;
    case GL_DECAL:
      // RGB: Cs; RGBA: Cf(1 − As) + Cs·As; other formats undefined -> fragment unchanged (A12).
      if (base == GL_RGB) c = ct;
      if (base == GL_RGBA) c = Vec3(cf) * (1.0 - at) + ct * at;
      break;
    case GL_BLEND:
      if (has_color) c = Vec3(cf) * (Vec3(1.0) - ct) + Vec3(cc) * ct;
      if (base == GL_INTENSITY) a = cf.a * (1.0 - at) + cc.a * at;
      else if (base == GL_ALPHA || base == GL_LUMINANCE_ALPHA || base == GL_RGBA) a = cf.a * at;
      break;
    case GL_ADD:
      if (has_color) c = glm::min(Vec3(1.0), Vec3(cf) + ct);
      if (base == GL_INTENSITY) a = std::min(1.0, cf.a + at);
      else if (base == GL_ALPHA || base == GL_LUMINANCE_ALPHA || base == GL_RGBA) a = cf.a * at;
      break;
    default:
      break;
  }
  return Vec4(c, a);
}

}  // namespace passim
