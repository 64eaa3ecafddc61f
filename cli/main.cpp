// passim: the command line (README.md; each command's --help).
//   passim run FILE.pass --out DIR     replay a trace: images + counters.json
//   passim run FILE.trace --snapshot S replay an apitrace trace: snapshots + counters.json
//   passim convert FILE.trace -o F.pass  an apitrace trace as a canonical .pass
//   passim demo [--out DIR]            the main job: Figure 7's variants at 8 and 12 bits
//   passim program NAME [...]          one of the papers' pass programs (--list)
//   passim info                        machine profiles, widths, limits, calls
// Exit status: 0 ok, 1 trace or run error, 2 usage, 3 output differs from --expect.
#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <iterator>
#include <optional>
#include <sstream>
#include <streambuf>

#include "pipeline/allocator.hpp"
#include "trace_io/apitrace_replay.hpp"
#include "trace_io/query_log.hpp"
#include "pipeline/calls.hpp"
#include "reports/image_io.hpp"
#include "pipeline/profile.hpp"
#include "reports/program_report.hpp"
#include "reports/report.hpp"
#include "trace_io/trace.hpp"
#include "cli/apitrace_command.hpp"
#include "cli/args.hpp"
#include "cli/cross_check_command.hpp"
#include "cli/cost_command.hpp"
#include "cli/figures.hpp"
#include "cli/html_report.hpp"
#include "cli/progress.hpp"
#include "cli/study_command.hpp"
#include "programs/programs.hpp"
#include "programs/reference.hpp"

namespace fs = std::filesystem;
using namespace passim;

namespace {

constexpr int kOk = 0, kRunError = 1, kUsage = 2, kMismatch = 3;

void print_counters_summary(const nlohmann::json& report) {
  std::cout << fmt::format("  {:<28} {:>12} {:>12} {:>12}\n", "pass", "fragments", "written", "killed");
  for (const auto& p : report["passes"]) {
    const auto& c = p["counters"];
    const auto killed = c["killed_scissor"].get<std::uint64_t>() + c["killed_alpha"].get<std::uint64_t>() +
                        c["killed_stencil"].get<std::uint64_t>() + c["killed_depth"].get<std::uint64_t>();
    std::string label = std::string(2 * p["depth"].get<std::size_t>(), ' ') + p["label"].get<std::string>();
    std::cout << fmt::format("  {:<28} {:>12} {:>12} {:>12}\n", label, c["fragments_generated"].get<std::uint64_t>(),
                             c["fragments_written"].get<std::uint64_t>(), killed);
  }
}

struct RunCommand {
  fs::path trace, out = "out";
  bool strict = false, tiff = false, write_expected = false, quiet = false;
  std::string expect, record;
  std::uint64_t max_memory = kDefaultMemoryBudget;
  std::vector<fs::path> allow_files;
  bool reference = false, cross_check = false;
  std::string queries, queries_arrays;  // --queries FILE, --queries-arrays DIR
};

// The replay's progress, from the re-recording the replay offers (ReplayOptions::record): the
// calls replayed come out as canonical text about as long as the trace's own, so the bytes
// written, against the trace's size, say how far it is (a call with a large array weighs what
// its text weighs). They are handed on to `forward` (the --record text), or dropped.
class ReplayMeter : public std::streambuf {
 public:
  ReplayMeter(std::streambuf* forward, Progress& progress, std::uintmax_t total)
      : forward_(forward), progress_(progress), total_(std::max<std::uintmax_t>(1, total)) {}

 protected:
  int_type overflow(int_type c) override {
    if (c == traits_type::eof()) return c;
    count(1);
    return forward_ ? forward_->sputc(static_cast<char>(c)) : c;
  }
  std::streamsize xsputn(const char* s, std::streamsize n) override {
    count(static_cast<std::uintmax_t>(n));
    return forward_ ? forward_->sputn(s, n) : n;
  }

