#include "cli/study_command.hpp"

#include <fmt/format.h>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <stdexcept>

#include "reports/image_io.hpp"
#include "cli/args.hpp"
#include "reports/cost.hpp"
#include "programs/plot.hpp"

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

// The plots (docs/studies.md): metrics against the colour width, one series per other
// setting; self-shadowing against the bias, one series per width.
void write_plots(const fs::path& out, const nlohmann::json& sweep, const std::vector<StudyRow>& rows) {
  const std::string what = fmt::format("{} {}x{} on {}", sweep.at("program").get<std::string>(),
                                       sweep.at("filter").get<int>(), sweep.at("filter").get<int>(),
                                       sweep.at("scene").get<std::string>());
  // A series per combination of the other settings, named by those that vary.
  auto varies = [&](auto&& field) {
    return std::any_of(rows.begin(), rows.end(), [&](const StudyRow& r) { return field(r) != field(rows.front()); });
  };
  const bool depth_varies = varies([](const StudyRow& r) { return static_cast<double>(r.depth_bits); });
  const bool bias_varies = varies([](const StudyRow& r) { return r.bias_steps8; });
  const bool map_varies = varies([](const StudyRow& r) { return static_cast<double>(r.map_size); });
  auto group_name = [&](const StudyRow& r) {
    std::string name;
    if (depth_varies) name += fmt::format("depth {} ", r.depth_bits);
    if (bias_varies) name += fmt::format("bias {:g} ", r.bias_steps8);
    if (map_varies) name += fmt::format("map {} ", r.map_size);
    return name.empty() ? std::string("all") : name.substr(0, name.size() - 1);
  };
  auto by_bits = [&](const std::string& title, const std::string& y_label, bool log_y, auto&& value,
                     const std::string& file) {
    PlotSpec plot{fmt::format("{}: {}", what, title), "colour bits", y_label, log_y, {}};
    for (const StudyRow& r : rows) {
      const std::string name = group_name(r);
      auto it = std::find_if(plot.series.begin(), plot.series.end(), [&](const PlotSeries& p) { return p.name == name; });
      if (it == plot.series.end()) it = plot.series.insert(plot.series.end(), PlotSeries{name, {}, {}});
      it->x.push_back(r.color_bits);
      it->y.push_back(value(r));
    }
    write_plot(out / file, plot);
  };
  by_bits("mean absolute attenuation error", "error", true, [](const StudyRow& r) { return r.mean_abs_error; },
          "error_vs_bits.png");
  by_bits("precision (−log2 relative RMS error)", "bits", false, [](const StudyRow& r) { return r.precision_bits; },
          "precision_vs_bits.png");
  by_bits("shadow levels", "levels", false, [](const StudyRow& r) { return static_cast<double>(r.levels); },
          "levels_vs_bits.png");
  by_bits("misclassified pixels against the reference (lit but shadowed + shadowed but lit)", "pixels", false,
          [](const StudyRow& r) { return static_cast<double>(r.reference.lit_shadowed + r.reference.shadowed_lit); },
          "misclassified_vs_bits.png");
  by_bits("self-shadowed pixels against the reference", "pixels", false,
          [](const StudyRow& r) { return static_cast<double>(r.reference.self_shadowed); },
          "self_shadowing_vs_bits.png");
  std::vector<double> biases;
  for (const StudyRow& r : rows)
    if (std::find(biases.begin(), biases.end(), r.bias_steps8) == biases.end()) biases.push_back(r.bias_steps8);
  if (biases.size() > 1) {
    PlotSpec plot{fmt::format("{}: self-shadowing (exact test) against the bias", what), "bias (8-bit steps of depth)",
                  "self-shadowed pixels", false, {}};
    for (const StudyRow& r : rows) {
      std::string name = fmt::format("{} bits", r.color_bits);
      if (depth_varies) name += fmt::format(", depth {}", r.depth_bits);
      if (map_varies) name += fmt::format(", map {}", r.map_size);
      auto it = std::find_if(plot.series.begin(), plot.series.end(), [&](const PlotSeries& p) { return p.name == name; });
      if (it == plot.series.end()) it = plot.series.insert(plot.series.end(), PlotSeries{name, {}, {}});
      it->x.push_back(r.bias_steps8);
      it->y.push_back(r.exact.self_shadowed);  // acne against the true shadows (docs/studies.md)
    }
    write_plot(out / "self_shadowing_vs_bias.png", plot);
  }
}

