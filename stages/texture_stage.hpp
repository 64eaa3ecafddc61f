// Texturing of fragment spans (§3.8): sample the bound texture at each fragment's s/q,
// t/q, r/q and λ, combine with the fragment colour by the texture environment, and pass
// the span on. Placed between rasterization and the per-fragment operations, as the
// modelled machines texture before the depth test.
#pragma once
#include <array>
#include <atomic>
#include <cstdint>

#include "pipeline/counters.hpp"
#include "pipeline/texture.hpp"
#include "stages/fragment_span.hpp"
#include "stages/texture_sample.hpp"

namespace passim {

struct TextureStageSetup {
  const TextureObject* texture = nullptr;
  int dims = 2;
  int last_level = 0;
  GLenum env_mode = GL_MODULATE;
  Vec4 env_color{0.0, 0.0, 0.0, 0.0};
  std::array<int, 4> fragment_bits{8, 8, 8, 8};
  bool filter_8_8 = false;  // ArithmeticOptions::texture_filter_8_8
  bool operator==(const TextureStageSetup&) const = default;
};

class TextureStage final : public FragmentSink {
 public:
  explicit TextureStage(Counters*& counters) : counters_(counters) {}
  // Also works out, once per setup rather than per span, which path the spans take and what
  // that path reads (the level's geometry, its replace codes).
  void configure(const TextureStageSetup& setup, FragmentSink& next);
  void process(FragmentSpan& span) override;
  // Make the tables this setup's sampling reads (TexelDecoding's replace codes at the
  // fragment widths), so that several threads can then sample without building them. They
  // are per format, at most 4 << 16 entries: `split` is not needed for them (kept for the
  // callers that offer the lanes).
  static void make_caches(const TextureStageSetup& setup, const RowSplitter* split = nullptr);
  // Fragments the fast paths textured on this thread (for tests; per thread, so that
  // raster lanes do not contend for one counter).
  static std::uint64_t fast_path_fragments_here();
  static void reset_fast_path_fragments_here();

 private:
  enum class Path { kNearestReplace, kLinearReplace, kGeneral };
  FragmentSink* next_ = nullptr;
  Counters*& counters_;
  TextureStageSetup setup_;
  Path path_ = Path::kGeneral;
  LevelGeometry geometry_;                    // the base level's (fast paths)
  const std::uint16_t* codes_ = nullptr;      // its replace codes (NEAREST)
  std::array<bool, 4> replace_{};             // the components REPLACE takes (Table 3.18)
  const double* fragment_values_[4] = {};     // code -> value at the fragment widths
};

}  // namespace passim
