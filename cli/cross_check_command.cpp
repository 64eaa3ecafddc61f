#include "cli/cross_check_command.hpp"

#include <fmt/format.h>

#include <iostream>

namespace passim {

int cross_check_command(const std::string& what, const CrossCheckRun& run, bool quiet) {
  const CrossCheckReport report = cross_check(run);
  if (!report.same) {
    std::cerr << fmt::format("passim: {}: the fast paths differ from the reference {}\n", what, report.difference);
    return 3;
  }
  if (!quiet)
    std::cout << fmt::format("{}: cross-check passed: the reference paths (scalar kernels, general paths, one "
                             "thread) and the fast paths agree on every plane at the end of each of {} passes, "
                             "and on every plane, counter and image at the end\n",
                             what, report.checkpoints);
  return 0;
}

}  // namespace passim
