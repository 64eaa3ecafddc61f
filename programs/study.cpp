#include "programs/study.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>
#include <mutex>
#include <stdexcept>
#include <thread>
#include <tuple>

#include "pipeline/fixed_point.hpp"
#include "programs/reference.hpp"

namespace passim {

std::vector<ProgramOptions> StudySweep::points() const {
  std::vector<ProgramOptions> out;
  const std::vector<int> maps = map_sizes.empty() ? std::vector<int>{0} : map_sizes;
  const std::vector<double> bs = biases.empty() ? std::vector<double>{std::numeric_limits<double>::quiet_NaN()} : biases;
  const std::vector<int> depths = depth_bits.empty() ? std::vector<int>{base.depth_bits} : depth_bits;
  for (int map : maps)
    for (double bias8 : bs)
      for (int depth : depths)
        for (int bits : color_bits) {
          ProgramOptions o = base;
          o.map_size = map;
          o.depth_bits = depth;
          o.color_bits = bits;
          // The bias is a depth, in 8-bit steps of the encoding's range, the same at every
          // width: 2^(bits − 8) steps of the width (hw-shadow: of its depth plane).
          if (!std::isnan(bias8))
            o.bias = bias8 * std::ldexp(1.0, (o.program == "hw-shadow" ? depth : bits) - 8);
          out.push_back(o);
        }
  return out;
}

namespace {

std::string fnv_text(const std::string& s) {
  std::vector<std::uint32_t> codes(s.begin(), s.end());
  return fnv1a_hex(codes, 1);
}

nlohmann::json sweep_json(const StudySweep& s) {
  const ProgramOptions& b = s.base;
  nlohmann::json biases = nlohmann::json::array();
  for (double v : s.biases) biases.push_back(std::isnan(v) ? nlohmann::json("default") : nlohmann::json(v));
  return {{"program", b.program}, {"scene", b.scene},         {"profile", b.profile},     {"filter", b.filter},
          {"depths", b.depths},   {"width", b.width},         {"height", b.height},       {"seed", b.seed},
          {"color_bits", s.color_bits}, {"depth_bits", s.depth_bits.empty() ? std::vector<int>{b.depth_bits} : s.depth_bits},
          {"bias_8bit_steps", biases},  {"map_sizes", s.map_sizes}};
}

}  // namespace

std::string StudySweep::id() const { return fnv_text(sweep_json(*this).dump()); }

AttenuationError attenuation_error(const ProgramRun& run) { return attenuation_error(run, exact_attenuation(run)); }

AttenuationError attenuation_error(const ProgramRun& run, const std::vector<double>& exact) {
  // Errors against the algorithm without quantisation, over the pixels that see a surface.
  const CapturedImage& att = run.image("attenuation");
  const double max_code = static_cast<double>((std::uint64_t{1} << att.bits[0]) - 1);
  AttenuationError r;
  double sum_abs = 0.0, sum_sq = 0.0, sum_ref = 0.0;
  std::size_t n = 0;
  for (std::size_t k = 0; k < exact.size(); ++k) {
    if (exact[k] < 0.0) continue;
    const double e = std::abs(static_cast<double>(att.codes[k]) / max_code - exact[k]);
    sum_abs += e, sum_sq += e * e, sum_ref += exact[k] * exact[k];
    if (e > 1.0 / max_code) ++r.wrong_pixels;
    ++n;
  }
  if (n > 0) {
    r.mean_abs = sum_abs / static_cast<double>(n);
    // −log2 of the relative RMS error; 64 stands for "no error at all".
    r.precision_bits = sum_sq > 0.0 && sum_ref > 0.0 ? -0.5 * std::log2(sum_sq / sum_ref) : 64.0;
  }
  return r;
}

StudyRow run_study_point(const ProgramOptions& point, int index) {
  ProgramSession session(point);
  session.frame();
  const ProgramRun run = session.finish();
  const ProgramOptions& o = run.options;
  StudyRow row;
  row.index = index;
  row.color_bits = o.color_bits;
  row.depth_bits = o.depth_bits;
  row.map_size = run.map_size;
  const bool hw = o.program == "hw-shadow";
  row.bias_steps8 = o.bias / std::ldexp(1.0, (hw ? o.depth_bits : o.color_bits) - 8);
  const CapturedImage& att = run.image("attenuation");
  row.levels = count_levels(att);
  const std::vector<double> reference = exact_attenuation(run);
  const AttenuationError err = attenuation_error(run, reference);
  row.mean_abs_error = err.mean_abs;
  row.wrong_pixels = err.wrong_pixels;
  row.precision_bits = err.precision_bits;
  // The edge strip's cell: the final image's region of Figure 7's inset (scaled to the
  // image size), each pixel 4x4, at 8 bits.
  {
    const CapturedImage& fin = run.image("final");
    const int w = std::max(1, fin.width / 8), h = std::max(1, fin.height / 8), mag = 4;
    const int x0 = fin.width * 250 / 800, y0 = fin.height * 210 / 600;
    CapturedImage& e = row.edge;
    e.name = fmt::format("edge-{}", index);
    e.plane = "rgb";
    e.width = w * mag;
    e.height = h * mag;
    e.channels = 3;
    e.bits = {8, 8, 8, 0};
    e.codes.resize(static_cast<std::size_t>(e.width) * static_cast<std::size_t>(e.height) * 3);
    for (int y = 0; y < e.height; ++y)
      for (int x = 0; x < e.width; ++x)
        for (int k = 0; k < 3; ++k) {
          const std::size_t src = (static_cast<std::size_t>(y0 + y / mag) * static_cast<std::size_t>(fin.width) +
                                   static_cast<std::size_t>(x0 + x / mag)) * 3 + static_cast<std::size_t>(k);
          e.codes[(static_cast<std::size_t>(y) * static_cast<std::size_t>(e.width) + static_cast<std::size_t>(x)) * 3 +
                  static_cast<std::size_t>(k)] = rescale_code(fin.codes[src], fin.bits[static_cast<std::size_t>(k)], 8);
        }
    e.hash = fnv1a_hex(e.codes, 1);
  }
  const Classification c = classify(run, &reference);
  row.reference = c.reference;
  row.exact = c.exact;
  row.surfaces = c.surfaces;
  const View& light = run.scene.light;
  if (hw) {
    // A window-depth step at the receivers' distance d: dz = d²(f − n)/(f·n) / 2^bits.
    const double d = glm::length(light.center - light.eye), f = light.far_plane, nn = light.near_plane;
    row.depth_step_world = d * d * (f - nn) / (f * nn) / std::ldexp(1.0, o.depth_bits);
  } else {
    row.depth_step_world = (light.far_plane - light.near_plane) / std::ldexp(1.0, o.color_bits);
  }
  return row;
}

std::vector<StudyRow> run_study(const StudySweep& sweep, int jobs, int shard_index, int shard_count,
                                const std::function<void(int, int)>& progress) {
  const std::vector<ProgramOptions> points = sweep.points();
  std::vector<int> mine;
  for (int i = 0; i < static_cast<int>(points.size()); ++i)
    if (i % shard_count == shard_index) mine.push_back(i);
  std::vector<StudyRow> rows(mine.size());
  std::atomic<std::size_t> next{0};
  std::atomic<int> done{0};
  std::mutex report;
  std::exception_ptr failure;
  auto work = [&] {
    for (std::size_t k; (k = next.fetch_add(1)) < mine.size();) {
      try {
        rows[k] = run_study_point(points[static_cast<std::size_t>(mine[k])], mine[k]);
      } catch (...) {
        std::lock_guard<std::mutex> lock(report);
        if (!failure) failure = std::current_exception();
        next = mine.size();
        return;
      }
      const int d = ++done;
      std::lock_guard<std::mutex> lock(report);
      if (progress) progress(d, static_cast<int>(mine.size()));
    }
  };
  std::vector<std::thread> threads;
  for (int t = 1; t < std::max(1, jobs); ++t) threads.emplace_back(work);
  work();
  for (std::thread& t : threads) t.join();
  if (failure) std::rethrow_exception(failure);
  return rows;
}

namespace {

// 12345 -> "12,345".
std::string grouped(long v) {
  std::string digits = std::to_string(v < 0 ? -v : v), out;
  for (std::size_t k = 0; k < digits.size(); ++k) {
    if (k > 0 && (digits.size() - k) % 3 == 0) out += ',';
    out += digits[k];
  }
  return (v < 0 ? "-" : "") + out;
}

}  // namespace

nlohmann::json study_headline(const std::vector<StudyRow>& rows) {
  struct Pair {
    const StudyRow* at8 = nullptr;
    const StudyRow* at12 = nullptr;
  };
  // The points at 8 and 12 bits with the same other settings, in sweep order.
  std::vector<std::pair<std::tuple<int, int, double>, Pair>> pairs;
  for (const StudyRow& r : rows) {
    if (r.color_bits != 8 && r.color_bits != 12) continue;
    const auto key = std::make_tuple(r.depth_bits, r.map_size, r.bias_steps8);
    auto it = std::find_if(pairs.begin(), pairs.end(), [&](const auto& p) { return p.first == key; });
    if (it == pairs.end()) it = pairs.insert(pairs.end(), {key, Pair{}});
    (r.color_bits == 8 ? it->second.at8 : it->second.at12) = &r;
  }
  std::erase_if(pairs, [](const auto& p) { return !p.second.at8 || !p.second.at12; });
  if (pairs.empty()) return nullptr;
  auto misclassified = [](const StudyRow& r) { return r.reference.lit_shadowed + r.reference.shadowed_lit; };
  auto leaks = [](const StudyRow& r) { return r.exact.shadowed_lit; };
  nlohmann::json points = nlohmann::json::array();
  // Where 12 bits does not have fewer than 8: the biases (and other settings), per measure.
  std::vector<std::string> misclassified_not, leaks_not;
  const StudyRow* last_failure[2] = {nullptr, nullptr};
  int more_acne = 0;
  std::string biases;
  for (const auto& [key, p] : pairs) {
    const StudyRow &a = *p.at8, &b = *p.at12;
    points.push_back({{"depth_bits", a.depth_bits},
                      {"map_size", a.map_size},
                      {"bias_8bit_steps", a.bias_steps8},
                      {"misclassified", {misclassified(a), misclassified(b)}},
                      {"light_leaks", {leaks(a), leaks(b)}},
                      {"self_shadowed", {a.exact.self_shadowed, b.exact.self_shadowed}}});
    const bool other_settings = a.depth_bits != pairs[0].second.at8->depth_bits ||
                                a.map_size != pairs[0].second.at8->map_size;
    const std::string where = fmt::format("{:g}{}", a.bias_steps8,
                                          other_settings ? fmt::format(" (depth {} bits, map {}²)", a.depth_bits,
                                                                       a.map_size)
                                                         : "");
    if (misclassified(b) >= misclassified(a)) misclassified_not.push_back(where), last_failure[0] = &a;
    if (leaks(b) >= leaks(a)) leaks_not.push_back(where), last_failure[1] = &a;
    if (b.exact.self_shadowed > a.exact.self_shadowed) ++more_acne;
    biases += fmt::format("{}{:g}", biases.empty() ? "" : ", ", a.bias_steps8);
  }
  auto at12 = [&](const StudyRow* at8) {
    return std::find_if(pairs.begin(), pairs.end(), [&](const auto& p) { return p.second.at8 == at8; })->second.at12;
  };
  auto list = [](const std::vector<std::string>& items) {
    std::string out;
    for (std::size_t k = 0; k < items.size(); ++k) out += (k ? ", " : "") + items[k];
    return out;
  };
  // The counts at the sweep's first and last bias, for the sentence.
  const StudyRow &f8 = *pairs.front().second.at8, &f12 = *pairs.front().second.at12;
  const StudyRow &l8 = *pairs.back().second.at8, &l12 = *pairs.back().second.at12;
  auto span = [&](auto&& value, const StudyRow& x, const StudyRow& y) {
    return pairs.size() == 1 ? grouped(value(x)) : fmt::format("{}–{}", grouped(value(x)), grouped(value(y)));
  };
  const bool holds = misclassified_not.empty() && leaks_not.empty();
  std::string statement;
  const std::string where = pairs.size() == 1 ? fmt::format("at the one bias swept ({})", biases)
                                              : fmt::format("at every bias swept ({})", biases);
  if (holds) {
    statement = fmt::format(
        "12 bits reduces misclassification and light leaks {}: misclassified pixels {} at 8 bits against {} at 12, "
        "light leaks {} against {}{}.",
        where, span(misclassified, f8, l8), span(misclassified, f12, l12), span(leaks, f8, l8), span(leaks, f12, l12),
        pairs.size() == 1 ? "" : " (from the first bias to the last)");
  } else {
    std::vector<std::string> parts;
    if (!misclassified_not.empty()) {
      const StudyRow& a = *last_failure[0];
      parts.push_back(fmt::format("misclassification at bias {} ({} pixels at 8 bits, {} at 12 at bias {:g})",
                                  list(misclassified_not), grouped(misclassified(a)),
                                  grouped(misclassified(*at12(&a))), a.bias_steps8));
    }
    if (!leaks_not.empty()) {
      const StudyRow& a = *last_failure[1];
      parts.push_back(fmt::format("light leaks at bias {} ({} at 8 bits, {} at 12 at bias {:g})", list(leaks_not),
                                  grouped(leaks(a)), grouped(leaks(*at12(&a))), a.bias_steps8));
    }
    statement = fmt::format("12 bits does not reduce {} in this sweep.", list(parts));
  }
  statement += fmt::format(
      " Self-shadowing, shown against the bias at both widths, is higher at 12 bits at {} of {} point{} "
      "({} pixels at 8 bits against {} at 12 at bias {:g}).",
      more_acne, pairs.size(), pairs.size() == 1 ? "" : "s", grouped(l8.exact.self_shadowed),
      grouped(l12.exact.self_shadowed), l8.bias_steps8);
  return {{"claim", "12 bits reduces misclassification and light leaks at every bias; self-shadowing shown "
                    "against bias at both widths"},
          {"holds", holds},
          {"statement", statement},
          {"explanation",
           "Quantisation alone cannot shadow a lit surface: the receiver's depth a and the map's depth c go "
           "through the same grid of N = 2^bits codes, and ⌊a·N⌋ − k > ⌊c·N⌋ implies a − k/N > c, so a "
           "pixel the unquantised test (same samples, same bias k) leaves lit stays lit. Self-shadowing comes "
           "from the sampling mismatch between a pixel and the texels it reads — the map holds the depth at "
           "each texel's sample, not at the pixel's point — which a finer grid shows more of, while a coarse "
           "one floors both into the same code. What 12 bits buys is fewer occluders floored into their "
           "receiver's code: fewer light leaks and fewer misclassified pixels."},
          {"points", points}};
}

std::string study_csv(const std::vector<StudyRow>& rows) {
  std::string out =
      "index,color_bits,depth_bits,map_size,bias_8bit_steps,levels,mean_abs_error,wrong_pixels,precision_bits,"
      "lit_but_shadowed,shadowed_but_lit,self_shadowed,exact_lit_but_shadowed,exact_shadowed_but_lit,"
      "exact_self_shadowed,surfaces,depth_step_world\n";
  for (const StudyRow& r : rows)
    out += fmt::format("{},{},{},{},{:.9g},{},{:.9g},{},{:.9g},{},{},{},{},{},{},{},{:.9g}\n", r.index,
                       r.color_bits, r.depth_bits, r.map_size, r.bias_steps8, r.levels, r.mean_abs_error,
                       r.wrong_pixels, r.precision_bits, r.reference.lit_shadowed, r.reference.shadowed_lit,
                       r.reference.self_shadowed,
                       r.exact.lit_shadowed, r.exact.shadowed_lit, r.exact.self_shadowed, r.surfaces,
                       r.depth_step_world);
  return out;
}

namespace {

nlohmann::json row_json(const StudyRow& r) {
  return {{"index", r.index},
          {"color_bits", r.color_bits},
          {"depth_bits", r.depth_bits},
          {"map_size", r.map_size},
          {"bias_8bit_steps", r.bias_steps8},
          {"levels", r.levels},
          {"mean_abs_error", r.mean_abs_error},
          {"wrong_pixels", r.wrong_pixels},
          {"precision_bits", r.precision_bits},
          {"lit_but_shadowed", r.reference.lit_shadowed},
          {"shadowed_but_lit", r.reference.shadowed_lit},
          {"self_shadowed", r.reference.self_shadowed},
          {"exact_lit_but_shadowed", r.exact.lit_shadowed},
          {"exact_shadowed_but_lit", r.exact.shadowed_lit},
          {"exact_self_shadowed", r.exact.self_shadowed},
          {"surfaces", r.surfaces},
          {"depth_step_world", r.depth_step_world}};
}

StudyRow row_from_json(const nlohmann::json& j) {
  StudyRow r;
  r.index = j.at("index").get<int>();
  r.color_bits = j.at("color_bits").get<int>();
  r.depth_bits = j.at("depth_bits").get<int>();
  r.map_size = j.at("map_size").get<int>();
  r.bias_steps8 = j.at("bias_8bit_steps").get<double>();
  r.levels = j.at("levels").get<int>();
  r.mean_abs_error = j.at("mean_abs_error").get<double>();
  r.wrong_pixels = j.at("wrong_pixels").get<int>();
  r.precision_bits = j.at("precision_bits").get<double>();
  r.reference.lit_shadowed = j.at("lit_but_shadowed").get<int>();
  r.reference.shadowed_lit = j.at("shadowed_but_lit").get<int>();
  r.reference.self_shadowed = j.at("self_shadowed").get<int>();
  r.exact.lit_shadowed = j.at("exact_lit_but_shadowed").get<int>();
  r.exact.shadowed_lit = j.at("exact_shadowed_but_lit").get<int>();
  r.exact.self_shadowed = j.at("exact_self_shadowed").get<int>();
  r.surfaces = j.at("surfaces").get<int>();
  r.depth_step_world = j.at("depth_step_world").get<double>();
  return r;
}

}  // namespace

nlohmann::json sweep_description(const StudySweep& sweep) {
  nlohmann::json s = sweep_json(sweep);
  s["id"] = sweep.id();
  s["points"] = sweep.points().size();
  return s;
}

nlohmann::json study_json(const nlohmann::json& sweep_description, const std::vector<StudyRow>& rows, int shard_index,
                          int shard_count) {
  nlohmann::json out{{"sweep", sweep_description}, {"shard", fmt::format("{}/{}", shard_index + 1, shard_count)}};
  if (shard_count == 1) out["headline"] = study_headline(rows);  // a slice's rows are only part of the sweep
  out["rows"] = nlohmann::json::array();
  for (const StudyRow& r : rows) out["rows"].push_back(row_json(r));
  return out;
}

std::vector<StudyRow> merge_study(const std::vector<nlohmann::json>& slices, nlohmann::json& sweep_out) {
  if (slices.empty()) throw std::runtime_error("nothing to merge");
  try {
    const nlohmann::json& first = slices.front().at("sweep");
    const std::size_t points = first.at("points").get<std::size_t>();
    std::vector<StudyRow> rows;
    std::vector<bool> seen(points, false);
    for (const nlohmann::json& s : slices) {
      if (s.at("sweep") != first)
        throw std::runtime_error(fmt::format("slices of different sweeps (ids {} and {})", first.at("id").dump(),
                                             s.at("sweep").at("id").dump()));
      for (const nlohmann::json& j : s.at("rows")) {
        StudyRow r = row_from_json(j);
        if (r.index < 0 || static_cast<std::size_t>(r.index) >= points)
          throw std::runtime_error(fmt::format("point {} is outside the sweep's {} points", r.index, points));
        if (seen[static_cast<std::size_t>(r.index)])
          throw std::runtime_error(fmt::format("point {} appears in two slices", r.index));
        seen[static_cast<std::size_t>(r.index)] = true;
        rows.push_back(r);
      }
    }
    const auto missing = std::find(seen.begin(), seen.end(), false);
    if (missing != seen.end())
      throw std::runtime_error(fmt::format("point {} is in no slice (a shard missing?)", missing - seen.begin()));
    std::sort(rows.begin(), rows.end(), [](const StudyRow& a, const StudyRow& b) { return a.index < b.index; });
    sweep_out = first;
    return rows;
  } catch (const nlohmann::json::exception& e) {
    throw std::runtime_error(fmt::format("not a study.json slice: {}", e.what()));
  }
}

std::vector<ProvenanceRow> precision_provenance(
    const ProgramOptions& options, const std::function<void(int, int, const std::string&)>& progress) {
  struct Variant {
    const char* stage;
    const char* widening;
    void (*widen)(ProgramOptions&);
  };
  // In pipeline order: the planes take the encoded depth first, then the copy to texture, the
  // counting copy through the colour table, the accumulation.
  const Variant variants[] = {
      {"as given", "", [](ProgramOptions&) {}},
      {"colour planes widened to 16 bits", "the colour planes to 16 bits", [](ProgramOptions& o) { o.color_bits = 16; }},
      {"texture formats widened to 16 bits", "the texture formats to 16 bits",
       [](ProgramOptions& o) { o.texture_bits = 16; }},
      {"colour table widened to 16 bits", "the colour table to 16 bits", [](ProgramOptions& o) { o.table_bits = 16; }},
      {"accumulation widened to 32 bits", "the accumulation buffer to 32 bits",
       [](ProgramOptions& o) { o.accum_bits = 32; }},
  };
  const int total = 2 * static_cast<int>(std::size(variants));  // each run, then its reference
  std::vector<ProvenanceRow> rows;
  for (const Variant& v : variants) {
    ProgramOptions o = options;
    if (o.program != "hw-shadow") {  // the bias stays the same depth when the planes widen
      if (std::isnan(o.bias)) o.bias = std::ldexp(1.0, o.color_bits - 8);
      const double bias8 = o.bias / std::ldexp(1.0, o.color_bits - 8);
      v.widen(o);
      o.bias = bias8 * std::ldexp(1.0, o.color_bits - 8);
    } else {
      v.widen(o);
    }
    const int done = 2 * static_cast<int>(rows.size());
    if (progress) progress(done, total, fmt::format("{}: the program", v.stage));
    ProgramSession session(o);
    session.frame();
    const ProgramRun run = session.finish();
    if (progress) progress(done + 1, total, fmt::format("{}: its double-precision reference", v.stage));
    rows.push_back({v.stage, v.widening, count_levels(run.image("attenuation")), attenuation_error(run)});
  }
  if (progress) progress(total, total, "");
  return rows;
}

nlohmann::json provenance_json(const ProgramOptions& o, const std::vector<ProvenanceRow>& rows, double threshold) {
  const double base = rows.front().error.precision_bits;
  nlohmann::json out{{"program", o.program},           {"scene", o.scene},          {"filter", o.filter},
                     {"depths", o.depths},             {"width", o.width},          {"height", o.height},
                     {"color_bits", o.color_bits},     {"texture_bits", o.texture_bits},
                     {"table_bits", o.table_bits},     {"accum_bits", o.accum_bits}, {"profile", o.profile},
                     {"threshold_bits", threshold}};
  out["rows"] = nlohmann::json::array();
  const ProvenanceRow* first = nullptr;
  for (const ProvenanceRow& r : rows) {
    const double gain = r.error.precision_bits - base;
    out["rows"].push_back({{"stage", r.stage},
                           {"levels", r.levels},
                           {"mean_abs_error", r.error.mean_abs},
                           {"wrong_pixels", r.error.wrong_pixels},
                           {"precision_bits", r.error.precision_bits},
                           {"recovers_bits", gain}});
    if (!first && !r.widening.empty() && gain > threshold) first = &r;
  }
  if (first) {
    out["first_loss"] = first->stage;
    out["statement"] = fmt::format("widening {} recovers {:.2f} bits of precision (from {:.2f} to {:.2f})",
                                   first->widening, first->error.precision_bits - base, base,
                                   first->error.precision_bits);
  } else {
    out["first_loss"] = nullptr;
    out["statement"] = fmt::format(
        "widening no single stage recovers more than {:g} bits: the loss is shared between stages, or lies in the "
        "algorithm (its sampling), not in a width", threshold);
  }
  return out;
}

}  // namespace passim
