#include "programs/reference.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <fmt/format.h>

#include <map>
#include <random>

#include "pipeline/fixed_point.hpp"

namespace passim {

// ---------------------------------------------------------------- ray caster

RayCaster::RayCaster(const Scene& scene) {
  for (std::size_t m = 0; m < scene.meshes.size(); ++m) {
    const std::vector<float>& p = scene.meshes[m].positions;
    for (std::size_t k = 0; k + 8 < p.size(); k += 9) {
      const glm::dvec3 a(p[k], p[k + 1], p[k + 2]), b(p[k + 3], p[k + 4], p[k + 5]), c(p[k + 6], p[k + 7], p[k + 8]);
      const glm::dvec3 n = glm::cross(b - a, c - a);
      const double len = glm::length(n);
      if (len == 0.0) continue;  // degenerate: covers nothing
      triangles_.push_back({a, b - a, c - a, n / len, static_cast<int>(m)});
    }
  }
  nodes_.reserve(2 * triangles_.size() + 1);
  if (!triangles_.empty()) build(0, static_cast<int>(triangles_.size()));
}

// A bounding-volume hierarchy split at the median of the longest axis.
int RayCaster::build(int first, int count) {
  Node node;
  node.lo = glm::dvec3(1e300);
  node.hi = glm::dvec3(-1e300);
  for (int k = first; k < first + count; ++k) {
    const Triangle& t = triangles_[static_cast<std::size_t>(k)];
    for (const glm::dvec3& v : {t.a, t.a + t.e1, t.a + t.e2}) node.lo = glm::min(node.lo, v), node.hi = glm::max(node.hi, v);
  }
  const int index = static_cast<int>(nodes_.size());
  nodes_.push_back(node);
  if (count <= 4) {
    nodes_[static_cast<std::size_t>(index)].first = first;
    nodes_[static_cast<std::size_t>(index)].count = count;
    return index;
  }
  const glm::dvec3 extent = node.hi - node.lo;
  const int axis = extent.x >= extent.y && extent.x >= extent.z ? 0 : extent.y >= extent.z ? 1 : 2;
  auto centroid = [&](const Triangle& t) { return 3.0 * t.a[axis] + t.e1[axis] + t.e2[axis]; };
  const auto begin = triangles_.begin() + first, mid = begin + count / 2, end = begin + count;
  std::nth_element(begin, mid, end, [&](const Triangle& x, const Triangle& y) { return centroid(x) < centroid(y); });
  const int left = build(first, count / 2);
  const int right = build(first + count / 2, count - count / 2);
  nodes_[static_cast<std::size_t>(index)].left = left;
  nodes_[static_cast<std::size_t>(index)].right = right;
  return index;
}

std::optional<RayCaster::Hit> RayCaster::first_hit(const glm::dvec3& origin, const glm::dvec3& dir, double t_min,
                                                   double t_max) const {
  if (nodes_.empty()) return std::nullopt;
  std::optional<Hit> best;
  const glm::dvec3 inv(1.0 / dir.x, 1.0 / dir.y, 1.0 / dir.z);
  int stack[128];
  int top = 0;
  stack[top++] = 0;
  while (top > 0) {
    const Node& n = nodes_[static_cast<std::size_t>(stack[--top])];
    // Slab test against the node's box.
    double t0 = t_min, t1 = t_max;
    for (int a = 0; a < 3; ++a) {
      double ta = (n.lo[a] - origin[a]) * inv[a], tb = (n.hi[a] - origin[a]) * inv[a];
      if (ta > tb) std::swap(ta, tb);
      if (std::isnan(ta) || std::isnan(tb)) continue;  // a zero direction component inside the slab
      t0 = std::max(t0, ta), t1 = std::min(t1, tb);
    }
    if (t0 > t1) continue;
    if (n.left >= 0) {
      stack[top++] = n.left;
      stack[top++] = n.right;
      continue;
    }
    for (int k = n.first; k < n.first + n.count; ++k) {
      const Triangle& tr = triangles_[static_cast<std::size_t>(k)];
      // Möller–Trumbore.
      const glm::dvec3 p = glm::cross(dir, tr.e2);
      const double det = glm::dot(tr.e1, p);
      if (det == 0.0) continue;
      const glm::dvec3 s = origin - tr.a;
      const double u = glm::dot(s, p) / det;
      if (u < 0.0 || u > 1.0) continue;
      const glm::dvec3 q = glm::cross(s, tr.e1);
      const double v = glm::dot(dir, q) / det;
      if (v < 0.0 || u + v > 1.0) continue;
      const double t = glm::dot(tr.e2, q) / det;
      if (t <= t_min || t >= t_max) continue;
      t_max = t;
      best = Hit{t, tr.mesh, tr.normal};
    }
  }
  return best;
}

// ---------------------------------------------------------------- camera and light

namespace {

struct Frame {
  glm::dmat4 view, projection, inverse;  // inverse of projection·view
};

Frame frame_of(const View& v, double aspect) {
  Frame f;
  f.view = v.view_matrix();
  f.projection = v.projection_matrix(aspect);
  f.inverse = glm::inverse(f.projection * f.view);
  return f;
}

// The ray through normalised device coordinates (nx, ny), from the near to the far
// plane (t in [0, 1]).
std::pair<glm::dvec3, glm::dvec3> ndc_ray(const Frame& f, double nx, double ny) {
  glm::dvec4 a = f.inverse * glm::dvec4(nx, ny, -1.0, 1.0), b = f.inverse * glm::dvec4(nx, ny, 1.0, 1.0);
  const glm::dvec3 pa = glm::dvec3(a) / a.w, pb = glm::dvec3(b) / b.w;
  return {pa, pb - pa};
}

}  // namespace

std::vector<PixelSurface> camera_surfaces(const Scene& scene, const RayCaster& caster, int width, int height) {
  const Frame cam = frame_of(scene.camera, static_cast<double>(width) / height);
  std::vector<PixelSurface> out(static_cast<std::size_t>(width) * static_cast<std::size_t>(height));
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      const auto [o, d] = ndc_ray(cam, 2.0 * (x + 0.5) / width - 1.0, 2.0 * (y + 0.5) / height - 1.0);
      const auto hit = caster.first_hit(o, d, 0.0, 1.0);
      if (!hit) continue;
      PixelSurface& s = out[static_cast<std::size_t>(y) * static_cast<std::size_t>(width) + static_cast<std::size_t>(x)];
      s.hit = true;
      s.position = o + hit->t * d;
      s.normal = glm::dot(hit->normal, d) > 0.0 ? -hit->normal : hit->normal;  // the side the camera sees
      s.mesh = hit->mesh;
    }
  return out;
}

