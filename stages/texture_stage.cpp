#include "stages/texture_stage.hpp"

#include "pipeline/fixed_point.hpp"
#include "stages/texture_env.hpp"
#include "stages/texture_sample.hpp"

namespace passim {

void TextureStage::process(FragmentSpan& span) {
  const TextureObject& tex = *setup_.texture;
  const TextureLevel& base = tex.levels[static_cast<std::size_t>(tex.base_level)];
  const GLenum env_base = base.format.base == GL_DEPTH_COMPONENT ? tex.depth_texture_mode : base.format.base;
  const auto& bits = setup_.fragment_bits;
  Counters& counters = *counters_;
  const double* values[4] = {code_values(bits[0]), code_values(bits[1]), code_values(bits[2]), code_values(bits[3])};
  for (int i = 0; i < span.count; ++i) {
    const TexelValue tv =
        sample_texture(tex, setup_.dims, span.s[i], span.t[i], span.r[i], span.lambda[i], setup_.last_level, counters);
    std::uint16_t* c = span.rgba + 4 * i;
    const Vec4 cf(values[0][c[0]], values[1][c[1]], values[2][c[2]], values[3][c[3]]);
    const Vec4 out = apply_texture_env(setup_.env_mode, env_base, cf, tv, setup_.env_color);
    // A4: the textured colour is rounded to the fragment colour width.
    for (int k = 0; k < 4; ++k) c[k] = static_cast<std::uint16_t>(float_to_fixed(out[k], bits[k]));
  }
  next_->process(span);
}

}  // namespace passim
