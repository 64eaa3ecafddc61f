// The .pass trace format (docs/trace-format.md): reading, replaying and writing.
#pragma once
#include <filesystem>
#include <memory>
#include <ostream>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

#include "pipeline/context.hpp"
#include "pipeline/framebuffer.hpp"
#include "pipeline/memory_budget.hpp"
#include "pipeline/profile.hpp"

namespace passim {

inline constexpr int kTraceFormatVersion = 1;

// A malformed trace: the message names file and line.
struct TraceError : std::runtime_error {
  TraceError(const std::string& file, int line, const std::string& message);
  std::string file;
  int line;
  std::string message;
};

// Every setting that affects the bits; a trace's header records all of them.
struct TraceSettings {
  std::string profile = "ideal";
  FramebufferConfig framebuffer;
  int subpixel_bits = -1;  // -1: the profile's
  // The settings' header lines ("@framebuffer ...", ...).
  std::vector<std::string> header_lines() const;
  // The machine profile with the subpixel override applied.
  MachineProfile machine() const;
};

// An image a trace asks for (@output) captured at that point of the replay.
struct CapturedImage {
  std::string name;
  std::string plane;  // "color", "rgb", "alpha", "depth" or "stencil"
  std::string buffer;  // colour buffer name ("GL_BACK") for colour planes
  int width = 0, height = 0;
  std::array<int, 4> bits{};  // colour widths, or {depth_bits,0,0,0} / {stencil_bits,...}
  int channels = 4;
  std::vector<std::uint32_t> codes;  // row 0 at the bottom, `channels` codes per pixel
  std::string hash;  // FNV-1a 64 of the codes, hex
};

// Receives each GL error raised during a replay, with its trace location.
struct ReplayOptions {
  bool strict = false;           // a GL error ends the replay (TraceError)
  class TraceWriter* record = nullptr;  // re-record every call (canonical form)
  std::ostream* diagnostics = nullptr;  // GL errors reported here as they happen; the skipped calls at the end
  std::uint64_t max_memory = kDefaultMemoryBudget;  // the run's memory budget (memory_budget.hpp)
  // Folders besides the trace's own that side files may come from (side_files.hpp).
  std::vector<std::filesystem::path> allow_files;
  Context::PassEndObserver pass_end;  // installed on the replay's context (the cross-check)
  class QueryLog* queries = nullptr;   // receives what every query returned (--queries)
  // When above 0, the window is at most this wide and high: a larger @framebuffer (or the
  // default 800x600) is cut down to it. For fuzzing, where every run must be quick; the
  // commands never set it.
  int window_limit = 0;
};

// A call a replay did not run, once per name: its count, where it was first (an apitrace call
// number, a .pass line) and why.
struct SkippedCall {
  std::string name;
  std::uint64_t count = 0;
  std::uint64_t first_call = 0;
  std::string why;
};
// One line per skipped call, as every replay prints them at its end:
// "passim: skipped 12 calls of glFooBar (not modelled by passim)".
std::string skipped_lines(const std::vector<SkippedCall>& skipped);

struct ReplayResult {
  TraceSettings settings;
  std::unique_ptr<Context> context;
  std::vector<CapturedImage> images;
  // In the order first met; counters.json's "skipped_calls". An apitrace replay's: a .pass
  // trace runs every call it names (an unknown name is an error).
  std::vector<SkippedCall> skipped;
};

// Replays a .pass file. Throws TraceError (with file:line) for malformed input,
// missing side files and, with `strict`, GL errors.
ReplayResult replay_trace(const std::filesystem::path& file, const ReplayOptions& options = {});
// The same from text (`name` is used in messages; side files are read from `base_dir`).
ReplayResult replay_trace_text(const std::string& text, const std::string& name,
                               const std::filesystem::path& base_dir, const ReplayOptions& options = {});

// A window rectangle of a capture; width 0 means the whole framebuffer.
struct CaptureRegion {
  int x = 0, y = 0, width = 0, height = 0;
};

// Captures a plane ("color", "rgb" / "alpha" = the colour buffer without / only its alpha, "depth",
// "stencil") of the context's framebuffer, or a rectangle of it, as an @output does.
// The region must lie inside the framebuffer.
CapturedImage capture_plane(const Context& ctx, const std::string& name, const std::string& plane,
                            GLenum buffer, CaptureRegion region = {});
// FNV-1a (64 bits): of codes, each as its `bytes_per_code` low bytes, little-endian; of bytes.
std::string fnv1a_hex(const std::vector<std::uint32_t>& codes, int bytes_per_code);
std::uint64_t fnv1a(std::span<const std::byte> bytes);

// Writes a trace: header, then one canonical line per call.
class TraceWriter final : public CallSink {
 public:
  explicit TraceWriter(std::ostream& out) : out_(out) {}
  void write_header(const TraceSettings& settings);
  void on_call(const Call& call) override;
  // Directives that are not GL calls.
  void output(const std::string& name, const std::string& plane, const std::string& buffer,
              CaptureRegion region = {});
  void swap();

 private:
  std::ostream& out_;
};

}  // namespace passim
