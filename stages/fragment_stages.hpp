// The chain a primitive's fragments run through, in the modelled machine's order:
// [texture] -> [fog] -> per-fragment operations (design note "stages"). One chain per
// thread of rasterization: the Context's own, and one per raster lane (pipeline/raster_lanes).
#pragma once
#include <array>

#include "stages/fog.hpp"
#include "stages/fragment_span.hpp"
#include "stages/fragment_ops.hpp"
#include "stages/rasterizer.hpp"
#include "stages/texture_stage.hpp"

namespace passim {

// Everything the chain's stages read for one primitive, by value or by pointer to state
// that does not change while the primitive's fragments are processed.
struct FragmentStagesSetup {
  bool texture = false;
  TextureStageSetup texture_setup;
  bool fog = false;
  FogState fog_state;
  FragmentOpsInput ops;
  RasterTarget target;  // its color_bits are the fragment colour widths
  bool operator==(const FragmentStagesSetup&) const = default;
};

struct FragmentStages {
  // `counters` is where the stages count: a pointer the owner may re-aim between primitives.
  FragmentStages(Framebuffer& fb, Counters*& counters) : ops(fb, counters), texture(counters), fog(counters) {}
  FragmentOps ops;
  TextureStage texture;
  FogStage fog;
  FragmentSink* first = &ops;

  void connect(const FragmentStagesSetup& s) {
    ops.configure(s.ops);
    FragmentSink& after_texture = s.fog ? static_cast<FragmentSink&>(fog) : static_cast<FragmentSink&>(ops);
    if (s.fog) fog.configure(s.fog_state, s.target.color_bits, ops);
    if (s.texture) texture.configure(s.texture_setup, after_texture);
    first = s.texture ? static_cast<FragmentSink*>(&texture) : &after_texture;
  }
};

// A thread's own chain with what it works in: span buffers, and counters the chain counts
// into (added to a pass's by the owner). Not movable: the chain holds `counting` by reference.
// On cache lines of its own: lanes count into theirs side by side.
struct alignas(64) LaneStages {
  LaneStages(Framebuffer& fb, int width) : spans(width), stages(fb, counting) {}
  LaneStages(const LaneStages&) = delete;
  LaneStages& operator=(const LaneStages&) = delete;
  Counters counters;
  Counters* counting = &counters;
  SpanBuffers spans;
  FragmentStages stages;
};

}  // namespace passim
