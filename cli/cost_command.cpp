#include "cli/cost_command.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <nlohmann/json.hpp>

#include "reports/cost.hpp"
#include "reports/paper_check.hpp"
#include "trace_io/apitrace_replay.hpp"
#include "trace_io/trace.hpp"

namespace passim {
namespace {

// The per-stage work columns, with the unit each is printed in.
struct Column {
  CostStage stage;
  const char* header;
  double scale;  // work is divided by this for printing
};
const Column kColumns[] = {{CostStage::Geometry, "vertices", 1},      {CostStage::Setup, "triangles", 1},
                           {CostStage::Fill, "fragments", 1},         {CostStage::Texture, "texels", 1},
                           {CostStage::Framebuffer, "fb MB", 1e6},    {CostStage::PixelPath, "pixels", 1},
                           {CostStage::Convolution, "convolved", 1},  {CostStage::Accumulation, "accum px", 1},
                           {CostStage::Clear, "cleared", 1},          {CostStage::TextureLoad, "tex MB", 1e6}};

std::string work_text(double w, double scale) {
  if (w == 0.0) return "-";
  return scale == 1.0 ? fmt::format("{:.0f}", w) : fmt::format("{:.2f}", w / scale);
}

void print_text(const FrameCost& f, const std::string& title) {
  std::cout << fmt::format("{}: {}\n", f.profile, title);
  std::string head = fmt::format("  {:<34} {:<12} {:>9}", "pass", "bound by", "ms");
  for (const Column& c : kColumns) head += fmt::format(" {:>10}", c.header);
  std::cout << head << "\n";
  for (const PassCost& p : f.passes) {
    std::string row = fmt::format("  {:<34} {:<12} {:>9.3f}", p.label.substr(0, 34),
                                  p.idle ? "-" : cost_stage_name(p.bound), 1e3 * p.total);
    for (const Column& c : kColumns) row += fmt::format(" {:>10}", work_text(p.work[static_cast<int>(c.stage)], c.scale));
    std::cout << row << "\n";
  }
  std::cout << fmt::format("  {:<34} {:<12} {:>9.3f}   = {:.2f} frames per second\n\n", "total", "", 1e3 * f.seconds,
                           f.fps());
}

void print_markdown(const FrameCost& f, const std::string& title) {
  std::cout << fmt::format("### {} — {}\n\n| pass | bound by | ms |", f.profile, title);
  for (const Column& c : kColumns) std::cout << " " << c.header << " |";
  std::cout << "\n|---|---|---|";
  for (std::size_t k = 0; k < std::size(kColumns); ++k) std::cout << "---|";
  std::cout << "\n";
  for (const PassCost& p : f.passes) {
    std::cout << fmt::format("| {} | {} | {:.3f} |", p.label, p.idle ? "-" : cost_stage_name(p.bound), 1e3 * p.total);
    for (const Column& c : kColumns) std::cout << " " << work_text(p.work[static_cast<int>(c.stage)], c.scale) << " |";
    std::cout << "\n";
  }
  std::cout << fmt::format("| **total** | | **{:.3f}** | {:.2f} fps |\n\n", 1e3 * f.seconds, f.fps());
}

void print_csv_header() {
  std::cout << "profile,pass,index,bound,seconds,overhead";
  for (int s = 0; s < kCostStages; ++s) {
    const std::string n = cost_stage_name(static_cast<CostStage>(s));
    std::cout << "," << n << " work," << n << " seconds";
  }
  std::cout << "\n";
}

std::string csv_field(const std::string& s) {
  if (s.find_first_of(",\"\n") == std::string::npos) return s;
  std::string q = "\"";
  for (char c : s) q += c == '"' ? std::string("\"\"") : std::string(1, c);
  return q + "\"";
}

void print_csv(const FrameCost& f) {
  for (std::size_t i = 0; i < f.passes.size(); ++i) {
    const PassCost& p = f.passes[i];
    std::cout << fmt::format("{},{},{},{},{:.9g},{:.9g}", csv_field(f.profile), csv_field(p.label), i,
                             p.idle ? "" : cost_stage_name(p.bound), p.total, p.overhead);
    for (int s = 0; s < kCostStages; ++s)
      std::cout << fmt::format(",{:.9g},{:.9g}", p.work[static_cast<std::size_t>(s)], p.seconds[static_cast<std::size_t>(s)]);
    std::cout << "\n";
  }
  std::cout << fmt::format("{},total,,,{:.9g},", csv_field(f.profile), f.seconds);
  for (int s = 0; s < kCostStages; ++s) std::cout << ",,";
  std::cout << "\n";
}

// The paper's six published frame rates against the model's predictions: with the profile's
// rates, and held out (each with the free rates fitted to the other five; docs/cost-model.md).
int paper_comparison(const CostCommand& c) {
  for (const std::string& name : c.profiles) {
    const MachineProfile& profile = timed_profile(name);
    const std::vector<std::vector<Pass>> runs = published_runs(profile);
    const std::vector<PaperPrediction> rows = paper_predictions(profile, runs);
    // The free rates fitted to Figure 7's four, and to all six: how well any rates can do.
    std::vector<bool> figure7(rows.size(), false), all(rows.size(), true);
    for (std::size_t k = 0; k < 4; ++k) figure7[k] = true;
    const RateFit fit7 = fit_published(profile, runs, figure7), fit6 = fit_published(profile, runs, all);
    auto rates_json = [](const RateFit& f) {
      const CostRates& r = f.rates;
      return nlohmann::json{{"triangles", r.triangles},         {"pixels", r.pixels},
                            {"scale_bias", r.scale_bias},       {"color_table", r.color_table},
                            {"clear", r.clear},                 {"texture_load_bytes", r.texture_load_bytes},
                            {"pass_overhead", r.pass_overhead}, {"margin", f.margin}};
    };
    if (c.format == "json") {
      nlohmann::json j = nlohmann::json::array();
      for (const PaperPrediction& p : rows)
        j.push_back({{"what", p.published.what},
                     {"published_low", p.published.low},
                     {"published_high", p.published.high},
                     {"predicted", p.with_profile},
                     {"miss", range_miss(p.with_profile, p.published.low, p.published.high)},
                     {"held_out", p.held_out},
                     {"held_out_miss", range_miss(p.held_out, p.published.low, p.published.high)}});
      std::cout << nlohmann::json{{"profile", profile.name},
                                  {"fitted_rates", fitted_rate_names()},
                                  {"rows", j},
                                  {"fits", {{"figure7", rates_json(fit7)}, {"all_six", rates_json(fit6)}}}}
                       .dump(2)
                << "\n";
      continue;
    }
    std::cout << fmt::format(
        "{}: predicted against published frames per second (Brabec & Seidel §5, Octane VPro/8), at {} bits\n"
        "  'profile': the profile's rates (fitted to Figure 7); 'held out': the free rates fitted to the other five\n"
        "  published rates only, then this one predicted. Miss: how far outside the published range.\n",
        profile.name, profile.color_bits[0]);
    std::cout << fmt::format("  {:<32} {:>11} {:>9} {:>7} {:>9} {:>7}\n", "", "published", "profile", "miss", "held out",
                             "miss");
    double worst = 0.0;
    for (const PaperPrediction& p : rows) {
      const PublishedFrameRate& r = p.published;
      const double miss = range_miss(p.with_profile, r.low, r.high), held = range_miss(p.held_out, r.low, r.high);
      worst = std::max(worst, std::abs(held));
      std::cout << fmt::format("  {:<32} {:>11} {:>9.2f} {:>+6.0f}% {:>9.2f} {:>+6.0f}%\n", r.what,
                               fmt::format("{:g}–{:g}", r.low, r.high), p.with_profile, 100.0 * miss, p.held_out,
                               100.0 * held);
    }
    std::cout << fmt::format("  held-out predictions miss their published range by {:.0f} % at worst\n", 100.0 * worst);
    auto margin_text = [](double m) {
      return m >= 0.0 ? fmt::format("every prediction inside its range, {:.1f} % from its nearer end", 100.0 * m)
                      : fmt::format("no rates put every prediction inside: the worst misses by {:.0f} %",
                                    100.0 * (std::exp(-m) - 1.0));
    };
    std::cout << fmt::format("  the free rates fitted to Figure 7's four: {}\n", margin_text(fit7.margin));
    std::cout << fmt::format("  the free rates fitted to all six: {}\n\n", margin_text(fit6.margin));
  }
  return 0;
}

}  // namespace

int cost_command(const CostCommand& c) {
  try {
    if (c.paper) return paper_comparison(c);
    std::vector<FrameCost> frames;
    std::vector<std::string> titles;
    if (!c.trace.empty()) {
      ReplayResult replay;
      std::string what = "replayed at its own widths";
      if (looks_like_apitrace(c.trace)) {  // docs/apitrace.md: the visual's widths on the ideal profile
        ApitraceReplay a = replay_apitrace(c.trace, ApitraceOptions{});
        if (a.error) throw std::runtime_error(*a.error);
        replay = std::move(a.result);
        what = fmt::format("apitrace, {} calls, {} frames, all counted", a.calls, a.frames);
      } else {
        replay = replay_trace(c.trace);
      }
      for (const std::string& name : c.profiles) {
        frames.push_back(frame_cost(replay.context->passes(), timed_profile(name)));
        titles.push_back(fmt::format("trace {} ({})", c.trace, what));
      }
    } else {
      for (const std::string& name : c.profiles) {
        const MachineProfile& profile = timed_profile(name);
        ProgramOptions o = c.program;
        o.profile = profile.name;
        if (!c.bits_given) o.color_bits = profile.color_bits[0];
        ProgramSession session(o);
        session.frame();
        const ProgramRun& run = session.run();
        frames.push_back(frame_cost(run.result.context->passes(), profile));
        titles.push_back(fmt::format("{} on {} ({} triangles), {}-bit colour, {}² map", o.program, run.scene.name,
                                     run.triangles, o.color_bits, run.map_size));
      }
    }
    if (c.format == "json") {
      nlohmann::json j = nlohmann::json::array();
      for (const FrameCost& f : frames) j.push_back(cost_json(f));
      for (std::size_t k = 0; k < frames.size(); ++k) j[k]["what"] = titles[k];
      std::cout << j.dump(2) << "\n";
    } else if (c.format == "csv") {
      print_csv_header();
      for (const FrameCost& f : frames) print_csv(f);
    } else {
      for (std::size_t k = 0; k < frames.size(); ++k)
        c.format == "markdown" ? print_markdown(frames[k], titles[k]) : print_text(frames[k], titles[k]);
    }
  } catch (const TraceError& e) {
    std::cerr << "passim: " << e.what() << "\n";
    return 1;
  } catch (const std::exception& e) {
    std::cerr << "passim: " << e.what() << "\n";
    return 1;
  }
  return 0;
}

}  // namespace passim
