#include "cli/html_report.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <iterator>
#include <limits>
#include <nlohmann/json.hpp>
#include <sstream>

#include "reports/cost.hpp"
#include "reports/image_io.hpp"
#include "programs/programs.hpp"

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

// RFC 4648 base64, for embedding a PNG as a data: URL.
std::string base64(const std::string& bytes) {
  static const char* const table = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  std::size_t i = 0;
  for (; i + 2 < bytes.size(); i += 3) {
    const unsigned v = (static_cast<unsigned char>(bytes[i]) << 16) | (static_cast<unsigned char>(bytes[i + 1]) << 8) |
                       static_cast<unsigned char>(bytes[i + 2]);
    out += {table[(v >> 18) & 63], table[(v >> 12) & 63], table[(v >> 6) & 63], table[v & 63]};
  }
  if (i < bytes.size()) {
    unsigned v = static_cast<unsigned char>(bytes[i]) << 16;
    if (i + 1 < bytes.size()) v |= static_cast<unsigned char>(bytes[i + 1]) << 8;
    out += {table[(v >> 18) & 63], table[(v >> 12) & 63], i + 1 < bytes.size() ? table[(v >> 6) & 63] : '=', '='};
  }
  return out;
}

struct Series {
  std::string name;
  std::vector<std::pair<double, double>> points;
};

// An inline SVG line chart (log y optional).
std::string svg_chart(const std::string& title, const std::string& y_label, const std::vector<Series>& series,
                      bool log_y) {
  const int w = 640, h = 300, left = 70, right = w - 200, top = 30, bottom = h - 40;
  double x0 = std::numeric_limits<double>::infinity(), x1 = -x0, y0 = x0, y1 = -x0;
  auto fy = [&](double y) { return log_y ? std::log10(y) : y; };
  for (const Series& s : series)
    for (auto [x, y] : s.points) {
      if (log_y && !(y > 0)) continue;
      x0 = std::min(x0, x), x1 = std::max(x1, x), y0 = std::min(y0, fy(y)), y1 = std::max(y1, fy(y));
    }
  if (!std::isfinite(x0)) x0 = 0, x1 = 1, y0 = 0, y1 = 1;
  if (x1 == x0) x0 -= 1, x1 += 1;
  if (y1 == y0) y0 -= 1, y1 += 1;
  auto px = [&](double x) { return left + (x - x0) / (x1 - x0) * (right - left); };
  auto py = [&](double y) { return bottom - (fy(y) - y0) / (y1 - y0) * (bottom - top); };
  std::string svg = fmt::format(
      "<svg class=\"chart\" xmlns=\"http://www.w3.org/2000/svg\" width=\"{}\" height=\"{}\" viewBox=\"0 0 {} {}\">"
      "<text x=\"{}\" y=\"18\" class=\"t\">{}</text><line x1=\"{}\" y1=\"{}\" x2=\"{}\" y2=\"{}\" class=\"axis\"/>"
      "<line x1=\"{}\" y1=\"{}\" x2=\"{}\" y2=\"{}\" class=\"axis\"/><text x=\"4\" y=\"{}\" class=\"l\">{}</text>",
      w, h, w, h, left, escape(title), left, bottom, right, bottom, left, top, left, bottom, top - 6, escape(y_label));
  for (const Series& s : series)
    for (auto [x, y] : s.points) {
      (void)y;
      svg += fmt::format("<text x=\"{:.1f}\" y=\"{}\" class=\"l\" text-anchor=\"middle\">{:g}</text>", px(x), bottom + 16, x);
    }
  svg += fmt::format("<text x=\"4\" y=\"{:.1f}\" class=\"l\">{:.3g}</text><text x=\"4\" y=\"{:.1f}\" class=\"l\">{:.3g}</text>",
                     py(log_y ? std::pow(10.0, y1) : y1) + 4, log_y ? std::pow(10.0, y1) : y1,
                     py(log_y ? std::pow(10.0, y0) : y0), log_y ? std::pow(10.0, y0) : y0);
  const char* colours[] = {"#0072b2", "#d55e00", "#009e73", "#cc79a7", "#e69f00", "#56b4e9", "#000000"};
  for (std::size_t k = 0; k < series.size(); ++k) {
    std::string pts;
    for (auto [x, y] : series[k].points)
      if (!log_y || y > 0) pts += fmt::format("{:.1f},{:.1f} ", px(x), py(y));
    const char* c = colours[k % std::size(colours)];
    svg += fmt::format("<polyline points=\"{}\" fill=\"none\" stroke=\"{}\" stroke-width=\"2\"/>", pts, c);
    svg += fmt::format("<rect x=\"{}\" y=\"{}\" width=\"10\" height=\"10\" fill=\"{}\"/><text x=\"{}\" y=\"{}\" class=\"l\">{}</text>",
                       right + 12, top + 16 * static_cast<int>(k), c, right + 26, top + 9 + 16 * static_cast<int>(k),
                       escape(series[k].name));
  }
  return svg + "</svg>";
}

}  // namespace

