#include "programs/scenes.hpp"

#include <cmath>
#include <vector>

namespace passim {
namespace {

struct MeshVertex {
  float n[3];
  float p[3];
};

void emit(Context& ctx, const std::vector<MeshVertex>& mesh) {
  ctx.glBegin(GL_TRIANGLES);
  for (const MeshVertex& v : mesh) {
    ctx.glNormal3fv(v.n);
    ctx.glVertex3fv(v.p);
  }
  ctx.glEnd();
}

constexpr float kPi = 3.14159265358979323846f;

MeshVertex sphere_point(float r, float cx, float cy, float cz, int i, int j, int slices, int stacks) {
  const float th = kPi * static_cast<float>(j) / static_cast<float>(stacks);
  const float ph = 2.0f * kPi * static_cast<float>(i) / static_cast<float>(slices);
  const float nx = std::sin(th) * std::cos(ph), ny = std::cos(th), nz = std::sin(th) * std::sin(ph);
  return {{nx, ny, nz}, {cx + r * nx, cy + r * ny, cz + r * nz}};
}

MeshVertex torus_point(float R, float r, float cx, float cy, float cz, float tilt, int i, int j, int nmaj, int nmin) {
  const float u = 2.0f * kPi * static_cast<float>(i) / static_cast<float>(nmaj);
  const float v = 2.0f * kPi * static_cast<float>(j) / static_cast<float>(nmin);
  const float nx = std::cos(v) * std::cos(u), ny = std::sin(v), nz = std::cos(v) * std::sin(u);
  const float x = (R + r * std::cos(v)) * std::cos(u), y = r * std::sin(v), z = (R + r * std::cos(v)) * std::sin(u);
  const float ct = std::cos(tilt), st = std::sin(tilt);
  return {{nx, ny * ct - nz * st, ny * st + nz * ct}, {cx + x, cy + y * ct - z * st, cz + y * st + z * ct}};
}

}  // namespace

int emit_bench_scene(Context& ctx) {
  std::vector<MeshVertex> ground, sphere, torus;
  const float half = 8.0f, s = 2.0f * half / 16.0f;
  for (int j = 0; j < 16; ++j)
    for (int i = 0; i < 16; ++i) {
      const float x0 = -half + s * static_cast<float>(i), x1 = x0 + s;
      const float z0 = -half + s * static_cast<float>(j), z1 = z0 + s;
      for (const auto& [x, z] : {std::pair{x0, z0}, {x0, z1}, {x1, z1}, {x0, z0}, {x1, z1}, {x1, z0}})
        ground.push_back({{0, 1, 0}, {x, 0, z}});
    }
  const int slices = 48, stacks = 36;
  for (int j = 0; j < stacks; ++j)
    for (int i = 0; i < slices; ++i) {
      auto P = [&](int a, int b) { return sphere_point(1.6f, -2.0f, 1.6f, 0.0f, a, b, slices, stacks); };
      if (j != 0)
        for (const auto& v : {P(i, j), P(i + 1, j), P(i + 1, j + 1)}) sphere.push_back(v);
      if (j != stacks - 1)
        for (const auto& v : {P(i, j), P(i + 1, j + 1), P(i, j + 1)}) sphere.push_back(v);
    }
  for (int i = 0; i < 48; ++i)
    for (int j = 0; j < 32; ++j) {
      auto P = [&](int a, int b) { return torus_point(1.6f, 0.5f, 2.4f, 1.5f, 0.8f, 1.1f, a, b, 48, 32); };
      for (const auto& v : {P(i, j), P(i + 1, j + 1), P(i + 1, j), P(i, j), P(i, j + 1), P(i + 1, j + 1)})
        torus.push_back(v);
    }
  ctx.glColor3f(0.55f, 0.75f, 0.45f);
  emit(ctx, ground);
  ctx.glColor3f(0.85f, 0.35f, 0.30f);
  emit(ctx, sphere);
  ctx.glColor3f(0.35f, 0.45f, 0.90f);
  emit(ctx, torus);
  return static_cast<int>((ground.size() + sphere.size() + torus.size()) / 3);
}

void setup_bench_scene_view(Context& ctx) {
  const FramebufferConfig& c = ctx.config();
  ctx.glMatrixMode(GL_PROJECTION);
  ctx.glLoadIdentity();
  ctx.gluPerspective(45.0, static_cast<double>(c.width) / c.height, 1.0, 40.0);
  ctx.glMatrixMode(GL_MODELVIEW);
  ctx.glLoadIdentity();
  ctx.gluLookAt(0, 6, 12, 0, 1, 0, 0, 1, 0);
  ctx.glClearColor(0.2f, 0.2f, 0.3f, 1.0f);
  ctx.glEnable(GL_DEPTH_TEST);
  ctx.glDepthFunc(GL_LESS);
  ctx.glShadeModel(GL_SMOOTH);
  ctx.glEnable(GL_CULL_FACE);
  ctx.glCullFace(GL_BACK);
  const float pos[4] = {6.0f, 12.0f, 6.0f, 1.0f};
  ctx.glLightfv(GL_LIGHT0, GL_POSITION, pos);
  ctx.glEnable(GL_LIGHT0);
  ctx.glEnable(GL_LIGHTING);
  ctx.glColorMaterial(GL_FRONT_AND_BACK, GL_AMBIENT_AND_DIFFUSE);
  ctx.glEnable(GL_COLOR_MATERIAL);
}

}  // namespace passim
