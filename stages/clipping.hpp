// Primitive clipping, OpenGL 1.2.1 §2.11: the view volume -w <= x, y, z <= w and
// the enabled client-defined planes (p · eye >= 0), for convex polygons, line segments and
// points.
#pragma once
#include <array>
#include <vector>

#include "stages/vertex.hpp"

namespace passim {

struct ClipPlanes {
  std::array<Vec4, 6> user{};  // eye coordinates
  unsigned user_enabled = 0;   // bit i: plane i enabled
};

// True when the point lies inside every plane (§2.11: points are clipped as a whole).
bool point_inside(const ProcessedVertex& v, const ClipPlanes& planes);

// The trivial accept: no user plane enabled and the vertex inside the view volume. A polygon
// whose vertices all pass it is drawn as it is (clip_polygon leaves it untouched, cut false).
bool trivially_inside(const ProcessedVertex& v, const ClipPlanes& planes);

// Clips the convex polygon `poly` in place (Sutherland-Hodgman, attributes interpolated
// with the same parameter t as the clip coordinates). `scratch` is reused storage.
// Returns false when nothing is left; `cut` tells whether any plane cut the polygon.
bool clip_polygon(std::vector<ProcessedVertex>& poly, std::vector<ProcessedVertex>& scratch,
                  const ClipPlanes& planes, bool& cut);

// Clips the segment a → b in place (§2.11: a cut end point takes the attributes at the same
// parameter t as its clip coordinates, a + t·(b − a)). Returns false when nothing is left;
// `cut` tells whether any plane cut the segment.
bool clip_line(ProcessedVertex& a, ProcessedVertex& b, const ClipPlanes& planes, bool& cut);

}  // namespace passim
