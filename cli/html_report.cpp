#include "cli/html_report.hpp"

#include <fmt/format.h>
#include <stdlib.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <iterator>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>

#include "cli/figures.hpp"
#include "cli/progress.hpp"
#include "programs/programs.hpp"
#include "reports/cost.hpp"
#include "reports/image_io.hpp"
#include "reports/paper_check.hpp"

namespace fs = std::filesystem;

namespace passim {
namespace {

std::string escape(const std::string& s) {
  std::string out;
  for (char c : s) {
    switch (c) {
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '&': out += "&amp;"; break;
      case '"': out += "&quot;"; break;
      default: out += c;
    }
  }
  return out;
}

std::string read_file(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error(fmt::format("cannot read {}", path.string()));
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

// A temporary folder, removed with its files when this goes out of scope.
struct TempDir {
  fs::path path;
  TempDir() {
    std::string pattern = (fs::temp_directory_path() / "passim-report-XXXXXX").string();
    if (!mkdtemp(pattern.data())) throw std::runtime_error("cannot make a temporary folder for the figures");
    path = pattern;
  }
  ~TempDir() {
    std::error_code ec;
    fs::remove_all(path, ec);
  }
};

// A figure drawn by passim.figures as SVG, inline: its XML prolog dropped, the root marked as a
// chart (or a picture), scaled to the page's width by the style sheet.
std::string inline_svg(const fs::path& file, const char* css_class) {
  std::string svg = read_file(file);
  const std::size_t start = svg.find("<svg");
  if (start == std::string::npos) throw std::runtime_error(fmt::format("{}: not an SVG file", file.string()));
  svg = svg.substr(start);
  svg.replace(0, 4, fmt::format("<svg class=\"{}\"", css_class));
  return svg;
}

// study.json's columns, in the table's order, with their units (docs/studies.md).
struct Column {
  const char* name;
  const char* unit;
};
const Column kColumns[] = {{"color_bits", "bits"},
                           {"depth_bits", "bits"},
                           {"map_size", "texels"},
                           {"bias_8bit_steps", "8-bit steps"},
                           {"levels", "count"},
                           {"mean_abs_error", "fraction"},
                           {"wrong_pixels", "pixels"},
                           {"precision_bits", "bits"},
                           {"lit_but_shadowed", "pixels"},
                           {"shadowed_but_lit", "pixels"},
                           {"self_shadowed", "pixels"},
                           {"exact_lit_but_shadowed", "pixels"},
                           {"exact_shadowed_but_lit", "pixels"},
                           {"exact_self_shadowed", "pixels"},
                           {"surfaces", "pixels"},
                           {"depth_step_world", "world units"}};

// "exact_shadowed_but_lit" may break after each underscore.
std::string breakable(const std::string& name) {
  std::string out;
  for (char c : name) out += c == '_' ? std::string("_<wbr>") : std::string(1, c);
  return out;
}

std::string number(const nlohmann::json& v) {
  if (v.is_number_integer() || v.is_number_unsigned()) return v.dump();
  if (v.is_number_float()) return fmt::format("{:.6g}", v.get<double>());
  return escape(v.dump());
}

// The values a column takes over the rows, in order: "4, 6, 8" or "4–16 (13 widths)".
std::string values_of(const nlohmann::json& rows, const char* column) {
  std::vector<double> values;
  for (const nlohmann::json& r : rows) {
    const double v = r.at(column).get<double>();
    if (std::find(values.begin(), values.end(), v) == values.end()) values.push_back(v);
  }
  std::sort(values.begin(), values.end());
  std::string out;
  for (double v : values) out += fmt::format("{}{:g}", out.empty() ? "" : ", ", v);
  return out;
}

std::string sweep_table(const nlohmann::json& sweep, const nlohmann::json& rows) {
  const int filter = sweep.at("filter").get<int>();
  const bool bias_default = sweep.at("bias_8bit_steps").empty();
  const bool map_default = sweep.at("map_sizes").empty();
  const std::pair<std::string, std::string> entries[] = {
      {"program", sweep.at("program").get<std::string>() +
                      (filter > 1 ? fmt::format(", footprint {}×{}", filter, filter) : std::string())},
      {"scene", fmt::format("{}, camera image {}×{} pixels", sweep.at("scene").get<std::string>(),
                            sweep.at("width").get<int>(), sweep.at("height").get<int>())},
      {"machine profile", sweep.at("profile").get<std::string>()},
      {"colour widths (bits per channel)", values_of(rows, "color_bits")},
      {"depth widths (bits)", values_of(rows, "depth_bits")},
      {"depth bias (8-bit steps of depth)",
       values_of(rows, "bias_8bit_steps") + (bias_default ? " (not swept: the program's default)" : "")},
      {"shadow-map size (texels per side)", values_of(rows, "map_size") + (map_default ? " (the scene's)" : "")},
      {"depths per map cell (mdsm)", std::to_string(sweep.at("depths").get<int>())},
      {"jitter seed (pcf)", std::to_string(sweep.at("seed").get<std::uint32_t>())},
      {"points", fmt::format("{} (every combination of the values above)", rows.size())},
      {"sweep id", sweep.at("id").get<std::string>()}};
  std::string html = "<table class=\"sweep\">";
  for (const auto& [name, value] : entries)
    html += fmt::format("<tr><th>{}</th><td>{}</td></tr>", escape(name), escape(value));
  return html + "</table>";
}

std::string rows_table(const nlohmann::json& rows) {
  std::string html = "<table class=\"rows\"><tr>";
  for (const Column& c : kColumns)
    html += fmt::format("<th>{}<br><span class=\"unit\">{}</span></th>", breakable(c.name), c.unit);
  html += "</tr>";
  for (const nlohmann::json& r : rows) {
    html += "<tr>";
    for (const Column& c : kColumns) html += "<td>" + number(r.at(c.name)) + "</td>";
    html += "</tr>";
  }
  return html + "</table>";
}

// The program of the study on each modelled machine, at that machine's own colour width.
std::string cost_section(const nlohmann::json& sweep, const std::vector<std::string>& profiles) {
  std::string html =
      "<h2 id=\"cost\">Cost on the modelled machines</h2><p>The study's program on each machine at that machine's "
      "own colour width (docs/cost-model.md): each pass's time is its slowest stage plus a fixed overhead.</p>";
  for (const std::string& name : profiles) {
    const MachineProfile& p = timed_profile(name);
    ProgramOptions o;
    o.program = sweep.at("program").get<std::string>();
    o.filter = sweep.at("filter").get<int>();
    o.depths = sweep.at("depths").get<int>();
    o.scene = sweep.at("scene").get<std::string>();
    o.width = sweep.at("width").get<int>();
    o.height = sweep.at("height").get<int>();
    o.profile = p.name;
    o.color_bits = p.color_bits[0];
    try {
      ProgramSession session(o);
      session.frame();
      const FrameCost f = frame_cost(session.run().result.context->passes(), p);
      html += fmt::format("<h3>{} at {} bits: {:.2f} frames per second ({:.2f} ms a frame)</h3>", escape(p.name),
                          o.color_bits, f.fps(), 1e3 * f.seconds);
      html += "<table class=\"cost\"><tr><th>pass</th><th>bound by</th><th>time (ms)</th></tr>";
      for (const PassCost& pc : f.passes)
        html += fmt::format("<tr><td>{}</td><td>{}</td><td>{:.3f}</td></tr>", escape(pc.label),
                            pc.idle ? "-" : cost_stage_name(pc.bound), 1e3 * pc.total);
      html += "</table>";
    } catch (const ProgramError& e) {  // e.g. a width or filter beyond the machine's limits
      html += fmt::format("<h3>{} at {} bits</h3><p>Cannot run there: {}</p>", escape(p.name), o.color_bits,
                          escape(e.what()));
    }
  }
  return html;
}

// The cost model against the paper's six published frame rates, each also predicted held out.
std::string paper_section(const MachineProfile& vpro) {
  const std::vector<PaperPrediction> rows = paper_predictions(vpro, published_runs(vpro));
  std::string html = fmt::format(
      "<h2 id=\"paper\">The cost model against the paper</h2><p>Brabec &amp; Seidel §5 publish six frame rates on "
      "the Octane VPro/8. <em>Profile</em>: {}'s rates, whose free rates were fitted to the four of Figure 7. "
      "<em>Held out</em>: the free rates fitted to the other five published rates only, then this one predicted "
      "(leave-one-out). The two Figure 8 rows with the profile's rates are the held-out check of that fit. Miss: "
      "how far outside the published range.</p><table class=\"paper\"><tr><th>published frame rate</th>"
      "<th>published (fps)</th><th>profile (fps)</th><th>miss</th><th>held out (fps)</th><th>miss</th></tr>",
      escape(vpro.name));
  for (const PaperPrediction& p : rows) {
    const PublishedFrameRate& r = p.published;
    html += fmt::format("<tr><td>{}</td><td>{:g}–{:g}</td><td>{:.2f}</td><td>{:+.0f} %</td><td>{:.2f}</td>"
                        "<td>{:+.0f} %</td></tr>",
                        escape(r.what), r.low, r.high, p.with_profile, 100.0 * range_miss(p.with_profile, r.low, r.high),
                        p.held_out, 100.0 * range_miss(p.held_out, r.low, r.high));
  }
  return html + "</table>";
}

const char* kStyle =
    "body{font-family:sans-serif;margin:1.5em auto;max-width:1150px;padding:0 1em;color:#222;line-height:1.4}"
    "table{border-collapse:collapse;margin:0.8em 0;font-size:13px}"
    "td,th{border:1px solid #ccc;padding:2px 6px;text-align:right;vertical-align:top}th{background:#f4f4f4}"
    "table.sweep th,table.sweep td,table.cost td:first-child,table.paper td:first-child{text-align:left}"
    "table.rows{width:100%;table-layout:fixed;font-size:11px}table.rows th{font-weight:normal;overflow-wrap:anywhere}"
    ".unit{color:#666;font-size:10px}figure{margin:1em 0}figcaption{color:#444;font-size:13px}"
    "svg.chart,svg.picture{max-width:100%;height:auto}p.claim{font-size:17px;font-weight:bold}"
    "p.explanation{max-width:60em}";

}  // namespace

int html_report_command(const std::string& study_dir, const std::string& out_file,
                        const std::vector<std::string>& cost_profiles, bool quiet) {
  try {
    const fs::path dir(study_dir);
    nlohmann::json study;
    try {
      study = nlohmann::json::parse(read_file(dir / "study.json"));
    } catch (const nlohmann::json::exception& e) {
      throw std::runtime_error(fmt::format("{}: not valid JSON: {}", (dir / "study.json").string(), e.what()));
    }
    for (const std::string& name : cost_profiles) timed_profile(name);  // refused before any work
    const nlohmann::json& sweep = study.at("sweep");
    const nlohmann::json& rows = study.at("rows");
    const bool with_paper = std::find(cost_profiles.begin(), cost_profiles.end(), "octane-vpro8") != cost_profiles.end();
    Progress progress("passim report html", 2 + (cost_profiles.empty() ? 0 : 1) + (with_paper ? 1 : 0), quiet, "steps");
    int step = 0;
    progress.step(step, "the figures");
    // The figures: the same code as the study's files (python/passim/figures.py), as SVG.
    const TempDir figures;
    const FigureRun drawn = draw_figures({"study", dir.string(), "--out", figures.path.string(), "--formats", "svg"});
    if (!drawn.ok) throw std::runtime_error("the figures could not be drawn: " + drawn.message);
    progress.step(++step);
    auto figure = [&](const char* name, const std::string& caption, const char* css = "chart") {
      const fs::path file = figures.path / (std::string(name) + ".svg");
      if (!fs::exists(file)) return std::string();
      return fmt::format("<figure id=\"{}\">{}<figcaption>{}</figcaption></figure>", name, inline_svg(file, css),
                         caption);
    };
    const std::string what = fmt::format("{}{} on {}", sweep.at("program").get<std::string>(),
                                         sweep.at("filter").get<int>() > 1
                                             ? fmt::format(" {}×{}", sweep.at("filter").get<int>(), sweep.at("filter").get<int>())
                                             : std::string(),
                                         sweep.at("scene").get<std::string>());
    std::string html = "<!DOCTYPE html><html lang=\"en\"><head><meta charset=\"utf-8\"><meta name=\"viewport\" "
                       "content=\"width=device-width\"><title>passim: " + escape(what) + "</title><style>" + kStyle +
                       "</style></head><body>";
    html += "<h1>passim precision study: " + escape(what) + "</h1>";
    // The headline first: the 8-vs-12-bit claim as this sweep measures it.
    const nlohmann::json headline = study.value("headline", nlohmann::json());
    html += "<h2 id=\"headline\">8 against 12 bits</h2>";
    if (!headline.is_null()) {
      html += "<p class=\"claim\">" + escape(headline.at("statement").get<std::string>()) + "</p>";
      html += "<p class=\"explanation\">" + escape(headline.at("explanation").get<std::string>()) + "</p>";
      html += figure("8_vs_12_bits",
                     "Misclassified pixels (against the program's algorithm in double precision), light leaks "
                     "(shadowed pixels left lit, against the exact shadow test) and self-shadowing (lit surfaces "
                     "facing the light that are shadowed, against the exact test), against the bias, at 8 and 12 "
                     "bits.");
    } else {
      html += "<p>This sweep has no point at 8 bits beside one at 12 with the same other settings, so it cannot "
              "state the 8-against-12-bit claim: sweep <code>--bits 8,12</code> (and <code>--bias</code>) for it.</p>";
    }
    html += "<h2 id=\"sweep\">The sweep</h2>" + sweep_table(sweep, rows);
    html += "<h2 id=\"figures\">Against the colour width</h2>";
    html += figure("error_vs_bits", "Mean absolute attenuation error against the algorithm in double precision.");
    html += figure("precision_vs_bits", "Precision: −log₂ of the relative RMS error (64: no error).");
    html += figure("levels_vs_bits", "Distinct values of the attenuation image, values one code apart as one.");
    html += figure("misclassified_vs_bits", "Pixels lit by the reference and attenuated, or the reverse.");
    html += figure("light_leaks_vs_bits", "Pixels the exact shadow test shadows that the program leaves lit.");
    html += figure("self_shadowing_vs_bits", "Lit surfaces facing the light that the program shadows (acne).");
    html += figure("self_shadowing_vs_bias", "Self-shadowing against the bias, one series per width.");
    html += "<h2 id=\"rows\">Every point</h2>" + rows_table(rows) +
            "<p>docs/studies.md defines every column; the same rows are in study.csv and study.json.</p>";
    html += figure("edge_strip", "One shadow edge per point: Figure 7's inset region, each pixel 4×4.", "picture");
    if (!cost_profiles.empty()) {
      progress.step(step, "the cost of the program on each machine");
      html += cost_section(sweep, cost_profiles);
      progress.step(++step);
    }
    if (with_paper) {
      progress.step(step, "the cost model against the paper's frame rates");
      html += paper_section(timed_profile("octane-vpro8"));
      progress.step(++step);
    }
    progress.step(++step);
    progress.finish();
    html += "<p>docs/cost-model.md describes the cost model, its rates and their sources.</p></body></html>\n";
    const fs::path out = out_file.empty() ? dir / "report.html" : fs::path(out_file);
    write_text_file(out, html);
    std::cout << "wrote " << out.string() << "\n";
  } catch (const std::exception& e) {
    std::cerr << "passim report html: " << e.what() << "\n";
    return 1;
  }
  return 0;
}

}  // namespace passim
