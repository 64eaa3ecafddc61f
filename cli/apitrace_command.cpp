#include "cli/apitrace_command.hpp"

#include <fmt/format.h>

#include <filesystem>
#include <iostream>
#include <optional>
#include <stdexcept>
#include <sstream>

#include "cli/args.hpp"
#include "cli/cross_check_command.hpp"
#include "trace_io/apitrace_replay.hpp"
#include "trace_io/query_log.hpp"
#include "reports/image_io.hpp"
#include "reports/report.hpp"

namespace passim {

namespace fs = std::filesystem;

namespace {
constexpr int kOk = 0, kRunError = 1, kUsage = 2;

// The command line's settings as replay options; false (message printed) for a usage error.
bool to_options(const ApitraceCommand& c, ApitraceOptions& o) {
  try {
    o.profile = c.profile;
    o.color_bits = c.bits;
    o.depth_bits = c.depth_bits;
    o.stencil_bits = c.stencil_bits;
    o.accum_bits = c.accum_bits;
    o.strict = c.strict;
    o.max_memory = c.max_memory;
    o.diagnostics = c.quiet ? nullptr : &std::cerr;
    if (!c.size.empty()) parse_size(c.size, o.width, o.height);
    if (!c.snapshot.empty()) o.snapshot = CallSet::parse(c.snapshot);
    if (!c.snapshot_at.empty()) {
      if (c.snapshot_at != "flush") throw std::invalid_argument("--snapshot-at takes 'flush'");
      o.snapshot_at_flush = true;
    }
  } catch (const std::invalid_argument& e) {
    std::cerr << "passim: " << e.what() << "\n";
    return false;
  }
  if (c.bits != 0 && (c.bits < 1 || c.bits > 16)) {
    std::cerr << "passim: --bits takes 1..16\n";
    return false;
  }
  return true;
}

}  // namespace

int apitrace_run_command(const ApitraceCommand& c) {
  ApitraceOptions o;
  if (!to_options(c, o)) return kUsage;
  if (c.cross_check) {
    o.diagnostics = nullptr;
    return cross_check_command(c.trace, [&](const KernelPaths& paths, Context::PassEndObserver observer) {
      const ScopedKernelPaths scope(paths);
      ApitraceOptions run = o;
      run.pass_end = std::move(observer);
      ApitraceReplay r = replay_apitrace(c.trace, run);
      if (r.error) throw std::runtime_error(*r.error);
      return std::move(r.result);
    }, c.quiet);
  }
  std::optional<ScopedKernelPaths> reference;
  if (c.reference) reference.emplace(KernelPaths::reference());
  std::optional<QueryLog> queries;
  if (!c.queries.empty()) {
    queries.emplace(c.queries_arrays.empty() ? std::nullopt : std::optional<fs::path>(c.queries_arrays));
    o.queries = &*queries;
  }
  ApitraceReplay r = replay_apitrace(c.trace, o);
  // A replay that stops with an error writes nothing (no image of a run that failed is left).
  if (r.result.context && !r.error) {
    const fs::path out = c.out;
    fs::create_directories(out);
    std::vector<fs::path> files;
    std::vector<std::string> names;
    for (const CapturedImage& img : r.result.images) {
      files.push_back(write_image(img, out, c.tiff));
      names.push_back(files.back().filename().string());
    }
    nlohmann::json report = run_report(r.result, c.trace, names);
    nlohmann::json unsupported = nlohmann::json::array();
    for (const SkippedCall& s : r.unsupported)
      unsupported.push_back({{"call", s.name}, {"count", s.count}, {"first_call", s.first_call}});
    report["apitrace"] = {{"calls", r.calls}, {"frames", r.frames}, {"unsupported", unsupported}};
    write_text_file(out / "counters.json", report.dump(2) + "\n");
    files.push_back(out / "counters.json");
    if (queries) {
      queries->commit();
      write_text_file(c.queries, queries->json().dump(2) + "\n");
      files.push_back(c.queries);
    }
    if (!c.quiet) {
      const FramebufferConfig& f = r.result.settings.framebuffer;
      std::cout << fmt::format("{} -> {}: {} calls, {} frames; {}x{}, colour {},{},{},{}, depth {}, stencil {}, "
                               "accumulation {}, {}-buffered\n",
                               c.trace, c.out, r.calls, r.frames, f.width, f.height, f.color_bits[0], f.color_bits[1],
                               f.color_bits[2], f.color_bits[3], f.depth_bits, f.stencil_bits, f.accum_bits,
                               f.double_buffer ? "double" : "single");
      for (const auto& file : files) std::cout << "  wrote " << file.string() << "\n";
      if (r.result.images.empty() && !r.error)
        std::cout << "  no snapshot taken: choose calls with --snapshot CALLSET (e.g. 'frame') or --snapshot-at flush\n";
    }
  }
  if (r.error) {
    std::cerr << "passim: " << *r.error << "\n";
    return kRunError;
  }
  return kOk;
}

int apitrace_convert_command(const ApitraceCommand& c) {
  ApitraceOptions o;
  if (!to_options(c, o)) return kUsage;
  std::ostringstream text;
  TraceWriter writer(text);
  o.record = &writer;
  ApitraceReplay r = replay_apitrace(c.trace, o);
  if (r.error) {
    std::cerr << "passim: " << *r.error << "\n" << "passim: " << c.pass_out << " not written\n";
    return kRunError;
  }
  std::string header = fmt::format("# converted by passim from the apitrace trace {} ({} calls, {} frames)\n",
                                   fs::path(c.trace).filename().string(), r.calls, r.frames);
  for (const SkippedCall& s : r.unsupported)
    header += fmt::format("# not replayed: {} x{} (first at call {})\n", s.name, s.count, s.first_call);
  // The version line must come first: the comments go after it.
  std::string body = text.str();
  const std::size_t eol = body.find('\n');
  body.insert(eol + 1, header);
  write_text_file(c.pass_out, body);
  if (!c.quiet) std::cout << fmt::format("{} -> {} ({} calls, {} frames)\n", c.trace, c.pass_out, r.calls, r.frames);
  return kOk;
}

}  // namespace passim