bool in_shadow_exact(const RayCaster& caster, const Scene& scene, const PixelSurface& s) {
  const glm::dvec3 to_light = scene.light.eye - s.position;
  // Start a hair off the surface so the surface itself does not count.
  return caster.first_hit(s.position + 1e-6 * glm::length(to_light) * s.normal, to_light, 1e-9, 1.0).has_value();
}

// ---------------------------------------------------------------- same samples

namespace {

// The scene as the light's rasterizer sees it: every triangle in the map's window
// coordinates with x and y snapped to 1/2^subpixel_bits of a texel (the hardware's
// vertex snapping, docs/arithmetic.md), for one jitter of the image plane. A map
// sample is then the nearest snapped triangle covering the sample point, its depth
// interpolated in double: perspective-correctly for the ramp's s (§3.8 eq. 3.4),
// linearly for window z.
class SnappedLightView {
 public:
  SnappedLightView(const Scene& scene, const Frame& light, int map, double jx, double jy, int subpixel_bits)
      : map_(map) {
    const double grid = std::ldexp(1.0, subpixel_bits);
    const double n = scene.light.near_plane, f = scene.light.far_plane;
    for (const Mesh& mesh : scene.meshes)
      for (std::size_t k = 0; k + 8 < mesh.positions.size(); k += 9) {
        Tri t;
        bool ok = true;
        for (int v = 0; v < 3; ++v) {
          const std::size_t i = k + 3 * static_cast<std::size_t>(v);
          const glm::dvec4 p(mesh.positions[i], mesh.positions[i + 1], mesh.positions[i + 2], 1.0);
          const glm::dvec4 eye = light.view * p, clip = light.projection * eye;
          if (clip.w <= 0.0) ok = false;
          t.x[v] = std::round(((clip.x / clip.w * 0.5 + 0.5) * map + jx) * grid) / grid;
          t.y[v] = std::round(((clip.y / clip.w * 0.5 + 0.5) * map + jy) * grid) / grid;
          t.inv_w[v] = 1.0 / clip.w;
          t.s[v] = (-eye.z - n) / (f - n);
          t.z[v] = clip.z / clip.w * 0.5 + 0.5;
        }
        t.area = (t.x[1] - t.x[0]) * (t.y[2] - t.y[0]) - (t.x[2] - t.x[0]) * (t.y[1] - t.y[0]);
        if (!ok || t.area == 0.0) continue;
        tris_.push_back(t);
      }
    // Bin the triangles into cells of 8x8 texels.
    cells_ = (map + 7) / 8;
    bins_.resize(static_cast<std::size_t>(cells_) * static_cast<std::size_t>(cells_));
    for (std::size_t k = 0; k < tris_.size(); ++k) {
      const Tri& t = tris_[k];
      auto cell = [&](double c) { return std::clamp(static_cast<int>(std::floor(c / 8.0)), 0, cells_ - 1); };
      const int x0 = cell(std::min({t.x[0], t.x[1], t.x[2]})), x1 = cell(std::max({t.x[0], t.x[1], t.x[2]}));
      const int y0 = cell(std::min({t.y[0], t.y[1], t.y[2]})), y1 = cell(std::max({t.y[0], t.y[1], t.y[2]}));
      if (std::max({t.x[0], t.x[1], t.x[2]}) < 0.0 || std::min({t.x[0], t.x[1], t.x[2]}) > map ||
          std::max({t.y[0], t.y[1], t.y[2]}) < 0.0 || std::min({t.y[0], t.y[1], t.y[2]}) > map)
        continue;
      for (int y = y0; y <= y1; ++y)
        for (int x = x0; x <= x1; ++x) bins_[static_cast<std::size_t>(y * cells_ + x)].push_back(static_cast<int>(k));
    }
  }

