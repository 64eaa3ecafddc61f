// Built-in scenes, emitted through a Context as GL 1.x code would emit them.
#pragma once
#include "pipeline/context.hpp"

namespace passim {

// The benchmark scene of the peer measurements (shared/peers/osmesa-bench): a 16x16
// ground grid (512 triangles), a sphere of 48x36 (3360) and a tilted torus of 48x32
// (3072): 6944 triangles as GL_TRIANGLES with per-vertex normals and colour material.
// Returns the number of triangles emitted.
int emit_bench_scene(Context& ctx);

// The camera of that scene: 45° perspective from (0, 6, 12) looking at (0, 1, 0), and
// a positional light at (6, 12, 6), lighting on with COLOR_MATERIAL, depth test, culling.
void setup_bench_scene_view(Context& ctx);

}  // namespace passim
