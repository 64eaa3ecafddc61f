// Working storage of a Context's stages (private to the pipeline).
#pragma once
#include <vector>

#include "pipeline/context.hpp"
#include "stages/fragment_ops.hpp"
#include "stages/fragment_span.hpp"
#include "stages/fog.hpp"
#include "stages/texture_stage.hpp"

namespace passim {

struct Context::Scratch {
  Scratch(Framebuffer& fb, int width)
      : spans(width), fragment_ops(fb, counters), texture_stage(counters), fog_stage(counters) {}
  Counters* counters = nullptr;  // the current pass's counters
  SpanBuffers spans;
  FragmentOps fragment_ops;
  TextureStage texture_stage;  // -> fog_stage or fragment_ops
  FogStage fog_stage;          // -> fragment_ops
  std::vector<ProcessedVertex> polygon, clip_scratch;
  std::vector<RasterVertex> window;
  // A copied rectangle and the convolution's output: kept between calls, so that a copy of
  // the whole window does not map and fault in fresh pages each time.
  std::vector<Rgba> rectangle, rectangle_spare;
};

}  // namespace passim