  // The nearest surface covering window point (x, y): its s and window z, or nothing.
  std::optional<std::pair<double, double>> sample(double x, double y) const {
    if (x < 0.0 || y < 0.0 || x >= map_ || y >= map_) return std::nullopt;
    const auto& bin = bins_[static_cast<std::size_t>(static_cast<int>(y / 8.0) * cells_ + static_cast<int>(x / 8.0))];
    std::optional<std::pair<double, double>> best;
    for (int k : bin) {
      const Tri& t = tris_[static_cast<std::size_t>(k)];
      double b[3];
      for (int v = 0; v < 3; ++v) {
        const int a = (v + 1) % 3, c = (v + 2) % 3;
        b[v] = ((t.x[c] - t.x[a]) * (y - t.y[a]) - (t.y[c] - t.y[a]) * (x - t.x[a])) / t.area;
      }
      if (b[0] < 0.0 || b[1] < 0.0 || b[2] < 0.0) continue;
      const double z = b[0] * t.z[0] + b[1] * t.z[1] + b[2] * t.z[2];
      const double q = b[0] * t.inv_w[0] + b[1] * t.inv_w[1] + b[2] * t.inv_w[2];
      const double s = (b[0] * t.s[0] * t.inv_w[0] + b[1] * t.s[1] * t.inv_w[1] + b[2] * t.s[2] * t.inv_w[2]) / q;
      if (!best || z < best->second) best = std::make_pair(s, z);
    }
    return best;
  }

 private:
  struct Tri {
    double x[3], y[3], inv_w[3], s[3], z[3], area;
  };
  int map_, cells_ = 0;
  std::vector<Tri> tris_;
  std::vector<std::vector<int>> bins_;
};

class SameSampleEvaluator {
 public:
  // `exact`: the algorithm without the pipeline's quantisation — exact geometry (no
  // vertex snapping) and depths at 40 bits (a step of 10^-12 of the depth range).
  explicit SameSampleEvaluator(const ProgramRun& run, bool exact = false)
      : run_(run), o_(run.options), scene_(run.scene), caster_(run.scene), map_(run.map_size) {
    exact_ = exact;
    cam_ = frame_of(scene_.camera, static_cast<double>(o_.width) / o_.height);
    light_ = frame_of(scene_.light, 1.0);
    hw_ = o_.program == "hw-shadow";
    bits_ = exact ? 40 : hw_ ? o_.depth_bits : o_.color_bits;
    max_code_ = (std::int64_t{1} << bits_) - 1;
    subpixel_bits_ = run.result.settings.machine().limits.subpixel_bits;
  }

