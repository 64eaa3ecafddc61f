#include "stages/accumulate.hpp"

#include "pipeline/fixed_point.hpp"
#include "stages/clear.hpp"

#include "stages/avx2.hpp"
#include "stages/kernel_paths.hpp"

namespace passim {

// ---------------------------------------------------------------- scalar reference

void accumulate_row_scalar(const AccumRowOp& s, std::int32_t* acc, const std::uint16_t* read, int n) {
  for (int i = 0; i < n; ++i)
    for (int k = 0; k < 4; ++k) {
      std::int32_t& code = acc[4 * i + k];
      const double a = code / s.scale;
      double result;
      switch (s.op) {
        case GL_ACCUM: result = a + s.term[k][read[4 * i + k] & s.code_mask[k]]; break;
        case GL_LOAD: result = s.term[k][read[4 * i + k] & s.code_mask[k]]; break;
        case GL_ADD: result = a + s.value; break;
        default: result = a * s.value; break;  // GL_MULT
      }
      // A21: round half up (A1), saturate to [−1, 1] (NaN to −1).
      code = static_cast<std::int32_t>(round_half_up(clamp_nan_low(result, -1.0, 1.0) * s.scale));
    }
}

void return_row_scalar(const AccumRowOp& s, const std::int32_t* acc, std::uint16_t* out, int n) {
  for (int i = 0; i < n; ++i)
    for (int k = 0; k < 4; ++k) {
      const double v = s.value * (acc[4 * i + k] / s.scale);
      // §2.13.9 conversion of clamp(v, 0, 1) (float_to_fixed with the channel's maximum).
      out[4 * i + k] = static_cast<std::uint16_t>(clamp_nan_low(v, 0.0, 1.0) * s.color_max[k] + 0.5);
    }
}

// ---------------------------------------------------------------- the operation

void accumulate(GLenum op, double value, const PixelBox& r, const ColorPlane& read,
                const std::vector<ColorBufferId>& draw, const std::array<bool, 4>& mask, Framebuffer& fb,
                Counters& counters) {
  const FramebufferConfig& cfg = fb.config;
  const int abits = cfg.accum_bits;
  const int width = r.x1 - r.x0;
  const std::uint64_t pixels = static_cast<std::uint64_t>(width) * static_cast<std::uint64_t>(r.y1 - r.y0);
  AccumRowOp row_op;
  row_op.op = op;
  row_op.value = value;
  row_op.scale = static_cast<double>((std::int64_t{1} << (abits - 1)) - 1);
  // ACCUM and LOAD: value·c for every code of each channel, computed once per call (the
  // same product the per-pixel expression gives). An absent channel reads as 1 (A21).
  std::array<std::vector<double>, 4> terms;
  if (op == GL_ACCUM || op == GL_LOAD)
    for (int k = 0; k < 4; ++k) {
      const int bits = cfg.color_bits[k];
      const std::uint32_t codes = bits ? max_code(bits) + 1 : 1;
      terms[k].resize(codes);
      const double* values = bits ? code_values(bits) : nullptr;
      for (std::uint32_t c = 0; c < codes; ++c) terms[k][c] = value * (values ? values[c] : 1.0);
      row_op.term[k] = terms[k].data();
      row_op.code_mask[k] = bits ? max_code(bits) : 0;
    }
  for (int k = 0; k < 4; ++k) row_op.color_max[k] = static_cast<double>(max_code(cfg.color_bits[k]));
  const bool wide = use_avx2();
  std::vector<std::uint16_t> returned(op == GL_RETURN ? 4 * static_cast<std::size_t>(std::max(width, 0)) : 0);
  for (int y = r.y0; y < r.y1 && width > 0; ++y) {
    const std::size_t p = fb.pixel_index(r.x0, y);
    std::int32_t* acc = &fb.accum[4 * p];
    if (op != GL_RETURN) {
      const std::uint16_t* codes = &read.rgba[4 * p];
      (wide ? accumulate_row_avx2 : accumulate_row_scalar)(row_op, acc, codes, width);
      continue;
    }
    (wide ? return_row_avx2 : return_row_scalar)(row_op, acc, returned.data(), width);
    for (ColorBufferId id : draw) {
      std::uint16_t* c = &fb.color[static_cast<int>(id)].rgba[4 * p];
      for (int k = 0; k < 4; ++k) {
        if (!mask[k] || cfg.color_bits[k] == 0) continue;
        for (int i = 0; i < width; ++i) c[4 * i + k] = returned[4 * static_cast<std::size_t>(i) + static_cast<std::size_t>(k)];
      }
    }
  }
  const std::uint64_t accum_bits = 4u * static_cast<std::uint64_t>(abits);
  const std::uint64_t color_bits =
      static_cast<std::uint64_t>(cfg.color_bits[0] + cfg.color_bits[1] + cfg.color_bits[2] + cfg.color_bits[3]);
  int mask_bits = 0;
  for (int k = 0; k < 4; ++k)
    if (mask[k]) mask_bits += cfg.color_bits[k];
  switch (op) {
    case GL_ACCUM: counters.accum_accum_pixels += pixels; break;
    case GL_LOAD: counters.accum_load_pixels += pixels; break;
    case GL_ADD: counters.accum_add_pixels += pixels; break;
    case GL_MULT: counters.accum_mult_pixels += pixels; break;
    default: counters.accum_return_pixels += pixels; break;
  }
  if (op == GL_RETURN) {
    counters.accum_bits_read += pixels * accum_bits;
    counters.color_bits_written += pixels * static_cast<std::uint64_t>(mask_bits) * draw.size();
  } else {
    if (op == GL_ACCUM || op == GL_LOAD) counters.color_bits_read += pixels * color_bits;
    if (op != GL_LOAD) counters.accum_bits_read += pixels * accum_bits;
    counters.accum_bits_written += pixels * accum_bits;
  }
}

}  // namespace passim
