// passim report html: one self-contained page (inline SVG charts, embedded images) of a
// study directory and the cost of its program (docs/studies.md).
#pragma once
#include <string>
#include <vector>

namespace passim {

int html_report_command(const std::string& study_dir, const std::string& out_file,
                        const std::vector<std::string>& cost_profiles, bool quiet = false);

}  // namespace passim
