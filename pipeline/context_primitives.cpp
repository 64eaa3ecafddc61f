// Context: the vertex pipeline and primitive assembly (§2.10-§3.5): each vertex transformed,
// lit and given its texture coordinates, primitives assembled, clipped, given their facing
// and colours, and handed to the rasterizer.
#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstring>
#include <fmt/format.h>
#include <glm/gtc/matrix_transform.hpp>

#include "pipeline/checked_size.hpp"
#include "pipeline/context.hpp"
#include "pipeline/context_internal.hpp"
#include "pipeline/context_scratch.hpp"
#include "pipeline/fixed_point.hpp"
#include "stages/clipping.hpp"
#include "stages/lighting.hpp"
#include "stages/line_rasterizer.hpp"
#include "stages/rasterizer.hpp"

namespace passim {

// ---------------------------------------------------------------- vertex processing (§2.10-2.13)
double Context::vertex_color(double c, int bits) const {
  // §2.13.6 clamp to [0, 1]; A4 rounds to the fragment width unless the profile says otherwise.
  if (profile_.arithmetic.quantise_vertex_colors) return quantise(c, bits);
  return clamp_nan_low(c, 0.0, 1.0);
}

void Context::submit_vertex(const Vec4& object) {
  if (!in_begin_) return;  // §2.6.3: Vertex outside Begin/End is undefined; it is ignored here
  Counters& c = counters();
  ++c.vertices;
  emit_primitive_vertex(process_vertex(object, c));
}

bool Context::sphere_map_texgen() const {
  // §2.10.4: SPHERE_MAP generates s or t from the eye-space normal.
  return texturing_enabled_ && ((textures_.gen[0].enabled && textures_.gen[0].mode == GL_SPHERE_MAP) ||
                                (textures_.gen[1].enabled && textures_.gen[1].mode == GL_SPHERE_MAP));
}

void Context::prepare_vertex_processing() {
  const bool sphere_map = sphere_map_texgen();
  if (lighting_.enabled || sphere_map) normal_matrix();  // computed when the modelview changed
  if (lighting_.enabled && (materials_dirty_ || vertex_materials_.empty())) {
    vertex_materials_.push_back(lighting_.material);
    materials_dirty_ = false;
  }
}

ProcessedVertex Context::process_vertex(const Vec4& object, Counters& c) {
  prepare_vertex_processing();
  count_vertex_processing(c, 1);
  return transform_vertex(object, current_.normal);
}

void Context::count_vertex_processing(Counters& c, std::uint64_t vertices) const {
  // The modelled machine lights every vertex (and both faces with two-sided lighting), and
  // evaluates each enabled texgen coordinate while a texture target is enabled; the counters
  // say so. (The simulator lights only the faces of polygons that survive culling, and a
  // display-list block's distinct vertices once: the same bits.)
  if (lighting_.enabled) c.lighting_evaluations += vertices * (lighting_.two_side ? 2 : 1);
  if (texturing_enabled_)
    for (const TexGenState& g : textures_.gen)
      if (g.enabled) c.texgen_evaluations += vertices;
}

ProcessedVertex Context::transform_vertex(const Vec4& object, const Vec3& normal) const {
  // §2.10-2.13: transformation, lighting inputs or colour, texture coordinates. The result
  // is assembled at the end from locals, with no call in between, so that the compiler drops
  // the default initialisers' stores (a 128-byte memset per vertex, a third of this
  // function's time when it was built in place).
  const Vec4 eye = transform_.modelview.back() * object;
  const Vec4 clip = transform_.projection.back() * eye;
  std::array<Vec4, 2> color{Vec4(0.0), Vec4(0.0)};
  std::uint32_t material_index = 0;
  bool light_pending = false;
  const bool sphere_map = sphere_map_texgen();
  Vec3 n(0.0);
  if (lighting_.enabled || sphere_map) {
    // §2.10.3: normals transform by the inverse transpose of the modelview's upper 3x3.
    const Mat4& inv = normal_matrix_;  // fresh: prepare_vertex_processing
    n = Vec3(normal.x * inv[0][0] + normal.y * inv[0][1] + normal.z * inv[0][2],
             normal.x * inv[1][0] + normal.y * inv[1][1] + normal.z * inv[1][2],
             normal.x * inv[2][0] + normal.y * inv[2][1] + normal.z * inv[2][2]);
    if (transform_.normalize) {
      const double len = std::sqrt(glm::dot(n, n));
      if (len > 0.0) n /= len;
    } else if (transform_.rescale_normal) {
      const double f = 1.0 / std::sqrt(inv[0][2] * inv[0][2] + inv[1][2] * inv[1][2] + inv[2][2] * inv[2][2]);
      n *= f;
    }
  }
  if (lighting_.enabled) {
    // Lit when the polygon's facing is known (light_pending_vertex).
    material_index = static_cast<std::uint32_t>(vertex_materials_.size() - 1);
    light_pending = true;
  } else {
    for (int k = 0; k < 4; ++k) color[0][k] = vertex_color(current_.color[k], fragment_bits_[k]);
    color[1] = color[0];
  }
  // Texture coordinates are carried only while a texture target is enabled: texgen (§2.10.4),
  // then the texture matrix.
  Vec4 tex(0.0, 0.0, 0.0, 1.0);
  if (texturing_enabled_) {
    Vec4 tc = current_.texcoord;
    for (int k = 0; k < 4; ++k) {
      const TexGenState& g = textures_.gen[static_cast<std::size_t>(k)];
      if (!g.enabled) continue;
      if (g.mode == GL_OBJECT_LINEAR) {
        tc[k] = glm::dot(g.object_plane, object);
      } else if (g.mode == GL_EYE_LINEAR) {
        tc[k] = glm::dot(g.eye_plane, eye);
      } else {
        // SPHERE_MAP: u = unit eye->vertex, r = u − 2n'(n'·u), m = 2·sqrt(rx² + ry² + (rz + 1)²).
        Vec3 u = Vec3(eye) / eye.w;
        const double len = std::sqrt(glm::dot(u, u));
        if (len > 0.0) u /= len;
        const Vec3 r = u - 2.0 * n * glm::dot(n, u);
        const double m = 2.0 * std::sqrt(r.x * r.x + r.y * r.y + (r.z + 1.0) * (r.z + 1.0));
        tc[k] = (k == 0 ? r.x : r.y) / m + 0.5;
      }
    }
    tex = transform_.texture.back() * tc;
  }
  ProcessedVertex v;
  v.clip = clip;
  v.eye = eye;
  v.color = color;
  v.tex = tex;
  v.normal_eye = light_pending ? n : Vec3(0.0);
  v.material_index = material_index;
  v.light_pending = light_pending;
  v.edge_flag = current_.edge_flag;
  return v;
}

void Context::light_pending_vertex(ProcessedVertex& v, int face) const {
  // §2.13.1 with the material current when the vertex was given; §2.13.6 clamp, A4 rounding.
  // No texturing between primary and secondary colour yet, so the colour sum happens here.
  const Material& m = vertex_materials_[v.material_index][static_cast<std::size_t>(face)];
  const LitColor lit = light_vertex(lighting_, m, v.eye, face == 0 ? v.normal_eye : -v.normal_eye);
  for (int k = 0; k < 4; ++k) {
    const double value = lit.primary[k] + (k < 3 ? lit.secondary[k] : 0.0);
    v.color[static_cast<std::size_t>(face)][k] = vertex_color(value, fragment_bits_[k]);
  }
  if (!lighting_.two_side) v.color[1] = v.color[0];
}

void Context::emit_primitive_vertex(const ProcessedVertex& v) {
  const std::uint64_t i = prim_vertex_count_++;
  auto& buf = prim_vertices_;
  switch (begin_mode_) {
    case GL_POINTS: draw_point(v); return;
    case GL_LINES:
      buf.push_back(v);
      if (buf.size() == 2) {
        line_stipple_counter_ = 0;  // §3.4.2: reset before every separate segment
        draw_line(buf[0], buf[1]);
        buf.clear();
      }
      return;
    case GL_LINE_STRIP: case GL_LINE_LOOP:
      // buf: the previous vertex; for a loop the first vertex before it (closed at End).
      if (!buf.empty()) draw_line(buf.back(), v);
      if (buf.size() == (begin_mode_ == GL_LINE_LOOP ? 2u : 1u)) buf.back() = v;
      else buf.push_back(v);
      return;
    case GL_TRIANGLES: {
      buf.push_back(v);
      if (buf.size() == 3) {
        const ProcessedVertex* p[3] = {&buf[0], &buf[1], &buf[2]};
        draw_polygon(p, 3, buf[2]);
        buf.clear();
      }
      return;
    }
    case GL_TRIANGLE_STRIP: {
      buf.push_back(v);
      if (buf.size() == 3) {
        // §2.6.1: triangle i is (i, i+1, i+2), with the first two swapped for odd i
        // so that every triangle keeps the strip's orientation.
        const ProcessedVertex* p[3] = {&buf[0], &buf[1], &buf[2]};
        if (i % 2 == 1) std::swap(p[0], p[1]);
        draw_polygon(p, 3, buf[2], false);
        buf.erase(buf.begin());
      }
      return;
    }
    case GL_TRIANGLE_FAN: {
      buf.push_back(v);
      if (buf.size() == 3) {
        const ProcessedVertex* p[3] = {&buf[0], &buf[1], &buf[2]};
        draw_polygon(p, 3, buf[2], false);
        buf.erase(buf.begin() + 1);
      }
      return;
    }
    case GL_QUADS: {
      buf.push_back(v);
      if (buf.size() == 4) {
        if (profile_.arithmetic.immediate_quads_as_triangle_pairs && !drawing_arrays_ &&
            polygon_.mode_front == GL_FILL && polygon_.mode_back == GL_FILL) {
          // The profile's decomposition (profile.hpp) of filled quads; the provoking vertex
          // stays v3. (A quad drawn as lines or points keeps its four edges.)
          const ProcessedVertex* first[3] = {&buf[0], &buf[1], &buf[3]};
          const ProcessedVertex* second[3] = {&buf[1], &buf[2], &buf[3]};
          draw_polygon(first, 3, buf[3]);
          draw_polygon(second, 3, buf[3]);
        } else {
          const ProcessedVertex* p[4] = {&buf[0], &buf[1], &buf[2], &buf[3]};
          draw_polygon(p, 4, buf[3]);
        }
        buf.clear();
      }
      return;
    }
    case GL_QUAD_STRIP: {
      buf.push_back(v);
      if (buf.size() == 4) {
        // §2.6.1: quad j is (2j, 2j+1, 2j+3, 2j+2); the provoking vertex is 2j+3.
        const ProcessedVertex* p[4] = {&buf[0], &buf[1], &buf[3], &buf[2]};
        draw_polygon(p, 4, buf[3], false);
        buf.erase(buf.begin(), buf.begin() + 2);
      }
      return;
    }
    default:  // GL_POLYGON: drawn at End
      buf.push_back(v);
      return;
  }
}

RasterVertex Context::to_window(const ProcessedVertex& v, int face) const {
  // §2.10.1: viewport transformation of normalised device coordinates.
  RasterVertex r;
  const double iw = 1.0 / v.clip.w;
  // A subnormal w (found by fuzzing) has an infinite reciprocal: divide instead, which keeps
  // x/w within [-1, 1] after clipping. Every other w keeps the reciprocal, and its bits.
  const bool tiny_w = !std::isfinite(iw);
  auto ndc = [&](double c) { return tiny_w ? c / v.clip.w : c * iw; };
  const double half_w = viewport_.width / 2.0, half_h = viewport_.height / 2.0;
  r.x = ndc(v.clip.x) * half_w + (viewport_.x + half_w);
  r.y = ndc(v.clip.y) * half_h + (viewport_.y + half_h);
  const double n = viewport_.near_val, f = viewport_.far_val;
  r.z = ndc(v.clip.z) * ((f - n) / 2.0) + (n + f) / 2.0;
  r.w = v.clip.w;
  r.color = v.color[face];
  r.tex = v.tex;
  r.eye_z = v.eye.z / v.eye.w;
  return r;
}


void Context::draw_point(const ProcessedVertex& v) {
  Counters& c = counters();
  ++c.primitives_in;
  if (!finite_vertex(v)) {
    warn_once("a vertex with NaN or infinite coordinates was dropped (its primitive is counted as clipped out)");
    ++c.primitives_clipped_out;
    return;
  }
  if (!point_inside(v, clip_planes_of(transform_))) {
    ++c.primitives_clipped_out;
    return;
  }
  TriangleOptions options;
  const FragmentStagesSetup& setup = primitive_stages_setup(options);
  ProcessedVertex lit = v;
  if (lit.light_pending) light_pending_vertex(lit, 0);
  const RasterVertex w = to_window(lit, 0);
  if (!w.finite_position()) {
    warn_once("a vertex with NaN or infinite window coordinates was dropped (its primitive is counted as clipped out)");
    ++c.primitives_clipped_out;
    return;
  }
  if (scratch_->lanes) {
    scratch_->lanes->point(w, polygon_.point_size, setup, c);
    raster_queued_ = true;
    return;
  }
  rasterize_point(w, polygon_.point_size, setup.target, scratch_->spans, fragment_sink(), c);
}

void Context::draw_line(const ProcessedVertex& va, const ProcessedVertex& vb) {
  Counters& c = counters();
  ++c.primitives_in;
  if (!finite_vertex(va) || !finite_vertex(vb)) {
    warn_once("a vertex with NaN or infinite coordinates was dropped (its primitive is counted as clipped out)");
    ++c.primitives_clipped_out;
    return;
  }
  // Lines take the front colours (§2.13.1); lit before clipping, which interpolates them.
  ProcessedVertex a = va, b = vb;
  if (a.light_pending) light_pending_vertex(a, 0);
  if (b.light_pending) light_pending_vertex(b, 0);
  // §2.13.7: flat shading takes the segment's second vertex (also for a loop's closing segment,
  // whose second vertex is the loop's first).
  const Vec4 flat_color = b.color[0];
  const Vec4 end = b.clip;
  bool cut = false;
  if (!clip_line(a, b, clip_planes_of(transform_), cut)) {
    ++c.primitives_clipped_out;
    return;
  }
  if (cut) ++c.primitives_clipped;
  const RasterVertex wa = to_window(a, 0), wb = to_window(b, 0);
  if (!wa.finite_position() || !wb.finite_position()) {
    warn_once("a vertex with NaN or infinite window coordinates was dropped (its primitive is counted as clipped out)");
    ++c.primitives_clipped_out;
    return;
  }
  rasterize_line_segment(wa, wb, flat_color, 0.0, b.clip != end);
}

void Context::rasterize_line_segment(const RasterVertex& a, const RasterVertex& b, const Vec4& flat_color,
                                     double depth_offset, bool open_end) {
  Counters& c = counters();
  TriangleOptions setup_options;
  const FragmentStagesSetup& setup = primitive_stages_setup(setup_options);
  TriangleOptions attributes = setup_options;
  attributes.flat = lighting_.shade_model == GL_FLAT;
  attributes.flat_color = flat_color;
  LineOptions options;
  options.width = line_width_of(polygon_.line_width);
  options.depth_offset = depth_offset;
  options.open_end = open_end;
  if (polygon_.line_stipple) {
    options.stipple = true;
    options.stipple_pattern = polygon_.stipple_pattern;
    options.stipple_factor = polygon_.stipple_repeat;
    options.stipple_counter = line_stipple_counter_;
    line_stipple_counter_ += line_fragment_count(a, b, options.width, open_end, setup.target.subpixel_bits);
  }
  if (scratch_->lanes) {
    scratch_->lanes->line(a, b, attributes, options, setup, c);
    raster_queued_ = true;
    return;
  }
  rasterize_line(a, b, attributes, options, setup.target, scratch_->spans, fragment_sink(), c);
}

double Context::polygon_mode_offset(const std::vector<RasterVertex>& win, const RasterTarget& target) const {
  // §3.5.5 (A7) on the plane of the first three vertices (A34), snapped as for filling (A5); a
  // degenerate first triangle has slope 0.
  const double r = target.depth_bits > 0 ? 1.0 / static_cast<double>(max_code(target.depth_bits)) : 0.0;
  double m = 0.0;
  if (win.size() >= 3) {
    const double unit = static_cast<double>(std::int64_t{2} << target.subpixel_bits);
    double x[3], y[3];
    for (int k = 0; k < 3; ++k) {
      x[k] = static_cast<double>(snap_coordinate(win[static_cast<std::size_t>(k)].x, target.subpixel_bits)) / unit;
      y[k] = static_cast<double>(snap_coordinate(win[static_cast<std::size_t>(k)].y, target.subpixel_bits)) / unit;
    }
    const double ex1 = x[1] - x[0], ey1 = y[1] - y[0], ex2 = x[2] - x[0], ey2 = y[2] - y[0];
    const double det = ex1 * ey2 - ex2 * ey1;
    if (det != 0.0) {
      const double dz1 = win[1].z - win[0].z, dz2 = win[2].z - win[0].z;
      m = std::max(std::fabs((dz1 * ey2 - dz2 * ey1) / det), std::fabs((dz2 * ex1 - dz1 * ex2) / det));
    }
  }
  return m * polygon_.offset_factor + r * polygon_.offset_units;
}

bool Context::assemble_polygon(const ProcessedVertex* const* vertices, int count, const ProcessedVertex& provoking,
                               PolygonWork& work, Counters& c) const {
  ++c.primitives_in;
  std::vector<ProcessedVertex>& poly = work.polygon;
  poly.clear();
  for (int k = 0; k < count; ++k) {
    if (!finite_vertex(*vertices[k])) {
      work.warnings |= PolygonWork::kNonFiniteVertex;
      ++c.primitives_clipped_out;
      return false;
    }
    poly.push_back(*vertices[k]);
    if (!work.edge_flags) poly.back().edge_flag = true;
  }
  bool cut = false;
  if (!clip_polygon(poly, work.clip_scratch, clip_planes_of(transform_), cut)) {
    ++c.primitives_clipped_out;
    return false;
  }
  if (cut) ++c.primitives_clipped;

  // Window coordinates, then facing from the signed area (§3.5.1, eq. 3.6).
  std::vector<RasterVertex>& win = work.window;
  win.resize(poly.size());
  for (std::size_t k = 0; k < poly.size(); ++k) {
    win[k] = to_window(poly[k], 0);
    if (!win[k].finite_position()) {
      work.warnings |= PolygonWork::kNonFiniteWindow;
      ++c.primitives_clipped_out;
      return false;
    }
  }
  const Facing facing = polygon_facing(win.data(), win.size(), c);
  if (!facing.drawn) return false;
  const int face = facing.face;
  ProcessedVertex flat_source = provoking;
  if (provoking.light_pending) {
    // Light the polygon's vertices for the face that is drawn, then clip again with the lit
    // colours (the same clip, so the same positions; trivially inside polygons skip it).
    if (cut) {
      poly.clear();
      for (int k = 0; k < count; ++k) {
        poly.push_back(*vertices[k]);
        if (!work.edge_flags) poly.back().edge_flag = true;
        light_pending_vertex(poly.back(), face);
      }
      clip_polygon(poly, work.clip_scratch, clip_planes_of(transform_), cut);
    } else {
      for (ProcessedVertex& v : poly) light_pending_vertex(v, face);  // poly holds the vertices themselves
    }
    light_pending_vertex(flat_source, face);
    for (std::size_t k = 0; k < poly.size(); ++k) win[k].color = poly[k].color[static_cast<std::size_t>(face)];
  } else if (face == 1) {
    for (std::size_t k = 0; k < poly.size(); ++k) win[k].color = poly[k].color[1];
  }
  work.mode = facing.front ? polygon_.mode_front : polygon_.mode_back;
  work.flat_color = flat_source.color[static_cast<std::size_t>(face)];
  return true;
}

Context::Facing Context::polygon_facing(const RasterVertex* win, std::size_t count, Counters& c) const {
  double area = 0.0;
  for (std::size_t k = 0; k < count; ++k) {
    const RasterVertex& a = win[k];
    const RasterVertex& b = win[(k + 1) % count];
    area += a.x * b.y - b.x * a.y;
  }
  return facing_of_area(area, c);
}

Context::Facing Context::triangle_facing(const RasterVertex& a, const RasterVertex& b, const RasterVertex& v,
                                         Counters& c) const {
  double area = 0.0;
  area += a.x * b.y - b.x * a.y;
  area += b.x * v.y - v.x * b.y;
  area += v.x * a.y - a.x * v.y;
  return facing_of_area(area, c);
}

Context::Facing Context::facing_of_area(double area, Counters& c) const {
  Facing f;
  f.front = (polygon_.front_face == GL_CCW) ? area > 0.0 : area < 0.0;
  if (polygon_.cull_enabled && (polygon_.cull_face == GL_FRONT_AND_BACK ||
                                (f.front ? polygon_.cull_face == GL_FRONT : polygon_.cull_face == GL_BACK))) {
    ++c.primitives_culled;
    return f;
  }
  f.drawn = true;
  f.face = (lighting_.enabled && lighting_.two_side && !f.front) ? 1 : 0;
  return f;
}

void Context::note_polygon_warnings(unsigned warnings) {
  if (warnings & PolygonWork::kNonFiniteVertex)
    warn_once("a vertex with NaN or infinite coordinates was dropped (its primitive is counted as clipped out)");
  if (warnings & PolygonWork::kNonFiniteWindow)
    warn_once("a vertex with NaN or infinite window coordinates was dropped (its primitive is counted as clipped out)");
}

TriangleOptions Context::polygon_options(const TriangleOptions& setup_options, const Vec4& flat_color) const {
  TriangleOptions options = setup_options;
  options.flat = lighting_.shade_model == GL_FLAT;
  options.flat_color = flat_color;
  options.offset = polygon_.offset_fill;
  options.offset_factor = polygon_.offset_factor;
  options.offset_units = polygon_.offset_units;
  return options;
}

void Context::draw_polygon(const ProcessedVertex* const* vertices, int count, const ProcessedVertex& provoking,
                           bool edge_flags) {
  Counters& c = counters();
  PolygonWork& work = scratch_->polygon_work;
  work.warnings = 0;
  work.edge_flags = edge_flags;
  const bool drawn = assemble_polygon(vertices, count, provoking, work, c);
  note_polygon_warnings(work.warnings);
  if (!drawn) return;
  const std::vector<RasterVertex>& win = work.window;
  TriangleOptions setup_options;
  const FragmentStagesSetup& setup = primitive_stages_setup(setup_options);
  RasterLanes* lanes = scratch_->lanes.get();
  if (lanes) raster_queued_ = true;
  const std::vector<ProcessedVertex>& poly = work.polygon;  // the same vertices, with their edge flags
  if (work.mode == GL_POINT) {
    // §3.5.4: the vertices that start a boundary edge, as points; §3.5.5 offset when enabled.
    const double offset = polygon_.offset_point ? polygon_mode_offset(win, setup.target) : 0.0;
    for (std::size_t k = 0; k < win.size(); ++k) {
      if (!poly[k].edge_flag) continue;
      RasterVertex w = win[k];
      w.z += offset;
      if (lanes) lanes->point(w, polygon_.point_size, setup, c);
      else rasterize_point(w, polygon_.point_size, setup.target, scratch_->spans, fragment_sink(), c);
    }
    return;
  }
  if (work.mode == GL_LINE) {
    // §3.5.4: the boundary edges (an edge starts at a vertex whose flag is true) as connected
    // segments for the stipple, its counter reset at each polygon (A33); §3.5.5 offset.
    const double offset = polygon_.offset_line ? polygon_mode_offset(win, setup.target) : 0.0;
    line_stipple_counter_ = 0;
    for (std::size_t k = 0; k < win.size(); ++k)
      if (poly[k].edge_flag) rasterize_line_segment(win[k], win[(k + 1) % win.size()], work.flat_color, offset);
    return;
  }
  const TriangleOptions options = polygon_options(setup_options, work.flat_color);
  // §3.5.1: a convex polygon may be decomposed; a fan from the first vertex.
  for (std::size_t k = 1; k + 1 < win.size(); ++k) {
    if (lanes) lanes->triangle(win[0], win[k], win[k + 1], options, setup, c);
    else rasterize_triangle(win[0], win[k], win[k + 1], options, setup.target, scratch_->spans, fragment_sink(), c);
  }
}

}  // namespace passim
