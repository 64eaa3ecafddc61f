#include "cli/study_command.hpp"

#include <fmt/format.h>

#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iostream>
#include <map>
#include <set>
#include <sstream>
#include <stdexcept>

#include "reports/image_io.hpp"
#include "cli/args.hpp"
#include "cli/figures.hpp"
#include "cli/progress.hpp"
#include "cli/process.hpp"
#include "reports/cost.hpp"
#include "trace_io/trace.hpp"

namespace fs = std::filesystem;

namespace passim {
namespace {

// "4-16", "8,12", "4-8,12": integers and inclusive ranges; each within [lo, hi].
std::vector<int> int_list(const std::string& text, const char* what, int lo, int hi) {
  std::vector<int> out;
  std::size_t start = 0;
  while (start <= text.size()) {
    const std::size_t comma = text.find(',', start);
    const std::string item = text.substr(start, comma == std::string::npos ? std::string::npos : comma - start);
    int a = 0, b = 0;
    char tail = 0;
    if (std::sscanf(item.c_str(), "%d-%d%c", &a, &b, &tail) == 2) {
    } else if (std::sscanf(item.c_str(), "%d%c", &a, &tail) == 1) {
      b = a;
    } else {
      throw std::invalid_argument(fmt::format("{} '{}': expected numbers and ranges like 4-16 or 8,12", what, text));
    }
    if (a > b || a < lo || b > hi)
      throw std::invalid_argument(fmt::format("{} '{}': values must lie in {}..{}", what, item, lo, hi));
    for (int v = a; v <= b; ++v) out.push_back(v);
    if (comma == std::string::npos) break;
    start = comma + 1;
  }
  return out;
}

std::vector<double> double_list(const std::string& text, const char* what) {
  std::vector<double> out;
  std::size_t start = 0;
  while (start <= text.size()) {
    const std::size_t comma = text.find(',', start);
    const std::string item = text.substr(start, comma == std::string::npos ? std::string::npos : comma - start);
    char* end = nullptr;
    const double v = std::strtod(item.c_str(), &end);
    if (item.empty() || *end != '\0' || !std::isfinite(v) || v < 0.0)
      throw std::invalid_argument(fmt::format("{} '{}': expected non-negative numbers like 0,0.5,1", what, item));
    out.push_back(v);
    if (comma == std::string::npos) break;
    start = comma + 1;
  }
  return out;
}

// The study's files: the edge images, study.csv, study.json and, for a whole sweep (a slice
// draws nothing: passim merge does), the figures in `figures` formats ("none": none), drawn by
// matplotlib (cli/figures.hpp). Figures that cannot be drawn (no python3 or matplotlib) leave the
// tables in place and say why.
void write_outputs(const fs::path& out, const nlohmann::json& sweep, const std::vector<StudyRow>& rows, int shard,
                   int shards, const std::string& figures, const char* who) {
  fs::create_directories(out);
  for (const StudyRow& r : rows)
    if (!r.edge.codes.empty()) write_image(r.edge, out);
  write_text_file(out / "study.csv", study_csv(rows));
  write_text_file(out / "study.json", study_json(sweep, rows, shard, shards).dump(1) + "\n");
  if (shards == 1 && figures != "none") {
    const FigureRun f = draw_figures({"study", out.string(), "--formats", figures});
    if (!f.ok) std::cerr << fmt::format("{}: the figures were not drawn: {}\n", who, f.message);
  }
}

std::string host_name() {
  char name[256] = {};
  return gethostname(name, sizeof name - 1) == 0 ? std::string(name) : std::string("host");
}

// `out` as an absolute path without a trailing "/" or "." (so that it has a file name).
fs::path normal_dir(const std::string& out) {
  fs::path dir = fs::absolute(out).lexically_normal();
  if (!dir.has_filename() && dir.has_parent_path() && dir != dir.root_path()) dir = dir.parent_path();
  return dir;
}

// Writes a run's files (`write` fills the folder it is given) so that a run killed midway
// leaves no half-written result, above all no study.json, which marks a shard as done
// (docs/cluster.md). A folder that does not exist yet is made whole in a temporary folder
// beside it and renamed into place; into a folder that exists (it may hold other files) the
// files are renamed one by one, study.json last. Every rename stays on one file system.
void write_dir_atomically(const std::string& out_arg, const std::function<void(const fs::path&)>& write) {
  const fs::path out = normal_dir(out_arg);
  const std::string tag = fmt::format("partial-{}-{}", host_name(), getpid());
  const bool fresh = !fs::exists(out);
  // A shard's leftover from a killed task is .<shard>.partial-*: passim study resume removes it.
  const fs::path tmp = fresh ? out.parent_path() / fmt::format(".{}.{}", out.filename().string(), tag)
                             : out / ("." + tag);
  std::error_code ec;
  fs::create_directories(tmp);
  try {
    write(tmp);
  } catch (...) {
    fs::remove_all(tmp, ec);
    throw;
  }
  if (fresh) {
    fs::rename(tmp, out, ec);
    if (!ec) return;
    // `out` appeared meanwhile (the same shard run twice): its files are these same bytes,
    // so they are replaced one by one as below.
  }
  std::vector<fs::path> files;
  for (const fs::directory_entry& e : fs::directory_iterator(tmp)) files.push_back(e.path().filename());
  std::sort(files.begin(), files.end(), [](const fs::path& a, const fs::path& b) {
    return std::make_pair(a == "study.json", a.string()) < std::make_pair(b == "study.json", b.string());
  });
  for (const fs::path& f : files) {
    fs::rename(tmp / f, out / f, ec);
    if (ec) {
      const std::string why = ec.message();
      fs::remove_all(tmp, ec);
      throw std::runtime_error(fmt::format("cannot write {}: {}", (out / f).string(), why));
    }
  }
  fs::remove_all(tmp, ec);
}

int slurm_study_command(const StudyCommand& c, const StudySweep& sweep);

// The rows as a text table: every column of study.csv but the index, the light leaks among
// them (docs/studies.md names each column with its unit).
void print_study_table(const std::vector<StudyRow>& rows) {
  std::cout << "  pixels misclassified against the double-precision reference (ref ...) and against the exact\n"
               "  shadow test (exact ...): lit->sh lit pixels shadowed, sh->lit shadowed pixels left lit (light\n"
               "  leaks), self surfaces facing the light shadowed (acne); wrong px: more than one code off the\n"
               "  reference; step: one depth code in world units\n";
  std::cout << fmt::format("  {:>4} {:>5} {:>6} {:>5} {:>6} {:>9} {:>9} {:>6} {:>9} {:>9} {:>9} {:>9} {:>9} {:>9} {:>9}\n",
                           "bits", "depth", "bias8", "map", "levels", "mean err", "wrong px", "prec", "ref l->s",
                           "ref s->l", "ref self", "exact l->s", "exact s->l", "exact self", "step");
  for (const StudyRow& r : rows)
    std::cout << fmt::format(
        "  {:>4} {:>5} {:>6.3g} {:>5} {:>6} {:>9.5f} {:>9} {:>6.2f} {:>9} {:>9} {:>9} {:>9} {:>9} {:>9} {:>9.3g}\n",
        r.color_bits, r.depth_bits, r.bias_steps8, r.map_size, r.levels, r.mean_abs_error, r.wrong_pixels,
        r.precision_bits, r.reference.lit_shadowed, r.reference.shadowed_lit, r.reference.self_shadowed,
        r.exact.lit_shadowed, r.exact.shadowed_lit, r.exact.self_shadowed, r.depth_step_world);
}

}  // namespace

int study_command(const StudyCommand& c) {
  StudySweep sweep;
  int shard = 0, shards = 1;
  try {
    sweep.base = c.base;
    parse_size(c.size, sweep.base.width, sweep.base.height);
    sweep.color_bits = int_list(c.bits, "--bits", 4, 16);
    if (!c.depth_bits.empty()) sweep.depth_bits = int_list(c.depth_bits, "--depth-bits", 1, 32);
    if (!c.biases.empty()) sweep.biases = double_list(c.biases, "--bias");
    if (!c.maps.empty()) {
      sweep.map_sizes = int_list(c.maps, "--map", 1, 65536);
      for (int m : sweep.map_sizes)
        if ((m & (m - 1)) != 0) throw std::invalid_argument(fmt::format("--map {}: a power of two", m));
    }
    if (!c.filter.empty()) sweep.base.filter = parse_filter(c.filter);
    int i = 0, n = 0;
    char tail = 0;
    if (std::sscanf(c.shard.c_str(), "%d/%d%c", &i, &n, &tail) != 2 || n < 1 || i < 1 || i > n)
      throw std::invalid_argument(fmt::format("--shard {}: expected i/n with 1 <= i <= n, e.g. 2/3", c.shard));
    shard = i - 1, shards = n;
    if (c.jobs < 1 || c.jobs > 256) throw std::invalid_argument(fmt::format("--jobs {}: 1 to 256", c.jobs));
    if (!find_profile(c.base.profile)) throw std::invalid_argument(fmt::format("unknown profile '{}'", c.base.profile));
  } catch (const std::exception& e) {
    std::cerr << "passim study: " << e.what() << "\n";
    return 1;
  }
  if (c.slurm.enabled) return slurm_study_command(c, sweep);
  Progress progress("passim study", static_cast<int>(sweep.points().size() / static_cast<std::size_t>(shards) +
                                                     (static_cast<std::size_t>(shard) < sweep.points().size() %
                                                      static_cast<std::size_t>(shards))),
                     c.quiet, "points");
  try {
    const std::vector<StudyRow> rows =
        run_study(sweep, c.jobs, shard, shards, [&](int done, int) { progress.step(done); });
    progress.finish();
    write_dir_atomically(c.out, [&](const fs::path& dir) {
      write_outputs(dir, sweep_description(sweep), rows, shard, shards, c.figures, "passim study");
    });
    if (!c.quiet) {
      std::cout << fmt::format("{} on {}: {} of {} points -> {}/study.csv, study.json{}\n", sweep.base.program,
                               sweep.base.scene, rows.size(), sweep.points().size(), c.out,
                               shards == 1 && c.figures != "none" ? ", figures" : "");
      print_study_table(rows);
      if (shards == 1) {
        const nlohmann::json h = study_headline(rows);
        if (!h.is_null()) std::cout << "\n" << h.at("statement").get<std::string>() << "\n";
      }
    }
  } catch (const std::exception& e) {
    progress.finish();
    std::cerr << "passim study: " << e.what() << "\n";
    return 1;
  }
  return 0;
}

int provenance_command(const StudyCommand& c) {
  try {
    ProgramOptions o = c.base;
    parse_size(c.size, o.width, o.height);
    if (!c.filter.empty()) o.filter = parse_filter(c.filter);
    Progress progress("passim study provenance", 10, c.quiet || c.json, "runs");
    const std::vector<ProvenanceRow> rows =
        precision_provenance(o, [&](int done, int, const std::string& next) { progress.step(done, next); });
    progress.finish();
    const nlohmann::json doc = provenance_json(o, rows);
    if (!c.out.empty()) write_text_file(c.out, doc.dump(1) + "\n");
    if (c.json) {
      std::cout << doc.dump(1) << "\n";
      return 0;
    }
    std::cout << fmt::format("{} on {}: {}-bit colour, texture formats {}, colour table {}, accumulation {}\n",
                             o.program, o.scene, o.color_bits,
                             o.texture_bits ? std::to_string(o.texture_bits) + " bits" : std::string("as the colour"),
                             o.table_bits ? std::to_string(o.table_bits) + " bits" : std::string("as the colour"),
                             o.accum_bits ? std::to_string(o.accum_bits) + " bits" : std::string("default"));
    std::cout << fmt::format("  {:<36} {:>7} {:>11} {:>9} {:>15} {:>9}\n", "", "levels", "mean error", "wrong px",
                             "precision bits", "recovers");
    for (const nlohmann::json& r : doc.at("rows"))
      std::cout << fmt::format("  {:<36} {:>7} {:>11.6f} {:>9} {:>15.2f} {:>9}\n", r.at("stage").get<std::string>(),
                               r.at("levels").get<int>(), r.at("mean_abs_error").get<double>(),
                               r.at("wrong_pixels").get<int>(), r.at("precision_bits").get<double>(),
                               r.at("stage") == "as given" ? std::string("")
                                                           : fmt::format("{:+.2f}", r.at("recovers_bits").get<double>()));
    std::cout << doc.at("statement").get<std::string>() << "\n";
    if (!c.out.empty()) std::cout << "wrote " << c.out << "\n";
  } catch (const std::exception& e) {
    std::cerr << "passim study provenance: " << e.what() << "\n";
    return 1;
  }
  return 0;
}

namespace {

// Applies one KEY=VALUE change to a program's options.
void apply_change(ProgramOptions& o, const std::string& change) {
  const std::size_t eq = change.find('=');
  if (eq == std::string::npos) throw std::invalid_argument(fmt::format("--what-if {}: expected KEY=VALUE", change));
  const std::string key = change.substr(0, eq), value = change.substr(eq + 1);
  auto number = [&]() {
    char* end = nullptr;
    const double v = std::strtod(value.c_str(), &end);
    if (value.empty() || *end != '\0' || !std::isfinite(v))
      throw std::invalid_argument(fmt::format("--what-if {}: '{}' is not a number", change, value));
    return v;
  };
  if (key == "bits") {
    const double bias8 = std::isnan(o.bias) ? 1.0 : o.bias / std::ldexp(1.0, o.color_bits - 8);
    o.color_bits = static_cast<int>(number());
    if (o.program != "hw-shadow") o.bias = bias8 * std::ldexp(1.0, o.color_bits - 8);  // the same depth
  } else if (key == "depth-bits") {
    o.depth_bits = static_cast<int>(number());
  } else if (key == "texture-bits") {
    o.texture_bits = static_cast<int>(number());
  } else if (key == "table-bits") {
    o.table_bits = static_cast<int>(number());
  } else if (key == "accum-bits") {
    o.accum_bits = static_cast<int>(number());
  } else if (key == "map") {
    o.map_size = static_cast<int>(number());
  } else if (key == "depths") {
    o.depths = static_cast<int>(number());
  } else if (key == "filter") {
    o.filter = parse_filter(value, "--what-if filter=");
  } else if (key == "bias") {  // in 8-bit steps of depth
    o.bias = number() * std::ldexp(1.0, (o.program == "hw-shadow" ? o.depth_bits : o.color_bits) - 8);
  } else if (key == "remove") {  // a stage taken out of the pixel path, whatever the program enables
    if (value == "color-tables") o.remove_color_tables = true;
    else if (value == "convolution") o.remove_convolution = true;
    else if (value == "color-matrix") o.remove_color_matrix = true;
    else
      throw std::invalid_argument(fmt::format(
          "--what-if {}: unknown stage '{}' (color-tables, convolution, color-matrix)", change, value));
  } else {
    throw std::invalid_argument(fmt::format(
        "--what-if {}: unknown setting '{}' (bits, depth-bits, texture-bits, table-bits, accum-bits, map, depths, "
        "filter, bias, remove)", change, key));
  }
}

}  // namespace

int what_if_command(const StudyCommand& c) {
  try {
    ProgramOptions base = c.base;
    parse_size(c.size, base.width, base.height);
    if (!c.filter.empty()) base.filter = parse_filter(c.filter);
    ProgramOptions changed = base;
    for (const std::string& w : c.what_if) apply_change(changed, w);
    const MachineProfile* timed = find_profile(c.cost_profile);
    if (!timed || timed->rates.triangles <= 0.0)
      throw std::invalid_argument(fmt::format("--cost {}: not a profile with cost rates", c.cost_profile));
    struct Result {
      int levels;
      AttenuationError error;
      double fps;
      std::uint64_t fragments;
    };
    Progress progress("passim study what-if", 4, c.quiet, "runs");
    int done = 0;
    auto measure = [&](const ProgramOptions& o, const char* which) {
      progress.step(done++, fmt::format("{}: the program", which));
      ProgramSession session(o);
      session.frame();
      const ProgramRun run = session.finish();
      const Counters total = run.result.context->total_counters();
      progress.step(done++, fmt::format("{}: its double-precision reference", which));
      return Result{count_levels(run.image("attenuation")), attenuation_error(run),
                    frame_cost(run.result.context->passes(), *timed).fps(), total.fragments_generated};
    };
    const Result a = measure(base, "as given"), b = measure(changed, "what if");
    progress.step(done);
    progress.finish();
    std::string what;
    for (const std::string& w : c.what_if) what += (what.empty() ? "" : ", ") + w;
    std::cout << fmt::format("{} on {}: as given against what if {}\n", base.program, base.scene, what);
    std::cout << fmt::format("  {:<34} {:>12} {:>12} {:>10}\n", "", "as given", "what if", "change");
    std::cout << fmt::format("  {:<34} {:>12} {:>12} {:>+10}\n", "shadow levels", a.levels, b.levels, b.levels - a.levels);
    std::cout << fmt::format("  {:<34} {:>12.2f} {:>12.2f} {:>+10.2f}\n", "precision bits", a.error.precision_bits,
                             b.error.precision_bits, b.error.precision_bits - a.error.precision_bits);
    std::cout << fmt::format("  {:<34} {:>12.6f} {:>12.6f} {:>+10.6f}\n", "mean attenuation error", a.error.mean_abs,
                             b.error.mean_abs, b.error.mean_abs - a.error.mean_abs);
    std::cout << fmt::format("  {:<34} {:>12} {:>12} {:>+10}\n", "pixels more than a code off", a.error.wrong_pixels,
                             b.error.wrong_pixels, b.error.wrong_pixels - a.error.wrong_pixels);
    std::cout << fmt::format("  {:<34} {:>12} {:>12} {:>+10}\n", "fragments", a.fragments, b.fragments,
                             static_cast<std::int64_t>(b.fragments) - static_cast<std::int64_t>(a.fragments));
    std::cout << fmt::format("  {:<34} {:>12.2f} {:>12.2f} {:>+9.0f}%\n", fmt::format("fps on {}", timed->name), a.fps,
                             b.fps, 100.0 * (b.fps / a.fps - 1.0));
  } catch (const std::exception& e) {
    std::cerr << "passim study what-if: " << e.what() << "\n";
    return 1;
  }
  return 0;
}

int merge_command(const std::vector<std::string>& dirs, const std::string& out, const std::string& figures) {
  try {
    std::vector<nlohmann::json> slices;
    for (const std::string& d : dirs) {
      const fs::path file = fs::path(d) / "study.json";
      std::ifstream in(file);
      if (!in) throw std::runtime_error(fmt::format("cannot read {}", file.string()));
      try {
        slices.push_back(nlohmann::json::parse(in));
      } catch (const std::exception& e) {
        throw std::runtime_error(fmt::format("{}: not valid JSON: {}", file.string(), e.what()));
      }
    }
    nlohmann::json sweep;
    const std::vector<StudyRow> rows = merge_study(slices, sweep);
    write_dir_atomically(out, [&](const fs::path& dir) {
      // The slices' edge images come along (the strip is made from them).
      for (const std::string& d : dirs)
        for (const StudyRow& r : rows) {
          const fs::path edge = fs::path(d) / fmt::format("edge-{}.png", r.index);
          if (fs::exists(edge)) fs::copy_file(edge, dir / edge.filename(), fs::copy_options::overwrite_existing);
        }
      write_outputs(dir, sweep, rows, 0, 1, figures, "passim merge");
    });
    std::cout << fmt::format("merged {} slices, {} points -> {}/study.csv, study.json\n", slices.size(), rows.size(), out);
  } catch (const std::exception& e) {
    std::cerr << "passim merge: " << e.what() << "\n";
    return 1;
  }
  return 0;
}

// ---- A sweep as a Slurm array job (docs/cluster.md) ----
//
// The study's folder DIR holds
//   slurm/shards.sbatch   an array job: task i runs shard i/N into shards/i
//   slurm/merge.sbatch    passim merge of shards/1 .. shards/N into DIR itself
//   slurm/jobs.json       the sweep, N, the job names and every submission
//   slurm/logs/           shard-<i>.out and merge.out (appended to at every attempt)
// A shard is done when shards/i/study.json is there and belongs to the sweep: a shard's folder
// appears whole or not at all (write_dir_atomically), so a killed task is simply redone.

namespace {

std::string trim(const std::string& s) {
  const std::size_t a = s.find_first_not_of(" \t\r\n"), b = s.find_last_not_of(" \t\r\n");
  return a == std::string::npos ? std::string() : s.substr(a, b - a + 1);
}

// Each line of a command's message, indented, for quoting it in ours.
std::string indented(const std::string& text) {
  std::string out;
  std::stringstream lines(trim(text));
  for (std::string line; std::getline(lines, line);) out += "  " + line + "\n";
  return out.empty() ? std::string("  (no message)\n") : out;
}

// A word for a bash script: as it is when it is plain, else in single quotes.
std::string shell_quote(const std::string& s) {
  if (!s.empty() && s.find_first_not_of("ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789_./:=,+-@%") ==
                        std::string::npos)
    return s;
  std::string q = "'";
  for (char ch : s) q += ch == '\'' ? std::string("'\\''") : std::string(1, ch);
  return q + "'";
}

// Shard numbers as Slurm writes array indices ("1-3,7"), and back (brackets and a "%4"
// throttle, as squeue may show them, are ignored).
std::string shard_ranges(std::vector<int> shards) {
  std::sort(shards.begin(), shards.end());
  std::string out;
  for (std::size_t k = 0; k < shards.size();) {
    std::size_t e = k;
    while (e + 1 < shards.size() && shards[e + 1] == shards[e] + 1) ++e;
    if (!out.empty()) out += ',';
    out += e == k ? std::to_string(shards[k]) : fmt::format("{}-{}", shards[k], shards[e]);
    k = e + 1;
  }
  return out;
}

std::vector<int> parse_ranges(std::string text) {
  text.erase(std::remove_if(text.begin(), text.end(), [](char ch) { return ch == '[' || ch == ']'; }), text.end());
  text = text.substr(0, text.find('%'));
  std::vector<int> out;
  std::stringstream items(text);
  for (std::string item; std::getline(items, item, ',');) {
    int a = 0, b = 0;
    char tail = 0;
    if (std::sscanf(item.c_str(), "%d-%d%c", &a, &b, &tail) == 2) {
      for (int v = a; v <= b; ++v) out.push_back(v);
    } else if (std::sscanf(item.c_str(), "%d%c", &a, &tail) == 1) {
      out.push_back(a);
    }
  }
  return out;
}

// Local time as sacct's --starttime takes it.
std::string now_for_slurm() {
  const std::time_t t = std::time(nullptr);
  std::tm local{};
  localtime_r(&t, &local);
  char text[32] = {};
  std::strftime(text, sizeof text, "%Y-%m-%dT%H:%M:%S", &local);
  return text;
}

// The last line of a log that says something (a killed task's reason is there), shortened.
std::string last_line(const fs::path& file) {
  std::ifstream in(file);
  std::string line, last;
  while (std::getline(in, line))
    if (!trim(line).empty()) last = trim(line);
  return last.size() > 160 ? last.substr(0, 157) + "..." : last;
}

// A Slurm study's folder and its record (slurm/jobs.json).
struct SlurmStudy {
  fs::path dir;
  nlohmann::json record;
  int shards = 0, points = 0;
  std::string sweep_id, name;  // name: the jobs' names start with it (passim-<hash of dir>)