 private:
  void count(std::uintmax_t n) {
    bytes_ += n;
    if (bytes_ >= next_) {
      progress_.step(static_cast<int>(std::min<std::uintmax_t>(99, 100 * bytes_ / total_)));
      next_ = bytes_ + total_ / 200 + 1;
    }
  }
  std::streambuf* forward_;
  Progress& progress_;
  std::uintmax_t total_, bytes_ = 0, next_ = 0;
};

// A trace this large shows its progress (re-recording it costs about a quarter more time).
constexpr std::uintmax_t kLongTraceBytes = 8u << 20;

int run_command(const RunCommand& c) {
  const fs::path& trace = c.trace;
  const fs::path& out = c.out;
  const bool quiet = c.quiet;
  const std::string& expect = c.expect;
  const std::string& record = c.record;
  std::ostringstream recorded;
  std::error_code size_error;
  const std::uintmax_t size = fs::file_size(trace, size_error);
  const bool watch = !quiet && !size_error && size >= kLongTraceBytes;
  Progress progress(fmt::format("passim run {}", trace.filename().string()), 100, !watch, "%");
  ReplayMeter meter(record.empty() ? nullptr : recorded.rdbuf(), progress, size);
  std::ostream metered(&meter);
  TraceWriter writer(watch ? metered : recorded);
  ReplayOptions options;
  options.strict = c.strict;
  options.diagnostics = &std::cerr;
  options.max_memory = c.max_memory;
  options.allow_files = c.allow_files;
  if (!record.empty() || watch) options.record = &writer;
  std::optional<QueryLog> queries;
  if (!c.queries.empty()) {
    queries.emplace(c.queries_arrays.empty() ? std::nullopt : std::optional<fs::path>(c.queries_arrays));
    options.queries = &*queries;
  }
  RunOutput result;
  try {
    if (c.cross_check) {
      options.diagnostics = nullptr;  // each run would report the same GL errors
      return cross_check_command(trace.string(), [&](const KernelPaths& paths, Context::PassEndObserver observer) {
        const ScopedKernelPaths scope(paths);
        ReplayOptions o = options;
        o.pass_end = std::move(observer);
        return replay_trace(trace, o);
      }, quiet);
    }
    std::optional<ScopedKernelPaths> reference;
    if (c.reference) reference.emplace(KernelPaths::reference());
    result = run_trace_to_dir(trace, out, options, c.tiff);
    progress.finish();
    if (!record.empty()) write_text_file(record, recorded.str());
    if (queries) {
      queries->commit();
      write_text_file(c.queries, queries->json().dump(2) + "\n");
      result.files.push_back(c.queries);
    }
  } catch (const TraceError& e) {
    std::cerr << "passim: " << e.what() << "\n";
    return kRunError;
  } catch (const std::exception& e) {
    std::cerr << "passim: " << trace.string() << ": " << e.what() << "\n";
    return kRunError;
  }
  if (!quiet) {
    std::cout << fmt::format("{} -> {}\n", trace.string(), out.string());
    for (const auto& f : result.files) std::cout << "  wrote " << f.string() << "\n";
    print_counters_summary(result.report);
    for (const auto& w : result.report["warnings"]) std::cerr << "passim: warning: " << w.get<std::string>() << "\n";
  }
  if (c.write_expected) {
    const fs::path path = out / "expected.json";
    write_text_file(path, expectation_of(result.report).dump(2) + "\n");
    if (!quiet) std::cout << "  wrote " << path.string() << "\n";
  }
  if (!expect.empty()) {
    std::ifstream in(expect);
    if (!in) {
      std::cerr << "passim: cannot read expectation file " << expect << "\n";
      return kRunError;
    }
    nlohmann::json expected;
    try {
      expected = nlohmann::json::parse(in);
    } catch (const std::exception& e) {
      std::cerr << "passim: " << expect << ": not valid JSON: " << e.what() << "\n";
      return kRunError;
    }
    const auto diffs = check_expectation(result.report, expected);
    if (!diffs.empty()) {
      std::cerr << "passim: " << trace.string() << " differs from " << expect << ":\n";
      for (const auto& d : diffs) std::cerr << "  " << d << "\n";
      return kMismatch;
    }
    if (!quiet) std::cout << "  matches " << expect << "\n";
  }
  return kOk;
}

// Writes a program run's images, counters.json and trace.pass into `out`.
std::vector<fs::path> write_program_outputs(const ProgramRun& run, const fs::path& out, bool tiff) {
  fs::create_directories(out);
  std::vector<fs::path> files;
  std::vector<std::string> names;
  for (const CapturedImage& img : run.result.images) {
    files.push_back(write_image(img, out, tiff));
    names.push_back(files.back().filename().string());
  }
  const nlohmann::json report = program_report(run, names);
  write_text_file(out / "counters.json", report.dump(2) + "\n");
  files.push_back(out / "counters.json");
  write_text_file(out / "trace.pass", run.trace);
  files.push_back(out / "trace.pass");
  return files;
}

struct ProgramCommand {
  ProgramOptions options;
  std::string size = "800x600", filter, out = "out";
  bool list = false, no_jitter = false, tiff = false, quiet = false, reference = false, cross_check = false;
};

int program_command(ProgramCommand& c) {
  if (c.list) {
    for (const ProgramInfo& p : program_list())
      std::cout << fmt::format("{:<11} {}\n            {}\n", p.name, p.section, p.summary);
    std::cout << "\nScenes: paper, fig8, edges, or an .obj file (--scene).\n";
    return kOk;
  }
  ProgramOptions& o = c.options;
  try {
    parse_size(c.size, o.width, o.height);
    if (!c.filter.empty()) o.filter = parse_filter(c.filter);
  } catch (const std::invalid_argument& e) {
    std::cerr << "passim: " << e.what() << "\n";
    return kUsage;
  }
  o.jitter = !c.no_jitter;
  const auto info = std::find_if(program_list().begin(), program_list().end(),
                                 [&](const ProgramInfo& p) { return p.name == o.program; });
  if (info != program_list().end() && info->reference) {
    try {
      const ReferenceRun ref = run_reference(o);
      fs::create_directories(c.out);
      const fs::path image = write_image(ref.image, c.out, c.tiff);
      const int levels = count_levels(ref.image);
      const nlohmann::json j = reference_report(ref, image.filename().string());
      write_text_file(fs::path(c.out) / "reference.json", j.dump(2) + "\n");
      if (!c.quiet)
        std::cout << fmt::format("{} on {} (double precision, no pipeline) -> {}\n  wrote {}\n  wrote {}\n"
                                 "  shadow levels in the attenuation image: {}\n",
                                 o.program, ref.scene.name, c.out, image.string(), (fs::path(c.out) / "reference.json").string(),
                                 levels);
    } catch (const std::exception& e) {
      std::cerr << "passim: " << e.what() << "\n";
      return kRunError;
    }
    return kOk;
  }
  if (c.cross_check) {
    try {
      return cross_check_command(fmt::format("program {}", o.program),
                                 [&](const KernelPaths& paths, Context::PassEndObserver observer) {
                                   const ScopedKernelPaths scope(paths);
                                   ProgramOptions p = o;
                                   if (!paths.specialised) p.threads = 1;
                                   p.pass_end = std::move(observer);
                                   return std::move(run_program(p).result);
                                 },
                                 c.quiet);
    } catch (const std::exception& e) {
      std::cerr << "passim: " << e.what() << "\n";
      return kRunError;
    }
  }
  std::optional<ScopedKernelPaths> reference;
  if (c.reference) {
    reference.emplace(KernelPaths::reference());
    o.threads = 1;
  }
  ProgramRun run;
  std::vector<fs::path> files;
  try {
    run = run_program(o);
    files = write_program_outputs(run, c.out, c.tiff);
  } catch (const std::exception& e) {
    std::cerr << "passim: " << e.what() << "\n";
    return kRunError;
  }
  if (!c.quiet) {
    std::cout << fmt::format("{} on {} ({} triangles), {}-bit colour, {}-bit depth, {}² map -> {}\n",
                             run.options.program, run.scene.name, run.triangles, o.color_bits, o.depth_bits,
                             run.map_size, c.out);
    for (const auto& f : files) std::cout << "  wrote " << f.string() << "\n";
    print_counters_summary(run_report(run.result, "trace.pass", {}));
    std::cout << fmt::format("  shadow levels in the attenuation image: {}\n", count_levels(run.image("attenuation")));
  }
  return kOk;
}

int info_command(bool calls) {
  if (calls) {
    for (const CallInfo* c : all_calls()) std::cout << describe_call(*c) << "\n";
    std::cout << "\nArrays read the elements in brackets (docs/trace-format.md); a trace must give at least those.\n";
    return kOk;
  }
  std::cout << "Machine profiles (select with '@profile NAME' in a trace):\n\n";
  for (const MachineProfile& p : machine_profiles()) {
    const MachineLimits& l = p.limits;
    std::cout << fmt::format("{}\n  {}\n", p.name, p.description);
    std::cout << fmt::format("  widths: colour {},{},{},{}  depth {}  stencil {}  accumulation {}\n", p.color_bits[0],
                             p.color_bits[1], p.color_bits[2], p.color_bits[3], p.depth_bits, p.stencil_bits,
                             p.accum_bits);
    std::cout << fmt::format(
        "  limits: framebuffer {}  viewport {}  texture {}  lights {}  clip planes {}  subpixel bits {}\n"
        "          convolution {}x{}  colour table {}  histogram {}  pixel map {}  list nesting {}\n",
        l.max_framebuffer_size, l.max_viewport_size, l.max_texture_size, l.max_lights, l.max_clip_planes,
        l.subpixel_bits, l.max_convolution_width, l.max_convolution_height, l.max_color_table_width,
        l.max_histogram_width, l.max_pixel_map_table, l.max_list_nesting);
    std::cout << fmt::format("  sources: {}\n", p.sources);
    const CostRates& r = p.rates;
    if (r.triangles > 0.0)
      std::cout << fmt::format(
          "  cost rates (M/s): vertices {:g}  triangles {:g}  fragments {:g}  texture {:g}  framebuffer {:g} MB\n"
          "          pixels {:g}  scale/bias {:g}  table {:g}  matrix {:g}  convolution {:g}/{:g}/{:g}\n"
          "          accumulation {:g}  clear {:g}  texture load {:g} MB  pass overhead {:g} us\n"
          "          ({})\n",
          r.vertices / 1e6, r.triangles / 1e6, r.fragments / 1e6, r.texture_lookups / 1e6, r.framebuffer_bytes / 1e6,
          r.pixels / 1e6, r.scale_bias / 1e6, r.color_table / 1e6, r.color_matrix / 1e6, r.convolution[0] / 1e6,
          r.convolution[1] / 1e6, r.convolution[2] / 1e6, r.accumulation / 1e6, r.clear / 1e6,
          r.texture_load_bytes / 1e6, r.pass_overhead * 1e6, r.sources);
    else
      std::cout << "  cost rates: none (not a timed machine)\n";
    std::cout << "\n";
  }
  return kOk;
}

// The main job: Figure 7's four variants (shadow map, PCF 2x2, fast PCF 2x2, fast PCF
// 4x4) at 8 and 12 bits on the paper scene; a side-by-side figure with its panels labelled
// (matplotlib, cli/figures.hpp) and a table.
int demo_command(const fs::path& out, const std::string& scene, bool quiet) {
  struct Variant {
    const char* label;
    const char* program;
    int filter;
  };
  const Variant variants[] = {{"shadow map", "shadow-map", 0},
                              {"PCF 2x2", "pcf", 2},
                              {"fast PCF 2x2", "fast-pcf", 2},
                              {"fast PCF 4x4", "fast-pcf", 4}};
  std::string table =
      "| variant | bits | passes | shadow-map passes | levels | fragments | pixels copied | accumulation ops | "
      "time (s) |\n|---|---|---|---|---|---|---|---|---|\n";
  // The inset: the shadow edge of the large sphere on the ground, as Figure 7's red box
  // (window coordinates, row 0 at the bottom).
  const int inset_x = 250, inset_y = 210, inset_w = 100, inset_h = 75;
  nlohmann::json panels = nlohmann::json::array();
  std::string scene_name;
  int triangles = 0;
  try {
    fs::create_directories(out);
    Progress progress("passim demo", 8, quiet, "runs");
    int done = 0;
    for (int bits : {8, 12}) {
      for (const Variant& v : variants) {
        progress.step(done, fmt::format("{}, {} bits", v.label, bits));
        ProgramOptions o;
        o.program = v.program;
        o.filter = v.filter;
        o.color_bits = bits;
        o.scene = scene;
        const auto t0 = std::chrono::steady_clock::now();
        const ProgramRun r = run_program(o);
        const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        const fs::path dir = out / fmt::format("{}-{}x{}-{}bit", v.program, std::max(1, r.options.filter),
                                               std::max(1, r.options.filter), bits);
        write_program_outputs(r, dir, false);
        int passes = 0, map_passes = 0;
        for (const Pass& p : r.result.context->passes()) {
          if (p.label == "(unmarked)") continue;
          ++passes;
          if (p.label.rfind("shadow map", 0) == 0) ++map_passes;
        }
        const Counters c = r.result.context->total_counters();
        const int levels = count_levels(r.image("attenuation"));
        table += fmt::format("| {} | {} | {} | {} | {} | {} | {} | {} | {:.2f} |\n", v.label, bits, passes, map_passes,
                             levels, c.fragments_generated, c.pixels_drawn + c.pixels_read,
                             c.accum_load_pixels + c.accum_accum_pixels + c.accum_return_pixels, seconds);
        panels.push_back({{"variant", v.label}, {"bits", bits}, {"levels", levels},
                          {"image", fs::absolute(dir / image_file_name(r.image("final"))).string()}});
        scene_name = r.scene.name, triangles = r.triangles;
        progress.step(++done);
        if (!quiet) {
          progress.finish();
          std::cout << fmt::format("  {:<13} {:>2} bits: {:>2} passes, {:>2} shadow levels  -> {}\n", v.label, bits,
                                   passes, levels, dir.string());
        }
      }
    }
    const std::string md = fmt::format(
        "# Figure 7 variants on the {} scene ({} triangles, 800x600, 512² map)\n\n"
        "Panels of figure7.png, labelled (a)-(h) as the paper's: 8 bits (each variant's image, the inset "
        "magnified below it), then 12 bits.\n"
        "'levels' counts distinct values of the attenuation image, values one code apart as one level.\n\n{}",
        scene_name, triangles, table);
    write_text_file(out / "figure7.md", md);
    const nlohmann::json manifest{
        {"title", fmt::format("Figure 7 of Brabec & Seidel on the {} scene: 8 bits (a-d), 12 bits (e-h)", scene_name)},
        {"inset", {{"x", inset_x}, {"y", inset_y}, {"width", inset_w}, {"height", inset_h}}},
        {"panels", panels}};
    write_text_file(out / "figure7.json", manifest.dump(1) + "\n");
    const FigureRun figure = draw_figures({"figure7", (out / "figure7.json").string(), (out / "figure7.png").string()});
    if (!quiet) std::cout << "\n" << md << "\n";
    if (!figure.ok) {
      std::cerr << "passim demo: figure7.png was not drawn: " << figure.message << "\n";
      if (!quiet) std::cout << "Wrote " << (out / "figure7.md").string() << "; each run's images, counters.json and trace.pass are beside it.\n";
      return kRunError;
    }
    if (!quiet)
      std::cout << "Wrote " << (out / "figure7.png").string() << " and " << (out / "figure7.md").string()
                << "; each run's images, counters.json and trace.pass are beside them.\n";
  } catch (const std::exception& e) {
    std::cerr << "passim: " << e.what() << "\n";
    return kRunError;
  }
  return kOk;
}

}  // namespace

