#include "programs/scene.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <glm/gtc/matrix_transform.hpp>
#include <stdexcept>

#include "pipeline/memory_budget.hpp"
#include "trace_io/obj_file.hpp"

namespace passim {
namespace {

constexpr double kPi = 3.14159265358979323846;

// Mesh builders. Every triangle is counter-clockwise seen from the side its normals
// point to, so back-face culling keeps the outside.
struct MeshBuilder {
  Mesh mesh;
  MeshBuilder(std::string name, glm::vec3 color, bool receiver = true) {
    mesh.name = std::move(name);
    mesh.color = color;
    mesh.receiver = receiver;
  }
  void vertex(glm::dvec3 p, glm::dvec3 n) {
    for (int k = 0; k < 3; ++k) {
      mesh.positions.push_back(static_cast<float>(p[k]));
      mesh.normals.push_back(static_cast<float>(n[k]));
    }
  }
  void triangle(glm::dvec3 a, glm::dvec3 b, glm::dvec3 c, glm::dvec3 n) {
    vertex(a, n), vertex(b, n), vertex(c, n);
  }
  // A quad a b c d, counter-clockwise seen from where n points.
  void quad(glm::dvec3 a, glm::dvec3 b, glm::dvec3 c, glm::dvec3 d, glm::dvec3 n) {
    triangle(a, b, c, n);
    triangle(a, c, d, n);
  }
};

// A ground grid in y = 0 of cells x cells, from -half to half in x and z.
Mesh ground(double half, int cells, glm::vec3 color) {
  MeshBuilder b("ground", color);
  const double s = 2.0 * half / cells;
  for (int j = 0; j < cells; ++j)
    for (int i = 0; i < cells; ++i) {
      const double x0 = -half + s * i, x1 = x0 + s, z0 = -half + s * j, z1 = z0 + s;
      b.quad({x0, 0, z0}, {x0, 0, z1}, {x1, 0, z1}, {x1, 0, z0}, {0, 1, 0});
    }
  return b.mesh;
}

Mesh sphere(std::string name, glm::dvec3 c, double r, int slices, int stacks, glm::vec3 color) {
  MeshBuilder b(std::move(name), color);
  auto normal = [&](int i, int j) {
    const double th = kPi * j / stacks, ph = 2.0 * kPi * i / slices;
    return glm::dvec3(std::sin(th) * std::cos(ph), std::cos(th), std::sin(th) * std::sin(ph));
  };
  auto put = [&](int i, int j) { b.vertex(c + r * normal(i, j), normal(i, j)); };
  for (int j = 0; j < stacks; ++j)
    for (int i = 0; i < slices; ++i) {
      if (j != 0) put(i, j), put(i + 1, j), put(i + 1, j + 1);
      if (j != stacks - 1) put(i, j), put(i + 1, j + 1), put(i, j + 1);
    }
  return b.mesh;
}

// A torus around the y axis, tilted by `tilt` radians about x.
Mesh torus(std::string name, glm::dvec3 c, double major, double minor, double tilt, int nmaj, int nmin,
           glm::vec3 color) {
  MeshBuilder b(std::move(name), color);
  const glm::dmat3 rot = glm::dmat3(glm::rotate(glm::dmat4(1.0), tilt, glm::dvec3(1, 0, 0)));
  auto put = [&](int i, int j) {
    const double u = 2.0 * kPi * i / nmaj, v = 2.0 * kPi * j / nmin;
    const glm::dvec3 n(std::cos(v) * std::cos(u), std::sin(v), std::cos(v) * std::sin(u));
    const glm::dvec3 p((major + minor * std::cos(v)) * std::cos(u), minor * std::sin(v),
                       (major + minor * std::cos(v)) * std::sin(u));
    b.vertex(c + rot * p, rot * n);
  };
  for (int i = 0; i < nmaj; ++i)
    for (int j = 0; j < nmin; ++j) {
      put(i, j), put(i + 1, j + 1), put(i + 1, j);
      put(i, j), put(i, j + 1), put(i + 1, j + 1);
    }
  return b.mesh;
}

// An axis-aligned box from lo to hi, turned by `yaw` radians about its vertical axis.
void box(MeshBuilder& b, glm::dvec3 lo, glm::dvec3 hi, double yaw = 0.0) {
  const glm::dvec3 mid = 0.5 * (lo + hi);
  const glm::dmat3 rot = glm::dmat3(glm::rotate(glm::dmat4(1.0), yaw, glm::dvec3(0, 1, 0)));
  auto P = [&](double x, double y, double z) { return mid + rot * (glm::dvec3(x, y, z) - mid); };
  auto N = [&](double x, double y, double z) { return rot * glm::dvec3(x, y, z); };
  const double x0 = lo.x, y0 = lo.y, z0 = lo.z, x1 = hi.x, y1 = hi.y, z1 = hi.z;
  b.quad(P(x0, y1, z0), P(x0, y1, z1), P(x1, y1, z1), P(x1, y1, z0), N(0, 1, 0));   // top
  b.quad(P(x0, y0, z0), P(x1, y0, z0), P(x1, y0, z1), P(x0, y0, z1), N(0, -1, 0));  // bottom
  b.quad(P(x0, y0, z1), P(x1, y0, z1), P(x1, y1, z1), P(x0, y1, z1), N(0, 0, 1));   // front
  b.quad(P(x1, y0, z0), P(x0, y0, z0), P(x0, y1, z0), P(x1, y1, z0), N(0, 0, -1));  // back
  b.quad(P(x1, y0, z1), P(x1, y0, z0), P(x1, y1, z0), P(x1, y1, z1), N(1, 0, 0));   // right
  b.quad(P(x0, y0, z0), P(x0, y0, z1), P(x0, y1, z1), P(x0, y1, z0), N(-1, 0, 0));  // left
}

// A vertical cylinder (a thin pole) standing on the ground, with a top cap.
void cylinder(MeshBuilder& b, glm::dvec3 base, double r, double h, int sides) {
  auto rim = [&](int i, double y) {
    const double a = 2.0 * kPi * i / sides;
    return glm::dvec3(base.x + r * std::cos(a), base.y + y, base.z + r * std::sin(a));
  };
  for (int i = 0; i < sides; ++i) {
    const double a0 = 2.0 * kPi * i / sides, a1 = 2.0 * kPi * (i + 1) / sides;
    const glm::dvec3 n0(std::cos(a0), 0, std::sin(a0)), n1(std::cos(a1), 0, std::sin(a1));
    // Seen from outside, counter-clockwise means decreasing angle at the top edge.
    b.vertex(rim(i, 0), n0), b.vertex(rim(i + 1, h), n1), b.vertex(rim(i + 1, 0), n1);
    b.vertex(rim(i, 0), n0), b.vertex(rim(i, h), n0), b.vertex(rim(i + 1, h), n1);
    b.triangle(glm::dvec3(base.x, base.y + h, base.z), rim(i + 1, h), rim(i, h), {0, 1, 0});
  }
}

// A flat star-shaped plate at height y (top and bottom faces): its edges run at every
// angle across the shadow map's sampling grid.
Mesh star_plate(double y, double outer, double inner, int points, double turn, glm::vec3 color) {
  MeshBuilder b("star", color, false);
  const glm::dvec3 c(0, y, 0);
  auto corner = [&](int k) {
    const double a = turn + kPi * k / points;
    const double r = k % 2 == 0 ? outer : inner;
    return glm::dvec3(r * std::cos(a), y, r * std::sin(a));
  };
  for (int k = 0; k < 2 * points; ++k) {
    b.triangle(c, corner(k + 1), corner(k), {0, 1, 0});
    b.triangle(c, corner(k), corner(k + 1), {0, -1, 0});
  }
  return b.mesh;
}

Scene paper_scene() {
  Scene s;
  s.name = "paper";
  s.description = "Figure 7's kind of scene: a ground plane, two spheres, a tilted torus, boxes, thin poles "
                  "and a slatted fence; one light; 800x600 camera; 512² map";
  s.meshes.push_back(ground(7.0, 40, {0.75f, 0.75f, 0.70f}));
  s.meshes.push_back(sphere("sphere", {-3.2, 1.4, -1.2}, 1.4, 32, 20, {0.85f, 0.35f, 0.30f}));
  s.meshes.push_back(sphere("small-sphere", {2.8, 0.8, 2.4}, 0.8, 24, 16, {0.90f, 0.80f, 0.30f}));
  s.meshes.push_back(torus("torus", {1.6, 1.9, -2.4}, 1.3, 0.4, 1.0, 36, 18, {0.35f, 0.45f, 0.90f}));
  MeshBuilder boxes("boxes", {0.55f, 0.70f, 0.45f});
  box(boxes, {-1.0, 0.0, 1.5}, {0.2, 1.2, 2.7}, 0.4);
  box(boxes, {4.0, 0.0, -1.0}, {5.0, 2.2, 0.0}, -0.3);
  box(boxes, {-5.5, 0.0, 2.5}, {-4.7, 0.6, 3.3}, 0.9);
  s.meshes.push_back(boxes.mesh);
  MeshBuilder poles("poles", {0.60f, 0.60f, 0.65f});
  for (const glm::dvec3 p : {glm::dvec3(-1.2, 0, -3.5), glm::dvec3(0.4, 0, -0.4), glm::dvec3(3.4, 0, 1.0),
                             glm::dvec3(-2.6, 0, 2.0)})
    cylinder(poles, p, 0.07, 3.2, 16);
  s.meshes.push_back(poles.mesh);
  MeshBuilder fence("fence", {0.70f, 0.55f, 0.40f});
  for (int k = 0; k < 9; ++k) {
    const double x = -5.2 + 0.45 * k;
    box(fence, {x, 0.0, -4.8}, {x + 0.08, 1.8, -4.72});
  }
  box(fence, {-5.3, 1.5, -4.82}, {-1.4, 1.58, -4.70});
  s.meshes.push_back(fence.mesh);
  s.camera.eye = {0.0, 7.0, 12.5};
  s.camera.center = {0.0, 0.8, 0.0};
  s.camera.fovy_degrees = 45.0;
  s.camera.near_plane = 2.0;
  s.camera.far_plane = 40.0;
  s.light.eye = {-8.0, 18.0, 9.0};
  fit_light_frustum(s);
  return s;
}

Scene fig8_scene() {
  Scene s;
  s.name = "fig8";
  s.description = "Figure 8's kind of scene: a cluster of spheres, boxes and a torus on a ground plane, "
                  "1024² map";
  s.default_map_size = 1024;
  s.meshes.push_back(ground(8.0, 24, {0.70f, 0.72f, 0.75f}));
  for (int k = 0; k < 5; ++k) {
    const double a = 2.0 * kPi * k / 5.0;
    s.meshes.push_back(sphere(fmt::format("sphere{}", k), {2.6 * std::cos(a), 0.7, 2.6 * std::sin(a)}, 0.7, 24,
                              16, {0.8f, 0.4f + 0.1f * static_cast<float>(k), 0.3f}));
  }
  s.meshes.push_back(torus("torus", {0.0, 1.6, 0.0}, 1.1, 0.3, 0.5, 36, 16, {0.3f, 0.5f, 0.9f}));
  MeshBuilder boxes("boxes", {0.55f, 0.70f, 0.45f});
  box(boxes, {-0.5, 0.0, -0.5}, {0.5, 1.0, 0.5}, 0.3);
  box(boxes, {3.5, 0.0, -3.5}, {4.3, 2.5, -2.7}, 0.2);
  s.meshes.push_back(boxes.mesh);
  s.camera.eye = {0.0, 6.0, 9.0};
  s.camera.center = {0.0, 0.6, 0.0};
  s.camera.near_plane = 2.0;
  s.camera.far_plane = 30.0;
  s.light.eye = {-5.0, 10.0, 4.0};
  fit_light_frustum(s);
  return s;
}

Scene edges_scene() {
  Scene s;
  s.name = "edges";
  s.description = "A 13-point star plate 1.5 above a flat ground, lit from straight above: its edges cross "
                  "the map's grid at every angle and phase, so every count of shadowed samples occurs";
  s.meshes.push_back(ground(4.0, 4, {0.8f, 0.8f, 0.8f}));
  s.meshes.push_back(star_plate(1.5, 2.6, 1.1, 13, 0.1234, {0.9f, 0.5f, 0.3f}));
  s.camera.eye = {0.0, 9.0, 3.0};
  s.camera.center = {0.0, 0.0, 0.0};
  s.camera.fovy_degrees = 40.0;
  s.camera.near_plane = 4.0;
  s.camera.far_plane = 16.0;
  s.light.eye = {0.0, 12.0, 0.0};
  s.light.up = {0.0, 0.0, -1.0};
  fit_light_frustum(s);
  return s;
}

Scene obj_scene(const std::string& file) {
  // The user's own file, named on the command line: its folder is where it (and its material
  // library) may be read from.
  const std::filesystem::path path(file);
  std::vector<ObjShape> shapes;
  try {
    shapes = read_obj(SideFiles(path.parent_path()), path.filename().string(), kDefaultMemoryBudget);
  } catch (const std::runtime_error& e) {  // ObjError, SideFileRefused
    throw std::runtime_error(fmt::format("{}: {}", file, e.what()));
  }
  Scene s;
  s.name = path.filename().string();
  s.description = fmt::format("OBJ file {} on a ground plane", file);
  glm::dvec3 lo(1e300), hi(-1e300);
  for (const ObjShape& shape : shapes) {
    MeshBuilder b(shape.name.empty() ? "object" : shape.name, {0.8f, 0.8f, 0.8f});
    if (shape.diffuse) b.mesh.color = {(*shape.diffuse)[0], (*shape.diffuse)[1], (*shape.diffuse)[2]};
    for (std::size_t t = 0; t + 2 < shape.corners.size(); t += 3) {
      glm::dvec3 p[3], n[3];
      bool have_normals = true;
      for (int k = 0; k < 3; ++k) {
        const ObjCorner& c = shape.corners[t + static_cast<std::size_t>(k)];
        p[k] = {c.position[0], c.position[1], c.position[2]};
        if (c.normal) n[k] = {(*c.normal)[0], (*c.normal)[1], (*c.normal)[2]};
        else have_normals = false;
        lo = glm::min(lo, p[k]);
        hi = glm::max(hi, p[k]);
      }
      if (!have_normals) {
        glm::dvec3 face = glm::cross(p[1] - p[0], p[2] - p[0]);
        const double len = glm::length(face);
        face = len > 0.0 ? face / len : glm::dvec3(0, 1, 0);
        n[0] = n[1] = n[2] = face;
      }
      for (int k = 0; k < 3; ++k) b.vertex(p[k], n[k]);
    }
    if (b.mesh.triangles() > 0) s.meshes.push_back(std::move(b.mesh));
  }
  if (s.meshes.empty()) throw std::runtime_error(fmt::format("{}: the OBJ file has no faces", file));
  // Put the object on a ground plane: normalise it to a radius of 3 standing at y = 0.
  const glm::dvec3 mid = 0.5 * (lo + hi);
  const double radius = std::max(0.5 * glm::length(hi - lo), 1e-9);
  const double scale = 3.0 / radius;
  for (Mesh& m : s.meshes)
    for (std::size_t k = 0; k < m.positions.size(); k += 3) {
      m.positions[k] = static_cast<float>((m.positions[k] - mid.x) * scale);
      m.positions[k + 1] = static_cast<float>((m.positions[k + 1] - lo.y) * scale);
      m.positions[k + 2] = static_cast<float>((m.positions[k + 2] - mid.z) * scale);
    }
  s.meshes.insert(s.meshes.begin(), ground(7.0, 16, {0.75f, 0.75f, 0.70f}));
  s.camera.eye = {0.0, 6.5, 11.0};
  s.camera.center = {0.0, (hi.y - lo.y) * scale * 0.4, 0.0};
  s.camera.near_plane = 2.0;
  s.camera.far_plane = 40.0;
  s.light.eye = {-5.0, 12.0, 6.0};
  fit_light_frustum(s);
  return s;
}

}  // namespace

glm::dmat4 View::view_matrix() const { return glm::lookAt(eye, center, up); }

glm::dmat4 View::projection_matrix(double aspect) const {
  return glm::perspective(glm::radians(fovy_degrees), aspect, near_plane, far_plane);
}

int Scene::triangles() const {
  int n = 0;
  for (const Mesh& m : meshes) n += m.triangles();
  return n;
}

void fit_light_frustum(Scene& scene) {
  View& light = scene.light;
  glm::dvec3 lo(1e300), hi(-1e300);
  for (const Mesh& m : scene.meshes)
    if (m.receiver)
      for (std::size_t k = 0; k + 2 < m.positions.size(); k += 3)
        lo = glm::min(lo, glm::dvec3(m.positions[k], m.positions[k + 1], m.positions[k + 2])),
        hi = glm::max(hi, glm::dvec3(m.positions[k], m.positions[k + 1], m.positions[k + 2]));
  light.center = 0.5 * (lo + hi);
  const glm::dvec3 dir = glm::normalize(light.center - light.eye);
  if (std::abs(glm::dot(dir, glm::normalize(light.up))) > 0.99) light.up = {0.0, 0.0, -1.0};
  // The field of view: the widest angle of a receiver vertex from the light's axis.
  // Near and far: the scene's bounding sphere seen from the light (the usual set-up of
  // a light frustum; it spends the depth encoding on the whole sphere).
  const glm::dmat4 view = light.view_matrix();
  double tan_half = 0.0;
  glm::dvec3 all_lo(1e300), all_hi(-1e300);
  for (const Mesh& m : scene.meshes)
    for (std::size_t k = 0; k + 2 < m.positions.size(); k += 3) {
      const glm::dvec3 p(m.positions[k], m.positions[k + 1], m.positions[k + 2]);
      all_lo = glm::min(all_lo, p), all_hi = glm::max(all_hi, p);
      const glm::dvec4 e = view * glm::dvec4(p, 1.0);
      const double depth = -e.z;
      if (m.receiver && depth > 0.0) tan_half = std::max({tan_half, std::abs(e.x) / depth, std::abs(e.y) / depth});
    }
  light.fovy_degrees = glm::degrees(2.0 * std::atan(std::min(tan_half * 1.02, 20.0)));
  const glm::dvec3 mid = 0.5 * (all_lo + all_hi);
  const double radius = 0.5 * glm::length(all_hi - all_lo);
  const double dist = glm::dot(mid - light.eye, glm::normalize(light.center - light.eye));
  light.near_plane = std::max(dist - radius, 0.01 * (dist + radius));
  light.far_plane = dist + radius;
}

std::vector<std::string> builtin_scene_names() { return {"paper", "fig8", "edges"}; }

Scene make_scene(const std::string& name) {
  if (name == "paper") return paper_scene();
  if (name == "fig8") return fig8_scene();
  if (name == "edges") return edges_scene();
  if (name.size() > 4 && name.compare(name.size() - 4, 4, ".obj") == 0) return obj_scene(name);
  throw std::runtime_error(fmt::format("unknown scene '{}' (paper, fig8, edges, or an .obj file)", name));
}

void draw_scene(Context& ctx, const Scene& scene) {
  ctx.glEnableClientState(GL_VERTEX_ARRAY);
  ctx.glEnableClientState(GL_NORMAL_ARRAY);
  for (const Mesh& m : scene.meshes) {
    ctx.glColor3f(m.color.r, m.color.g, m.color.b);
    ctx.glVertexPointer(3, GL_FLOAT, 0, m.positions.data());
    ctx.glNormalPointer(GL_FLOAT, 0, m.normals.data());
    ctx.glDrawArrays(GL_TRIANGLES, 0, static_cast<GLsizei>(m.positions.size() / 3));
  }
  ctx.glDisableClientState(GL_VERTEX_ARRAY);
  ctx.glDisableClientState(GL_NORMAL_ARRAY);
}

}  // namespace passim