  fs::path slurm_dir() const { return dir / "slurm"; }
  fs::path record_file() const { return slurm_dir() / "jobs.json"; }
  fs::path shards_script() const { return slurm_dir() / "shards.sbatch"; }
  fs::path merge_script() const { return slurm_dir() / "merge.sbatch"; }
  fs::path shard_log(int k) const { return slurm_dir() / "logs" / fmt::format("shard-{}.out", k); }
  fs::path merge_log() const { return slurm_dir() / "logs" / "merge.out"; }
  fs::path shard_dir(int k) const { return dir / "shards" / std::to_string(k); }
  std::string shards_job() const { return name + "-shards"; }
  std::string merge_job() const { return name + "-merge"; }
  void save() const { write_text_file(record_file(), record.dump(1) + "\n"); }
};

std::string job_name_for(const fs::path& dir) {
  const std::string text = dir.string();
  return fmt::format("passim-{}", fnv1a_hex(std::vector<std::uint32_t>(text.begin(), text.end()), 1).substr(0, 8));
}

SlurmStudy load_slurm_study(const std::string& dir_arg) {
  SlurmStudy s;
  s.dir = normal_dir(dir_arg);
  std::ifstream in(s.record_file());
  if (!in)
    throw std::runtime_error(fmt::format("{}: not a Slurm study (no slurm/jobs.json; 'passim study precision ... "
                                         "--slurm --out DIR' makes one)", s.dir.string()));
  try {
    s.record = nlohmann::json::parse(in);
    s.shards = s.record.at("shards").get<int>();
    s.points = s.record.at("sweep").at("points").get<int>();
    s.sweep_id = s.record.at("sweep").at("id").get<std::string>();
    s.name = s.record.at("job_name").get<std::string>();
    if (s.shards < 1 || s.points < s.shards) throw std::runtime_error("shards out of range");
  } catch (const std::exception& e) {
    throw std::runtime_error(fmt::format("{}: not a valid record: {}", s.record_file().string(), e.what()));
  }
  return s;
}

// A study.json that belongs to the sweep, as slice `shard` ("k/N") or as the merged whole
// ("1/1"); its number of rows, or -1.
int result_rows(const fs::path& file, const std::string& sweep_id, const std::string& shard) {
  std::ifstream in(file);
  if (!in) return -1;
  try {
    const nlohmann::json j = nlohmann::json::parse(in);
    if (j.at("sweep").at("id").get<std::string>() != sweep_id || j.at("shard").get<std::string>() != shard) return -1;
    return static_cast<int>(j.at("rows").size());
  } catch (const std::exception&) {
    return -1;
  }
}

enum class ShardKind { done, running, pending, failed, missing };
constexpr const char* kShardKinds[] = {"done", "running", "pending", "failed", "missing"};

struct ShardStatus {
  ShardKind kind = ShardKind::missing;
  std::string detail;  // Slurm's state or the log's last line
};

struct QueuedJob {
  std::string job, state, reason;  // the array's job id for a shard task
};

struct StudyStatus {
  std::vector<ShardStatus> shards;  // shard k at k - 1
  int points_done = 0;
  bool slurm = false;       // squeue answered
  std::string slurm_note;   // why not
  std::vector<QueuedJob> merges;         // merge jobs in the queue
  std::set<std::string> arrays;          // array jobs with shards in the queue
  std::string merge = "not run";         // done, queued, running, failed, not run
  std::string merge_detail;
};

StudyStatus study_status(const SlurmStudy& s) {
  StudyStatus st;
  st.shards.resize(static_cast<std::size_t>(s.shards));
  for (int k = 1; k <= s.shards; ++k) {
    const int rows = result_rows(s.shard_dir(k) / "study.json", s.sweep_id, fmt::format("{}/{}", k, s.shards));
    if (rows >= 0) {
      st.shards[static_cast<std::size_t>(k - 1)].kind = ShardKind::done;
      st.points_done += rows;
    }
  }
  // The queue: squeue -r lists every array task on a line of its own.
  std::map<int, QueuedJob> queued_shards;
  if (find_on_path("squeue").empty()) {
    st.slurm_note = "squeue is not on the PATH";
  } else {
    const ProcessResult q = run_process({"squeue", "--noheader", "--array", "--name",
                                         s.shards_job() + "," + s.merge_job(), "--format", "%F|%K|%t|%r|%j"});
    if (!q.started || q.status != 0) {
      // Its last line says why (squeue's earlier ones are the steps that led there).
      const std::string said = trim(q.err.empty() ? q.out : q.err);
      st.slurm_note = said.substr(said.rfind('\n') == std::string::npos ? 0 : said.rfind('\n') + 1);
      if (st.slurm_note.empty()) st.slurm_note = fmt::format("squeue ended with status {}", q.status);
    } else {
      st.slurm = true;
      std::stringstream lines(q.out);
      for (std::string line; std::getline(lines, line);) {
        std::vector<std::string> f;
        std::stringstream fields(trim(line));
        for (std::string x; std::getline(fields, x, '|');) f.push_back(x);
        if (f.size() != 5) continue;
        const QueuedJob job{f[0], f[2], f[3]};
        if (f[4] == s.merge_job()) {
          st.merges.push_back(job);
        } else if (f[4] == s.shards_job()) {
          st.arrays.insert(f[0]);
          for (int k : parse_ranges(f[1]))
            if (k >= 1 && k <= s.shards) queued_shards[k] = job;
        }
      }
    }
  }
  // Why finished tasks failed, where the cluster keeps accounting (the one-node test's does not).
  std::map<int, std::string> accounted;
  if (st.slurm && !find_on_path("sacct").empty()) {
    std::string since;
    for (const nlohmann::json& sub : s.record.value("submissions", nlohmann::json::array()))
      if (since.empty()) since = sub.value("submitted", "");
    if (!since.empty()) {
      const ProcessResult a = run_process({"sacct", "--noheader", "--parsable2", "--allocations", "--name",
                                           s.shards_job(), "--starttime", since, "--format", "JobID,State"});
      std::stringstream lines(a.status == 0 ? a.out : std::string());
      for (std::string line; std::getline(lines, line);) {  // "123_4|TIMEOUT", later jobs later
        const std::size_t us = line.find('_'), bar = line.find('|');
        if (us == std::string::npos || bar == std::string::npos || bar < us) continue;
        for (int k : parse_ranges(line.substr(us + 1, bar - us - 1))) accounted[k] = trim(line.substr(bar + 1));
      }
    }
  }
  for (int k = 1; k <= s.shards; ++k) {
    ShardStatus& sh = st.shards[static_cast<std::size_t>(k - 1)];
    if (sh.kind == ShardKind::done) continue;
    if (const auto q = queued_shards.find(k); q != queued_shards.end()) {
      sh.kind = q->second.state == "PD" ? ShardKind::pending : ShardKind::running;
      sh.detail = q->second.state == "PD" ? q->second.reason : q->second.state;
    } else if (fs::exists(s.shard_log(k))) {  // it ran and left no result
      sh.kind = ShardKind::failed;
      const auto a = accounted.find(k);
      sh.detail = a != accounted.end() ? a->second + ": " + last_line(s.shard_log(k)) : last_line(s.shard_log(k));
      if (!st.slurm) sh.detail += " (or still running: the queue is not known)";
    }
  }
  if (result_rows(s.dir / "study.json", s.sweep_id, "1/1") == s.points) {
    st.merge = "done";
  } else if (!st.merges.empty()) {
    const QueuedJob& m = st.merges.back();
    st.merge = m.state == "PD" ? "queued" : "running";
    st.merge_detail = fmt::format("job {}{}", m.job, m.state == "PD" ? ", waiting: " + m.reason : "");
  } else if (fs::exists(s.merge_log())) {
    st.merge = "failed";
    st.merge_detail = last_line(s.merge_log());
  }
  return st;
}

std::vector<int> shards_of(const StudyStatus& st, std::initializer_list<ShardKind> kinds) {
  std::vector<int> out;
  for (std::size_t k = 0; k < st.shards.size(); ++k)
    if (std::find(kinds.begin(), kinds.end(), st.shards[k].kind) != kinds.end()) out.push_back(static_cast<int>(k) + 1);
  return out;
}

// sbatch --parsable prints "<id>" or "<id>;<cluster>".
std::string parsed_job_id(const std::string& out) {
  const std::string id = trim(out.substr(0, out.find(';')));
  if (id.empty() || id.find_first_not_of("0123456789") != std::string::npos)
    throw std::runtime_error(fmt::format("sbatch printed '{}' instead of a job id", trim(out)));
  return id;
}

// Submits the shards `to_run` (none: the merge alone) and the merge after them and after
// `still_queued` arrays of earlier submissions; records the submission in slurm/jobs.json.
// A refusal: sbatch's message, where the scripts are, 1.
std::string submit_again(const SlurmStudy& s) {
  return fmt::format(
      "The scripts are in {}/ (shards.sbatch, merge.sbatch): correct them, or the options, and submit with\n"
      "'passim study resume {}', or by hand: sbatch {}, then\n"
      "sbatch --dependency=afterok:<its job id> {}\n",
      s.slurm_dir().string(), s.dir.string(), s.shards_script().string(), s.merge_script().string());
}

// Says so when sbatch is not on the PATH.
bool sbatch_missing(const SlurmStudy& s, const std::string& who) {
  if (!find_on_path("sbatch").empty()) return false;
  std::cerr << fmt::format("{}: sbatch is not on the PATH: submitting needs Slurm's commands (a cluster's login "
                           "node, perhaps after 'module load slurm').\n{}", who, submit_again(s));
  return true;
}

int submit_study(SlurmStudy& s, const std::vector<int>& to_run, const std::set<std::string>& still_queued,
                 const std::string& who) {
  const std::string again = submit_again(s);
  if (sbatch_missing(s, who)) return 1;
  std::string array_job;
  if (!to_run.empty()) {
    std::vector<std::string> cmd{"sbatch", "--parsable"};
    if (static_cast<int>(to_run.size()) != s.shards) cmd.push_back(fmt::format("--array={}", shard_ranges(to_run)));
    cmd.push_back(s.shards_script().string());
    const ProcessResult r = run_process(cmd);
    try {
      if (r.status != 0) throw std::runtime_error("");
      array_job = parsed_job_id(r.out);
    } catch (const std::exception& e) {
      std::cerr << fmt::format("{}: sbatch refused the shards' array job:\n{}{}", who,
                               indented(r.err + (r.status == 0 ? e.what() : "")), again);
      return 1;
    }
  }
  std::vector<std::string> after;
  if (!array_job.empty()) after.push_back("afterok:" + array_job);
  for (const std::string& id : still_queued) after.push_back("afterany:" + id);
  // A merge that can no longer run (a shard failed) leaves the queue instead of waiting there
  // for ever; resume submits another.
  std::vector<std::string> cmd{"sbatch", "--parsable", "--kill-on-invalid-dep=yes"};
  if (!after.empty()) {
    std::string dep = "--dependency=";
    for (const std::string& a : after) dep += (dep.back() == '=' ? "" : ",") + a;
    cmd.push_back(dep);
  }
  cmd.push_back(s.merge_script().string());
  const ProcessResult m = run_process(cmd);
  std::string merge_job;
  std::string merge_error;
  try {
    if (m.status != 0) throw std::runtime_error("");
    merge_job = parsed_job_id(m.out);
  } catch (const std::exception& e) {
    merge_error = indented(m.err + (m.status == 0 ? e.what() : ""));
  }
  nlohmann::json sub{{"shards", shard_ranges(to_run)}, {"array_job", array_job}, {"merge_job", merge_job},
                     {"submitted", now_for_slurm()}};
  s.record["submissions"].push_back(sub);
  s.save();
  if (!merge_error.empty()) {
    std::cerr << fmt::format("{}: {}sbatch refused the merge job:\n{}Submit it by hand once the shards are done: "
                             "sbatch {} (or: passim study resume {})\n",
                             who, array_job.empty() ? "" : fmt::format("shards {} are submitted as array job {}, but ",
                                                                        shard_ranges(to_run), array_job),
                             merge_error, s.merge_script().string(), s.dir.string());
    return 1;
  }
  if (!array_job.empty())
    std::cout << fmt::format("submitted shards {} of {} as array job {}, and the merge as job {} after them\n",
                             shard_ranges(to_run), s.shards, array_job, merge_job);
  else
    std::cout << fmt::format("submitted the merge as job {}\n", merge_job);
  std::cout << fmt::format("  where it stands: passim study status {}\n", s.dir.string());
  return 0;
}

// The study's own options, as the shards' command line repeats them (the defaults spelled out).
std::vector<std::string> study_arguments(const StudyCommand& c) {
  std::vector<std::string> a{"study", "precision", "--program", c.base.program};
  auto add = [&](const char* option, const std::string& value) {
    if (!value.empty()) a.insert(a.end(), {option, value});
  };
  add("--filter", c.filter);
  add("--scene", c.base.scene);
  add("--size", c.size);
  add("--profile", c.base.profile);
  add("--depths", std::to_string(c.base.depths));
  add("--bits", c.bits);
  add("--depth-bits", c.depth_bits);
  add("--bias", c.biases);
  add("--map", c.maps);
  add("--figures", c.figures);
  add("--jobs", std::to_string(c.jobs));
  a.push_back("--quiet");
  return a;
}

// --slurm-extra "--account=lab --qos short": one #SBATCH line per option (with the words
// that follow it). Options passim sets itself, which status and resume rely on, are refused.
std::vector<std::string> extra_lines(const std::string& extra) {
  std::vector<std::string> lines;
  std::stringstream words(extra);
  for (std::string w; words >> w;) {
    if (w[0] == '-') {
      for (const char* own : {"-a", "--array", "-J", "--job-name", "-o", "--output", "-D", "--chdir", "--open-mode"})
        if (w == own || w.rfind(std::string(own) + "=", 0) == 0 || (own[1] != '-' && w.rfind(own, 0) == 0))
          throw std::invalid_argument(fmt::format(
              "--slurm-extra: {} is set by passim (status and resume rely on it); edit the scripts instead", w));
      lines.push_back(w);
    } else if (lines.empty()) {
      throw std::invalid_argument(fmt::format("--slurm-extra '{}': sbatch options, e.g. --account=lab", extra));
    } else {
      lines.back() += " " + w;
    }
  }
  return lines;
}

std::string sbatch_options(const StudyCommand& c, const fs::path& cwd) {
  std::string o = fmt::format("#SBATCH --chdir={}\n", cwd.string());
  if (!c.slurm.partition.empty()) o += fmt::format("#SBATCH --partition={}\n", c.slurm.partition);
  if (!c.slurm.time.empty()) o += fmt::format("#SBATCH --time={}\n", c.slurm.time);
  if (!c.slurm.mem.empty()) o += fmt::format("#SBATCH --mem={}\n", c.slurm.mem);
  for (const std::string& line : extra_lines(c.slurm.extra)) o += "#SBATCH " + line + "\n";
  return o;
}

std::string shards_script(const StudyCommand& c, const SlurmStudy& s, const fs::path& passim, const fs::path& cwd) {
  std::string args;
  for (const std::string& a : study_arguments(c)) args += fmt::format(" {}", shell_quote(a));
  return fmt::format(
      "#!/bin/bash\n"
      "# One shard of a passim precision study per array task (written by passim study precision --slurm;\n"
      "# docs/cluster.md). The task's index is the shard's number: task i runs --shard i/{n} (passim counts\n"
      "# shards from 1) and writes shards/i of the study's folder, whole or not at all.\n"
      "#   submit all:        sbatch {script}\n"
      "#   some shards only:  sbatch --array={n} {script}   (or a list, e.g. 1,3-4)\n"
      "#   then the merge:    sbatch --dependency=afterok:<the array's job id> {merge}\n"
      "#   one shard here:    SLURM_ARRAY_TASK_ID=1 bash {script}\n"
      "#   where it stands:   passim study status {dir}   (passim study resume {dir} redoes what failed)\n"
      "#SBATCH --job-name={job}\n"
      "#SBATCH --array=1-{n}\n"
      "#SBATCH --cpus-per-task={cpus}\n"
      "#SBATCH --output={logs}/shard-%a.out\n"
      "#SBATCH --open-mode=append\n"
      "{options}"
      "set -euo pipefail\n"
      "PASSIM={passim}\n"
      "STUDY={dir}\n"
      "SHARD=${{SLURM_ARRAY_TASK_ID:?run by sbatch --array, or give SLURM_ARRAY_TASK_ID}}\n"
      "echo \"passim shard $SHARD/{n} on $(hostname) at $(date -Is)\"\n"
      "exec \"$PASSIM\"{args} \\\n"
      "    --shard \"$SHARD/{n}\" --out \"$STUDY/shards/$SHARD\"\n",
      fmt::arg("n", s.shards), fmt::arg("script", s.shards_script().string()),
      fmt::arg("merge", s.merge_script().string()), fmt::arg("dir", s.dir.string()), fmt::arg("job", s.shards_job()),
      fmt::arg("cpus", c.jobs), fmt::arg("logs", (s.slurm_dir() / "logs").string()),
      fmt::arg("options", sbatch_options(c, cwd)), fmt::arg("passim", shell_quote(passim.string())),
      fmt::arg("args", args));
}

std::string merge_script(const StudyCommand& c, const SlurmStudy& s, const fs::path& passim, const fs::path& cwd) {
  return fmt::format(
      "#!/bin/bash\n"
      "# Joins the {n} shards of a passim precision study into the files one machine's run writes\n"
      "# (study.csv, study.json, the plots, the edge strip), in the study's folder itself (written by\n"
      "# passim study precision --slurm; docs/cluster.md). Submit it after the shards' array job:\n"
      "#   sbatch --dependency=afterok:<the array's job id> {script}\n"
      "#SBATCH --job-name={job}\n"
      "#SBATCH --cpus-per-task=1\n"
      "#SBATCH --output={logs}/merge.out\n"
      "#SBATCH --open-mode=append\n"
      "{options}"
      "set -euo pipefail\n"
      "PASSIM={passim}\n"
      "STUDY={dir}\n"
      "echo \"passim merge of {n} shards on $(hostname) at $(date -Is)\"\n"
      "slices=()\n"
      "for ((i = 1; i <= {n}; i++)); do slices+=(\"$STUDY/shards/$i\"); done\n"
      "exec \"$PASSIM\" merge \"${{slices[@]}}\" --figures {figures} --out \"$STUDY\"\n",
      fmt::arg("n", s.shards), fmt::arg("script", s.merge_script().string()), fmt::arg("job", s.merge_job()),
      fmt::arg("logs", (s.slurm_dir() / "logs").string()), fmt::arg("options", sbatch_options(c, cwd)),
      fmt::arg("passim", shell_quote(passim.string())), fmt::arg("dir", s.dir.string()),
      fmt::arg("figures", shell_quote(c.figures)));
}

int slurm_study_command(const StudyCommand& c, const StudySweep& sweep) {
  SlurmStudy s;
  try {
    const nlohmann::json description = sweep_description(sweep);
    s.points = description.at("points").get<int>();
    s.shards = c.slurm.array_size != 0 ? c.slurm.array_size : std::min(s.points, kDefaultMaxShards);
    if (s.shards < 1 || s.shards > s.points)
      throw std::invalid_argument(
          fmt::format("--array-size {}: 1 to the sweep's {} points (one shard per task)", s.shards, s.points));
    extra_lines(c.slurm.extra);  // refused, if it is, before anything is written
    s.dir = normal_dir(c.out);
    s.sweep_id = description.at("id").get<std::string>();
    s.name = job_name_for(s.dir);
    const fs::path cwd = fs::current_path(), passim = fs::read_symlink("/proc/self/exe");
    // #SBATCH lines are split at blanks, so these paths cannot have any.
    for (const fs::path& p : {s.dir, cwd, passim})
      if (p.string().find_first_of(" \t\n'\"\\") != std::string::npos)
        throw std::invalid_argument(fmt::format("'{}': the Slurm scripts cannot name a path with blanks or quotes",
                                                p.string()));
    if (fs::exists(s.record_file())) {
      const SlurmStudy old = load_slurm_study(s.dir.string());
      if (!old.record.value("submissions", nlohmann::json::array()).empty())
        throw std::runtime_error(fmt::format(
            "{} holds a Slurm study already submitted: 'passim study status {}' (or resume), or choose another --out",
            s.dir.string(), s.dir.string()));
    }
    fs::create_directories(s.slurm_dir() / "logs");  // Slurm does not make the logs' folder
    s.record = {{"study", s.dir.string()}, {"passim", passim.string()}, {"shards", s.shards},
                {"job_name", s.name},      {"sweep", description},      {"submissions", nlohmann::json::array()}};
    write_text_file(s.shards_script(), shards_script(c, s, passim, cwd));
    write_text_file(s.merge_script(), merge_script(c, s, passim, cwd));
    s.save();
  } catch (const std::exception& e) {
    std::cerr << "passim study: " << e.what() << "\n";
    return 1;
  }
  std::cout << fmt::format("{} point{} in {} shard{}: wrote {} and {}\n", s.points, s.points == 1 ? "" : "s", s.shards,
                           s.shards == 1 ? "" : "s", s.shards_script().string(), s.merge_script().filename().string());
  if (c.slurm.no_submit) {
    std::cout << fmt::format("  submit: passim study resume {}\n  or by hand: sbatch {}, then\n"
                             "  sbatch --dependency=afterok:<its job id> {}\n",
                             s.dir.string(), s.shards_script().string(), s.merge_script().string());
    return 0;
  }
  std::vector<int> all(static_cast<std::size_t>(s.shards));
  for (int k = 0; k < s.shards; ++k) all[static_cast<std::size_t>(k)] = k + 1;
  return submit_study(s, all, {}, "passim study");
}

}  // namespace

int study_status_command(const std::string& dir, bool json) {
  try {
    const SlurmStudy s = load_slurm_study(dir);
    const StudyStatus st = study_status(s);
    std::map<ShardKind, std::vector<int>> by_kind;
    for (std::size_t k = 0; k < st.shards.size(); ++k) by_kind[st.shards[k].kind].push_back(static_cast<int>(k) + 1);
    if (json) {
      nlohmann::json out{{"study", s.dir.string()},       {"points", s.points},     {"points_done", st.points_done},
                         {"shard_count", s.shards},       {"slurm", st.slurm},      {"merge", st.merge},
                         {"merge_detail", st.merge_detail}};
      if (!st.slurm) out["slurm_note"] = st.slurm_note;
      for (int kind = 0; kind < 5; ++kind) {
        nlohmann::json list = nlohmann::json::array();
        for (int k : by_kind[static_cast<ShardKind>(kind)]) {
          const ShardStatus& sh = st.shards[static_cast<std::size_t>(k - 1)];
          list.push_back(sh.detail.empty() ? nlohmann::json(k) : nlohmann::json{{"shard", k}, {"detail", sh.detail}});
        }
        out["shards"][kShardKinds[kind]] = list;
      }
      std::cout << out.dump(1) << "\n";
      return 0;
    }
    const nlohmann::json& sweep = s.record.at("sweep");
    std::cout << fmt::format("{}: {} on {}, {} points in {} shards (Slurm jobs {}-*)\n", s.dir.string(),
                             sweep.at("program").get<std::string>(), sweep.at("scene").get<std::string>(), s.points,
                             s.shards, s.name);
    std::cout << fmt::format("  points done: {} of {}\n", st.points_done, s.points);
    std::string counts;
    for (int kind = 0; kind < 5; ++kind)
      counts += fmt::format("{}{} {}", kind ? ", " : "", by_kind[static_cast<ShardKind>(kind)].size(), kShardKinds[kind]);
    std::cout << "  shards: " << counts << "\n";
    for (ShardKind kind : {ShardKind::running, ShardKind::pending, ShardKind::missing})
      if (!by_kind[kind].empty())
        std::cout << fmt::format("  {}: {}\n", kShardKinds[static_cast<int>(kind)], shard_ranges(by_kind[kind]));
    for (int k : by_kind[ShardKind::failed])
      std::cout << fmt::format("  failed: {} ({}): {}\n", k, fs::relative(s.shard_log(k), s.dir).string(),
                               st.shards[static_cast<std::size_t>(k - 1)].detail);
    std::cout << fmt::format("  merge: {}{}\n", st.merge, st.merge_detail.empty() ? "" : " (" + st.merge_detail + ")");
    if (!st.slurm) std::cout << fmt::format("  Slurm not reachable ({}): shards from their files only\n", st.slurm_note);
    if (st.merge != "done" && st.merges.empty() && by_kind[ShardKind::running].empty() &&
        by_kind[ShardKind::pending].empty())
      std::cout << fmt::format("  to submit what is missing or failed: passim study resume {}\n", s.dir.string());
  } catch (const std::exception& e) {
    std::cerr << "passim study status: " << e.what() << "\n";
    return 1;
  }
  return 0;
}

int study_resume_command(const std::string& dir) {
  SlurmStudy s;
  std::vector<int> to_run;
  StudyStatus st;
  try {
    s = load_slurm_study(dir);
    st = study_status(s);
    if (!st.slurm) {
      if (sbatch_missing(s, "passim study resume")) return 1;
      throw std::runtime_error(fmt::format(
          "Slurm is not reachable ({}): without the queue a running shard cannot be told from a failed one",
          st.slurm_note));
    }
    to_run = shards_of(st, {ShardKind::failed, ShardKind::missing});
    if (to_run.empty() && st.merge == "done") {
      std::cout << fmt::format("nothing to resume: all {} shards are done and merged into {}\n", s.shards,
                               s.dir.string());
      return 0;
    }
    if (to_run.empty() && !st.merges.empty()) {
      std::cout << fmt::format("nothing to resume: no shard failed or is missing, and the merge is {} ({})\n",
                               st.merge, st.merge_detail);
      return 0;
    }
    // Merges still queued wait on the earlier arrays only: the new one replaces them.
    std::vector<std::string> cancel{"scancel"};
    for (const QueuedJob& m : st.merges) cancel.push_back(m.job);
    if (cancel.size() > 1) {
      const ProcessResult r = run_process(cancel);
      if (r.status != 0)
        std::cerr << fmt::format("passim study resume: could not cancel the earlier merge job(s):\n{}", indented(r.err));
    }
    // What killed tasks left half-written (.<shard>.partial-*), now that none of them runs.
    std::error_code ec;
    if (fs::is_directory(s.dir / "shards"))
      for (const fs::directory_entry& e : fs::directory_iterator(s.dir / "shards"))
        for (int k : to_run)
          if (e.path().filename().string().rfind(fmt::format(".{}.partial-", k), 0) == 0) fs::remove_all(e.path(), ec);
  } catch (const std::exception& e) {
    std::cerr << "passim study resume: " << e.what() << "\n";
    return 1;
  }
  const std::vector<int> failed = shards_of(st, {ShardKind::failed}), missing = shards_of(st, {ShardKind::missing});
  if (!failed.empty()) std::cout << fmt::format("failed: shards {}\n", shard_ranges(failed));
  if (!missing.empty()) std::cout << fmt::format("missing: shards {}\n", shard_ranges(missing));
  return submit_study(s, to_run, st.arrays, "passim study resume");
}

}  // namespace passim
