// counters.json: what a run did, per pass and in total, with its images' hashes
// (docs/counters.md), and the check of a run against a golden expectation file.
#pragma once
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "trace_io/trace.hpp"

namespace passim {

nlohmann::json run_report(const ReplayResult& run, const std::string& trace_name,
                          const std::vector<std::string>& image_files);

// Compares a report with an expectation: every image hash and every counter the
// expectation names must be equal (an expectation may name a subset of the counters).
// Returns the differences, empty when the run meets the expectation.
std::vector<std::string> check_expectation(const nlohmann::json& report, const nlohmann::json& expected);

// The expectation a report would satisfy exactly (images, passes, totals).
nlohmann::json expectation_of(const nlohmann::json& report);

// Runs a trace and writes its images and counters.json into `out_dir`.
struct RunOutput {
  nlohmann::json report;
  std::vector<std::filesystem::path> files;
};
RunOutput run_trace_to_dir(const std::filesystem::path& trace, const std::filesystem::path& out_dir,
                           const ReplayOptions& options, bool prefer_tiff = false);

}  // namespace passim
