// The cost model (docs/cost-model.md): each pass's counters turned into the time each
// stage of a modelled machine would need; the pass takes as long as its slowest stage
// (the stages are pipelined) plus a fixed per-pass overhead, a frame the sum of its passes.
#pragma once
#include <array>
#include <string>
#include <vector>

#include "pipeline/counters.hpp"
#include "pipeline/profile.hpp"

namespace passim {

// The stages the model times, in pipeline order.
enum class CostStage : int {
  Geometry,      // vertices transformed and lit
  Setup,         // triangles set up (after culling and clipping)
  Fill,          // fragments through the per-fragment operations
  Texture,       // texture lookups
  Framebuffer,   // bytes of colour, depth and stencil read and written
  PixelPath,     // pixel groups drawn, read, copied, through scale/bias, tables, colour matrix
  Convolution,   // pixels convolved (rate by filter size)
  Accumulation,  // accumulation-buffer pixel operations
  Clear,         // pixels cleared (per buffer)
  TextureLoad,   // bytes written into texture memory
  Count
};
inline constexpr int kCostStages = static_cast<int>(CostStage::Count);
const char* cost_stage_name(CostStage s);

struct PassCost {
  std::string label;
  std::array<double, kCostStages> work{};     // units of each stage (vertices, bytes, ...)
  std::array<double, kCostStages> seconds{};  // work / rate (0 where the machine has no rate)
  double overhead = 0.0;
  double total = 0.0;       // max(seconds) + overhead
  CostStage bound = CostStage::Geometry;
  bool idle = true;         // the pass did no timed work
};

struct FrameCost {
  std::string profile;
  std::vector<PassCost> passes;
  double seconds = 0.0;
  double fps() const { return seconds > 0.0 ? 1.0 / seconds : 0.0; }
};

// One pass's cost on `profile` (its CostRates) for a framebuffer of `config` widths.
PassCost pass_cost(const Pass& pass, const MachineProfile& profile);
FrameCost frame_cost(const std::vector<Pass>& passes, const MachineProfile& profile);

}  // namespace passim