void write_outputs(const fs::path& out, const nlohmann::json& sweep, const std::vector<StudyRow>& rows, int shard,
                   int shards) {
  fs::create_directories(out);
  for (const StudyRow& r : rows)
    if (!r.edge.codes.empty()) write_image(r.edge, out);
  write_text_file(out / "study.csv", study_csv(rows));
  write_text_file(out / "study.json", study_json(sweep, rows, shard, shards).dump(1) + "\n");
  if (shards == 1) {  // a slice plots nothing: merge does
    write_plots(out, sweep, rows);
    std::vector<fs::path> edges;
    std::vector<std::string> labels;
    for (const StudyRow& r : rows) {
      edges.push_back(out / fmt::format("edge-{}.png", r.index));
      labels.push_back(fmt::format("{} bits", r.color_bits));
    }
    write_strip(out / "edge_strip.png", edges, labels);
  }
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
  const auto t0 = std::chrono::steady_clock::now();
  auto progress = [&](int done, int total) {
    const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    if (!c.quiet && s > 1.0) std::cerr << fmt::format("\rpassim study: {}/{} runs, {:.0f} s", done, total, s) << std::flush;
  };
  try {
    const std::vector<StudyRow> rows = run_study(sweep, c.jobs, shard, shards, progress);
    if (!c.quiet && std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count() > 1.0) std::cerr << "\n";
    write_outputs(c.out, sweep_description(sweep), rows, shard, shards);
    if (!c.quiet) {
      std::cout << fmt::format("{} on {}: {} of {} points -> {}/study.csv, study.json\n", sweep.base.program,
                               sweep.base.scene, rows.size(), sweep.points().size(), c.out);
      std::cout << "  misclassified pixels against the double-precision reference (lit->sh, sh->lit, self-sh)\n"
                   "  and against the exact shadow test (exact ...):\n";
      std::cout << fmt::format("  {:>4} {:>5} {:>6} {:>7} {:>9} {:>9} {:>8} {:>9} {:>9} {:>9} {:>11} {:>11} {:>11}\n",
                               "bits", "depth", "bias8", "levels", "mean err", "max err", "prec b", "lit->sh",
                               "sh->lit", "self-sh", "exact l->s", "exact self", "step world");
      for (const StudyRow& r : rows)
        std::cout << fmt::format(
            "  {:>4} {:>5} {:>6.3g} {:>7} {:>9.5f} {:>9.5f} {:>8.2f} {:>9} {:>9} {:>9} {:>11} {:>11} {:>11.3g}\n",
            r.color_bits, r.depth_bits, r.bias_steps8, r.levels, r.mean_abs_error, r.max_abs_error, r.precision_bits,
            r.reference.lit_shadowed, r.reference.shadowed_lit, r.reference.self_shadowed, r.exact.lit_shadowed,
            r.exact.self_shadowed,
            r.depth_step_world);
    }
  } catch (const std::exception& e) {
    std::cerr << "\npassim study: " << e.what() << "\n";
    return 1;
  }
  return 0;
}

int provenance_command(const StudyCommand& c) {
  try {
    ProgramOptions o = c.base;
    parse_size(c.size, o.width, o.height);
    if (!c.filter.empty()) o.filter = parse_filter(c.filter);
    const std::vector<ProvenanceRow> rows = precision_provenance(o);
    std::cout << fmt::format("{} on {}: {}-bit colour, texture formats {}, colour table {}, accumulation {}\n",
                             o.program, o.scene, o.color_bits,
                             o.texture_bits ? std::to_string(o.texture_bits) + " bits" : std::string("as the colour"),
                             o.table_bits ? std::to_string(o.table_bits) + " bits" : std::string("as the colour"),
                             o.accum_bits ? std::to_string(o.accum_bits) + " bits" : std::string("default"));
    std::cout << fmt::format("  {:<36} {:>7} {:>11} {:>15}\n", "", "levels", "mean error", "precision bits");
    for (const ProvenanceRow& r : rows)
      std::cout << fmt::format("  {:<36} {:>7} {:>11.6f} {:>15.2f}\n", r.stage, r.levels, r.error.mean_abs,
                               r.error.precision_bits);
    // In pipeline order (the planes take the encoded depth first, then the copy to
    // texture, the counting copy, the accumulation), the first stage whose widening
    // alone gains precision is where information is first lost.
    const double base = rows.front().error.precision_bits;
    const ProvenanceRow* first = nullptr;
    for (std::size_t k = 1; k < rows.size() && !first; ++k)
      if (rows[k].error.precision_bits > base + 0.05) first = &rows[k];
    if (first)
      std::cout << fmt::format("information is first lost where \"{}\" helps: +{:.2f} bits\n", first->stage,
                               first->error.precision_bits - base);
    else
      std::cout << "no single stage loses information on its own: widening any one alone gains nothing\n";
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
    auto measure = [&](const ProgramOptions& o) {
      ProgramSession session(o);
      session.frame();
      const ProgramRun run = session.finish();
      const Counters total = run.result.context->total_counters();
      return Result{count_levels(run.image("attenuation")), attenuation_error(run),
                    frame_cost(run.result.context->passes(), *timed).fps(), total.fragments_generated};
    };
    const Result a = measure(base), b = measure(changed);
    std::string what;
    for (const std::string& w : c.what_if) what += (what.empty() ? "" : ", ") + w;
    std::cout << fmt::format("{} on {}: as given against what if {}\n", base.program, base.scene, what);
    std::cout << fmt::format("  {:<34} {:>12} {:>12} {:>10}\n", "", "as given", "what if", "change");
    std::cout << fmt::format("  {:<34} {:>12} {:>12} {:>+10}\n", "shadow levels", a.levels, b.levels, b.levels - a.levels);
    std::cout << fmt::format("  {:<34} {:>12.2f} {:>12.2f} {:>+10.2f}\n", "precision bits", a.error.precision_bits,
                             b.error.precision_bits, b.error.precision_bits - a.error.precision_bits);
    std::cout << fmt::format("  {:<34} {:>12.6f} {:>12.6f} {:>+10.6f}\n", "mean attenuation error", a.error.mean_abs,
                             b.error.mean_abs, b.error.mean_abs - a.error.mean_abs);
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

int merge_command(const std::vector<std::string>& dirs, const std::string& out) {
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
    // The slices' edge images come along (the strip is made from them).
    fs::create_directories(out);
    for (const std::string& d : dirs)
      for (const StudyRow& r : rows) {
        const fs::path edge = fs::path(d) / fmt::format("edge-{}.png", r.index);
        if (fs::exists(edge)) fs::copy_file(edge, fs::path(out) / edge.filename(), fs::copy_options::overwrite_existing);
      }
    write_outputs(out, sweep, rows, 0, 1);
    std::cout << fmt::format("merged {} slices, {} points -> {}/study.csv, study.json\n", slices.size(), rows.size(), out);
  } catch (const std::exception& e) {
    std::cerr << "passim merge: " << e.what() << "\n";
    return 1;
  }
  return 0;
}

}  // namespace passim
