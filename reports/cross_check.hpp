// The run-time cross-check (`passim run|program --cross-check`): a run on the reference paths
// (stages/kernel_paths.hpp: scalar kernels, general paths, one thread) against the same run on
// the fast paths, compared at the end of every pass — every plane (colour buffers, depth,
// stencil, accumulation) — and at the end of the run: every plane, every pass's counters, every
// captured image. The first difference is named: the pass, the plane and the pixel.
#pragma once
#include <cstdint>
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "pipeline/context.hpp"
#include "stages/kernel_paths.hpp"
#include "trace_io/trace.hpp"

namespace passim {

// One whole run on the given paths with the observer installed on its context (and, for the
// reference, on one thread): a replay or a program.
using CrossCheckRun = std::function<ReplayResult(const KernelPaths& paths, Context::PassEndObserver observer)>;

struct CrossCheckReport {
  bool same = true;
  std::size_t checkpoints = 0;  // passes compared (besides the end of the run)
  std::string difference;       // the first one found, named
};

CrossCheckReport cross_check(const CrossCheckRun& run);

// The planes of a context as (name, FNV-1a 64 of their codes), in a fixed order.
std::vector<std::pair<std::string, std::uint64_t>> plane_digests(const Context& ctx);

}  // namespace passim
