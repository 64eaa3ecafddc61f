#include "cli/cost_command.hpp"

#include <fmt/format.h>

#include <iostream>
#include <nlohmann/json.hpp>

#include "reports/cost.hpp"
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

nlohmann::json to_json(const FrameCost& f) {
  nlohmann::json passes = nlohmann::json::array();
  for (const PassCost& p : f.passes) {
    nlohmann::json stages;
    for (int s = 0; s < kCostStages; ++s)
      stages[cost_stage_name(static_cast<CostStage>(s))] = {{"work", p.work[static_cast<std::size_t>(s)]},
                                                            {"seconds", p.seconds[static_cast<std::size_t>(s)]}};
    passes.push_back({{"label", p.label},
                      {"bound", p.idle ? "" : cost_stage_name(p.bound)},
                      {"seconds", p.total},
                      {"overhead", p.overhead},
                      {"stages", stages}});
  }
  return {{"profile", f.profile}, {"passes", passes}, {"seconds", f.seconds}, {"fps", f.fps()}};
}

const MachineProfile& timed_profile(const std::string& name) {
  const MachineProfile* p = find_profile(name);
  if (!p) throw ProgramError(fmt::format("unknown machine profile '{}' (passim info lists them)", name));
  if (p->rates.triangles <= 0.0)
    throw ProgramError(fmt::format("profile '{}' has no cost rates (octane-vpro8, o2, infinite-reality have)", name));
  return *p;
}

// The paper's six published frame rates against the model's prediction.
int paper_comparison(const CostCommand& c) {
  struct Published {
    const char* what;
    const char* program;
    int filter;
    const char* scene;
    double lo, hi;
    bool fitted;
  };
  const Published rows[] = {{"Fig. 7 shadow map", "shadow-map", 0, "paper", 25, 30, true},
                            {"Fig. 7 PCF 2x2", "pcf", 2, "paper", 9, 11, true},
                            {"Fig. 7 fast PCF 2x2", "fast-pcf", 2, "paper", 15, 20, true},
                            {"Fig. 7 fast PCF 4x4", "fast-pcf", 4, "paper", 4.5, 5.5, true},
                            {"Fig. 8 shadow map (1024²)", "shadow-map", 0, "fig8", 15, 15, false},
                            {"Fig. 8 fast PCF 2x2 (1024²)", "fast-pcf", 2, "fig8", 10, 10, false}};
  for (const std::string& name : c.profiles) {
    const MachineProfile& profile = timed_profile(name);
    std::cout << fmt::format("{}: predicted against published frames per second (Brabec & Seidel, Octane VPro/8)\n",
                             profile.name);
    std::cout << fmt::format("  {:<28} {:>10} {:>12} {:>8}  {}\n", "", "predicted", "published", "miss", "");
    for (const Published& r : rows) {
      ProgramOptions o;
      o.program = r.program;
      o.filter = r.filter;
      o.scene = r.scene;
      o.profile = profile.name;
      o.color_bits = profile.color_bits[0];
      ProgramSession session(o);
      session.frame();
      const FrameCost f = frame_cost(session.run().result.context->passes(), profile);
      const double fps = f.fps();
      const double miss = fps < r.lo ? fps / r.lo - 1.0 : fps > r.hi ? fps / r.hi - 1.0 : 0.0;
      const std::string published = r.lo == r.hi ? fmt::format("≈ {:.0f}", r.lo) : fmt::format("{:g}–{:g}", r.lo, r.hi);
      std::cout << fmt::format("  {:<28} {:>10.2f} {:>12} {:>+7.0f}%  {}\n", r.what, fps, published, 100.0 * miss,
                               r.fitted ? "(fitted)" : "(not fitted: a check)");
    }
    std::cout << "\n";
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
      for (const FrameCost& f : frames) j.push_back(to_json(f));
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
