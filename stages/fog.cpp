#include "stages/fog.hpp"

#include <cmath>

#include "pipeline/fixed_point.hpp"

namespace passim {

double fog_factor(const FogState& fog, double c) {
  double f;
  switch (fog.mode) {
    case GL_LINEAR: f = fog.end == fog.start ? 1.0 : (fog.end - c) / (fog.end - fog.start); break;
    case GL_EXP2: {
      const double dc = fog.density * c;
      f = std::exp(-(dc * dc));
      break;
    }
    default: f = std::exp(-(fog.density * c)); break;
  }
  return clamp_nan_low(f, 0.0, 1.0);
}

void FogStage::process(FragmentSpan& span) {
  for (int i = 0; i < span.count; ++i) {
    const double f = fog_factor(fog_, span.fog[i]);
    std::uint16_t* c = span.rgba + 4 * i;
    for (int k = 0; k < 3; ++k) {
      const double cf = fixed_to_float(c[k], bits_[k]);
      c[k] = static_cast<std::uint16_t>(float_to_fixed(f * cf + (1.0 - f) * fog_.color[k], bits_[k]));
    }
  }
  counters_->fog_operations += static_cast<std::uint64_t>(span.count);
  next_->process(span);
}

}  // namespace passim