  // The number of shadowed samples at pixel (px, py) moved by (ox, oy) pixels: the
  // range [lo, hi] it takes when each map sample independently moves by up to `h`
  // texels (h = 0: the exact count, lo = hi); lo = −1 where no surface is seen.
  std::pair<int, int> count(int px, int py, double ox, double oy, double h) {
    const auto [o, d] = ndc_ray(cam_, 2.0 * (px + 0.5 + ox) / o_.width - 1.0, 2.0 * (py + 0.5 + oy) / o_.height - 1.0);
    const auto hit = caster_.first_hit(o, d, 0.0, 1.0);
    if (!hit) return {-1, -1};
    const glm::dvec3 p = o + hit->t * d;
    const glm::dvec4 clip = light_.projection * light_.view * glm::dvec4(p, 1.0);
    const double u = (clip.x / clip.w * 0.5 + 0.5) * map_, v = (clip.y / clip.w * 0.5 + 0.5) * map_;
    int lo = 0, hi = 0;
    // One sample's decision at (i + dx, j + dy), exactly and moved by h in x and y.
    auto decide = [&](int i, int j, double dx, double dy, auto&& shadowed_by) {
      const double moves[5][2] = {{0, 0}, {h, 0}, {-h, 0}, {0, h}, {0, -h}};
      bool all = true, any = false;
      for (int m = 0; m < (h > 0.0 ? 5 : 1); ++m) {
        const bool s = shadowed_by(map_code(i, j, dx, dy, moves[m][0], moves[m][1]));
        all = all && s, any = any || s;
      }
      lo += all, hi += any;
    };
    if (hw_) {
      const double r = clip.z / clip.w * 0.5 + 0.5 - run_.bias_depth;
      const std::int64_t r_code = window_code(r);
      decide(clamp_texel(std::floor(u)), clamp_texel(std::floor(v)), 0.5, 0.5,
             [&](std::int64_t texel) { return texel <= r_code; });
      return {lo, hi};
    }
    const std::int64_t receiver = encode(depth_of(p) - run_.bias_depth);
    auto nearer = [&](std::int64_t texel) { return receiver > texel; };
    const std::string& prog = o_.program;
    if (prog == "shadow-map" || prog == "pcf") {
      const int ti = clamp_texel(std::floor(u)), tj = clamp_texel(std::floor(v));
      for (const MapSample& s : run_.samples) decide(ti, tj, s.dx, s.dy, nearer);
    } else if (prog == "fast-pcf") {
      // The packed texel after the (ds/2, dt/2) offset, and its phases' 2x2 blocks.
      const int x = static_cast<int>(std::floor(u + 0.5)), y = static_cast<int>(std::floor(v + 0.5));
      std::vector<std::pair<int, int>> phases = {{0, 0}};
      if (o_.filter == 4) phases = {{0, 0}, {1, 0}, {0, 1}, {1, 1}};
      for (auto [n0, m0] : phases)
        for (int b = 0; b < 2; ++b)
          for (int a = 0; a < 2; ++a) decide(clamp_texel(x - 1 + n0 + a), clamp_texel(y - 1 + m0 + b), 0.5, 0.5, nearer);
    } else {  // mdsm: each lookup's n-shadow test; the extra depths are exact here (h = 0)
      const int side = o_.filter;
      for (int j = 0; j < side; ++j)
        for (int i = 0; i < side; ++i) {
          const int ti = clamp_texel(std::floor(u + i - 0.5 * (side - 1)));
          const int tj = clamp_texel(std::floor(v + j - 0.5 * (side - 1)));
          for (int c = 0; c < o_.depths; ++c) {
            const double moves[5][2] = {{0, 0}, {h, 0}, {-h, 0}, {0, h}, {0, -h}};
            bool all = true, any = false;
            for (int m = 0; m < (h > 0.0 ? 5 : 1); ++m) {
              const bool s = mdsm_depths(ti, tj, moves[m][0], moves[m][1])[static_cast<std::size_t>(c)] < receiver;
              all = all && s, any = any || s;
            }
            lo += all, hi += any;
          }
        }
    }
    return {lo, hi};
  }