// One rule for --bits everywhere (README, "Running the papers' programs"): a program runs at the
// colour width of the machine profile it runs on unless --bits says otherwise — 8 bits on
// `ideal`, 12 on `octane-vpro8`. Commands that time a program run it on the machine they time
// (report cost, study what-if), so the width is that machine's.
constexpr const char* kBitsHelp = "Colour width per channel, 4-16 (default: the profile's, 8 on ideal, 12 on octane-vpro8)";
void default_bits(CLI::App* command, ProgramOptions& o) {
  if (command->count("--bits") > 0) return;
  if (const MachineProfile* p = find_profile(o.profile)) o.color_bits = p->color_bits[0];
}

int dispatch(int argc, char** argv) {
  CLI::App app{"passim: a bit-accurate model of the OpenGL 1.2 + imaging pipeline, for multipass algorithms"};
  app.require_subcommand(0, 1);
  app.footer("Exit status: 0 ok, 1 trace or run error (message names file:line), 2 usage, "
             "3 output differs from --expect.\nDocs: README.md, docs/.");

  auto* run = app.add_subcommand(
      "run", "Replay a .pass trace (its @output images and counters.json) or an apitrace .trace (docs/apitrace.md)");
  RunCommand rc;
  std::string trace_file, out_dir = "out";
  ApitraceCommand ac;
  run->add_option("trace", trace_file, "The .pass or apitrace .trace file to replay")->required();
  run->add_option("--out,-o", out_dir, "Directory for images and counters.json")->capture_default_str();
  run->add_flag("--strict", rc.strict, "Make any GL error fatal (exit 1)");
  run->add_option("--expect", rc.expect, "Check image hashes and counters against this JSON file (exit 3 if they differ)");
  run->add_option("--record", rc.record, "Also write the replay, re-recorded, as a canonical .pass trace");
  run->add_flag("--tiff", rc.tiff, "Write colour images wider than 8 bits as 16-bit TIFF instead of 16-bit PNG");
  run->add_flag("--write-expected", rc.write_expected, "Also write DIR/expected.json (hashes and counters of this run)");
  run->add_flag("--quiet,-q", rc.quiet, "Print nothing but errors");
  run->add_option("--queries", rc.queries,
                  "Write what every query returned (glGet*, glIsEnabled, glGetError, glReadPixels, glGetTexImage, "
                  "glGetHistogram, glGetMinmax, the tables and filters), in order, to this JSON file");
  run->add_option("--queries-arrays", rc.queries_arrays,
                  "Also write each query result of more than 64 values to this folder, one file each (the JSON "
                  "gives its hash and name)")
      ->needs(run->get_option("--queries"));
  // Input from strangers (docs/hostile-input.md): what a replay may take and read.
  auto input_limits = [](CLI::App* cmd, std::uint64_t& max_memory) {
    cmd->add_option("--max-memory", max_memory,
                    "Memory budget of the run, e.g. 512MiB or 2G: a GL allocation past it raises GL_OUT_OF_MEMORY, "
                    "anything else past it ends the run")
        ->transform(CLI::AsSizeValue(false))
        ->default_str("1GiB");
  };
  input_limits(run, rc.max_memory);
  // The reference and fast paths (stages/kernel_paths.hpp, reports/cross_check.hpp).
  auto path_options = [](CLI::App* cmd, bool& reference, bool& cross_check) {
    cmd->add_flag("--reference", reference,
                  "Run on the reference paths: scalar kernels, the general paths, one thread (the same bits, slower)");
    cmd->add_flag("--cross-check", cross_check,
                  "Run on the reference and on the fast paths and compare every plane after each pass and every "
                  "counter and image at the end; writes nothing; exit 3 naming the first difference")
        ->excludes(cmd->get_option("--reference"));
  };
  path_options(run, rc.reference, rc.cross_check);
  run->get_option("--cross-check")->excludes(run->get_option("--queries"));
  run->add_option("--allow-files", rc.allow_files,
                  "A folder side files (file(...), @mesh) may also come from; by default only the trace's own "
                  "folder (repeatable)")
      ->check(CLI::ExistingDirectory);
  // apitrace traces only: the framebuffer a .pass states in its header.
  auto apitrace_options = [&ac](CLI::App* cmd) {
    const char* group = "apitrace .trace options";
    cmd->add_option("--bits", ac.bits, "Colour width of every channel, 1-16 (default: the visual's at the profile's)")
        ->group(group);
    cmd->add_option("--depth-bits", ac.depth_bits, "Depth width 0-32 (default: the visual's)")->group(group);
    cmd->add_option("--stencil-bits", ac.stencil_bits, "Stencil width 0-8 (default: the visual's)")->group(group);
    cmd->add_option("--accum-bits", ac.accum_bits, "Accumulation width 0 or 2-32 (default: the visual's)")->group(group);
    cmd->add_option("--size", ac.size, "Window WIDTHxHEIGHT (default: the drawable's, from the first glViewport)")
        ->group(group);
    cmd->add_option("--profile", ac.profile, "Machine profile (passim info)")->group(group);
    cmd->add_option("--snapshot", ac.snapshot,
                    "Write the draw buffer after these calls: apitrace call-set syntax, e.g. 12,40-50/2,frame")
        ->group(group);
    cmd->add_option("--snapshot-at", ac.snapshot_at, "'flush': also after every glFlush and glFinish")->group(group);
  };
  apitrace_options(run);

  auto* convert = app.add_subcommand("convert", "Write an apitrace .trace as the equivalent canonical .pass trace");
  convert->add_option("trace", ac.trace, "The apitrace .trace file")->required();
  convert->add_option("--out,-o", ac.pass_out, "The .pass file to write")->required();
  convert->add_flag("--strict", ac.strict, "Make any unsupported call or GL error fatal (exit 1)");
  convert->add_flag("--quiet,-q", ac.quiet, "Print nothing but errors");
  apitrace_options(convert);
  input_limits(convert, ac.max_memory);

  auto* info = app.add_subcommand("info", "List machine profiles with their widths and limits");
  bool calls = false;
  info->add_flag("--calls", calls, "List the GL calls traces may use, with their signatures");

  auto* demo = app.add_subcommand("demo", "The main job on built-in defaults (what the quick start runs)");
  std::string demo_out = "out", demo_scene = "paper";
  demo->add_option("--out,-o", demo_out, "Output directory")->capture_default_str();
  demo->add_option("--scene", demo_scene, "paper, fig8, edges or FILE.obj")->capture_default_str();
  bool demo_quiet = false;
  demo->add_flag("--quiet,-q", demo_quiet, "Print nothing but errors");

  auto* program = app.add_subcommand("program", "Run one of the papers' pass programs (passim program --list)");
  ProgramCommand pc;
  program->add_option("name", pc.options.program,
                      "Program: shadow-map, pcf, fast-pcf, mdsm, hw-shadow; references: reeves, shader-pcf, mdsm-ref");
  program->add_flag("--list", pc.list, "Describe each program with its paper section");
  program->add_option("--bits", pc.options.color_bits, kBitsHelp);
  program->add_option("--depth-bits", pc.options.depth_bits, "Depth-buffer width")->capture_default_str();
  program->add_option("--accum-bits", pc.options.accum_bits, "Accumulation width (0: twice the colour width)")
      ->capture_default_str();
  program->add_option("--map", pc.options.map_size, "Shadow-map size (power of two; 0: the scene's, 512 or 1024)")
      ->capture_default_str();
  program->add_option("--size", pc.size, "Camera image WIDTHxHEIGHT")->capture_default_str();
  program->add_option("--filter", pc.filter, "Footprint NxN: pcf 2x2-4x4, fast-pcf 2x2 or 4x4, mdsm 1x1-3x3");
  program->add_option("--depths", pc.options.depths, "mdsm: depths per map cell, 1-3")->capture_default_str();
  program->add_option("--texture-bits", pc.options.texture_bits,
                      "Texture internal formats: 4, 8, 12, 16 (0: the smallest holding the colour width)")
      ->capture_default_str();
  program->add_option("--table-bits", pc.options.table_bits, "Counting colour table format: 4, 8, 12, 16 (0: as textures)")
      ->capture_default_str();
  program->add_option("--scene", pc.options.scene, "paper, fig8, edges or FILE.obj")->capture_default_str();
  program->add_option("--bias", pc.options.bias, "Depth bias in steps of the depth encoding (default: one 8-bit step, 2^(bits-8))");
  program->add_option("--profile", pc.options.profile, "Machine profile (passim info)")->capture_default_str();
  program->add_flag("--linear", pc.options.linear, "hw-shadow: LINEAR (2x2 filtered) compare");
  program->add_flag("--no-jitter", pc.no_jitter, "pcf: sample the strata's centres instead of jittering");
  program->add_option("--seed", pc.options.seed, "pcf, reeves: jitter seed")->capture_default_str();
  program->add_option("--sampling", pc.options.sampling, "reeves: random, gaussian or jittered")->capture_default_str();
  program->add_flag("--intermediates", pc.options.intermediates, "Also write every intermediate buffer");
  program->add_option("--threads", pc.options.threads,
                      "Threads of rasterization, 1-64: the same images and counters at any number (docs/threads.md)")
      ->check(CLI::Range(1, Context::kMaxThreads))
      ->capture_default_str();
  program->add_option("--out,-o", pc.out, "Output directory")->capture_default_str();
  program->add_flag("--tiff", pc.tiff, "Colour images wider than 8 bits as 16-bit TIFF instead of PNG");
  program->add_flag("--quiet,-q", pc.quiet, "Print nothing but errors");
  path_options(program, pc.reference, pc.cross_check);

  auto* report = app.add_subcommand("report", "Reports: cost (a trace or a program), html (a study)");
  report->require_subcommand(1);
  auto* cost = report->add_subcommand("cost", "Estimated time per pass and stage on modelled machines (docs/cost-model.md)");
  CostCommand cc;
  std::string cost_profiles = "octane-vpro8", cost_filter;
  bool cost_csv = false, cost_json = false, cost_markdown = false;
  cost->add_option("trace", cc.trace, "A .pass or apitrace .trace file (or give --program)");
  cost->add_option("--program", cc.program.program, "A program instead of a trace (passim program --list)");
  cost->add_option("--filter", cost_filter, "The program's footprint NxN");
  cost->add_option("--scene", cc.program.scene, "The program's scene")->capture_default_str();
  cost->add_option("--map", cc.program.map_size, "The program's shadow-map size");
  cost->add_option("--depths", cc.program.depths, "mdsm: the program's depths per map cell, 1-3")->capture_default_str();
  cost->add_option("--bits", cc.program.color_bits, "Colour width (default: each profile's own)");
  cost->add_option("--profile", cost_profiles, "Machine profiles, comma-separated")->capture_default_str();
  cost->add_flag("--csv", cost_csv, "CSV on stdout");
  cost->add_flag("--json", cost_json, "JSON on stdout");
  cost->add_flag("--markdown", cost_markdown, "Markdown tables on stdout");
  cost->add_flag("--paper", cc.paper, "Predicted against published frames per second (Figures 7 and 8)");

  auto* html = report->add_subcommand("html", "One self-contained HTML page of a study directory and its program's cost");
  std::string html_dir, html_out, html_cost = "octane-vpro8,o2";
  html->add_option("study", html_dir, "A study output directory (passim study precision --out)")->required();
  html->add_option("--out,-o", html_out, "The page (default: STUDY/report.html)");
  html->add_option("--cost", html_cost, "Timed profiles for the cost tables, comma-separated ('' for none)")
      ->capture_default_str();
  bool html_quiet = false;
  html->add_flag("--quiet,-q", html_quiet, "No progress line");
  auto* study = app.add_subcommand("study", "Precision studies (docs/studies.md)");
  study->require_subcommand(1);
  auto* precision = study->add_subcommand("precision", "A program over a sweep of widths, measured against its double-precision reference");
  StudyCommand sc;
  precision->add_option("--program", sc.base.program, "The program (passim program --list)")->required();
  precision->add_option("--filter", sc.filter, "Its footprint NxN");
  precision->add_option("--depths", sc.base.depths, "mdsm: depths per cell")->capture_default_str();
  precision->add_option("--scene", sc.base.scene, "paper, fig8, edges or FILE.obj")->capture_default_str();
  precision->add_option("--profile", sc.base.profile, "Machine profile")->capture_default_str();
  precision->add_option("--bits", sc.bits, "Colour widths swept: a list of values and ranges")->capture_default_str();
  precision->add_option("--figures", sc.figures, "The figures' formats (png, svg, pdf), or none")->capture_default_str();
  precision->add_option("--depth-bits", sc.depth_bits, "Depth widths (default 24)");
  precision->add_option("--bias", sc.biases, "Biases in 8-bit steps of depth, e.g. 0,0.5,1 (default: the program's)");
  precision->add_option("--map", sc.maps, "Shadow-map sizes (default: the scene's)");
  precision->add_option("--size", sc.size, "Camera image WIDTHxHEIGHT")->capture_default_str();
  precision->add_option("--jobs,-j", sc.jobs, "Runs in parallel (identical results)")->capture_default_str();
  auto* shard = precision->add_option("--shard", sc.shard, "Run slice i of n (i/n); passim merge joins the slices")->capture_default_str();
  precision->add_option("--out,-o", sc.out, "Output directory")->capture_default_str();
  precision->add_flag("--quiet,-q", sc.quiet, "No table, no progress line");
  auto* slurm = precision->add_flag("--slurm", sc.slurm.enabled,
      "Run the sweep as a Slurm array job: write sbatch scripts into --out and submit them (docs/cluster.md)")
      ->excludes(shard);
  precision->add_option("--array-size", sc.slurm.array_size,
      fmt::format("--slurm: shards, one per array task (default: one per point, at most {})", kDefaultMaxShards))
      ->check(CLI::PositiveNumber)
      ->needs(slurm);
  precision->add_option("--partition", sc.slurm.partition, "--slurm: the partition (default: the cluster's)")->needs(slurm);
  precision->add_option("--time", sc.slurm.time, "--slurm: time limit of each job, as sbatch takes it, e.g. 30 or 2:00:00")
      ->needs(slurm);
  precision->add_option("--mem", sc.slurm.mem, "--slurm: memory of each job, as sbatch takes it, e.g. 2G")->needs(slurm);
  precision->add_option("--slurm-extra", sc.slurm.extra,
      "--slurm: more sbatch options for both jobs, e.g. --slurm-extra=\"--account=lab --qos=short\"")->needs(slurm);
  precision->add_flag("--no-submit", sc.slurm.no_submit, "--slurm: write the scripts, submit nothing")->needs(slurm);
  auto* provenance = study->add_subcommand(
      "provenance", "Which stage first loses information: the run, then one stage at a time widened to its widest");
  StudyCommand pvc;
  pvc.size = "800x600";
  pvc.out = "";
  provenance->add_option("--program", pvc.base.program, "The program (passim program --list)")->required();
  provenance->add_option("--filter", pvc.filter, "Its footprint NxN");
  provenance->add_option("--depths", pvc.base.depths, "mdsm: depths per cell")->capture_default_str();
  provenance->add_option("--scene", pvc.base.scene, "paper, fig8, edges or FILE.obj")->capture_default_str();
  provenance->add_option("--size", pvc.size, "Camera image WIDTHxHEIGHT")->capture_default_str();
  provenance->add_option("--bits", pvc.base.color_bits, kBitsHelp);
  provenance->add_option("--texture-bits", pvc.base.texture_bits, "Texture internal formats: 4, 8, 12, 16 (0: as the colour)")
      ->capture_default_str();
  provenance->add_option("--table-bits", pvc.base.table_bits, "Colour table format: 4, 8, 12, 16 (0: as the colour)")
      ->capture_default_str();
  provenance->add_option("--accum-bits", pvc.base.accum_bits, "Accumulation width (0: the default)")->capture_default_str();
  provenance->add_option("--profile", pvc.base.profile, "Machine profile")->capture_default_str();
  provenance->add_flag("--json", pvc.json, "The runs as JSON on stdout, with the statement 'widening X recovers N bits'");
  provenance->add_option("--out,-o", pvc.out, "Also write the JSON document to this file");
  provenance->add_flag("--quiet,-q", pvc.quiet, "No progress line");
  auto* what_if = study->add_subcommand("what-if", "A program as given against the same with settings changed: image and cost");
  StudyCommand wic;
  what_if->add_option("--program", wic.base.program, "The program (passim program --list)")->required();
  what_if->add_option("--what-if", wic.what_if,
                      "KEY=VALUE (bits, depth-bits, texture-bits, table-bits, accum-bits, map, depths, filter, bias; remove=color-tables, remove=convolution, remove=color-matrix); repeatable")
      ->required();
  what_if->add_option("--filter", wic.filter, "Its footprint NxN");
  what_if->add_option("--depths", wic.base.depths, "mdsm: depths per cell")->capture_default_str();
  what_if->add_option("--scene", wic.base.scene, "paper, fig8, edges or FILE.obj")->capture_default_str();
  what_if->add_option("--size", wic.size, "Camera image WIDTHxHEIGHT")->capture_default_str();
  what_if->add_option("--bits", wic.base.color_bits, kBitsHelp);
  what_if->add_option("--texture-bits", wic.base.texture_bits, "Texture formats (0: as the colour)")->capture_default_str();
  what_if->add_option("--profile", wic.base.profile, "Machine profile the program runs on (default: the --cost one)");
  what_if->add_option("--cost", wic.cost_profile, "Machine profile the cost is estimated on")->capture_default_str();
  what_if->add_flag("--quiet,-q", wic.quiet, "No progress line");
  auto* status = study->add_subcommand("status", "Where a --slurm study stands: points and shards done, running, failed, missing");
  std::string status_dir;
  bool status_json = false;
  status->add_option("dir", status_dir, "The study's folder (its --out)")->required();
  status->add_flag("--json", status_json, "As JSON");
  auto* resume = study->add_subcommand("resume", "Submit again a --slurm study's failed and missing shards, and its merge");
  std::string resume_dir;
  resume->add_option("dir", resume_dir, "The study's folder (its --out)")->required();
  auto* merge = app.add_subcommand("merge", "Join sharded study outputs into the files an unsharded run writes");
  std::vector<std::string> merge_dirs;
  std::string merge_out = "study";
  merge->add_option("dirs", merge_dirs, "The slices' output directories")->required();
  merge->add_option("--out,-o", merge_out, "Output directory")->capture_default_str();
  std::string merge_figures = "png,svg,pdf";
  merge->add_option("--figures", merge_figures, "The figures' formats (png, svg, pdf), or none")->capture_default_str();

  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    app.exit(e);
    return kUsage;
  }
  if (*run) {
    if (looks_like_apitrace(trace_file)) {
      if (!rc.expect.empty() || !rc.record.empty() || rc.write_expected) {
        std::cerr << "passim run: --expect, --record and --write-expected are for .pass traces; "
                     "'passim convert' turns a .trace into one\n";
        return kUsage;
      }
      ac.trace = trace_file;
      ac.out = out_dir;
      ac.strict = rc.strict;
      ac.tiff = rc.tiff;
      ac.quiet = rc.quiet;
      ac.max_memory = rc.max_memory;
      ac.reference = rc.reference;
      ac.cross_check = rc.cross_check;
      ac.queries = rc.queries;
      ac.queries_arrays = rc.queries_arrays;
      if (!rc.allow_files.empty()) {
        std::cerr << "passim run: --allow-files is for .pass traces (an apitrace trace reads no side files)\n";
        return kUsage;
      }
      return apitrace_run_command(ac);
    }
    for (const char* o : {"--bits", "--depth-bits", "--stencil-bits", "--accum-bits", "--size", "--profile",
                          "--snapshot", "--snapshot-at"})
      if (run->count(o) > 0) {
        std::cerr << "passim run: " << o << " is for apitrace traces; a .pass trace states its settings in its header\n";
        return kUsage;
      }
    rc.trace = trace_file;
    rc.out = out_dir;
    return run_command(rc);
  }
  if (*convert) return apitrace_convert_command(ac);
  if (*info) return info_command(calls);
  if (*precision) return study_command(sc);
  if (*html) {
    return html_report_command(html_dir, html_out, parse_list(html_cost), html_quiet);
  }
  if (*provenance) {
    default_bits(provenance, pvc.base);
    return provenance_command(pvc);
  }
  if (*what_if) {
    if (what_if->count("--profile") == 0) wic.base.profile = wic.cost_profile;  // timed where it runs
    default_bits(what_if, wic.base);
    return what_if_command(wic);
  }
  if (*merge) return merge_command(merge_dirs, merge_out, merge_figures);
  if (*status) return study_status_command(status_dir, status_json);
  if (*resume) return study_resume_command(resume_dir);
  if (*cost) {
    cc.program_given = cost->count("--program") > 0;
    cc.bits_given = cost->count("--bits") > 0;
    cc.profiles = parse_list(cost_profiles);
    if (cost_csv + cost_json + cost_markdown > 1) {
      std::cerr << "passim report cost: choose one of --csv, --json, --markdown\n";
      return kUsage;
    }
    cc.format = cost_csv ? "csv" : cost_json ? "json" : cost_markdown ? "markdown" : "text";
    if (!cc.paper && cc.trace.empty() == !cc.program_given) {
      std::cerr << "passim report cost: give a trace or --program (not both), or --paper\n";
      return kUsage;
    }
    if (!cost_filter.empty()) {
      try {
        cc.program.filter = parse_filter(cost_filter);
      } catch (const std::invalid_argument& e) {
        std::cerr << "passim: " << e.what() << "\n";
        return kUsage;
      }
    }
    return cost_command(cc);
  }
  if (*program) {
    if (!pc.list && program->count("name") == 0) {
      std::cerr << "passim program: name a program (passim program --list)\n";
      return kUsage;
    }
    default_bits(program, pc.options);
    return program_command(pc);
  }
  if (*demo || app.get_subcommands().empty()) {
    if (app.get_subcommands().empty()) {
      std::cout << app.help() << "\n";
      return kOk;
    }
    return demo_command(demo_out, demo_scene, demo_quiet);
  }
  return kOk;
}

// The one error boundary (docs/hostile-input.md): whatever a command throws ends it with exit 1
// and a message, never an abort.
int main(int argc, char** argv) {
  passim::keep_large_blocks_in_the_heap();
  try {
    return dispatch(argc, argv);
  } catch (const std::bad_alloc&) {
    std::cerr << "passim: out of memory (the machine refused an allocation; --max-memory sets the run's budget)\n";
  } catch (const std::exception& e) {
    std::cerr << "passim: " << e.what() << "\n";
  } catch (...) {
    std::cerr << "passim: internal error: an unknown exception\n";
  }
  return kRunError;
}
