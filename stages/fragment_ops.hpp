// Per-fragment operations, OpenGL 1.2.1 §4.1, in the spec's order: pixel ownership
// (done by the rasterizer), scissor, alpha test, stencil test, depth test,
// blending (with ARB_imaging's constant colour and equations), dithering (a
// no-op, A3), logic op, then the masked write of §4.2.2 to each draw buffer.
#pragma once
#include <vector>

#include "pipeline/counters.hpp"
#include "pipeline/framebuffer.hpp"
#include "pipeline/profile.hpp"
#include "pipeline/state.hpp"
#include "stages/fragment_span.hpp"

namespace passim {

// Where the operations read their state: the Context's own state groups.
struct FragmentOpsInput {
  const FragmentOpsState* ops = nullptr;
  const FramebufferControlState* control = nullptr;
  const std::vector<ColorBufferId>* draw_buffers = nullptr;
  const std::array<int, 4>* fragment_bits = nullptr;  // widths of the span's colour codes
  const ArithmeticOptions* arithmetic = nullptr;      // the profile's open choices
  bool operator==(const FragmentOpsInput&) const = default;
};

// The comparison functions of AlphaFunc, StencilFunc and DepthFunc (NEVER ... ALWAYS).
bool compare(GLenum func, std::uint32_t incoming, std::uint32_t stored);
// §4.1.6 blend of one component: source, destination, factors and constant in [0, 1].
// `product_bits` > 0: each product (src·src_factor, dst·dst_factor) is first rounded to a code
// of that width (ArithmeticOptions::blend_products_rounded); 0: exact products, one rounding
// of the result (the default model).
double blend_component(GLenum equation, double src, double dst, double src_factor, double dst_factor,
                       int product_bits = 0);
// blend_component's result rounded to `max` = 2^n − 1 (float_to_fixed) when both factors
// are ZERO or ONE (or the equation is MIN/MAX, which ignores them) and source and
// destination are codes of that width: exact in integers, since s/M ± d/M lands within
// far less than half a step of (s ± d)/M. Tests compare it with the real arithmetic on
// every pair of 8-bit codes and on random 12- and 16-bit pairs.
std::uint32_t blend_codes_unit_factors(GLenum equation, bool src_one, bool dst_one, std::uint32_t s,
                                       std::uint32_t d, std::uint32_t max);
// True when blend_codes_unit_factors applies to this state.
bool blend_has_unit_factors(GLenum equation, GLenum src_factor, GLenum dst_factor);
// blend_codes_unit_factors over fragments [begin, end) of a span where live[i] != 0: source
// codes `src` (4 per fragment) into the destination codes `dst`, channels where written[k];
// returns the fragments blended. The SSE2 kernel (8 codes at once: unsigned saturating
// adds and subtracts, min as a − sat(a − b)) and the scalar reference give the same codes
// (`Blend.UnitFactorSpanKernelEqualsTheScalarLoop`).
struct UnitFactorBlend {
  GLenum equation = GL_FUNC_ADD;
  bool src_one = true, dst_one = true;
  std::uint32_t max[4] = {0, 0, 0, 0};
  bool written[4] = {true, true, true, true};
};
std::uint64_t blend_span_unit_factors(const UnitFactorBlend& b, const std::uint8_t* live, const std::uint16_t* src,
                                      std::uint16_t* dst, int begin, int end);
std::uint64_t blend_span_unit_factors_scalar(const UnitFactorBlend& b, const std::uint8_t* live,
                                             const std::uint16_t* src, std::uint16_t* dst, int begin, int end);
// §4.1.6 blending in reals, any factors and widths, over fragments [begin, end) where
// live[i] != 0: source codes `src` at src_bits (a channel of 0 bits reads 1), destination
// codes `dst` at dst_bits, each written channel's result rounded to its destination code
// (float_to_fixed); returns the fragments blended. The scalar loop is the definition; the
// AVX2 kernel (one fragment's four components per instruction, the same IEEE operations in
// the same order) gives the same codes (`Blend.RealFactorSpanKernelEqualsTheScalarLoop`).
struct RealBlend {
  GLenum equation = GL_FUNC_ADD, src_factor = GL_ONE, dst_factor = GL_ZERO;
  double constant[4] = {0.0, 0.0, 0.0, 0.0};  // BLEND_COLOR
  int src_bits[4] = {8, 8, 8, 8}, dst_bits[4] = {8, 8, 8, 8};
  bool written[4] = {true, true, true, true};  // channels with bits that the colour mask opens
  bool products_rounded = false;               // ArithmeticOptions::blend_products_rounded
};
std::uint64_t blend_span_reals(const RealBlend& b, const std::uint8_t* live, const std::uint16_t* src,
                               std::uint16_t* dst, int begin, int end);
std::uint64_t blend_span_reals_scalar(const RealBlend& b, const std::uint8_t* live, const std::uint16_t* src,
                                      std::uint16_t* dst, int begin, int end);
// §4.1.7 logic operation on n-bit codes.
std::uint32_t logic_op(GLenum op, std::uint32_t s, std::uint32_t d, std::uint32_t mask);

class FragmentOps final : public FragmentSink {
 public:
  FragmentOps(Framebuffer& fb, Counters*& counters) : fb_(fb), counters_(counters) {}
  void configure(const FragmentOpsInput& input) { in_ = input; }
  // A span of several rows is taken row by row.
  void process(FragmentSpan& span) override;

 private:
  // What the operations do, found from the state once per call of process.
  struct Plan {
    bool replace_only = false;  // replace_span's case
    std::uint32_t alpha_ref = 0;
    bool stencil_on = false, depth_on = false, logic_on = false, blend_on = false;
    int mask_bits = 0, total_bits = 0;
    bool same_widths = false, all_channels = false;
    bool written[4] = {false, false, false, false};
    bool unit_factors = false;  // blend_span_unit_factors applies
    UnitFactorBlend unit;
    RealBlend real;
  };
  Plan plan() const;
  void process_row(const Plan& plan, FragmentSpan& span);
  void replace_span(const FragmentSpan& span, int begin, int end, Counters& counters);
  // Return the number of fragments they kill.
  std::uint64_t depth_only(GLenum func, bool write, const FragmentSpan& span, int begin, int end,
                           std::uint32_t* stored, std::int64_t tested_hint, Counters& counters);
  std::uint64_t stencil_and_depth(const FragmentOpsState& ops, const FramebufferControlState& ctl,
                                  const FragmentSpan& span, int begin, int end, std::size_t row_base, bool depth_on,
                                  Counters& counters);
  Framebuffer& fb_;
  Counters*& counters_;
  FragmentOpsInput in_;
};

}  // namespace passim
