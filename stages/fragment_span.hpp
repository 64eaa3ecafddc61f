// A run of fragments on one row, as rasterization hands them to the
// per-fragment operations (design note: spans with a live mask).
#pragma once
#include <cstdint>
#include <vector>

namespace passim {

struct FragmentSpan {
  int y = 0;
  int x0 = 0;
  int count = 0;
  std::uint16_t* rgba = nullptr;  // 4 codes per fragment at the fragment colour widths
  std::uint32_t* depth = nullptr;  // window z codes at the depth-plane width
  std::uint8_t* live = nullptr;    // scratch for the fragment operations
  // Texture coordinates s/q, t/q, r/q and level of detail λ (set when texturing is on).
  double* s = nullptr;
  double* t = nullptr;
  double* r = nullptr;
  double* lambda = nullptr;
  double* fog = nullptr;  // fog coordinate c = |z_eye| (set when fog is on)
};

// Storage for one span of up to `max_width` fragments.
struct SpanBuffers {
  // rgba and depth have room past max_width for the padded span kernels (span_kernels.hpp).
  explicit SpanBuffers(int max_width)
      : rgba(4 * static_cast<std::size_t>(max_width + 4)),
        depth(static_cast<std::size_t>(max_width + 4)),
        live(max_width),
        s(max_width),
        t(max_width),
        r(max_width),
        lambda(max_width),
        fog(max_width) {}
  std::vector<std::uint16_t> rgba;
  std::vector<std::uint32_t> depth;
  std::vector<std::uint8_t> live;
  std::vector<double> s, t, r, lambda, fog;
  FragmentSpan span(int y, int x0, int count) {
    return FragmentSpan{y, x0, count, rgba.data(), depth.data(), live.data(), s.data(), t.data(), r.data(),
                        lambda.data(), fog.data()};
  }
};

class FragmentSink {
 public:
  virtual ~FragmentSink() = default;
  virtual void process(FragmentSpan& span) = 0;
};

}  // namespace passim
