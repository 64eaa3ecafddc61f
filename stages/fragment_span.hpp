// A run of fragments on one row, as rasterization hands them to the
// per-fragment operations (design note: spans with a live mask); or several such runs, one
// after another, a triangle's rows.
#pragma once
#include <cstdint>
#include <vector>

namespace passim {

// One row of a span of several rows: its window row, first column, fragments, and where its
// fragments start in the span's arrays.
struct SpanRow {
  int y = 0, x0 = 0, count = 0, offset = 0;
};

struct FragmentSpan {
  int y = 0;
  int x0 = 0;
  int count = 0;  // of every row, when there are several
  std::uint16_t* rgba = nullptr;  // 4 codes per fragment at the fragment colour widths
  std::uint32_t* depth = nullptr;  // window z codes at the depth-plane width
  std::uint8_t* live = nullptr;    // scratch for the fragment operations
  // Texture coordinates s/q, t/q, r/q and level of detail λ (set when texturing is on).
  double* s = nullptr;
  double* t = nullptr;
  double* r = nullptr;
  double* lambda = nullptr;
  double* fog = nullptr;  // fog coordinate c = |z_eye| (set when fog is on)
  // Several rows (y and x0 unused): the stages that read no position (texture, fog) take
  // them in one run; the per-fragment operations row by row (row()). Null: one row.
  const SpanRow* rows = nullptr;
  int row_count = 0;
  // Row `index` of a span of several rows, as a span of its own.
  FragmentSpan row(int index) const {
    const SpanRow& w = rows[index];
    const auto o = static_cast<std::size_t>(w.offset);
    return FragmentSpan{w.y, w.x0, w.count, rgba + 4 * o, depth + o, live + o, s + o, t + o, r + o, lambda + o, fog + o};
  }
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
        fog(max_width),
        rows(max_width) {}
  std::vector<std::uint16_t> rgba;
  std::vector<std::uint32_t> depth;
  std::vector<std::uint8_t> live;
  std::vector<double> s, t, r, lambda, fog;
  std::vector<SpanRow> rows;  // a span of several rows' (each row holds a fragment at least)
  int capacity() const { return static_cast<int>(live.size()); }
  FragmentSpan span(int y, int x0, int count) { return span_at(0, y, x0, count); }
  // A row's fragments stored from `offset` on, for a span of several rows.
  FragmentSpan span_at(int offset, int y, int x0, int count) {
    const auto o = static_cast<std::size_t>(offset);
    return FragmentSpan{y, x0, count, rgba.data() + 4 * o, depth.data() + o, live.data() + o, s.data() + o,
                        t.data() + o, r.data() + o, lambda.data() + o, fog.data() + o};
  }
};

class FragmentSink {
 public:
  virtual ~FragmentSink() = default;
  virtual void process(FragmentSpan& span) = 0;
};

}  // namespace passim