  int samples() const {
    if (hw_) return 1;
    if (o_.program == "fast-pcf") return o_.filter == 4 ? 16 : 4;
    if (o_.program == "mdsm") return o_.depths * o_.filter * o_.filter;
    return static_cast<int>(run_.samples.size());
  }

 private:
  int clamp_texel(double t) const { return static_cast<int>(std::clamp(t, 0.0, static_cast<double>(map_ - 1))); }

  // §2's encoding: s = (−z_eye − near)/(far − near) in the light's eye space.
  double depth_of(const glm::dvec3& p) const {
    const double z = (light_.view * glm::dvec4(p, 1.0)).z;
    return (-z - scene_.light.near_plane) / (scene_.light.far_plane - scene_.light.near_plane);
  }
  // The 1D ramp, NEAREST, CLAMP_TO_EDGE: code floor(s·2^bits), clamped.
  std::int64_t encode(double s) const {
    return std::clamp(static_cast<std::int64_t>(std::floor(s * std::ldexp(1.0, bits_))), std::int64_t{0}, max_code_);
  }

  // The code the map holds at texel (i, j) for the sample taken at (dx, dy) inside it
  // (the image plane jittered by (0.5 − dx, 0.5 − dy)), probed (mx, my) texels away
  // from the texel's centre; the cleared value (farthest) where the light sees nothing.
  // A window depth as the depth plane stores it (A25), or at 40 bits when exact.
  std::int64_t window_code(double z) const {
    z = std::clamp(z, 0.0, 1.0);
    return exact_ ? std::llround(z * static_cast<double>(max_code_)) : static_cast<std::int64_t>(float_to_fixed(z, bits_));
  }

  std::int64_t map_code(int i, int j, double dx, double dy, double mx = 0.0, double my = 0.0) {
    if (exact_) {  // the scene itself, through the sample point
      const auto [o, d] = ndc_ray(light_, 2.0 * (i + dx + mx) / map_ - 1.0, 2.0 * (j + dy + my) / map_ - 1.0);
      const auto hit = caster_.first_hit(o, d, 0.0, 1.0);
      if (!hit) return max_code_;
      const glm::dvec3 p = o + hit->t * d;
      if (!hw_) return encode(depth_of(p));
      const glm::dvec4 clip = light_.projection * light_.view * glm::dvec4(p, 1.0);
      return window_code(clip.z / clip.w * 0.5 + 0.5);
    }
    const std::pair<double, double> key{dx, dy};
    auto it = views_.find(key);
    if (it == views_.end())
      it = views_.emplace(key, SnappedLightView(scene_, light_, map_, 0.5 - dx, 0.5 - dy, subpixel_bits_)).first;
    const auto sample = it->second.sample(i + 0.5 + mx, j + 0.5 + my);
    if (!sample) return max_code_;
    if (hw_) return window_code(sample->second);
    return encode(sample->first);
  }

  // An n-SM cell: the map's depth, the 3x3 maximum and minimum (neighbours that exist).
  std::array<std::int64_t, 3> mdsm_depths(int i, int j, double mx, double my) {
    std::array<std::int64_t, 3> z{};
    z[0] = map_code(i, j, 0.5, 0.5, mx, my);
    z[1] = z[2] = z[0];
    for (int b = -1; b <= 1; ++b)
      for (int a = -1; a <= 1; ++a) {
        if (i + a < 0 || i + a >= map_ || j + b < 0 || j + b >= map_) continue;
        const std::int64_t c = map_code(i + a, j + b, 0.5, 0.5, mx, my);
        z[1] = std::max(z[1], c), z[2] = std::min(z[2], c);
      }
    return z;
  }

  const ProgramRun& run_;
  const ProgramOptions& o_;
  const Scene& scene_;
  RayCaster caster_;
  Frame cam_, light_;
  std::map<std::pair<double, double>, SnappedLightView> views_;
  int subpixel_bits_ = 4;
  bool exact_ = false;
  int map_ = 512, bits_ = 8;
  std::int64_t max_code_ = 255;
  bool hw_ = false;
};

}  // namespace

