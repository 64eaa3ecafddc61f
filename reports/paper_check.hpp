// The runs behind the cost model's check against the paper (docs/cost-model.md): each
// published frame rate's program on a profile, at the profile's colour width.
#pragma once
#include <vector>

#include "pipeline/profile.hpp"
#include "reports/cost.hpp"

namespace passim {

// The passes of each of published_frame_rates()' runs on `profile`, in that order.
std::vector<std::vector<Pass>> published_runs(const MachineProfile& profile);

}  // namespace passim
