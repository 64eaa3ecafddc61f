// libFuzzer target: the apitrace .trace reader and replay (docs/apitrace.md). Any input
// must end in calls replayed or an error message (ApitraceReplay::error): an exception of any
// kind escaping, a crash, a hang (-timeout), memory past -rss_limit_mb or a sanitizer report
// is a finding. An input that starts with apitrace's "at" is read as a file; any other input is
// taken as the decompressed stream and packed into one snappy chunk first, so that most
// mutations reach the event grammar instead of failing snappy's checks. Corpus:
// tests/fuzz/corpus/apitrace (the recorded programs' streams, tests/fuzz/README.md).
#include <snappy.h>

#include <cstddef>
#include <cstdint>
#include <sstream>
#include <string>

#include "trace_io/apitrace_replay.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  std::string bytes(reinterpret_cast<const char*>(data), size);
  if (!bytes.starts_with("at")) {
    std::string packed;
    snappy::Compress(bytes.data(), bytes.size(), &packed);
    const auto n = static_cast<std::uint32_t>(packed.size());
    bytes = "at";
    for (int k = 0; k < 4; ++k) bytes.push_back(static_cast<char>((n >> (8 * k)) & 0xff));
    bytes += packed;
  }
  std::istringstream in(bytes);
  passim::ApitraceOptions options;
  options.snapshot = passim::CallSet::parse("frame");
  // A fuzzed viewport may ask for a huge window: keep each run small and quick.
  options.width = 32;
  options.height = 32;
  options.max_memory = 256u << 20;  // the budget, well inside -rss_limit_mb=1024
  (void)passim::replay_apitrace(in, "fuzz.trace", options);
  return 0;
}
