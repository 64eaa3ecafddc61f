// passim report cost: the cost model's table for a trace or a program (docs/cost-model.md).
#pragma once
#include <string>
#include <vector>

#include "programs/programs.hpp"

namespace passim {

struct CostCommand {
  std::string trace;             // a .pass or apitrace .trace file, or empty with a program
  ProgramOptions program;        // used when `trace` is empty
  bool program_given = false;
  bool bits_given = false;       // else the first profile's colour width
  std::vector<std::string> profiles{"octane-vpro8"};
  std::string format = "text";   // text, csv, json, markdown
  bool paper = false;            // predicted against published fps, Figures 7 and 8
};

// Exit status as the CLI's: 0 ok, 1 run error (message on stderr), 2 usage.
int cost_command(const CostCommand& command);

}  // namespace passim
