#include "stages/accumulate.hpp"

#include "pipeline/fixed_point.hpp"
#include "stages/clear.hpp"

namespace passim {

void accumulate(GLenum op, double value, const AccumRegion& r, const ColorPlane& read,
                const std::vector<ColorBufferId>& draw, const std::array<bool, 4>& mask, Framebuffer& fb,
                Counters& counters) {
  const FramebufferConfig& cfg = fb.config;
  const int abits = cfg.accum_bits;
  const double scale = static_cast<double>((std::int64_t{1} << (abits - 1)) - 1);
  const std::uint64_t pixels =
      static_cast<std::uint64_t>(r.x1 - r.x0) * static_cast<std::uint64_t>(r.y1 - r.y0);
  const std::uint64_t accum_bits = 4u * static_cast<std::uint64_t>(abits);
  const std::uint64_t color_bits =
      static_cast<std::uint64_t>(cfg.color_bits[0] + cfg.color_bits[1] + cfg.color_bits[2] + cfg.color_bits[3]);
  int mask_bits = 0;
  for (int k = 0; k < 4; ++k)
    if (mask[k]) mask_bits += cfg.color_bits[k];
  const double* read_values[4];
  for (int k = 0; k < 4; ++k) read_values[k] = cfg.color_bits[k] ? code_values(cfg.color_bits[k]) : nullptr;
  auto read_value = [&](std::size_t p, int k) {
    return read_values[k] ? read_values[k][read.rgba[4 * p + static_cast<std::size_t>(k)]] : 1.0;  // no alpha: 1
  };
  for (int y = r.y0; y < r.y1; ++y)
    for (int x = r.x0; x < r.x1; ++x) {
      const std::size_t p = fb.pixel_index(x, y);
      std::int32_t* acc = &fb.accum[4 * p];
      if (op == GL_RETURN) {
        for (ColorBufferId id : draw) {
          std::uint16_t* c = &fb.color[static_cast<int>(id)].rgba[4 * p];
          for (int k = 0; k < 4; ++k)
            if (mask[k] && cfg.color_bits[k] > 0)
              c[k] = static_cast<std::uint16_t>(float_to_fixed(value * (acc[k] / scale), cfg.color_bits[k]));
        }
        continue;
      }
      for (int k = 0; k < 4; ++k) {
        const double a = acc[k] / scale;
        double result;
        switch (op) {
          case GL_ACCUM: result = a + value * read_value(p, k); break;
          case GL_LOAD: result = value * read_value(p, k); break;
          case GL_ADD: result = a + value; break;
          default: result = a * value; break;  // GL_MULT
        }
        acc[k] = accum_code(result, abits);
      }
    }
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
