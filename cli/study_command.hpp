// passim study precision and passim merge (docs/studies.md).
#pragma once
#include <string>
#include <vector>

#include "programs/study.hpp"

namespace passim {

struct StudyCommand {
  ProgramOptions base;
  std::string size = "800x600", bits = "4-16", depth_bits, biases, maps, filter, shard = "1/1", out = "study";
  std::vector<std::string> what_if;          // KEY=VALUE changes (study what-if)
  std::string cost_profile = "octane-vpro8";  // the machine the what-if is timed on
  int jobs = 1;
  bool quiet = false;
};
int study_command(const StudyCommand& command);
int provenance_command(const StudyCommand& command);
int what_if_command(const StudyCommand& command);
int merge_command(const std::vector<std::string>& dirs, const std::string& out);

}  // namespace passim
