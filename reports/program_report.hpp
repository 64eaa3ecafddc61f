// counters.json of a program run: the replay's report (reports/report.hpp) with the program's
// own section (its settings and the shadow levels of its attenuation image). One builder for
// the command line and the Python module, so both give the same document.
#pragma once
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "programs/programs.hpp"
#include "programs/reference.hpp"

namespace passim {

nlohmann::json program_report(const ProgramRun& run, const std::vector<std::string>& image_files);

// reference.json of a double-precision reference (reeves, shader-pcf, mdsm-ref): its settings,
// the levels of its attenuation image and the image's file and hash.
nlohmann::json reference_report(const ReferenceRun& ref, const std::string& image_file);

}  // namespace passim
