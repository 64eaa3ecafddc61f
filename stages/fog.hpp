// Fog (OpenGL 1.2.1 §3.10): C = f·Cr + (1 − f)·Cf on R, G, B, with f from the fog
// coordinate c = |z_eye|: LINEAR (e − c)/(e − s), EXP exp(−d·c), EXP2 exp(−(d·c)²),
// clamped to [0, 1]. Alpha is unchanged. The result is rounded to the fragment width (A4).
#pragma once
#include <array>

#include "pipeline/counters.hpp"
#include "pipeline/state.hpp"
#include "stages/fragment_span.hpp"

namespace passim {

// Table 6.9 (fog).
struct FogState {
  bool enabled = false;
  GLenum mode = GL_EXP;
  double density = 1.0, start = 0.0, end = 1.0;
  Vec4 color{0.0, 0.0, 0.0, 0.0};
  bool operator==(const FogState&) const = default;
};

double fog_factor(const FogState& fog, double c);

class FogStage final : public FragmentSink {
 public:
  explicit FogStage(Counters*& counters) : counters_(counters) {}
  void configure(const FogState& fog, const std::array<int, 4>& bits, FragmentSink& next) {
    fog_ = fog;
    bits_ = bits;
    next_ = &next;
  }
  void process(FragmentSpan& span) override;

 private:
  Counters*& counters_;
  FogState fog_;
  std::array<int, 4> bits_{};
  FragmentSink* next_ = nullptr;
};

}  // namespace passim
