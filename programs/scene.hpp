// The scenes the pass programs draw: triangle meshes with per-vertex normals, one
// light with the frustum its shadow map uses, and a camera (docs/programs.md).
#pragma once
#include <filesystem>
#include <glm/glm.hpp>
#include <string>
#include <vector>

#include "pipeline/context.hpp"

namespace passim {

struct Mesh {
  std::string name;
  std::vector<float> positions;  // x y z per vertex, three vertices per triangle
  std::vector<float> normals;    // one per vertex
  glm::vec3 color{0.8f};
  bool receiver = true;  // counted when the light frustum is fitted to the receivers

  int triangles() const { return static_cast<int>(positions.size() / 9); }
};

// A perspective view: the light's and the camera's are both this.
struct View {
  glm::dvec3 eye{0.0}, center{0.0}, up{0.0, 1.0, 0.0};
  double fovy_degrees = 45.0;
  double near_plane = 1.0, far_plane = 100.0;

  glm::dmat4 view_matrix() const;
  glm::dmat4 projection_matrix(double aspect) const;
};

struct Scene {
  std::string name;
  std::string description;
  std::vector<Mesh> meshes;
  View camera;
  View light;  // the light is a point light at light.eye; its frustum covers the receivers
  int default_map_size = 512;

  int triangles() const;
};

// The built-in scenes: "paper" (Figure 7's kind: ~7,000 triangles, ground, spheres, a
// torus, boxes, thin poles and slats), "fig8" (Figure 8: a denser cluster, 1024² map) and
// "edges" (a star-shaped plate over a flat ground, lit from straight above, so that every
// number of shadowed samples occurs along its edges).
std::vector<std::string> builtin_scene_names();
// Builds a built-in scene, or loads an OBJ file (any name ending in .obj) with a ground
// plane under it and the light and camera framing it. Throws std::runtime_error with
// the file's name and tinyobjloader's message when it cannot.
Scene make_scene(const std::string& name_or_file);

// Fits the light's near/far planes and field of view to the scene (the receivers'
// bounding sphere seen from the light) and points it at their centre.
void fit_light_frustum(Scene& scene);

// Draws every mesh as GL 1.1 code would: vertex and normal arrays, one glColor and one
// glDrawArrays per mesh (colour material supplies the material).
void draw_scene(Context& ctx, const Scene& scene);

}  // namespace passim
