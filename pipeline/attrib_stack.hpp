// The server and client attribute stacks (OpenGL 1.2.1 §6.1.14): what one PushAttrib or
// PushClientAttrib saves. Each state variable belongs to the group the "Attribute" column of
// its state table (§6.2, Tables 6.5-6.27) names; the groups are mapped to the state structs
// in pipeline/context_attrib.cpp, which counts the fields of every struct it saves field by
// field (field_count below), so a field added to such a struct stops the build until it is
// given its group there.
#pragma once
#include <array>
#include <cstddef>
#include <map>
#include <utility>
#include <vector>

#include "client/pixel_unpack.hpp"
#include "pipeline/gl.hpp"
#include "pipeline/state.hpp"
#include "pipeline/texture.hpp"
#include "stages/convolution.hpp"
#include "stages/fog.hpp"
#include "stages/pixel_transfer.hpp"
#include "stages/rasterizer.hpp"

namespace passim {

// The number of fields of an aggregate: the most initializers T{...} accepts (each field is
// one initializer, an array or struct field included, since any_field converts to it).
namespace detail {
struct any_field {
  template <class T>
  constexpr operator T() const noexcept;  // unevaluated only
};
template <class T, std::size_t... I>
constexpr bool brace_initializable(std::index_sequence<I...>) {
  return requires { T{(static_cast<void>(I), any_field{})...}; };
}
template <class T, std::size_t N = 0>
constexpr std::size_t field_count() {
  if constexpr (brace_initializable<T>(std::make_index_sequence<N + 1>{})) return field_count<T, N + 1>();
  else return N;
}
}  // namespace detail
template <class T>
inline constexpr std::size_t field_count = detail::field_count<T>();

// A texture object's parameters (Tables 6.13-6.14, attribute "texture"): the object without
// its images (attribute "—").
struct SavedTexture {
  GLuint name = 0;
  TextureObject parameters;  // levels left empty
};

// One PushAttrib: the groups of `mask`; only those groups' members are meaningful.
struct ServerAttribs {
  GLbitfield mask = 0;
  // CURRENT_BIT (Table 6.2, with the raster position)
  CurrentState current;
  RasterPosState raster;
  // POINT_BIT, LINE_BIT, POLYGON_BIT: the fields of PolygonState each group names
  PolygonState polygon;
  // ENABLE_BIT: every enable flag, as (capability, value)
  std::vector<std::pair<GLenum, bool>> enables;
  // the enables accepted but not modelled (each also in its own group)
  std::map<GLenum, bool> unmodelled_caps;
  // LIGHTING_BIT (Tables 6.7-6.8 and SHADE_MODEL of 6.6)
  LightingState lighting;
  // FOG_BIT
  FogState fog;
  // DEPTH_BUFFER_BIT, STENCIL_BUFFER_BIT, COLOR_BUFFER_BIT, SCISSOR_BIT, ACCUM_BUFFER_BIT
  FragmentOpsState fragment;
  FramebufferControlState fb_control;
  // VIEWPORT_BIT
  ViewportState viewport;
  // TRANSFORM_BIT (not the matrices: attribute "—")
  GLenum matrix_mode = GL_MODELVIEW;
  bool normalize = false, rescale_normal = false;
  std::array<Vec4, 6> clip_plane{};
  std::array<bool, 6> clip_enabled{};
  // HINT_BIT
  HintState hints;
  // LIST_BIT
  GLuint list_base = 0;
  // PIXEL_MODE_BIT (Tables 6.17-6.18 "pixel": not the tables', filters', histogram's or
  // minmax's contents, nor the pixel maps)
  PixelState pixel;
  double zoom_x = 1.0, zoom_y = 1.0;
  PixelTransferState transfer;  // the "pixel" fields only; its vectors are left empty
  // TEXTURE_BIT (Tables 6.12-6.16): enables, bindings, the bound objects' parameters,
  // environment and coordinate generation
  bool texture_1d = false, texture_2d = false;
  SavedTexture bound_1d, bound_2d;
  GLenum env_mode = GL_MODULATE;
  Vec4 env_color{0.0};
  std::array<TexGenState, 4> gen{};
};

// One PushClientAttrib (Tables 6.6 and 6.20: attributes vertex-array and pixel-store).
struct ClientAttribs {
  GLbitfield mask = 0;
  PixelStoreState pixel_store;
  ClientArrayState arrays;
};

}  // namespace passim
