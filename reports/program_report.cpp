#include "reports/program_report.hpp"

#include "reports/report.hpp"

namespace passim {

nlohmann::json program_report(const ProgramRun& run, const std::vector<std::string>& image_files) {
  nlohmann::json report = run_report(run.result, "trace.pass", image_files);
  const ProgramOptions& o = run.options;
  report["program"] = {{"name", o.program},
                       {"scene", run.scene.name},
                       {"triangles", run.triangles},
                       {"map_size", run.map_size},
                       {"filter", o.filter},
                       {"depths", o.depths},
                       {"bias_steps", o.bias},
                       {"levels", count_levels(run.image("attenuation"))}};
  return report;
}

nlohmann::json reference_report(const ReferenceRun& ref, const std::string& image_file) {
  return {{"reference", ref.options.program},
          {"scene", ref.scene.name},
          {"triangles", ref.scene.triangles()},
          {"map_size", ref.map_size},
          {"filter", ref.options.filter},
          {"depths", ref.options.depths},
          {"sampling", ref.options.sampling},
          {"seed", ref.options.seed},
          {"bias_steps", ref.options.bias},
          {"bias_depth", ref.bias_depth},
          {"levels", count_levels(ref.image)},
          {"images", {{{"name", "attenuation"}, {"file", image_file}, {"hash", ref.image.hash}}}}};
}

}  // namespace passim