std::vector<double> exact_attenuation(const ProgramRun& run) {
  SameSampleEvaluator eval(run, true);
  const ProgramOptions& o = run.options;
  const double samples = eval.samples();
  std::vector<double> out(static_cast<std::size_t>(o.width) * static_cast<std::size_t>(o.height), -1.0);
  for (int y = 0; y < o.height; ++y)
    for (int x = 0; x < o.width; ++x) {
      const int c = eval.count(x, y, 0, 0, 0.0).first;
      out[static_cast<std::size_t>(y) * static_cast<std::size_t>(o.width) + static_cast<std::size_t>(x)] =
          c < 0 ? -1.0 : c / samples;
    }
  return out;
}

SameSamples same_samples(const ProgramRun& run) {
  SameSampleEvaluator eval(run);
  SameSamples out;
  out.samples = eval.samples();
  const ProgramOptions& o = run.options;
  const CapturedImage& att = run.image("attenuation");
  const std::int64_t max_code = (std::int64_t{1} << att.bits[0]) - 1;
  const std::size_t n = static_cast<std::size_t>(o.width) * static_cast<std::size_t>(o.height);
  out.expected.assign(n, -1);
  out.measured.assign(n, 0);
  out.tie.assign(n, false);
  // A hair: the rasterizer snaps vertices to 1/16 pixel (texel), so coverage and
  // interpolated depths may move by up to 1/32; 0.05 covers that.
  const double h = 0.1;
  for (int y = 0; y < o.height; ++y)
    for (int x = 0; x < o.width; ++x) {
      const std::size_t k = static_cast<std::size_t>(y) * static_cast<std::size_t>(o.width) + static_cast<std::size_t>(x);
      out.measured[k] = static_cast<int>(std::llround(static_cast<double>(att.codes[k]) * out.samples / static_cast<double>(max_code)));
      const int e = eval.count(x, y, 0, 0, 0.0).first;
      out.expected[k] = e;
      if (e < 0) continue;
      ++out.compared;
      if (e == out.measured[k]) {
        ++out.agree;
        continue;
      }
      // Explained when the program's count is within what the pixel or its samples
      // moved by a hair give: the decision sits on a quantisation step.
      bool tie = false;
      const double moves[5][2] = {{0, 0}, {h, 0}, {-h, 0}, {0, h}, {0, -h}};
      for (const auto& m : moves) {
        const auto [lo, hi] = eval.count(x, y, m[0], m[1], h);
        tie = tie || (lo <= out.measured[k] && out.measured[k] <= hi);
      }
      out.tie[k] = tie;
      tie ? ++out.disagree_at_ties : ++out.disagree_unexplained;
    }
  return out;
}

Classification classify(const ProgramRun& run, const std::vector<double>* reference) {
  const RayCaster caster(run.scene);
  const ProgramOptions& o = run.options;
  const std::vector<PixelSurface> surfaces = camera_surfaces(run.scene, caster, o.width, o.height);
  const CapturedImage& att = run.image("attenuation");
  Classification c;
  c.self_shadowed_by_mesh.assign(run.scene.meshes.size(), 0);
  for (std::size_t k = 0; k < surfaces.size(); ++k) {
    const PixelSurface& s = surfaces[k];
    if (!s.hit) continue;
    ++c.surfaces;
    const bool exact = in_shadow_exact(caster, run.scene, s);
    const bool attenuated = att.codes[k] > 0;
    const bool faces = glm::dot(s.normal, run.scene.light.eye - s.position) > 0.0;
    if (!exact && faces) ++c.facing_light;
    if (!exact && attenuated) {
      ++c.exact.lit_shadowed;
      if (faces) ++c.exact.self_shadowed, ++c.self_shadowed_by_mesh[static_cast<std::size_t>(s.mesh)];
    }
    if (exact && !attenuated) ++c.exact.shadowed_lit;
    if (reference) {
      const double ref = (*reference)[k];
      if (ref == 0.0 && attenuated) {
        ++c.reference.lit_shadowed;
        if (faces) ++c.reference.self_shadowed;
      }
      if (ref > 0.0 && !attenuated) ++c.reference.shadowed_lit;
    }
  }
  return c;
}

