#include "stages/texture_stage.hpp"

#include "stages/kernel_paths.hpp"

#include "pipeline/fixed_point.hpp"
#include "stages/texture_env.hpp"
#include "stages/texture_sample.hpp"

namespace passim {

namespace {
thread_local std::uint64_t fast_path_fragments = 0;
}  // namespace

std::uint64_t TextureStage::fast_path_fragments_here() { return fast_path_fragments; }
void TextureStage::reset_fast_path_fragments_here() { fast_path_fragments = 0; }

namespace {
// The NEAREST/REPLACE fast path's condition (it reads TexelDecoding::replace_codes).
bool nearest_replace(const TextureObject& tex, const TextureLevel& base, GLenum env_mode) {
  return use_specialised() && tex.min_filter == GL_NEAREST && tex.mag_filter == GL_NEAREST &&
         env_mode == GL_REPLACE && base.format.base != GL_DEPTH_COMPONENT && texel_decoding(base.format);
}
}  // namespace

void TextureStage::make_caches(const TextureStageSetup& setup, const RowSplitter*) {
  const TextureObject& tex = *setup.texture;
  const TextureLevel& base = tex.levels[static_cast<std::size_t>(tex.base_level)];
  // The tables the fast paths read, made before the lanes start (they are shared).
  if (const TexelDecoding* d = texel_decoding(base.format)) d->replace_codes(setup.fragment_bits);
}

void TextureStage::configure(const TextureStageSetup& setup, FragmentSink& next) {
  setup_ = setup;
  next_ = &next;
  const TextureObject& tex = *setup_.texture;
  const TextureLevel& base = tex.levels[static_cast<std::size_t>(tex.base_level)];
  const auto& bits = setup_.fragment_bits;
  for (std::size_t k = 0; k < 4; ++k) fragment_values_[k] = code_values(bits[k]);
  // REPLACE (Table 3.18): which components the texture replaces, for both fast paths.
  const GLenum env_base = base.format.base == GL_DEPTH_COMPONENT ? tex.depth_texture_mode : base.format.base;
  const bool color = env_base != GL_ALPHA;
  const bool alpha =
      env_base == GL_ALPHA || env_base == GL_LUMINANCE_ALPHA || env_base == GL_RGBA || env_base == GL_INTENSITY;
  replace_ = {color, color, color, alpha};
  // Fast path: NEAREST at every λ on the base level, no comparison, REPLACE. The texel's
  // replacing components become float_to_fixed(texel value) at the fragment's widths
  // (Table 3.18 with A4's rounding), the others stay: the general path's arithmetic with
  // each code's result computed once (TexelDecoding::replace_codes). Every fragment reads a
  // stored texel (never the border colour): no general fallback.
  if (nearest_replace(tex, base, setup_.env_mode)) {
    path_ = Path::kNearestReplace;
    geometry_ = level_geometry(tex, base, setup_.dims);
    codes_ = geometry_.decoding->replace_codes(bits).data();
    return;
  }
  // Fast path: LINEAR for both filters (so λ chooses nothing), no comparison, REPLACE. The
  // filter is sample_texture's (linear_replace_span shares its expressions); REPLACE
  // takes the texel's components as NEAREST's fast path does; fragments whose footprint
  // reaches the border colour, or whose coordinates are not finite, take the general path.
  // (Not under A29's 8.8 filter, which the general sampler alone implements.)
  if (use_specialised() && !setup_.filter_8_8 && tex.min_filter == GL_LINEAR && tex.mag_filter == GL_LINEAR &&
      setup_.env_mode == GL_REPLACE && base.format.base != GL_DEPTH_COMPONENT && texel_decoding(base.format)) {
    path_ = Path::kLinearReplace;
    geometry_ = level_geometry(tex, base, setup_.dims);
    return;
  }
  path_ = Path::kGeneral;
}

void TextureStage::process(FragmentSpan& span) {
  const TextureObject& tex = *setup_.texture;
  const TextureLevel& base = tex.levels[static_cast<std::size_t>(tex.base_level)];
  const auto& bits = setup_.fragment_bits;
  Counters& counters = *counters_;
  if (path_ == Path::kNearestReplace) {
    nearest_replace_span(geometry_, codes_, span, replace_);
    const std::uint64_t fetched = static_cast<std::uint64_t>(span.count);
    fast_path_fragments += fetched;
    counters.texture_lookups += fetched;
    counters.texels_fetched += fetched;
    counters.texture_bits_read += fetched * static_cast<std::uint64_t>(geometry_.bits_per_texel);
    next_->process(span);
    return;
  }
  const GLenum env_base = base.format.base == GL_DEPTH_COMPONENT ? tex.depth_texture_mode : base.format.base;
  auto general = [&](int i) {
    const TexelValue tv =
        sample_texture(tex, setup_.dims, span.s[i], span.t[i], span.r[i], span.lambda[i], setup_.last_level, counters,
                       setup_.filter_8_8);
    std::uint16_t* c = span.rgba + 4 * i;
    const Vec4 cf(fragment_values_[0][c[0]], fragment_values_[1][c[1]], fragment_values_[2][c[2]],
                  fragment_values_[3][c[3]]);
    const Vec4 out = apply_texture_env(setup_.env_mode, env_base, cf, tv, setup_.env_color);
    // A4: the textured colour is rounded to the fragment colour width.
    for (int k = 0; k < 4; ++k) c[k] = static_cast<std::uint16_t>(float_to_fixed(out[k], bits[k]));
  };
  if (path_ == Path::kLinearReplace) {
    // span.live is the per-fragment operations' scratch; they set it afresh.
    const std::uint64_t filtered = linear_replace_span(geometry_, span, bits, replace_, span.live, counters);
    if (filtered < static_cast<std::uint64_t>(span.count))
      for (int i = 0; i < span.count; ++i)
        if (span.live[i]) general(i);
    fast_path_fragments += filtered;
    counters.texture_lookups += filtered;
    next_->process(span);
    return;
  }
  for (int i = 0; i < span.count; ++i) general(i);
  next_->process(span);
}

}  // namespace passim
