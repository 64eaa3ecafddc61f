// passim run FILE.trace and passim convert FILE.trace -o FILE.pass (docs/apitrace.md).
#pragma once
#include <cstdint>
#include <string>

namespace passim {

struct ApitraceCommand {
  std::string trace;
  std::string out = "out";      // run: directory for snapshots and counters.json
  std::string pass_out;          // convert: the .pass to write
  std::string profile = "ideal";
  std::string size;              // WxH; empty: the drawable's
  std::string snapshot;          // apitrace call set
  std::string snapshot_at;       // "flush"
  int bits = 0, depth_bits = -1, stencil_bits = -1, accum_bits = -1;
  bool strict = false, tiff = false, quiet = false;
  std::uint64_t max_memory = std::uint64_t{1} << 30;  // --max-memory
  bool reference = false, cross_check = false;         // the kernel paths (reports/cross_check.hpp)
  std::string queries, queries_arrays;                 // run: --queries FILE, --queries-arrays DIR
};

int apitrace_run_command(const ApitraceCommand& c);
int apitrace_convert_command(const ApitraceCommand& c);

}  // namespace passim
