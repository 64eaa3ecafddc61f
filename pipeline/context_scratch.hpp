// Working storage of a Context's stages (private to the pipeline).
#pragma once
#include <vector>

#include "pipeline/context.hpp"
#include "stages/fragment_ops.hpp"
#include "stages/fragment_span.hpp"

namespace passim {

struct Context::Scratch {
  Scratch(Framebuffer& fb, int width) : spans(width), fragment_ops(fb, counters) {}
  Counters* counters = nullptr;  // the current pass's counters
  SpanBuffers spans;
  FragmentOps fragment_ops;
  std::vector<ProcessedVertex> polygon, clip_scratch;
  std::vector<RasterVertex> window;
};

}  // namespace passim
