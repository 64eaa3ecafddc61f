// libFuzzer target: the .pass trace parser and replay (docs/trace-format.md). Any input must
// replay or end in a TraceError (the reader's own error, naming file:line). Anything else —
// another exception, a crash, a hang (-timeout), memory past -rss_limit_mb, a sanitizer
// report — is a finding: an uncaught exception aborts and libFuzzer reports it.
// Corpus: tests/fuzz/corpus/pass (traces/*.pass and their mutations); dictionary: pass.dict.
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>

#include "trace_io/trace.hpp"

namespace {

// The trace's folder: a fresh temporary one holding one small side file of each kind, so
// that fuzzed `file(...)` and `@mesh` reach the readers, and the confinement rules (no
// absolute paths, no `..`, no devices; trace_io/side_files.hpp) decide everything else.
std::filesystem::path trace_folder() {
  static const std::filesystem::path dir = [] {
    std::filesystem::path d = std::filesystem::temp_directory_path() / "passim-fuzz-pass";
    std::filesystem::create_directories(d);
    std::ofstream(d / "tri.obj") << "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvn 0 0 1\nf 1/1/1 2/1/1 3/1/1\n";
    const float values[6] = {0, 0, 1, 0, 0, 1};
    std::ofstream(d / "data.f32", std::ios::binary).write(reinterpret_cast<const char*>(values), sizeof values);
    return d;
  }();
  return dir;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  passim::ReplayOptions options;
  options.window_limit = 32;           // every run quick: a fuzzed trace may ask for 4096x4096
  options.max_memory = 256u << 20;     // the budget, well inside -rss_limit_mb=1024
  try {
    (void)passim::replay_trace_text(text, "fuzz.pass", trace_folder(), options);
  } catch (const passim::TraceError&) {
  }
  return 0;
}
