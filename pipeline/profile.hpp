// Machine profiles: plane widths, limits and (for the cost model) rates of a
// modelled workstation. Every figure says where it comes from in docs/cost-model.md.
#pragma once
#include <cstdint>
#include <array>
#include <string>
#include <vector>

namespace passim {

struct MachineLimits {
  int max_framebuffer_size = 4096;  // largest window width or height
  int max_viewport_size = 4096;
  int max_texture_size = 2048;
  // Texels one image may hold (above: GL_OUT_OF_MEMORY, §2.5), so a huge size in a trace
  // is an error, not an allocation failure.
  std::int64_t max_texture_texels = std::int64_t{4096} * 4096;
  int max_lights = 8;
  int max_clip_planes = 6;
  int max_modelview_stack = 32;
  int max_projection_stack = 2;
  int max_texture_stack = 2;
  int max_color_matrix_stack = 2;
  int max_list_nesting = 64;
  int max_convolution_width = 7;
  int max_convolution_height = 7;
  int max_color_table_width = 256;
  int max_histogram_width = 256;
  int max_pixel_map_table = 256;
  int max_eval_order = 8;
  int max_attrib_stack = 16;
  int max_client_attrib_stack = 16;
  int subpixel_bits = 4;  // window-coordinate snapping of vertices (A5)
};

// Choices of the arithmetic that the spec leaves open and machines made differently
// (docs/arithmetic.md). They affect the bits, so a trace header records the profile.
struct ArithmeticOptions {
  // A4: round the lit (or current) vertex colour to the fragment width before it is
  // interpolated. Off: the clamped real colour is interpolated (as Mesa does).
  bool quantise_vertex_colors = true;
  // §3.5.1 leaves a polygon's decomposition into triangles open, and with it how attributes
  // are interpolated across a quad whose attributes are not affine (four different colours,
  // projective texture coordinates). Off: a quad is clipped as a polygon and drawn as a fan
  // from its first vertex. On: a quad (v0, v1, v2, v3) given between glBegin and glEnd is
  // drawn as triangles (v0, v1, v3) and (v1, v2, v3), each clipped on its own — what Mesa 22
  // does in immediate mode, while its glDrawArrays/glDrawElements quads are fans
  // (docs/arithmetic.md, "Against Mesa").
  bool immediate_quads_as_triangle_pairs = false;
  // §4.1.6 does not say how exactly a blend is computed. Off: s·S + d·D in reals, rounded once
  // (A1). On: each product rounded to the colour width first, then combined — Mesa 22's 8-bit
  // blender (docs/arithmetic.md, "Against Mesa").
  bool blend_products_rounded = false;
  // §3.8.5 gives LINEAR's weights as reals (A11). On: a level whose components are all 8 bits
  // (no border, wrap REPEAT or CLAMP_TO_EDGE, no depth comparison) is filtered as Mesa 22's
  // llvmpipe AoS sampler does — coordinates in 8.8 fixed point, weights of 1/256, each lerp
  // a + ⌊(w·(b − a) + 128)/256⌋ on 8-bit codes (arithmetic.md A29, "Against Mesa").
  bool texture_filter_8_8 = false;
};

// Rates of the cost model (docs/cost-model.md), per second; 0 = the stage is not timed.
struct CostRates {
  double vertices = 0;           // transformed and lit
  double triangles = 0;          // set up for rasterization
  double fragments = 0;          // through the per-fragment operations
  double texture_lookups = 0;
  double framebuffer_bytes = 0;  // colour, depth, stencil bits read + written, / 8
  double pixels = 0;             // pixel groups through the pixel path (draw, read, copy)
  double scale_bias = 0, color_table = 0, color_matrix = 0;  // pixel-path operations
  double convolution[3] = {0, 0, 0};  // pixels/s through a 3x3, 5x5, 7x7 filter
  double accumulation = 0;       // accumulation-buffer pixel operations
  double clear = 0;              // pixels cleared per buffer
  double texture_load_bytes = 0;  // into texture memory
  double pass_overhead = 0;      // seconds per pass that does any work
  std::string sources;           // where each figure comes from
};

struct MachineProfile {
  std::string name;
  std::string description;
  std::array<int, 4> color_bits{8, 8, 8, 8};
  int depth_bits = 24;
  int stencil_bits = 8;
  int accum_bits = 16;  // per component, signed
  MachineLimits limits;
  ArithmeticOptions arithmetic;
  std::string sources;  // where the figures come from
  CostRates rates;
};

const std::vector<MachineProfile>& machine_profiles();
// nullptr when no profile has that name.
const MachineProfile* find_profile(const std::string& name);

}  // namespace passim
