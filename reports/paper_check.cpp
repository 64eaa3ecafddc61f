#include "reports/paper_check.hpp"

#include "programs/programs.hpp"

namespace passim {

std::vector<std::vector<Pass>> published_runs(const MachineProfile& profile) {
  std::vector<std::vector<Pass>> runs;
  for (const PublishedFrameRate& r : published_frame_rates()) {
    ProgramOptions o;
    o.program = r.program;
    o.filter = r.filter;
    o.scene = r.scene;  // fig8's map is 1024², the scene's own
    o.profile = profile.name;
    o.color_bits = profile.color_bits[0];
    ProgramSession session(o);
    session.frame();
    runs.push_back(session.run().result.context->passes());
  }
  return runs;
}

}  // namespace passim