namespace {

// The unquantised map: the light-depth s of the nearest surface through each texel
// centre (1 where the light sees nothing), computed when first asked.
class DoubleMap {
 public:
  DoubleMap(const Scene& scene, const RayCaster& caster, int size)
      : scene_(scene), caster_(caster), size_(size), light_(frame_of(scene.light, 1.0)),
        depth_(static_cast<std::size_t>(size) * static_cast<std::size_t>(size), -1.0) {}
  int size() const { return size_; }
  bool inside(int i, int j) const { return i >= 0 && j >= 0 && i < size_ && j < size_; }
  double at(int i, int j) {
    double& d = depth_[static_cast<std::size_t>(j) * static_cast<std::size_t>(size_) + static_cast<std::size_t>(i)];
    if (d < 0.0) {
      const auto [o, dir] = ndc_ray(light_, 2.0 * (i + 0.5) / size_ - 1.0, 2.0 * (j + 0.5) / size_ - 1.0);
      const auto hit = caster_.first_hit(o, dir, 0.0, 1.0);
      d = hit ? depth_of(o + hit->t * dir) : 1.0;
    }
    return d;
  }
  double depth_of(const glm::dvec3& p) const {
    const double z = (light_.view * glm::dvec4(p, 1.0)).z;
    return (-z - scene_.light.near_plane) / (scene_.light.far_plane - scene_.light.near_plane);
  }
  // (u, v) in texels of a world point.
  glm::dvec2 project(const glm::dvec3& p) const {
    const glm::dvec4 clip = light_.projection * light_.view * glm::dvec4(p, 1.0);
    return {(clip.x / clip.w * 0.5 + 0.5) * size_, (clip.y / clip.w * 0.5 + 0.5) * size_};
  }

 private:
  const Scene& scene_;
  const RayCaster& caster_;
  int size_;
  Frame light_;
  std::vector<double> depth_;
};


}  // namespace

