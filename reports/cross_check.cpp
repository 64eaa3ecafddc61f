#include "reports/cross_check.hpp"

#include <fmt/format.h>

#include <cstring>
#include <optional>

namespace passim {

namespace {

// A plane's codes as the cross-check reads them.
struct PlaneView {
  std::string name;
  const std::byte* data;
  std::size_t elements;
  std::size_t element_bytes;
  int per_pixel;  // elements a pixel
};

std::vector<PlaneView> planes_of(const Framebuffer& fb) {
  std::vector<PlaneView> out;
  auto add = [&](std::string name, const auto& v, int per_pixel) {
    if (v.empty()) return;
    out.push_back({std::move(name), reinterpret_cast<const std::byte*>(v.data()), v.size(), sizeof(v[0]), per_pixel});
  };
  add("colour buffer GL_FRONT", fb.color[0].rgba, 4);
  add("colour buffer GL_BACK", fb.color[1].rgba, 4);
  add("depth", fb.depth, 1);
  add("stencil", fb.stencil, 1);
  add("accumulation", fb.accum, 4);
  return out;
}

std::int64_t element(const PlaneView& p, std::size_t i) {
  const std::byte* e = p.data + i * p.element_bytes;
  switch (p.element_bytes) {
    case 1: return static_cast<std::int64_t>(static_cast<std::uint8_t>(*e));
    case 2: { std::uint16_t v; std::memcpy(&v, e, 2); return v; }
    default: { std::int32_t v; std::memcpy(&v, e, 4); return p.name == "depth" ? static_cast<std::int64_t>(static_cast<std::uint32_t>(v)) : v; }
  }
}

// The first element two framebuffers of one configuration disagree on, named.
std::string first_difference(const Framebuffer& reference, const Framebuffer& fast) {
  const std::vector<PlaneView> a = planes_of(reference), b = planes_of(fast);
  for (std::size_t k = 0; k < a.size() && k < b.size(); ++k) {
    for (std::size_t i = 0; i < a[k].elements && i < b[k].elements; ++i) {
      const std::int64_t ra = element(a[k], i), fb = element(b[k], i);
      if (ra == fb) continue;
      const std::size_t pixel = i / static_cast<std::size_t>(a[k].per_pixel);
      const int x = static_cast<int>(pixel % static_cast<std::size_t>(reference.width()));
      const int y = static_cast<int>(pixel / static_cast<std::size_t>(reference.width()));
      const std::string channel =
          a[k].per_pixel == 4 ? fmt::format(" channel {}", "RGBA"[i % 4]) : std::string();
      return fmt::format("{} differs at pixel ({}, {}){}: reference {}, fast {}", a[k].name, x, y, channel, ra, fb);
    }
  }
  return "the planes differ in size";
}

std::string pass_name(const Context& ctx, std::size_t pass) {
  const auto& passes = ctx.passes();
  return pass < passes.size() ? fmt::format("pass {} '{}'", pass, passes[pass].label) : fmt::format("pass {}", pass);
}

// Thrown by an observer to end a run at a checkpoint; not a std::exception, so it passes
// through the replays' own error handling.
struct StopAtCheckpoint {};

}  // namespace

std::vector<std::pair<std::string, std::uint64_t>> plane_digests(const Context& ctx) {
  std::vector<std::pair<std::string, std::uint64_t>> out;
  for (const PlaneView& p : planes_of(ctx.framebuffer()))
    out.emplace_back(p.name, fnv1a({p.data, p.elements * p.element_bytes}));
  return out;
}

CrossCheckReport cross_check(const CrossCheckRun& run) {
  CrossCheckReport report;
  struct Checkpoint {
    std::size_t pass;
    std::vector<std::pair<std::string, std::uint64_t>> digests;
  };
  std::vector<Checkpoint> expected;
  const ReplayResult reference = run(KernelPaths::reference(), [&](const Context& ctx, std::size_t pass) {
    expected.push_back({pass, plane_digests(ctx)});
  });
  report.checkpoints = expected.size();

  // The fast run, stopped at the first pass whose planes differ (its planes kept).
  std::size_t reached = 0;
  std::optional<Framebuffer> fast_planes;
  ReplayResult fast;
  try {
    fast = run(KernelPaths::fastest(), [&](const Context& ctx, std::size_t pass) {
      if (reached >= expected.size() || expected[reached].pass != pass ||
          expected[reached].digests != plane_digests(ctx)) {
        fast_planes.emplace(ctx.framebuffer());
        throw StopAtCheckpoint{};
      }
      ++reached;
    });
  } catch (const StopAtCheckpoint&) {
  }
  if (fast_planes) {
    report.same = false;
    if (reached >= expected.size()) {
      report.difference = fmt::format("the fast run ends more passes than the reference ({})", expected.size());
      return report;
    }
    // The reference again, to the same checkpoint, for its planes.
    std::optional<Framebuffer> reference_planes;
    std::size_t seen = 0;
    try {
      run(KernelPaths::reference(), [&](const Context& ctx, std::size_t) {
        if (seen++ == reached) {
          reference_planes.emplace(ctx.framebuffer());
          throw StopAtCheckpoint{};
        }
      });
    } catch (const StopAtCheckpoint&) {
    }
    report.difference = fmt::format("at the end of {}: {}", pass_name(*reference.context, expected[reached].pass),
                                    reference_planes ? first_difference(*reference_planes, *fast_planes)
                                                     : std::string("the planes differ"));
    return report;
  }
  auto differ = [&](std::string what) {
    report.same = false;
    report.difference = std::move(what);
    return report;
  };
  if (reached != expected.size())
    return differ(fmt::format("the fast run ends {} passes, the reference {}", reached, expected.size()));
  const Context& r = *reference.context;
  const Context& f = *fast.context;
  if (plane_digests(r) != plane_digests(f))
    return differ("at the end of the run: " + first_difference(r.framebuffer(), f.framebuffer()));
  if (r.passes().size() != f.passes().size())
    return differ(fmt::format("the reference counts {} passes, the fast run {}", r.passes().size(), f.passes().size()));
  for (std::size_t p = 0; p < r.passes().size(); ++p) {
    std::string field;
    Counters::for_each_field([&](const char* name, std::uint64_t Counters::*m) {
      if (field.empty() && r.passes()[p].counters.*m != f.passes()[p].counters.*m)
        field = fmt::format("counter {}: reference {}, fast {}", name, r.passes()[p].counters.*m,
                            f.passes()[p].counters.*m);
    });
    if (!field.empty()) return differ(fmt::format("{}: {}", pass_name(r, p), field));
  }
  if (r.error_log().size() != f.error_log().size())
    return differ(fmt::format("the reference raises {} GL errors, the fast run {}", r.error_log().size(),
                              f.error_log().size()));
  for (std::size_t i = 0; i < reference.images.size() && i < fast.images.size(); ++i)
    if (reference.images[i].hash != fast.images[i].hash)
      return differ(fmt::format("image '{}' differs", reference.images[i].name));
  return report;
}

}  // namespace passim
