// --reference and --cross-check for passim run and passim program (reports/cross_check.hpp).
#pragma once
#include <string>

#include "reports/cross_check.hpp"

namespace passim {

// Runs the cross-check of `what` (a trace or a program) and prints its verdict: exit 0 when
// the reference and fast paths agree, 3 (as --expect's difference) naming the first
// difference when not. Errors of the runs themselves propagate.
int cross_check_command(const std::string& what, const CrossCheckRun& run, bool quiet);

}  // namespace passim
