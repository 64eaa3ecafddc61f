#include "reports/report.hpp"

#include <fmt/format.h>

#include <algorithm>

#include "reports/image_io.hpp"

namespace passim {

nlohmann::json run_report(const ReplayResult& run, const std::string& trace_name,
                          const std::vector<std::string>& image_files) {
  using nlohmann::json;
  const Context& ctx = *run.context;
  const FramebufferConfig& f = run.settings.framebuffer;
  json j;
  j["passim_report"] = 1;
  j["trace"] = trace_name;
  j["settings"] = {{"profile", run.settings.profile},
                   {"width", f.width},
                   {"height", f.height},
                   {"color_bits", f.color_bits},
                   {"depth_bits", f.depth_bits},
                   {"stencil_bits", f.stencil_bits},
                   {"accum_bits", f.accum_bits},
                   {"double_buffer", f.double_buffer},
                   {"subpixel_bits", ctx.profile().limits.subpixel_bits}};
  json passes = json::array();
  for (std::size_t k = 0; k < ctx.passes().size(); ++k) {
    const Pass& p = ctx.passes()[k];
    passes.push_back({{"index", k}, {"label", p.label}, {"depth", p.depth}, {"counters", p.counters.to_json()}});
  }
  j["passes"] = passes;
  j["total"] = ctx.total_counters().to_json();
  json images = json::array();
  for (std::size_t k = 0; k < run.images.size(); ++k) {
    const CapturedImage& img = run.images[k];
    // "bits": each channel's width, so that a reader of a 16-bit file recovers the codes
    // (docs/images.md).
    json bits = json::array();
    for (int c = 0; c < std::min(img.channels, 4); ++c) bits.push_back(img.bits[static_cast<std::size_t>(c)]);
    json entry = {{"name", img.name}, {"plane", img.plane}, {"hash", img.hash}, {"width", img.width},
                  {"height", img.height}, {"bits", bits}};
    if (img.plane == "color") entry["buffer"] = img.buffer;
    if (k < image_files.size()) entry["file"] = image_files[k];
    images.push_back(entry);
  }
  j["images"] = images;
  json errors = json::array();
  for (const GlErrorRecord& e : ctx.error_log())
    errors.push_back({{"call", e.call}, {"error", enum_name(e.error)}, {"where", e.where}});
  j["gl_errors"] = errors;
  j["warnings"] = ctx.warnings();
  // The calls the replay did not run (queries; in an apitrace replay also what passim does
  // not model), as the replay printed them; "first": the call number or trace line.
  json skipped = json::array();
  for (const SkippedCall& c : run.skipped)
    skipped.push_back({{"call", c.name}, {"count", c.count}, {"first", c.first_call}, {"why", c.why}});
  j["skipped_calls"] = skipped;
  return j;
}

nlohmann::json expectation_of(const nlohmann::json& report) {
  nlohmann::json e;
  e["images"] = nlohmann::json::object();
  for (const auto& img : report["images"]) e["images"][img["name"].get<std::string>()] = img["hash"];
  e["passes"] = nlohmann::json::array();
  for (const auto& p : report["passes"]) e["passes"].push_back({{"label", p["label"]}, {"counters", p["counters"]}});
  e["total"] = report["total"];
  e["gl_errors"] = report["gl_errors"].size();
  return e;
}

std::vector<std::string> check_expectation(const nlohmann::json& report, const nlohmann::json& expected) {
  std::vector<std::string> diffs;
  auto compare_counters = [&](const std::string& where, const nlohmann::json& got, const nlohmann::json& want) {
    for (const auto& [key, value] : want.items()) {
      if (!got.contains(key)) diffs.push_back(fmt::format("{}: no counter '{}'", where, key));
      else if (got[key] != value)
        diffs.push_back(fmt::format("{}: {} is {}, expected {}", where, key, got[key].dump(), value.dump()));
    }
  };
  if (expected.contains("images")) {
    for (const auto& [name, hash] : expected["images"].items()) {
      bool found = false;
      for (const auto& img : report["images"]) {
        if (img["name"] != name) continue;
        found = true;
        if (img["hash"] != hash)
          diffs.push_back(fmt::format("image '{}': hash {}, expected {}", name, img["hash"].get<std::string>(),
                                      hash.get<std::string>()));
      }
      if (!found) diffs.push_back(fmt::format("image '{}' was not produced", name));
    }
  }
  if (expected.contains("passes")) {
    const auto& want = expected["passes"];
    const auto& got = report["passes"];
    if (want.size() != got.size())
      diffs.push_back(fmt::format("{} passes, expected {}", got.size(), want.size()));
    for (std::size_t k = 0; k < std::min(want.size(), got.size()); ++k) {
      const std::string where = fmt::format("pass {} \"{}\"", k, got[k]["label"].get<std::string>());
      if (want[k].contains("label") && want[k]["label"] != got[k]["label"])
        diffs.push_back(fmt::format("{}: label expected \"{}\"", where, want[k]["label"].get<std::string>()));
      if (want[k].contains("counters")) compare_counters(where, got[k]["counters"], want[k]["counters"]);
    }
  }
  if (expected.contains("total")) compare_counters("total", report["total"], expected["total"]);
  if (expected.contains("gl_errors") && expected["gl_errors"] != report["gl_errors"].size())
    diffs.push_back(fmt::format("{} GL errors, expected {}", report["gl_errors"].size(), expected["gl_errors"].dump()));
  return diffs;
}

RunOutput run_trace_to_dir(const std::filesystem::path& trace, const std::filesystem::path& out_dir,
                           const ReplayOptions& options, bool prefer_tiff) {
  ReplayResult run = replay_trace(trace, options);
  std::filesystem::create_directories(out_dir);
  RunOutput out;
  std::vector<std::string> names;
  for (const CapturedImage& img : run.images) {
    out.files.push_back(write_image(img, out_dir, prefer_tiff));
    names.push_back(out.files.back().filename().string());
  }
  out.report = run_report(run, trace.string(), names);
  const std::filesystem::path counters = out_dir / "counters.json";
  write_text_file(counters, out.report.dump(2) + "\n");
  out.files.push_back(counters);
  return out;
}

}  // namespace passim
