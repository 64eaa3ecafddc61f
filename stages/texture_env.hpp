// Texture environment (OpenGL 1.2.1 §3.8.9, Tables 3.18-3.19; ADD from
// EXT_texture_env_add): combines the fragment colour with the filtered texture value.
#pragma once
#include "pipeline/state.hpp"
#include "stages/texture_sample.hpp"

namespace passim {

// Cf: fragment colour, t: texture value of base format `base` (a depth texture passes its
// DEPTH_TEXTURE_MODE: LUMINANCE, INTENSITY or ALPHA), cc: TEXTURE_ENV_COLOR.
// Returns the new fragment colour (each component in [0, 1]).
Vec4 apply_texture_env(GLenum mode, GLenum base, const Vec4& cf, const TexelValue& t, const Vec4& cc);

}  // namespace passim
