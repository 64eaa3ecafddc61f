// The cost model (docs/cost-model.md): each pass's counters turned into the time each
// stage of a modelled machine would need; the pass takes as long as its slowest stage
// (the stages are pipelined) plus a fixed per-pass overhead, a frame the sum of its passes.
#pragma once
#include <array>
#include <nlohmann/json.hpp>
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

// The profile of that name if it has cost rates; std::invalid_argument naming the profiles
// that have them otherwise.
const MachineProfile& timed_profile(const std::string& name);

// One pass's cost on `profile` (its CostRates) for a framebuffer of `config` widths.
PassCost pass_cost(const Pass& pass, const MachineProfile& profile);
FrameCost frame_cost(const std::vector<Pass>& passes, const MachineProfile& profile);

// A frame's cost as `passim report cost --json` prints it: per pass the bounding stage, the
// seconds, and every stage's work and seconds; the frame's seconds and frames per second.
nlohmann::json cost_json(const FrameCost& frame);

// ---- The model against the paper (docs/cost-model.md, "The fit and its check") ----

// A frame rate Brabec & Seidel publish for the Octane VPro/8, as a range.
struct PublishedFrameRate {
  std::string what, program;
  int filter = 0;
  std::string scene;
  double low = 0.0, high = 0.0;  // frames per second
};
// Figure 7's four (paper scene, 512² map) and Figure 8's two (fig8 scene, 1024² map).
const std::vector<PublishedFrameRate>& published_frame_rates();
// How far fps lies outside [low, high], relative to the nearer end (0 inside).
double range_miss(double fps, double low, double high);

// The rates a fit may change: those no published figure gives (triangles, the plain pixel
// path, scale/bias, the colour table — the colour matrix the same —, clears, texture loads,
// the per-pass overhead); the others stay as the profile has them.
const std::vector<std::string>& fitted_rate_names();

struct RateFit {
  CostRates rates;
  double margin = 0.0;  // the least log margin inside the used ranges (negative: outside one)
};
// The free rates, starting from `start`, that put every used run's predicted frame rate inside
// its published range with the largest margin: a seeded random search (deterministic; the
// same search tools/fit_vpro_rates.py describes). runs[k] are the passes of published[k]'s run.
RateFit fit_rates(const std::vector<std::vector<Pass>>& runs, const std::vector<PublishedFrameRate>& published,
                  const std::vector<bool>& used, const CostRates& start, int iterations = 20000);

// The free rates fitted to the published rates marked `used`, from round starting values
// that owe nothing to the paper (the profile's other rates kept).
RateFit fit_published(const MachineProfile& profile, const std::vector<std::vector<Pass>>& runs,
                      const std::vector<bool>& used, int iterations = 20000,
                      const std::vector<PublishedFrameRate>& published = published_frame_rates());

// Each published rate beside the model's predictions: with the profile's rates, and held out
// (leave-one-out) — with the free rates fitted to the other five published rates only.
struct PaperPrediction {
  PublishedFrameRate published;
  double with_profile = 0.0;  // fps with the profile's own rates
  double held_out = 0.0;      // fps with the rates fitted without this one
  double held_out_fit_margin = 0.0;  // how well the other five could be fitted
};
std::vector<PaperPrediction> paper_predictions(const MachineProfile& profile, const std::vector<std::vector<Pass>>& runs,
                                               int iterations = 20000,
                                               const std::vector<PublishedFrameRate>& published = published_frame_rates());

}  // namespace passim
