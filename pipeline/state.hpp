// GL state, grouped as the state tables of the OpenGL 1.2.1 spec (§6.2) group it.
#pragma once
#include <array>
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "pipeline/gl.hpp"

namespace passim {

using Mat4 = glm::dmat4;
using Vec4 = glm::dvec4;
using Vec3 = glm::dvec3;

// Table 6.5 (transformation), with the viewport of Table 6.4/6.5.
struct TransformState {
  GLenum matrix_mode = GL_MODELVIEW;
  std::vector<Mat4> modelview{Mat4(1.0)};
  std::vector<Mat4> projection{Mat4(1.0)};
  std::vector<Mat4> texture{Mat4(1.0)};
  std::vector<Mat4> color{Mat4(1.0)};  // ARB_imaging colour matrix stack
  bool normalize = false;
  bool rescale_normal = false;
  std::array<Vec4, 6> clip_plane{};  // eye coordinates
  std::array<bool, 6> clip_enabled{};
};

struct ViewportState {
  int x = 0, y = 0, width = 0, height = 0;
  double near_val = 0.0, far_val = 1.0;
};

// Table 6.2 (current values).
struct CurrentState {
  Vec4 color{1.0, 1.0, 1.0, 1.0};
  Vec3 normal{0.0, 0.0, 1.0};
  Vec4 texcoord{0.0, 0.0, 0.0, 1.0};
  bool edge_flag = true;  // §2.6.2
};

struct Material {
  Vec4 ambient{0.2, 0.2, 0.2, 1.0};
  Vec4 diffuse{0.8, 0.8, 0.8, 1.0};
  Vec4 specular{0.0, 0.0, 0.0, 1.0};
  Vec4 emission{0.0, 0.0, 0.0, 1.0};
  double shininess = 0.0;
};

struct Light {
  bool enabled = false;
  Vec4 ambient{0.0, 0.0, 0.0, 1.0};
  Vec4 diffuse{0.0, 0.0, 0.0, 1.0};  // LIGHT0: (1,1,1,1)
  Vec4 specular{0.0, 0.0, 0.0, 1.0};  // LIGHT0: (1,1,1,1)
  Vec4 position{0.0, 0.0, 1.0, 0.0};  // eye coordinates (transformed at glLight time)
  Vec3 spot_direction{0.0, 0.0, -1.0};  // eye coordinates
  double spot_exponent = 0.0;
  double spot_cutoff = 180.0;
  double constant_attenuation = 1.0;
  double linear_attenuation = 0.0;
  double quadratic_attenuation = 0.0;
};

// Tables 6.8-6.9 (lighting).
struct LightingState {
  bool enabled = false;
  GLenum shade_model = GL_SMOOTH;
  bool color_material = false;
  GLenum color_material_face = GL_FRONT_AND_BACK;
  GLenum color_material_mode = GL_AMBIENT_AND_DIFFUSE;
  Vec4 model_ambient{0.2, 0.2, 0.2, 1.0};
  bool local_viewer = false;
  bool two_side = false;
  GLenum color_control = GL_SINGLE_COLOR;
  std::array<Material, 2> material{};  // [front, back]
  std::vector<Light> lights;
};

// Table 6.10-6.11 (rasterization: points, lines, polygons).
struct PolygonState {
  bool cull_enabled = false;
  GLenum cull_face = GL_BACK;
  GLenum front_face = GL_CCW;
  GLenum mode_front = GL_FILL, mode_back = GL_FILL;
  double offset_factor = 0.0, offset_units = 0.0;
  bool offset_fill = false, offset_line = false, offset_point = false;
  double point_size = 1.0;
  double line_width = 1.0;
  // §3.4.2 line stipple.
  bool line_stipple = false;
  std::uint16_t stipple_pattern = 0xFFFF;
  int stipple_repeat = 1;
};

// Table 6.15 (pixel operations).
struct FragmentOpsState {
  bool scissor_enabled = false;
  int scissor_x = 0, scissor_y = 0, scissor_width = 0, scissor_height = 0;
  bool alpha_test = false;
  GLenum alpha_func = GL_ALWAYS;
  double alpha_ref = 0.0;
  bool stencil_test = false;
  GLenum stencil_func = GL_ALWAYS;
  int stencil_ref = 0;
  std::uint32_t stencil_value_mask = 0xFFFFFFFFu;
  GLenum stencil_fail = GL_KEEP, stencil_depth_fail = GL_KEEP, stencil_depth_pass = GL_KEEP;
  bool depth_test = false;
  GLenum depth_func = GL_LESS;
  bool blend = false;
  GLenum blend_src = GL_ONE, blend_dst = GL_ZERO;
  GLenum blend_equation = GL_FUNC_ADD;
  Vec4 blend_color{0.0, 0.0, 0.0, 0.0};
  bool dither = true;
  bool logic_op_enabled = false;
  GLenum logic_op = GL_COPY;
};

// A rectangle of window pixels, [x0, x1) x [y0, y1).
struct PixelBox {
  int x0 = 0, y0 = 0, x1 = 0, y1 = 0;
};

// The pixels a clear, an accumulation or a stencil rectangle may touch: the window, cut by the
// scissor box when the scissor test is on (§4.1.2, §4.2.3, §4.2.4). In 64 bits: the box's
// x + width may pass INT_MAX.
inline PixelBox scissored_window(const FragmentOpsState& ops, int width, int height) {
  if (!ops.scissor_enabled) return {0, 0, width, height};
  auto clamp = [](std::int64_t v, std::int64_t lo, std::int64_t hi) { return static_cast<int>(v < lo ? lo : v > hi ? hi : v); };
  PixelBox b;
  b.x0 = clamp(ops.scissor_x, 0, width);
  b.y0 = clamp(ops.scissor_y, 0, height);
  b.x1 = clamp(std::int64_t{ops.scissor_x} + ops.scissor_width, b.x0, width);
  b.y1 = clamp(std::int64_t{ops.scissor_y} + ops.scissor_height, b.y0, height);
  return b;
}

// Table 6.16 (framebuffer control).
struct FramebufferControlState {
  GLenum draw_buffer = GL_BACK;
  std::array<bool, 4> color_mask{true, true, true, true};
  bool depth_mask = true;
  std::uint32_t stencil_writemask = 0xFFFFFFFFu;
  Vec4 clear_color{0.0, 0.0, 0.0, 0.0};
  double clear_depth = 1.0;
  int clear_stencil = 0;
  Vec4 clear_accum{0.0, 0.0, 0.0, 0.0};
};

// Table 6.17 (pixels; only what exists so far).
struct PixelState {
  GLenum read_buffer = GL_BACK;
};

// Table 6.25 (hints, attribute "hint"): they never change the bits here (docs/arithmetic.md),
// but are kept for the queries and the attribute stack.
struct HintState {
  GLenum perspective_correction = GL_DONT_CARE;
  GLenum point_smooth = GL_DONT_CARE;
  GLenum line_smooth = GL_DONT_CARE;
  GLenum polygon_smooth = GL_DONT_CARE;
  GLenum fog = GL_DONT_CARE;
};

// Table 6.6 (vertex arrays: client state).
struct ClientArray {
  bool enabled = false;
  int size = 4;
  GLenum type = GL_FLOAT;
  int stride = 0;
  const void* pointer = nullptr;
  std::size_t extent = SIZE_MAX;  // bytes behind pointer when known (trace replay), for bounds checks
};

struct ClientArrayState {
  ClientArray vertex, normal, color, texcoord;
  ClientArray edge_flag{false, 1, GL_UNSIGNED_BYTE};  // §2.8: one GLboolean an element
};

}  // namespace passim