ReferenceRun run_reference(const ProgramOptions& options) {
  ReferenceRun ref;
  ref.options = options;
  ProgramOptions& o = ref.options;
  const bool reeves = o.program == "reeves", shader = o.program == "shader-pcf", mdsm = o.program == "mdsm-ref";
  if (!reeves && !shader && !mdsm) throw ProgramError(fmt::format("'{}' is not a software reference", o.program));
  ref.scene = make_scene(o.scene);
  ref.map_size = o.map_size > 0 ? o.map_size : ref.scene.default_map_size;
  if (ref.map_size < 1 || ref.map_size > 16384) throw ProgramError(fmt::format("--map {}: 1 to 16384", ref.map_size));
  if (o.width < 1 || o.height < 1 || o.width > 8192 || o.height > 8192)
    throw ProgramError(fmt::format("--size {}x{}: 1 to 8192 on each side", o.width, o.height));
  if (o.color_bits < 1 || o.color_bits > 16) throw ProgramError(fmt::format("--bits {}: 1 to 16", o.color_bits));
  if (o.filter == 0) o.filter = shader ? 3 : reeves ? 3 : 2;
  if (shader && o.filter != 3) throw ProgramError("shader-pcf is the tutorial's 3x3 loop (--filter 3x3)");
  if (reeves && (o.filter < 1 || o.filter > 16)) throw ProgramError(fmt::format("reeves --filter {0}x{0}: 1 to 16", o.filter));
  if (mdsm && (o.filter < 1 || o.filter > 3 || o.depths < 1 || o.depths > 3))
    throw ProgramError("mdsm-ref: --filter 1x1 to 3x3 and --depths 1 to 3");
  if (reeves && o.sampling != "random" && o.sampling != "gaussian" && o.sampling != "jittered")
    throw ProgramError(fmt::format("--sampling {}: random, gaussian or jittered", o.sampling));
  if (std::isnan(o.bias)) o.bias = std::ldexp(1.0, o.color_bits - 8);
  if (!std::isfinite(o.bias)) throw ProgramError("--bias must be a finite number of steps");
  ref.bias_depth = o.bias / std::ldexp(1.0, o.color_bits);

  const RayCaster caster(ref.scene);
  DoubleMap map(ref.scene, caster, ref.map_size);
  const std::vector<PixelSurface> surfaces = camera_surfaces(ref.scene, caster, o.width, o.height);
  ref.attenuation.assign(surfaces.size(), 0.0);
  const int n = o.filter;
  for (std::size_t k = 0; k < surfaces.size(); ++k) {
    const PixelSurface& s = surfaces[k];
    if (!s.hit) continue;
    const double d = map.depth_of(s.position) - ref.bias_depth;
    const glm::dvec2 uv = map.project(s.position);
    // A lookup: shadowed when the map is nearer; outside the map lit (Reeves).
    auto shadowed = [&](double x, double y) {
      const int i = static_cast<int>(std::floor(x)), j = static_cast<int>(std::floor(y));
      return map.inside(i, j) && map.at(i, j) < d;
    };
    double a = 0.0;
    if (reeves) {
      // A generator per pixel, so any pixel's samples are reproducible on their own.
      std::mt19937 rng(o.seed * 2654435761u + static_cast<std::uint32_t>(k));
      const double x0 = uv.x - 0.5 * n, y0 = uv.y - 0.5 * n;
      int count = 0;
      for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
          double x, y;
          if (o.sampling == "jittered") {  // (c): one sample in each of the N×N cells
            x = x0 + i + uniform01(rng), y = y0 + j + uniform01(rng);
          } else if (o.sampling == "random") {  // (a): uniform over the box
            x = x0 + n * uniform01(rng), y = y0 + n * uniform01(rng);
          } else {  // (b): a Gaussian (σ = N/4, Box–Muller) kept inside the box
            const double r = std::sqrt(-2.0 * std::log(1.0 - uniform01(rng))), t = 2.0 * 3.14159265358979323846 * uniform01(rng);
            x = std::clamp(uv.x + 0.25 * n * r * std::cos(t), x0, x0 + n - 1e-9);
            y = std::clamp(uv.y + 0.25 * n * r * std::sin(t), y0, y0 + n - 1e-9);
          }
          count += shadowed(x, y);
        }
      a = static_cast<double>(count) / (n * n);
    } else if (shader) {
      // The tutorial: 9 lookups at the projection ± one texel; F = how many are lit.
      int lit = 0;
      for (int y = -1; y <= 1; ++y)
        for (int x = -1; x <= 1; ++x) lit += !shadowed(uv.x + x, uv.y + y);
      a = (9.0 - lit) / 9.0;  // the tutorial's factor 0.5 + lit/18 = 1 − a/2
    } else {
      // MDSM: Z1 ≥ … ≥ Zn = the 3x3 maximum, the depth, the 3x3 minimum (n = 3); the n-ST
      // counts the Zi nearer than the point; PCF(k, n) averages k lookups one texel apart.
      int count = 0;
      for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
          const int ti = static_cast<int>(std::floor(uv.x + i - 0.5 * (n - 1)));
          const int tj = static_cast<int>(std::floor(uv.y + j - 0.5 * (n - 1)));
          if (!map.inside(ti, tj)) continue;
          double z = map.at(ti, tj), hi = z, lo = z;
          for (int b = -1; b <= 1; ++b)
            for (int c = -1; c <= 1; ++c)
              if (map.inside(ti + c, tj + b)) hi = std::max(hi, map.at(ti + c, tj + b)), lo = std::min(lo, map.at(ti + c, tj + b));
          const double depths[3] = {z, hi, lo};
          for (int c = 0; c < o.depths; ++c) count += depths[c] < d;
        }
      a = static_cast<double>(count) / (o.depths * n * n);
    }
    ref.attenuation[k] = a;
  }
  CapturedImage& img = ref.image;
  img.name = "attenuation";
  img.plane = "alpha";
  img.width = o.width;
  img.height = o.height;
  img.channels = 1;
  img.bits = {16, 0, 0, 0};
  img.codes.resize(ref.attenuation.size());
  for (std::size_t k = 0; k < ref.attenuation.size(); ++k)
    img.codes[k] = static_cast<std::uint32_t>(std::llround(ref.attenuation[k] * 65535.0));
  img.hash = fnv1a_hex(img.codes, 2);
  return ref;
}

}  // namespace passim
