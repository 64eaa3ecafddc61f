#include "stages/clipping.hpp"

#include <algorithm>

namespace passim {
namespace {

// Signed distance to plane k: 0-5 the view volume (x >= -w, x <= w, y..., z...), 6-11 user planes.
double plane_distance(const ProcessedVertex& v, int k, const ClipPlanes& planes) {
  const Vec4& c = v.clip;
  switch (k) {
    case 0: return c.w + c.x;
    case 1: return c.w - c.x;
    case 2: return c.w + c.y;
    case 3: return c.w - c.y;
    case 4: return c.w + c.z;
    case 5: return c.w - c.z;
    default: return glm::dot(planes.user[k - 6], v.eye);
  }
}

bool plane_active(int k, const ClipPlanes& planes) { return k < 6 || (planes.user_enabled >> (k - 6)) & 1u; }

ProcessedVertex lerp(const ProcessedVertex& a, const ProcessedVertex& b, double t) {
  // §2.11: P = t·P1 + (1 - t)·P2 for every attribute, here written as a + t·(b - a).
  ProcessedVertex r;
  r.clip = a.clip + t * (b.clip - a.clip);
  r.eye = a.eye + t * (b.eye - a.eye);
  r.color[0] = a.color[0] + t * (b.color[0] - a.color[0]);
  r.color[1] = a.color[1] + t * (b.color[1] - a.color[1]);
  r.tex = a.tex + t * (b.tex - a.tex);
  return r;
}

}  // namespace

bool point_inside(const ProcessedVertex& v, const ClipPlanes& planes) {
  for (int k = 0; k < 12; ++k)
    if (plane_active(k, planes) && plane_distance(v, k, planes) < 0.0) return false;
  return true;
}

bool trivially_inside(const ProcessedVertex& v, const ClipPlanes& planes) {
  const Vec4& c = v.clip;
  return planes.user_enabled == 0 && -c.w <= c.x && c.x <= c.w && -c.w <= c.y && c.y <= c.w && -c.w <= c.z &&
         c.z <= c.w;
}

bool clip_polygon(std::vector<ProcessedVertex>& poly, std::vector<ProcessedVertex>& scratch,
                  const ClipPlanes& planes, bool& cut) {
  cut = false;
  if (std::all_of(poly.begin(), poly.end(), [&](const ProcessedVertex& v) { return trivially_inside(v, planes); }))
    return poly.size() >= 3;
  for (int k = 0; k < 12 && !poly.empty(); ++k) {
    if (!plane_active(k, planes)) continue;
    bool all_inside = true;
    for (const auto& v : poly) {
      if (plane_distance(v, k, planes) < 0.0) {
        all_inside = false;
        break;
      }
    }
    if (all_inside) continue;
    cut = true;
    scratch.clear();
    const std::size_t n = poly.size();
    for (std::size_t i = 0; i < n; ++i) {
      const ProcessedVertex& a = poly[i];
      const ProcessedVertex& b = poly[(i + 1) % n];
      const double da = plane_distance(a, k, planes);
      const double db = plane_distance(b, k, planes);
      if (da >= 0.0) scratch.push_back(a);
      if ((da >= 0.0) != (db >= 0.0)) {
        // §2.11: an edge introduced by clipping (from the vertex where the polygon leaves the
        // plane to where it comes back) is a boundary edge; the cut part of an original edge
        // keeps that edge's flag.
        scratch.push_back(lerp(a, b, da / (da - db)));
        scratch.back().edge_flag = da >= 0.0 ? true : a.edge_flag;
      }
    }
    poly.swap(scratch);
  }
  return poly.size() >= 3;
}

bool clip_line(ProcessedVertex& a, ProcessedVertex& b, const ClipPlanes& planes, bool& cut) {
  cut = false;
  if (trivially_inside(a, planes) && trivially_inside(b, planes)) return true;
  for (int k = 0; k < 12; ++k) {
    if (!plane_active(k, planes)) continue;
    const double da = plane_distance(a, k, planes);
    const double db = plane_distance(b, k, planes);
    if (da < 0.0 && db < 0.0) return false;
    if (da >= 0.0 && db >= 0.0) continue;
    cut = true;
    // The same parameter as polygon clipping's, from the vertex inside.
    if (da < 0.0) {
      a = lerp(b, a, db / (db - da));
    } else {
      b = lerp(a, b, da / (da - db));
    }
  }
  return true;
}

}  // namespace passim
