// libFuzzer target: the .pass trace parser and replay (docs/trace-format.md). Any input
// must replay or end in a TraceError: never a crash, a hang or a sanitizer report.
// Corpus: tests/fuzz/corpus/pass (seeded with traces/*.pass).
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>

#include "trace_io/trace.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    // Side files resolve in an empty directory: a fuzzed trace cannot reach the disk's files.
    (void)passim::replay_trace_text(text, "fuzz.pass", "/nonexistent-passim-fuzz");
  } catch (const passim::TraceError&) {
  }
  return 0;
}