int html_report_command(const std::string& study_dir, const std::string& out_file,
                        const std::vector<std::string>& cost_profiles) {
  try {
    const fs::path dir(study_dir);
    std::ifstream in(dir / "study.json");
    if (!in) throw std::runtime_error(fmt::format("cannot read {}", (dir / "study.json").string()));
    nlohmann::json study;
    try {
      study = nlohmann::json::parse(in);
    } catch (const std::exception& e) {
      throw std::runtime_error(fmt::format("{}: not valid JSON: {}", (dir / "study.json").string(), e.what()));
    }
    const nlohmann::json& sweep = study.at("sweep");
    const nlohmann::json& rows = study.at("rows");
    const std::string what = fmt::format("{} {}x{} on {}", sweep.at("program").get<std::string>(),
                                         sweep.at("filter").get<int>(), sweep.at("filter").get<int>(),
                                         sweep.at("scene").get<std::string>());
    std::string html = "<!DOCTYPE html><html lang=\"en\"><head><meta charset=\"utf-8\"><title>passim: " + escape(what) +
                       "</title><style>body{font-family:sans-serif;margin:2em;color:#222}table{border-collapse:collapse;"
                       "margin:1em 0}td,th{border:1px solid #ccc;padding:2px 8px;text-align:right}th{background:#f4f4f4}"
                       ".chart{margin:0.5em 1em 0.5em 0}.axis{stroke:#333}.t{font-size:14px}.l{font-size:11px}"
                       "img{max-width:100%}</style></head><body>";
    html += "<h1>passim precision study: " + escape(what) + "</h1>";
    html += "<p>Sweep <code>" + escape(sweep.at("id").get<std::string>()) + "</code>: " + escape(sweep.dump()) + "</p>";
    // Charts: one series per combination of the non-bits settings.
    auto chart = [&](const std::string& title, const std::string& y_label, bool log_y, auto&& value) {
      std::vector<Series> series;
      for (const nlohmann::json& r : rows) {
        const std::string name = fmt::format("depth {}, bias {:g}, map {}", r.at("depth_bits").get<int>(),
                                             r.at("bias_8bit_steps").get<double>(), r.at("map_size").get<int>());
        auto it = std::find_if(series.begin(), series.end(), [&](const Series& s) { return s.name == name; });
        if (it == series.end()) it = series.insert(series.end(), Series{name, {}});
        it->points.emplace_back(r.at("color_bits").get<double>(), value(r));
      }
      return svg_chart(title, y_label, series, log_y);
    };
    html += "<h2>Against the colour width</h2><div>";
    html += chart("mean absolute attenuation error", "error", true,
                  [](const nlohmann::json& r) { return r.at("mean_abs_error").get<double>(); });
    html += chart("precision (bits)", "bits", false, [](const nlohmann::json& r) { return r.at("precision_bits").get<double>(); });
    html += chart("shadow levels", "levels", false, [](const nlohmann::json& r) { return r.at("levels").get<double>(); });
    html += chart("misclassified pixels (against the reference)", "pixels", false, [](const nlohmann::json& r) {
      return r.at("lit_but_shadowed").get<double>() + r.at("shadowed_but_lit").get<double>();
    });
    html += chart("self-shadowed pixels (against the reference)", "pixels", false,
                  [](const nlohmann::json& r) { return r.at("self_shadowed").get<double>(); });
    html += "</div><h2>Table</h2><table><tr>";
    const char* columns[] = {"color_bits", "depth_bits", "map_size", "bias_8bit_steps", "levels", "mean_abs_error",
                             "max_abs_error", "precision_bits", "lit_but_shadowed", "shadowed_but_lit", "self_shadowed",
                             "exact_lit_but_shadowed", "exact_self_shadowed", "depth_step_world"};
    for (const char* c : columns) html += std::string("<th>") + c + "</th>";
    html += "</tr>";
    for (const nlohmann::json& r : rows) {
      html += "<tr>";
      for (const char* c : columns) {
        const nlohmann::json& v = r.at(c);
        html += "<td>" + (v.is_number_float() ? fmt::format("{:.6g}", v.get<double>()) : v.dump()) + "</td>";
      }
      html += "</tr>";
    }
    html += "</table>";
    const fs::path strip = dir / "edge_strip.png";
    if (fs::exists(strip)) {
      std::ifstream png(strip, std::ios::binary);
      const std::string bytes((std::istreambuf_iterator<char>(png)), std::istreambuf_iterator<char>());
      html += "<h2>One shadow edge per width (magnified 4×)</h2><img alt=\"edge strip\" src=\"data:image/png;base64," +
              base64(bytes) + "\">";
    }
    // The cost of the program at the sweep's first width on each timed profile.
    if (!cost_profiles.empty()) {
      ProgramOptions o;
      o.program = sweep.at("program").get<std::string>();
      o.filter = sweep.at("filter").get<int>();
      o.depths = sweep.at("depths").get<int>();
      o.scene = sweep.at("scene").get<std::string>();
      o.width = sweep.at("width").get<int>();
      o.height = sweep.at("height").get<int>();
      o.color_bits = sweep.at("color_bits").at(0).get<int>();
      ProgramSession session(o);
      session.frame();
      const ProgramRun& run = session.run();
      html += fmt::format("<h2>Cost at {} bits</h2>", o.color_bits);
      for (const std::string& name : cost_profiles) {
        const MachineProfile* p = find_profile(name);
        if (!p || p->rates.triangles <= 0.0) throw std::runtime_error(fmt::format("profile '{}' has no cost rates", name));
        const FrameCost f = frame_cost(run.result.context->passes(), *p);
        html += fmt::format("<h3>{}: {:.2f} frames per second</h3><table><tr><th>pass</th><th>bound by</th><th>ms</th></tr>",
                            escape(p->name), f.fps());
        for (const PassCost& pc : f.passes)
          html += fmt::format("<tr><td>{}</td><td>{}</td><td>{:.3f}</td></tr>", escape(pc.label),
                              pc.idle ? "-" : cost_stage_name(pc.bound), 1e3 * pc.total);
        html += "</table>";
      }
    }
    html += "<p>docs/studies.md defines every column; docs/cost-model.md the cost model.</p></body></html>\n";
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
