// Double-precision software references (no pipeline): a ray caster over the scene,
// the exact shadow test, the "same samples" evaluation of a hardware program's
// decisions, and the papers' filters (Reeves PCF, the tutorial's shader PCF, MDSM).
#pragma once
#include <glm/glm.hpp>
#include <optional>
#include <vector>

#include "programs/programs.hpp"
#include "programs/scene.hpp"

namespace passim {

class RayCaster {
 public:
  explicit RayCaster(const Scene& scene);
  struct Hit {
    double t = 0.0;
    int mesh = -1;
    glm::dvec3 normal{0.0};  // geometric, unit length, as wound (counter-clockwise front)
  };
  // The nearest hit with t in (t_min, t_max) along origin + t·dir.
  std::optional<Hit> first_hit(const glm::dvec3& origin, const glm::dvec3& dir, double t_min = 0.0,
                               double t_max = 1e300) const;

 private:
  struct Triangle {
    glm::dvec3 a, e1, e2, normal;
    int mesh;
  };
  struct Node {
    glm::dvec3 lo, hi;
    int left = -1, right = -1;  // children, or -1 for a leaf
    int first = 0, count = 0;   // the leaf's triangles
  };
  int build(int first, int count);
  std::vector<Triangle> triangles_;
  std::vector<Node> nodes_;
};

// Per camera pixel (row 0 at the bottom): the surface a pixel centre sees, from the
// scene's camera at width x height.
struct PixelSurface {
  bool hit = false;
  glm::dvec3 position{0.0}, normal{0.0};
  int mesh = -1;
};
std::vector<PixelSurface> camera_surfaces(const Scene& scene, const RayCaster& caster, int width, int height);

// The exact shadow test: is the segment from the surface point to the light blocked?
bool in_shadow_exact(const RayCaster& caster, const Scene& scene, const PixelSurface& s);

// The "same samples" reference of a hardware program run: for each pixel the number of
// shadowed samples the program should have counted, computed in double from the
// program's own sample positions, depth encoding and bias, and whether that pixel lies
// on a quantisation step (a tie: a sample or the pixel moved by a hair changes a code
// or a texel).
struct SameSamples {
  int samples = 1;                // samples per pixel (n·k for mdsm)
  std::vector<int> expected;      // per pixel; -1 where the pixel sees no surface
  std::vector<int> measured;      // per pixel, from the program's attenuation image
  std::vector<bool> tie;
  int compared = 0, agree = 0, disagree_at_ties = 0, disagree_unexplained = 0;
};
SameSamples same_samples(const ProgramRun& run);

// The program's algorithm in double without the pipeline's quantisation (exact geometry,
// unquantised depths; the program's sample positions, lookups and bias): the attenuation
// per pixel, −1 where the pixel sees no surface. The precision study's reference.
std::vector<double> exact_attenuation(const ProgramRun& run);

// Pixels a program classifies otherwise than a truth does.
struct Misclassified {
  int lit_shadowed = 0;   // lit by the truth (attenuation 0), attenuated by the program
  int shadowed_lit = 0;   // shadowed (attenuated) by the truth, left at 0 by the program
  int self_shadowed = 0;  // lit_shadowed on surfaces that face the light
};

// A run's attenuation classified per pixel against the exact shadow test (a shadow ray,
// double, no quantisation: the algorithm as a whole, sampling included) and, when given,
// against the program's double-precision reference (exact_attenuation: what the widths cost).
struct Classification {
  int surfaces = 0;      // pixels that see a surface
  Misclassified exact;   // against the exact shadow test
  Misclassified reference;  // against the reference (zero when none was given)
  int facing_light = 0;  // pixels on surfaces facing the light and lit by the exact test
  std::vector<int> self_shadowed_by_mesh;  // exact.self_shadowed per scene mesh (mesh 0: the ground)
};
Classification classify(const ProgramRun& run, const std::vector<double>* reference = nullptr);

// A software reference's result: the attenuation (fraction shadowed) per camera pixel in
// double, and as a 16-bit single-channel image named "attenuation".
struct ReferenceRun {
  ProgramOptions options;
  Scene scene;
  int map_size = 0;
  double bias_depth = 0.0;     // in the ramp's depth units, as the hardware programs'
  std::vector<double> attenuation;  // row 0 at the bottom; 0 where no surface is seen
  CapturedImage image;
};
// Runs reeves, shader-pcf or mdsm-ref (program_list() marks them `reference`) on an
// unquantised map: each texel's depth from a ray through its centre.
ReferenceRun run_reference(const ProgramOptions& options);

}  // namespace passim
