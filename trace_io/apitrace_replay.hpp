// Replaying apitrace .trace files (docs/apitrace.md): each recorded GL call runs on a
// passim Context exactly as a .pass call would; the window-system calls configure the
// framebuffer; chosen calls are snapshotted; what passim does not model is summarised.
#pragma once
#include <array>
#include <cstdint>
#include <filesystem>
#include <istream>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

#include "trace_io/call_set.hpp"
#include "trace_io/trace.hpp"

namespace passim {

struct ApitraceOptions {
  std::string profile = "ideal";
  // Overrides of what the recorded visual asks for; 0 / -1 take the visual's.
  int color_bits = 0;    // 1-16, every channel (alpha only if the visual has one)
  int depth_bits = -1;   // 0-32
  int stencil_bits = -1; // 0-8
  int accum_bits = -1;   // 0 or 2-32
  int width = 0, height = 0;  // 0: from the first glViewport (apitrace records the drawable's)
  int subpixel_bits = -1;
  std::optional<CallSet> snapshot;  // calls after which the draw buffer is captured
  bool snapshot_at_flush = false;   // ... and after every glFlush / glFinish
  bool strict = false;              // an unsupported call or a GL error ends the replay
  std::ostream* diagnostics = nullptr;  // GL errors as they happen, the skipped calls at the end
  TraceWriter* record = nullptr;        // write the replay as a canonical .pass (passim convert)
  std::uint64_t max_memory = kDefaultMemoryBudget;  // the run's memory budget (memory_budget.hpp)
  Context::PassEndObserver pass_end;  // installed on the replay's context (the cross-check)
  class QueryLog* queries = nullptr;   // receives what every query returned (--queries)
};

struct ApitraceReplay {
  ReplayResult result;  // images: the snapshots, named by call number ("0000000042")
  std::uint64_t calls = 0;   // calls read
  std::uint64_t frames = 0;  // glXSwapBuffers seen
  // Both also in result.skipped (in call order):
  std::vector<SkippedCall> unsupported;  // calls whose effect passim does not model
  std::vector<SkippedCall> ignored;      // unknown queries and window-system calls: no effect on the image
  std::optional<std::string> error;      // the replay stopped here (the message names the call)
};

// Never throws for bad input: a malformed trace, an unsupported call under `strict`, a GL
// error under `strict` end the replay with `error` set, keeping what was replayed.
ApitraceReplay replay_apitrace(const std::filesystem::path& file, const ApitraceOptions& options);
ApitraceReplay replay_apitrace(std::istream& in, const std::string& name, const ApitraceOptions& options);

// The summary printed after a replay: the skipped calls, one line each (skipped_lines).
std::string skipped_summary(const ApitraceReplay& replay);

// True when the file starts like an apitrace trace (snappy "at" or gzip).
bool looks_like_apitrace(const std::filesystem::path& file);

}  // namespace passim
