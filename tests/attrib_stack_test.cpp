// The attribute stacks (OpenGL 1.2.1 §6.1.14). For each group: its state set, the group
// pushed, its state and another group's changed, the group popped; the group's values come
// back and the other group's do not. The values expected are the ones set here, and which
// group a variable belongs to is read from the "Attribute" column of the spec's state tables
// (§6.2), not from the code.
#include <gtest/gtest.h>

#include <cstring>
#include <memory>
#include <vector>

#include "test_util.hpp"
#include "trace_io/call_runner.hpp"

using namespace passim;
using passim::test::pixel;

namespace {

Context make(bool double_buffer = false) {
  FramebufferConfig config = test::small_config(8, 8);
  config.double_buffer = double_buffer;
  return Context(config);
}

std::vector<double> get(Context& c, GLenum pname, int n = 1) {
  std::vector<double> v(16, -99.0);
  c.glGetDoublev(pname, v.data());
  v.resize(static_cast<std::size_t>(n));
  return v;
}
double get1(Context& c, GLenum pname) { return get(c, pname)[0]; }
bool on(Context& c, GLenum cap) { return c.glIsEnabled(cap) == GL_TRUE; }
GLenum error(Context& c) { return c.glGetError(); }
constexpr GLenum kNoError = GL_NO_ERROR;

using V = std::vector<double>;

}  // namespace

// Table 6.2: the current values and the raster position are "current".
TEST(AttribStack, CurrentBitRestoresCurrentValuesAndRasterPosition) {
  Context c = make();
  test::window_projection(c);
  c.glColor4f(0.0f, 1.0f, 0.0f, 1.0f);
  c.glNormal3f(1.0f, 0.0f, 0.0f);
  c.glTexCoord4f(1.0f, 2.0f, 3.0f, 4.0f);
  c.glEdgeFlag(GL_FALSE);
  c.glRasterPos2f(3.0f, 5.0f);  // window (3, 5); z 0 in an ortho of near -1, far 1: window z 1/2
  c.glFogf(GL_FOG_DENSITY, 0.5f);
  c.glPushAttrib(GL_CURRENT_BIT);
  c.glColor4f(1.0f, 0.0f, 0.0f, 0.0f);
  c.glNormal3f(0.0f, 1.0f, 0.0f);
  c.glTexCoord4f(0.0f, 0.0f, 0.0f, 1.0f);
  c.glEdgeFlag(GL_TRUE);
  c.glRasterPos2f(6.0f, 1.0f);
  c.glFogf(GL_FOG_DENSITY, 2.0f);  // fog: not pushed
  c.glPopAttrib();
  EXPECT_EQ(error(c), kNoError);
  EXPECT_EQ(get(c, GL_CURRENT_COLOR, 4), (V{0, 1, 0, 1}));
  EXPECT_EQ(get(c, GL_CURRENT_NORMAL, 3), (V{1, 0, 0}));
  EXPECT_EQ(get(c, GL_CURRENT_TEXTURE_COORDS, 4), (V{1, 2, 3, 4}));
  EXPECT_EQ(get1(c, GL_EDGE_FLAG), 0.0);
  EXPECT_EQ(get(c, GL_CURRENT_RASTER_POSITION, 4), (V{3, 5, 0.5, 1}));
  EXPECT_EQ(get(c, GL_CURRENT_RASTER_COLOR, 4), (V{0, 1, 0, 1}));
  EXPECT_EQ(get1(c, GL_FOG_DENSITY), 2.0);
}

// Table 6.9: POINT_SIZE and POINT_SMOOTH are "point"; LINE_WIDTH is "line".
TEST(AttribStack, PointBitRestoresPointState) {
  Context c = make();
  c.glPointSize(4.0f);
  c.glEnable(GL_POINT_SMOOTH);
  c.glPushAttrib(GL_POINT_BIT);
  c.glPointSize(7.0f);
  c.glDisable(GL_POINT_SMOOTH);
  c.glLineWidth(3.0f);
  c.glPopAttrib();
  EXPECT_EQ(get1(c, GL_POINT_SIZE), 4.0);
  EXPECT_TRUE(on(c, GL_POINT_SMOOTH));
  EXPECT_EQ(get1(c, GL_LINE_WIDTH), 3.0);
}

// Table 6.9: LINE_WIDTH, LINE_SMOOTH and LINE_STIPPLE are "line".
TEST(AttribStack, LineBitRestoresLineState) {
  Context c = make();
  c.glLineWidth(2.0f);
  c.glEnable(GL_LINE_SMOOTH);
  c.glEnable(GL_LINE_STIPPLE);
  c.glLineStipple(3, 0x00FF);
  c.glPushAttrib(GL_LINE_BIT);
  c.glLineWidth(5.0f);
  c.glDisable(GL_LINE_SMOOTH);
  c.glDisable(GL_LINE_STIPPLE);
  c.glLineStipple(1, 0xF0F0);
  c.glPointSize(6.0f);
  c.glPopAttrib();
  EXPECT_EQ(get1(c, GL_LINE_WIDTH), 2.0);
  EXPECT_TRUE(on(c, GL_LINE_SMOOTH));
  EXPECT_TRUE(on(c, GL_LINE_STIPPLE));
  EXPECT_EQ(get1(c, GL_LINE_STIPPLE_PATTERN), 255.0);  // 0x00FF
  EXPECT_EQ(get1(c, GL_LINE_STIPPLE_REPEAT), 3.0);
  EXPECT_EQ(get1(c, GL_POINT_SIZE), 6.0);
}

// Table 6.9: culling, facing, polygon modes, offset and their enables are "polygon".
TEST(AttribStack, PolygonBitRestoresPolygonState) {
  Context c = make();
  c.glCullFace(GL_FRONT);
  c.glEnable(GL_CULL_FACE);
  c.glFrontFace(GL_CW);
  c.glPolygonMode(GL_FRONT, GL_LINE);
  c.glPolygonMode(GL_BACK, GL_POINT);
  c.glPolygonOffset(1.5f, 2.0f);
  c.glEnable(GL_POLYGON_OFFSET_FILL);
  c.glEnable(GL_POLYGON_OFFSET_POINT);
  c.glEnable(GL_POLYGON_SMOOTH);
  c.glEnable(GL_POLYGON_STIPPLE);
  c.glPushAttrib(GL_POLYGON_BIT);
  c.glCullFace(GL_BACK);
  c.glDisable(GL_CULL_FACE);
  c.glFrontFace(GL_CCW);
  c.glPolygonMode(GL_FRONT_AND_BACK, GL_FILL);
  c.glPolygonOffset(0.0f, 0.0f);
  c.glDisable(GL_POLYGON_OFFSET_FILL);
  c.glDisable(GL_POLYGON_OFFSET_POINT);
  c.glEnable(GL_POLYGON_OFFSET_LINE);
  c.glDisable(GL_POLYGON_SMOOTH);
  c.glDisable(GL_POLYGON_STIPPLE);
  c.glPointSize(3.0f);
  c.glPopAttrib();
  EXPECT_EQ(error(c), kNoError);
  EXPECT_EQ(get1(c, GL_CULL_FACE_MODE), GL_FRONT);
  EXPECT_TRUE(on(c, GL_CULL_FACE));
  EXPECT_EQ(get1(c, GL_FRONT_FACE), GL_CW);
  EXPECT_EQ(get(c, GL_POLYGON_MODE, 2), (V{GL_LINE, GL_POINT}));
  EXPECT_EQ(get1(c, GL_POLYGON_OFFSET_FACTOR), 1.5);
  EXPECT_EQ(get1(c, GL_POLYGON_OFFSET_UNITS), 2.0);
  EXPECT_TRUE(on(c, GL_POLYGON_OFFSET_FILL));
  EXPECT_TRUE(on(c, GL_POLYGON_OFFSET_POINT));
  EXPECT_FALSE(on(c, GL_POLYGON_OFFSET_LINE));
  EXPECT_TRUE(on(c, GL_POLYGON_SMOOTH));
  EXPECT_TRUE(on(c, GL_POLYGON_STIPPLE));
  EXPECT_EQ(get1(c, GL_POINT_SIZE), 3.0);
}

// Table 6.10: only the stipple pattern is "polygon-stipple" (not modelled); the enable
// POLYGON_STIPPLE is "polygon/enable", so this group leaves it alone.
TEST(AttribStack, PolygonStippleBitLeavesTheStippleEnable) {
  Context c = make();
  c.glEnable(GL_POLYGON_STIPPLE);
  c.glPushAttrib(GL_POLYGON_STIPPLE_BIT);
  EXPECT_EQ(get1(c, GL_ATTRIB_STACK_DEPTH), 1.0);
  c.glDisable(GL_POLYGON_STIPPLE);
  c.glPopAttrib();
  EXPECT_EQ(error(c), kNoError);
  EXPECT_FALSE(on(c, GL_POLYGON_STIPPLE));
  EXPECT_EQ(get1(c, GL_ATTRIB_STACK_DEPTH), 0.0);
}

// Tables 6.17-6.18: the transfer modes, zoom, read buffer and the imaging enables and
// parameters are "pixel"; a colour table's contents are "—"; pixel storage is client state.
TEST(AttribStack, PixelModeBitRestoresPixelState) {
  Context c = make(true);
  c.glReadBuffer(GL_FRONT);
  c.glPixelZoom(2.0f, 3.0f);
  c.glPixelTransferf(GL_RED_SCALE, 2.0f);
  c.glPixelTransferi(GL_MAP_COLOR, 1);
  c.glPixelTransferf(GL_DEPTH_BIAS, 0.25f);
  c.glPixelTransferf(GL_POST_COLOR_MATRIX_GREEN_BIAS, 0.25f);
  c.glPixelTransferf(GL_POST_CONVOLUTION_BLUE_SCALE, 4.0f);
  c.glEnable(GL_HISTOGRAM);
  c.glEnable(GL_COLOR_TABLE);
  c.glEnable(GL_SEPARABLE_2D);
  const GLfloat scale2[4] = {2.0f, 2.0f, 2.0f, 2.0f}, scale1[4] = {1.0f, 1.0f, 1.0f, 1.0f};
  c.glColorTableParameterfv(GL_COLOR_TABLE, GL_COLOR_TABLE_SCALE, scale2);
  c.glPixelStorei(GL_UNPACK_ALIGNMENT, 2);
  c.glPushAttrib(GL_PIXEL_MODE_BIT);
  c.glReadBuffer(GL_BACK);
  c.glPixelZoom(1.0f, 1.0f);
  c.glPixelTransferf(GL_RED_SCALE, 1.0f);
  c.glPixelTransferi(GL_MAP_COLOR, 0);
  c.glPixelTransferf(GL_DEPTH_BIAS, 0.0f);
  c.glPixelTransferf(GL_POST_COLOR_MATRIX_GREEN_BIAS, 0.0f);
  c.glPixelTransferf(GL_POST_CONVOLUTION_BLUE_SCALE, 1.0f);
  c.glDisable(GL_HISTOGRAM);
  c.glDisable(GL_COLOR_TABLE);
  c.glDisable(GL_SEPARABLE_2D);
  c.glColorTableParameterfv(GL_COLOR_TABLE, GL_COLOR_TABLE_SCALE, scale1);
  const GLubyte entries[8] = {0, 0, 0, 0, 255, 255, 255, 255};
  c.glColorTable(GL_COLOR_TABLE, GL_RGBA, 2, GL_RGBA, GL_UNSIGNED_BYTE, entries);
  c.glPixelStorei(GL_UNPACK_ALIGNMENT, 8);
  c.glClearColor(0.5f, 0.5f, 0.5f, 0.5f);
  c.glPopAttrib();
  EXPECT_EQ(error(c), kNoError);
  EXPECT_EQ(get1(c, GL_READ_BUFFER), GL_FRONT);
  EXPECT_EQ(get1(c, GL_ZOOM_X), 2.0);
  EXPECT_EQ(get1(c, GL_ZOOM_Y), 3.0);
  EXPECT_EQ(get1(c, GL_RED_SCALE), 2.0);
  EXPECT_EQ(get1(c, GL_MAP_COLOR), 1.0);
  EXPECT_EQ(get1(c, GL_DEPTH_BIAS), 0.25);
  EXPECT_EQ(get1(c, GL_POST_COLOR_MATRIX_GREEN_BIAS), 0.25);
  EXPECT_EQ(get1(c, GL_POST_CONVOLUTION_BLUE_SCALE), 4.0);
  EXPECT_TRUE(on(c, GL_HISTOGRAM));
  EXPECT_TRUE(on(c, GL_COLOR_TABLE));
  EXPECT_TRUE(on(c, GL_SEPARABLE_2D));
  GLint v[4] = {};
  c.glGetColorTableParameteriv(GL_COLOR_TABLE, GL_COLOR_TABLE_SCALE, v);
  EXPECT_EQ(v[0], 2);
  c.glGetColorTableParameteriv(GL_COLOR_TABLE, GL_COLOR_TABLE_WIDTH, v);
  EXPECT_EQ(v[0], 2);  // the table defined after the push stays
  EXPECT_EQ(get1(c, GL_UNPACK_ALIGNMENT), 8.0);
  EXPECT_EQ(get(c, GL_COLOR_CLEAR_VALUE, 4), (V{0.5, 0.5, 0.5, 0.5}));
}

// Tables 6.7-6.8 and SHADE_MODEL: "lighting". The light's parameters are checked by what a
// lit point draws: LIGHT0 (diffuse 1, directional along +z) on the default material with
// normal +z gives 0.2·0.2 (model ambient × material ambient) + 0.8·1 (diffuse) = 0.84,
// code ⌊0.84·255 + ½⌋ = 214; with the light's diffuse 0 only 0.04, code ⌊10.2 + ½⌋ = 10.
TEST(AttribStack, LightingBitRestoresLightingState) {
  Context c = make();
  test::window_projection(c);
  c.glShadeModel(GL_FLAT);
  c.glEnable(GL_LIGHTING);
  c.glEnable(GL_LIGHT0);
  c.glEnable(GL_LIGHT1);
  const GLfloat ambient[4] = {0.125f, 0.25f, 0.375f, 0.5f};
  c.glLightModelfv(GL_LIGHT_MODEL_AMBIENT, ambient);
  c.glLightModeli(GL_LIGHT_MODEL_TWO_SIDE, 1);
  c.glColorMaterial(GL_FRONT, GL_DIFFUSE);
  c.glFogi(GL_FOG_MODE, GL_LINEAR);
  c.glPushAttrib(GL_LIGHTING_BIT);
  c.glShadeModel(GL_SMOOTH);
  c.glDisable(GL_LIGHT1);
  const GLfloat other[4] = {0.2f, 0.2f, 0.2f, 1.0f}, black[4] = {0.0f, 0.0f, 0.0f, 1.0f};
  c.glLightModelfv(GL_LIGHT_MODEL_AMBIENT, other);
  c.glLightModeli(GL_LIGHT_MODEL_TWO_SIDE, 0);
  c.glColorMaterial(GL_BACK, GL_AMBIENT);
  c.glLightfv(GL_LIGHT0, GL_DIFFUSE, black);
  c.glFogi(GL_FOG_MODE, GL_EXP2);
  c.glBegin(GL_POINTS);
  c.glNormal3f(0.0f, 0.0f, 1.0f);
  c.glVertex2f(3.5f, 3.5f);
  c.glEnd();
  EXPECT_EQ(pixel(c, 3, 3)[0], 10u);  // 0.2·0.2 + 0
  c.glDisable(GL_LIGHTING);
  c.glPopAttrib();
  EXPECT_EQ(error(c), kNoError);
  EXPECT_EQ(get1(c, GL_SHADE_MODEL), GL_FLAT);
  EXPECT_TRUE(on(c, GL_LIGHTING));
  EXPECT_TRUE(on(c, GL_LIGHT1));
  EXPECT_EQ(get(c, GL_LIGHT_MODEL_AMBIENT, 4), (V{0.125, 0.25, 0.375, 0.5}));
  EXPECT_EQ(get1(c, GL_LIGHT_MODEL_TWO_SIDE), 1.0);
  EXPECT_EQ(get1(c, GL_COLOR_MATERIAL_FACE), GL_FRONT);
  EXPECT_EQ(get1(c, GL_COLOR_MATERIAL_PARAMETER), GL_DIFFUSE);
  EXPECT_EQ(get1(c, GL_FOG_MODE), GL_EXP2);
  c.glLightModelfv(GL_LIGHT_MODEL_AMBIENT, other);
  c.glDisable(GL_LIGHT1);
  c.glBegin(GL_POINTS);
  c.glNormal3f(0.0f, 0.0f, 1.0f);
  c.glVertex2f(2.5f, 2.5f);
  c.glEnd();
  EXPECT_EQ(pixel(c, 2, 2)[0], 214u);  // the light's diffuse 1 restored: 0.04 + 0.8
}

// Table 6.6: the fog state is "fog"; SHADE_MODEL is "lighting".
TEST(AttribStack, FogBitRestoresFogState) {
  Context c = make();
  c.glEnable(GL_FOG);
  c.glFogi(GL_FOG_MODE, GL_LINEAR);
  c.glFogf(GL_FOG_START, 1.0f);
  c.glFogf(GL_FOG_END, 5.0f);
  c.glFogf(GL_FOG_DENSITY, 0.5f);
  const GLfloat color[4] = {0.25f, 0.5f, 0.75f, 1.0f}, other[4] = {1.0f, 1.0f, 1.0f, 1.0f};
  c.glFogfv(GL_FOG_COLOR, color);
  c.glShadeModel(GL_FLAT);
  c.glPushAttrib(GL_FOG_BIT);
  c.glDisable(GL_FOG);
  c.glFogi(GL_FOG_MODE, GL_EXP);
  c.glFogf(GL_FOG_START, 0.0f);
  c.glFogf(GL_FOG_END, 1.0f);
  c.glFogf(GL_FOG_DENSITY, 1.0f);
  c.glFogfv(GL_FOG_COLOR, other);
  c.glShadeModel(GL_SMOOTH);
  c.glPopAttrib();
  EXPECT_TRUE(on(c, GL_FOG));
  EXPECT_EQ(get1(c, GL_FOG_MODE), GL_LINEAR);
  EXPECT_EQ(get1(c, GL_FOG_START), 1.0);
  EXPECT_EQ(get1(c, GL_FOG_END), 5.0);
  EXPECT_EQ(get1(c, GL_FOG_DENSITY), 0.5);
  EXPECT_EQ(get(c, GL_FOG_COLOR, 4), (V{0.25, 0.5, 0.75, 1.0}));
  EXPECT_EQ(get1(c, GL_SHADE_MODEL), GL_SMOOTH);
}

// Tables 6.14-6.15: the depth test, function, writemask and clear value are "depth-buffer".
TEST(AttribStack, DepthBufferBitRestoresDepthState) {
  Context c = make();
  c.glEnable(GL_DEPTH_TEST);
  c.glDepthFunc(GL_GREATER);
  c.glDepthMask(GL_FALSE);
  c.glClearDepth(0.25);
  c.glPushAttrib(GL_DEPTH_BUFFER_BIT);
  c.glDisable(GL_DEPTH_TEST);
  c.glDepthFunc(GL_LESS);
  c.glDepthMask(GL_TRUE);
  c.glClearDepth(1.0);
  c.glStencilFunc(GL_NEVER, 1, 1);  // stencil-buffer: not pushed
  c.glPopAttrib();
  EXPECT_TRUE(on(c, GL_DEPTH_TEST));
  EXPECT_EQ(get1(c, GL_DEPTH_FUNC), GL_GREATER);
  EXPECT_EQ(get1(c, GL_DEPTH_WRITEMASK), 0.0);
  EXPECT_EQ(get1(c, GL_DEPTH_CLEAR_VALUE), 0.25);
  EXPECT_EQ(get1(c, GL_STENCIL_FUNC), GL_NEVER);
}

// Table 6.15: ACCUM_CLEAR_VALUE is "accum-buffer"; COLOR_CLEAR_VALUE is "color-buffer".
TEST(AttribStack, AccumBufferBitRestoresTheAccumulationClearValue) {
  Context c = make();
  c.glClearAccum(0.25f, 0.5f, 0.75f, 1.0f);
  c.glPushAttrib(GL_ACCUM_BUFFER_BIT);
  c.glClearAccum(0.0f, 0.0f, 0.0f, 0.0f);
  c.glClearColor(1.0f, 1.0f, 1.0f, 1.0f);
  c.glPopAttrib();
  EXPECT_EQ(get(c, GL_ACCUM_CLEAR_VALUE, 4), (V{0.25, 0.5, 0.75, 1.0}));
  EXPECT_EQ(get(c, GL_COLOR_CLEAR_VALUE, 4), (V{1, 1, 1, 1}));
}

// Tables 6.14-6.15: the stencil test, function, operations, writemask and clear value are
// "stencil-buffer" (masks read back through the 8 stencil bits).
TEST(AttribStack, StencilBufferBitRestoresStencilState) {
  Context c = make();
  c.glEnable(GL_STENCIL_TEST);
  c.glStencilFunc(GL_EQUAL, 3, 0x0F);
  c.glStencilOp(GL_INCR, GL_DECR, GL_INVERT);
  c.glStencilMask(0x3C);
  c.glClearStencil(5);
  c.glPushAttrib(GL_STENCIL_BUFFER_BIT);
  c.glDisable(GL_STENCIL_TEST);
  c.glStencilFunc(GL_ALWAYS, 0, 0xFF);
  c.glStencilOp(GL_KEEP, GL_KEEP, GL_KEEP);
  c.glStencilMask(0xFF);
  c.glClearStencil(0);
  c.glDepthFunc(GL_EQUAL);  // depth-buffer: not pushed
  c.glPopAttrib();
  EXPECT_TRUE(on(c, GL_STENCIL_TEST));
  EXPECT_EQ(get1(c, GL_STENCIL_FUNC), GL_EQUAL);
  EXPECT_EQ(get1(c, GL_STENCIL_REF), 3.0);
  EXPECT_EQ(get1(c, GL_STENCIL_VALUE_MASK), 15.0);
  EXPECT_EQ(get1(c, GL_STENCIL_FAIL), GL_INCR);
  EXPECT_EQ(get1(c, GL_STENCIL_PASS_DEPTH_FAIL), GL_DECR);
  EXPECT_EQ(get1(c, GL_STENCIL_PASS_DEPTH_PASS), GL_INVERT);
  EXPECT_EQ(get1(c, GL_STENCIL_WRITEMASK), 60.0);
  EXPECT_EQ(get1(c, GL_STENCIL_CLEAR_VALUE), 5.0);
  EXPECT_EQ(get1(c, GL_DEPTH_FUNC), GL_EQUAL);
}

// Tables 6.13-6.15: alpha test, blending, dither, logic op, draw buffer, colour writemask and
// clear colour are "color-buffer"; DEPTH_WRITEMASK is "depth-buffer".
TEST(AttribStack, ColorBufferBitRestoresColorBufferState) {
  Context c = make(true);
  c.glEnable(GL_ALPHA_TEST);
  c.glAlphaFunc(GL_GEQUAL, 0.5f);
  c.glEnable(GL_BLEND);
  c.glBlendFunc(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA);
  c.glBlendEquation(GL_MAX);
  c.glBlendColor(0.25f, 0.5f, 0.75f, 1.0f);
  c.glDisable(GL_DITHER);
  c.glEnable(GL_COLOR_LOGIC_OP);
  c.glEnable(GL_INDEX_LOGIC_OP);
  c.glLogicOp(GL_XOR);
  c.glColorMask(GL_TRUE, GL_FALSE, GL_TRUE, GL_FALSE);
  c.glClearColor(0.25f, 0.5f, 0.75f, 1.0f);
  c.glDrawBuffer(GL_FRONT);
  c.glPushAttrib(GL_COLOR_BUFFER_BIT);
  c.glDisable(GL_ALPHA_TEST);
  c.glAlphaFunc(GL_ALWAYS, 0.0f);
  c.glDisable(GL_BLEND);
  c.glBlendFunc(GL_ONE, GL_ZERO);
  c.glBlendEquation(GL_FUNC_ADD);
  c.glBlendColor(0.0f, 0.0f, 0.0f, 0.0f);
  c.glEnable(GL_DITHER);
  c.glDisable(GL_COLOR_LOGIC_OP);
  c.glDisable(GL_INDEX_LOGIC_OP);
  c.glLogicOp(GL_COPY);
  c.glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
  c.glClearColor(0.0f, 0.0f, 0.0f, 0.0f);
  c.glDrawBuffer(GL_BACK);
  c.glDepthMask(GL_FALSE);  // depth-buffer: not pushed
  c.glPopAttrib();
  EXPECT_EQ(error(c), kNoError);
  EXPECT_TRUE(on(c, GL_ALPHA_TEST));
  EXPECT_EQ(get1(c, GL_ALPHA_TEST_FUNC), GL_GEQUAL);
  EXPECT_EQ(get1(c, GL_ALPHA_TEST_REF), 0.5);
  EXPECT_TRUE(on(c, GL_BLEND));
  EXPECT_EQ(get1(c, GL_BLEND_SRC), GL_SRC_ALPHA);
  EXPECT_EQ(get1(c, GL_BLEND_DST), GL_ONE_MINUS_SRC_ALPHA);
  EXPECT_EQ(get1(c, GL_BLEND_EQUATION), GL_MAX);
  EXPECT_EQ(get(c, GL_BLEND_COLOR, 4), (V{0.25, 0.5, 0.75, 1.0}));
  EXPECT_FALSE(on(c, GL_DITHER));
  EXPECT_TRUE(on(c, GL_COLOR_LOGIC_OP));
  EXPECT_TRUE(on(c, GL_INDEX_LOGIC_OP));
  EXPECT_EQ(get1(c, GL_LOGIC_OP_MODE), GL_XOR);
  EXPECT_EQ(get(c, GL_COLOR_WRITEMASK, 4), (V{1, 0, 1, 0}));
  EXPECT_EQ(get(c, GL_COLOR_CLEAR_VALUE, 4), (V{0.25, 0.5, 0.75, 1.0}));
  EXPECT_EQ(get1(c, GL_DRAW_BUFFER), GL_FRONT);
  EXPECT_EQ(get1(c, GL_DEPTH_WRITEMASK), 0.0);
  // The restored draw buffer is the one drawn to: a clear reaches the front buffer only
  // (red and blue written, green and alpha masked: codes 64, 0, 191, 0 of 0.25, 0.75).
  c.glClear(GL_COLOR_BUFFER_BIT);
  EXPECT_EQ(pixel(c, 0, 0), (std::array<std::uint32_t, 4>{64, 0, 191, 0}));
}

// Table 6.5: VIEWPORT and DEPTH_RANGE are "viewport"; SCISSOR_BOX is "scissor".
TEST(AttribStack, ViewportBitRestoresViewportAndDepthRange) {
  Context c = make();
  c.glViewport(1, 2, 3, 4);
  c.glDepthRange(0.25, 0.75);
  c.glPushAttrib(GL_VIEWPORT_BIT);
  c.glViewport(0, 0, 8, 8);
  c.glDepthRange(0.0, 1.0);
  c.glScissor(1, 1, 2, 2);
  c.glPopAttrib();
  EXPECT_EQ(get(c, GL_VIEWPORT, 4), (V{1, 2, 3, 4}));
  EXPECT_EQ(get(c, GL_DEPTH_RANGE, 2), (V{0.25, 0.75}));
  EXPECT_EQ(get(c, GL_SCISSOR_BOX, 4), (V{1, 1, 2, 2}));
}

// Table 6.5: MATRIX_MODE, NORMALIZE, RESCALE_NORMAL and the clip planes with their enables
// are "transform"; the matrices and their stacks are "—".
TEST(AttribStack, TransformBitRestoresTransformStateButNotTheMatrices) {
  Context c = make();
  c.glMatrixMode(GL_TEXTURE);
  c.glEnable(GL_NORMALIZE);
  c.glEnable(GL_RESCALE_NORMAL);
  c.glEnable(GL_CLIP_PLANE2);
  c.glPushAttrib(GL_TRANSFORM_BIT);
  c.glMatrixMode(GL_MODELVIEW);
  c.glTranslatef(1.0f, 2.0f, 3.0f);
  c.glDisable(GL_NORMALIZE);
  c.glDisable(GL_RESCALE_NORMAL);
  c.glDisable(GL_CLIP_PLANE2);
  c.glEnable(GL_CLIP_PLANE4);
  c.glPopAttrib();
  EXPECT_EQ(get1(c, GL_MATRIX_MODE), GL_TEXTURE);
  EXPECT_TRUE(on(c, GL_NORMALIZE));
  EXPECT_TRUE(on(c, GL_RESCALE_NORMAL));
  EXPECT_TRUE(on(c, GL_CLIP_PLANE2));
  EXPECT_FALSE(on(c, GL_CLIP_PLANE4));
  const V m = get(c, GL_MODELVIEW_MATRIX, 16);
  EXPECT_EQ((V{m[12], m[13], m[14]}), (V{1, 2, 3}));
}

// A clip plane's equation is "transform": a point the pushed plane keeps is drawn, after a
// plane that would remove it was set and popped. Plane (1, 0, 0, −4) keeps x ≥ 4 (eye
// coordinates = object coordinates, identity modelview); (−1, 0, 0, 4) keeps x ≤ 4.
TEST(AttribStack, TransformBitRestoresClipPlaneEquations) {
  Context c = make();
  test::window_projection(c);
  const GLdouble keep_right[4] = {1, 0, 0, -4}, keep_left[4] = {-1, 0, 0, 4};
  c.glClipPlane(GL_CLIP_PLANE0, keep_right);
  c.glEnable(GL_CLIP_PLANE0);
  c.glPushAttrib(GL_TRANSFORM_BIT);
  c.glClipPlane(GL_CLIP_PLANE0, keep_left);
  c.glPopAttrib();
  c.glBegin(GL_POINTS);
  c.glVertex2f(6.5f, 1.5f);
  c.glVertex2f(1.5f, 1.5f);
  c.glEnd();
  EXPECT_EQ(pixel(c, 6, 1)[0], 255u);
  EXPECT_EQ(pixel(c, 1, 1)[0], 0u);
}

// §6.1.14 and Tables 6.12-6.14: TEXTURE_BIT restores the enables and bindings, then the
// bound objects' parameters; images and unbound objects are not restored.
TEST(AttribStack, TextureBitRestoresBindingsAndBoundObjectParameters) {
  Context c = make();
  GLuint t[2] = {};
  c.glGenTextures(2, t);
  c.glBindTexture(GL_TEXTURE_2D, t[0]);
  c.glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  c.glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP);
  const GLubyte texel[16] = {255, 0, 0, 255, 255, 0, 0, 255, 255, 0, 0, 255, 255, 0, 0, 255};
  c.glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA, 1, 1, 0, GL_RGBA, GL_UNSIGNED_BYTE, texel);
  c.glTexParameteri(GL_TEXTURE_1D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);  // the default 1D object
  c.glEnable(GL_TEXTURE_2D);
  c.glEnable(GL_TEXTURE_GEN_S);
  c.glPushAttrib(GL_TEXTURE_BIT);
  c.glBindTexture(GL_TEXTURE_2D, t[1]);
  c.glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
  c.glBindTexture(GL_TEXTURE_2D, t[0]);
  c.glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
  c.glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_REPEAT);
  c.glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA, 2, 2, 0, GL_RGBA, GL_UNSIGNED_BYTE, texel);
  c.glBindTexture(GL_TEXTURE_2D, t[1]);
  c.glTexParameteri(GL_TEXTURE_1D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  c.glDisable(GL_TEXTURE_2D);
  c.glDisable(GL_TEXTURE_GEN_S);
  c.glPopAttrib();
  EXPECT_EQ(error(c), kNoError);
  EXPECT_EQ(get1(c, GL_TEXTURE_BINDING_2D), t[0]);
  EXPECT_TRUE(on(c, GL_TEXTURE_2D));
  EXPECT_TRUE(on(c, GL_TEXTURE_GEN_S));
  GLint v = 0;
  c.glGetTexParameteriv(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, &v);
  EXPECT_EQ(v, GL_NEAREST);
  c.glGetTexParameteriv(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, &v);
  EXPECT_EQ(v, GL_CLAMP);
  c.glGetTexLevelParameteriv(GL_TEXTURE_2D, 0, GL_TEXTURE_WIDTH, &v);
  EXPECT_EQ(v, 2);  // the image defined after the push stays
  c.glGetTexParameteriv(GL_TEXTURE_1D, GL_TEXTURE_MAG_FILTER, &v);
  EXPECT_EQ(v, GL_NEAREST);
  c.glBindTexture(GL_TEXTURE_2D, t[1]);
  c.glGetTexParameteriv(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, &v);
  EXPECT_EQ(v, GL_LINEAR);  // not bound at the push: not restored
}

// Table 6.13: SCISSOR_TEST and SCISSOR_BOX are "scissor".
TEST(AttribStack, ScissorBitRestoresScissorState) {
  Context c = make();
  c.glEnable(GL_SCISSOR_TEST);
  c.glScissor(1, 2, 3, 4);
  c.glPushAttrib(GL_SCISSOR_BIT);
  c.glDisable(GL_SCISSOR_TEST);
  c.glScissor(0, 0, 8, 8);
  c.glViewport(2, 2, 4, 4);
  c.glPopAttrib();
  EXPECT_TRUE(on(c, GL_SCISSOR_TEST));
  EXPECT_EQ(get(c, GL_SCISSOR_BOX, 4), (V{1, 2, 3, 4}));
  EXPECT_EQ(get(c, GL_VIEWPORT, 4), (V{2, 2, 4, 4}));
}

// Table 6.25: the hints are "hint".
TEST(AttribStack, HintBitRestoresHints) {
  Context c = make();
  EXPECT_EQ(get1(c, GL_FOG_HINT), GL_DONT_CARE);
  c.glHint(GL_FOG_HINT, GL_NICEST);
  c.glHint(GL_PERSPECTIVE_CORRECTION_HINT, GL_FASTEST);
  c.glPushAttrib(GL_HINT_BIT);
  c.glHint(GL_FOG_HINT, GL_FASTEST);
  c.glHint(GL_PERSPECTIVE_CORRECTION_HINT, GL_NICEST);
  c.glHint(GL_LINE_SMOOTH_HINT, GL_NICEST);
  c.glPopAttrib();
  EXPECT_EQ(get1(c, GL_FOG_HINT), GL_NICEST);
  EXPECT_EQ(get1(c, GL_PERSPECTIVE_CORRECTION_HINT), GL_FASTEST);
  EXPECT_EQ(get1(c, GL_LINE_SMOOTH_HINT), GL_DONT_CARE);
}

// Table 6.26: AUTO_NORMAL is "eval/enable" (the maps are not modelled).
TEST(AttribStack, EvalBitRestoresAutoNormal) {
  Context c = make();
  c.glEnable(GL_AUTO_NORMAL);
  c.glPushAttrib(GL_EVAL_BIT);
  c.glDisable(GL_AUTO_NORMAL);
  c.glPopAttrib();
  EXPECT_TRUE(on(c, GL_AUTO_NORMAL));
}

// Table 6.27: LIST_BASE is "list".
TEST(AttribStack, ListBitRestoresListBase) {
  Context c = make();
  c.glListBase(7);
  c.glPushAttrib(GL_LIST_BIT);
  c.glListBase(9);
  c.glPopAttrib();
  EXPECT_EQ(get1(c, GL_LIST_BASE), 7.0);
}

// §6.1.14: ENABLE_BIT holds every enable, whatever its own group; other state of those
// groups is not restored by it.
TEST(AttribStack, EnableBitRestoresEnablesOnly) {
  Context c = make();
  for (GLenum cap : {GL_FOG, GL_DEPTH_TEST, GL_LIGHT3, GL_CLIP_PLANE5, GL_TEXTURE_GEN_Q, GL_POINT_SMOOTH,
                     GL_HISTOGRAM, GL_TEXTURE_1D})
    c.glEnable(cap);
  c.glFogf(GL_FOG_DENSITY, 0.5f);
  c.glPushAttrib(GL_ENABLE_BIT);
  for (GLenum cap : {GL_FOG, GL_DEPTH_TEST, GL_LIGHT3, GL_CLIP_PLANE5, GL_TEXTURE_GEN_Q, GL_POINT_SMOOTH,
                     GL_HISTOGRAM, GL_TEXTURE_1D})
    c.glDisable(cap);
  c.glEnable(GL_BLEND);
  c.glFogf(GL_FOG_DENSITY, 2.0f);
  c.glPopAttrib();
  for (GLenum cap : {GL_FOG, GL_DEPTH_TEST, GL_LIGHT3, GL_CLIP_PLANE5, GL_TEXTURE_GEN_Q, GL_POINT_SMOOTH,
                     GL_HISTOGRAM, GL_TEXTURE_1D})
    EXPECT_TRUE(on(c, cap)) << enum_name(cap);
  EXPECT_FALSE(on(c, GL_BLEND));
  EXPECT_EQ(get1(c, GL_FOG_DENSITY), 2.0);
}

// Every capability Enable accepts is restored by ENABLE_BIT and, without it, by the group its
// table row names beside "enable" (every enable of Tables 6.5-6.26 has one). Found by trying
// every value below 2^16 (all of GL 1.2's and ARB_imaging's capabilities): 38 named enables,
// 8 lights and 6 clip planes.
TEST(AttribStack, EveryEnableIsRestoredByEnableBitAndByItsOwnGroup) {
  Context c = make();
  int accepted = 0;
  for (GLenum cap = 0; cap < 0x10000; ++cap) {
    c.glEnable(cap);
    if (c.glGetError() != GL_NO_ERROR) continue;
    ++accepted;
    for (GLbitfield mask : {GLbitfield{GL_ENABLE_BIT}, GLbitfield{GL_ALL_ATTRIB_BITS & ~GLbitfield{GL_ENABLE_BIT}}}) {
      c.glPushAttrib(mask);
      c.glDisable(cap);
      c.glPopAttrib();
      EXPECT_TRUE(on(c, cap)) << enum_name(cap) << " after a pop of " << bitfield_name(mask);
    }
    c.glDisable(cap);
    c.glPushAttrib(GL_ENABLE_BIT);
    c.glEnable(cap);
    c.glPopAttrib();
    EXPECT_FALSE(on(c, cap)) << enum_name(cap);
  }
  EXPECT_EQ(accepted, 38 + 8 + 6);
  EXPECT_EQ(c.glGetError(), kNoError);
}

TEST(AttribStack, AllAttribBitsRestoresEveryGroup) {
  Context c = make();
  c.glColor4f(0.0f, 1.0f, 0.0f, 1.0f);
  c.glPointSize(2.0f);
  c.glLineWidth(3.0f);
  c.glCullFace(GL_FRONT);
  c.glShadeModel(GL_FLAT);
  c.glFogf(GL_FOG_START, 2.0f);
  c.glDepthFunc(GL_GREATER);
  c.glClearAccum(0.5f, 0.5f, 0.5f, 0.5f);
  c.glClearStencil(3);
  c.glViewport(1, 1, 2, 2);
  c.glMatrixMode(GL_PROJECTION);
  c.glEnable(GL_BLEND);
  c.glClearColor(0.5f, 0.5f, 0.5f, 0.5f);
  c.glHint(GL_FOG_HINT, GL_NICEST);
  c.glListBase(4);
  c.glPixelZoom(2.0f, 2.0f);
  c.glEnable(GL_TEXTURE_2D);
  c.glScissor(1, 1, 3, 3);
  c.glPushAttrib(GL_ALL_ATTRIB_BITS);
  c.glColor4f(1.0f, 0.0f, 0.0f, 0.0f);
  c.glPointSize(1.0f);
  c.glLineWidth(1.0f);
  c.glCullFace(GL_BACK);
  c.glShadeModel(GL_SMOOTH);
  c.glFogf(GL_FOG_START, 0.0f);
  c.glDepthFunc(GL_LESS);
  c.glClearAccum(0.0f, 0.0f, 0.0f, 0.0f);
  c.glClearStencil(0);
  c.glViewport(0, 0, 8, 8);
  c.glMatrixMode(GL_MODELVIEW);
  c.glDisable(GL_BLEND);
  c.glClearColor(0.0f, 0.0f, 0.0f, 0.0f);
  c.glHint(GL_FOG_HINT, GL_FASTEST);
  c.glListBase(0);
  c.glPixelZoom(1.0f, 1.0f);
  c.glDisable(GL_TEXTURE_2D);
  c.glScissor(0, 0, 8, 8);
  c.glPopAttrib();
  EXPECT_EQ(get(c, GL_CURRENT_COLOR, 4), (V{0, 1, 0, 1}));
  EXPECT_EQ(get1(c, GL_POINT_SIZE), 2.0);
  EXPECT_EQ(get1(c, GL_LINE_WIDTH), 3.0);
  EXPECT_EQ(get1(c, GL_CULL_FACE_MODE), GL_FRONT);
  EXPECT_EQ(get1(c, GL_SHADE_MODEL), GL_FLAT);
  EXPECT_EQ(get1(c, GL_FOG_START), 2.0);
  EXPECT_EQ(get1(c, GL_DEPTH_FUNC), GL_GREATER);
  EXPECT_EQ(get(c, GL_ACCUM_CLEAR_VALUE, 4), (V{0.5, 0.5, 0.5, 0.5}));
  EXPECT_EQ(get1(c, GL_STENCIL_CLEAR_VALUE), 3.0);
  EXPECT_EQ(get(c, GL_VIEWPORT, 4), (V{1, 1, 2, 2}));
  EXPECT_EQ(get1(c, GL_MATRIX_MODE), GL_PROJECTION);
  EXPECT_TRUE(on(c, GL_BLEND));
  EXPECT_EQ(get(c, GL_COLOR_CLEAR_VALUE, 4), (V{0.5, 0.5, 0.5, 0.5}));
  EXPECT_EQ(get1(c, GL_FOG_HINT), GL_NICEST);
  EXPECT_EQ(get1(c, GL_LIST_BASE), 4.0);
  EXPECT_EQ(get1(c, GL_ZOOM_X), 2.0);
  EXPECT_TRUE(on(c, GL_TEXTURE_2D));
  EXPECT_EQ(get(c, GL_SCISSOR_BOX, 4), (V{1, 1, 3, 3}));
}

// §6.1.14: the stack holds at least 16 entries (MAX_ATTRIB_STACK_DEPTH); a push onto a full
// stack is STACK_OVERFLOW, a pop of an empty one STACK_UNDERFLOW, and neither changes anything.
TEST(AttribStack, OverflowAndUnderflow) {
  Context c = make();
  EXPECT_EQ(get1(c, GL_MAX_ATTRIB_STACK_DEPTH), 16.0);
  EXPECT_EQ(get1(c, GL_ATTRIB_STACK_DEPTH), 0.0);
  c.glListBase(1);
  c.glPushAttrib(GL_LIST_BIT);
  for (int k = 1; k < 16; ++k) c.glPushAttrib(GL_FOG_BIT);
  EXPECT_EQ(error(c), kNoError);
  EXPECT_EQ(get1(c, GL_ATTRIB_STACK_DEPTH), 16.0);
  c.glListBase(2);
  c.glPushAttrib(GL_LIST_BIT);
  EXPECT_EQ(error(c), static_cast<GLenum>(GL_STACK_OVERFLOW));
  EXPECT_EQ(get1(c, GL_ATTRIB_STACK_DEPTH), 16.0);
  for (int k = 0; k < 15; ++k) c.glPopAttrib();
  EXPECT_EQ(get1(c, GL_LIST_BASE), 2.0);  // the fog entries restore fog only
  c.glPopAttrib();
  EXPECT_EQ(error(c), kNoError);
  EXPECT_EQ(get1(c, GL_LIST_BASE), 1.0);  // the first push's, not the refused one's
  c.glPopAttrib();
  EXPECT_EQ(error(c), static_cast<GLenum>(GL_STACK_UNDERFLOW));
  EXPECT_EQ(get1(c, GL_LIST_BASE), 1.0);
}

TEST(AttribStack, ClientOverflowAndUnderflow) {
  Context c = make();
  EXPECT_EQ(get1(c, GL_MAX_CLIENT_ATTRIB_STACK_DEPTH), 16.0);
  for (int k = 0; k < 16; ++k) c.glPushClientAttrib(GL_CLIENT_ALL_ATTRIB_BITS);
  EXPECT_EQ(error(c), kNoError);
  EXPECT_EQ(get1(c, GL_CLIENT_ATTRIB_STACK_DEPTH), 16.0);
  c.glPushClientAttrib(GL_CLIENT_PIXEL_STORE_BIT);
  EXPECT_EQ(error(c), static_cast<GLenum>(GL_STACK_OVERFLOW));
  for (int k = 0; k < 16; ++k) c.glPopClientAttrib();
  EXPECT_EQ(error(c), kNoError);
  c.glPopClientAttrib();
  EXPECT_EQ(error(c), static_cast<GLenum>(GL_STACK_UNDERFLOW));
  EXPECT_EQ(get1(c, GL_CLIENT_ATTRIB_STACK_DEPTH), 0.0);
}

// §2.6.3: none of the four is allowed between Begin and End (INVALID_OPERATION, no effect).
TEST(AttribStack, NotAllowedBetweenBeginAndEnd) {
  Context c = make();
  c.glPushAttrib(GL_ALL_ATTRIB_BITS);
  c.glPushClientAttrib(GL_CLIENT_ALL_ATTRIB_BITS);
  c.glBegin(GL_POINTS);
  c.glPushAttrib(GL_ALL_ATTRIB_BITS);
  c.glEnd();
  EXPECT_EQ(error(c), static_cast<GLenum>(GL_INVALID_OPERATION));
  c.glBegin(GL_POINTS);
  c.glPopAttrib();
  c.glEnd();
  EXPECT_EQ(error(c), static_cast<GLenum>(GL_INVALID_OPERATION));
  c.glBegin(GL_POINTS);
  c.glPushClientAttrib(GL_CLIENT_ALL_ATTRIB_BITS);
  c.glEnd();
  EXPECT_EQ(error(c), static_cast<GLenum>(GL_INVALID_OPERATION));
  c.glBegin(GL_POINTS);
  c.glPopClientAttrib();
  c.glEnd();
  EXPECT_EQ(error(c), static_cast<GLenum>(GL_INVALID_OPERATION));
  EXPECT_EQ(get1(c, GL_ATTRIB_STACK_DEPTH), 1.0);
  EXPECT_EQ(get1(c, GL_CLIENT_ATTRIB_STACK_DEPTH), 1.0);
}

// §5.4: PushAttrib and PopAttrib are compiled into display lists and run when the list is
// called; PushClientAttrib and PopClientAttrib are client state: run at once, never compiled.
TEST(AttribStack, PushAttribIsCompiledIntoListsPushClientAttribIsNot) {
  Context c = make();
  c.glNewList(1, GL_COMPILE);
  c.glPushAttrib(GL_FOG_BIT);
  c.glFogf(GL_FOG_DENSITY, 3.0f);
  c.glPopAttrib();
  c.glPushAttrib(GL_LIST_BIT);
  c.glPushClientAttrib(GL_CLIENT_PIXEL_STORE_BIT);
  c.glEndList();
  EXPECT_EQ(get1(c, GL_ATTRIB_STACK_DEPTH), 0.0);  // compiled, not run
  EXPECT_EQ(get1(c, GL_FOG_DENSITY), 1.0);
  EXPECT_EQ(get1(c, GL_CLIENT_ATTRIB_STACK_DEPTH), 1.0);  // run during compilation
  c.glPopClientAttrib();
  c.glFogf(GL_FOG_DENSITY, 0.5f);
  c.glCallList(1);
  EXPECT_EQ(error(c), kNoError);
  EXPECT_EQ(get1(c, GL_FOG_DENSITY), 0.5);  // set to 3 in the list, then popped
  EXPECT_EQ(get1(c, GL_ATTRIB_STACK_DEPTH), 1.0);  // the list's last push
  EXPECT_EQ(get1(c, GL_CLIENT_ATTRIB_STACK_DEPTH), 0.0);  // not in the list
  c.glPopAttrib();
  EXPECT_EQ(error(c), kNoError);
}

// Table 6.20: the pixel storage modes are "pixel-store"; the vertex arrays "vertex-array".
TEST(AttribStack, ClientPixelStoreBitRestoresPixelStorage) {
  Context c = make();
  c.glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  c.glPixelStorei(GL_PACK_ROW_LENGTH, 5);
  c.glPixelStorei(GL_UNPACK_LSB_FIRST, 1);
  c.glPushClientAttrib(GL_CLIENT_PIXEL_STORE_BIT);
  c.glPixelStorei(GL_UNPACK_ALIGNMENT, 8);
  c.glPixelStorei(GL_PACK_ROW_LENGTH, 0);
  c.glPixelStorei(GL_UNPACK_LSB_FIRST, 0);
  c.glEnableClientState(GL_NORMAL_ARRAY);
  c.glPopClientAttrib();
  EXPECT_EQ(get1(c, GL_UNPACK_ALIGNMENT), 1.0);
  EXPECT_EQ(get1(c, GL_PACK_ROW_LENGTH), 5.0);
  EXPECT_EQ(get1(c, GL_UNPACK_LSB_FIRST), 1.0);
  EXPECT_TRUE(on(c, GL_NORMAL_ARRAY));
}

// Tables 6.6-6.7: the arrays' enables and pointers come back: a point drawn from the restored
// vertex array lands at (2.5, 2.5), pixel (2, 2), not at the other array's (6, 6).
TEST(AttribStack, ClientVertexArrayBitRestoresArrays) {
  Context c = make();
  test::window_projection(c);
  const GLfloat a[2] = {2.5f, 2.5f};
  const GLshort b[3] = {6, 6, 0};
  c.glVertexPointer(2, GL_FLOAT, 0, a);
  c.glEnableClientState(GL_VERTEX_ARRAY);
  c.glPixelStorei(GL_UNPACK_ALIGNMENT, 2);
  c.glPushClientAttrib(GL_CLIENT_VERTEX_ARRAY_BIT);
  c.glVertexPointer(3, GL_SHORT, 0, b);
  c.glDisableClientState(GL_VERTEX_ARRAY);
  c.glEnableClientState(GL_COLOR_ARRAY);
  c.glPixelStorei(GL_UNPACK_ALIGNMENT, 8);
  c.glPopClientAttrib();
  EXPECT_TRUE(on(c, GL_VERTEX_ARRAY));
  EXPECT_FALSE(on(c, GL_COLOR_ARRAY));
  EXPECT_EQ(get1(c, GL_UNPACK_ALIGNMENT), 8.0);
  c.glDrawArrays(GL_POINTS, 0, 1);
  EXPECT_EQ(error(c), kNoError);
  EXPECT_EQ(pixel(c, 2, 2)[0], 255u);
  EXPECT_EQ(pixel(c, 6, 6)[0], 0u);
}

// A trace replayer hands the GL copies of the arrays' data and frees a copy when no array
// reads it any more: the data of arrays saved by PushClientAttrib must live until the pop
// restores them (an address sanitizer build sees a read of freed data otherwise).
TEST(AttribStack, ReplayKeepsSavedArrayDataAlive) {
  Context c = make();
  test::window_projection(c);
  CallRunner runner(c, true, nullptr);
  auto pointer_call = [&](int size, GLenum type, std::vector<std::byte> bytes, std::size_t count) {
    std::vector<Value> v(4);
    v[0].i = size;
    v[1].i = type;
    v[2].i = 0;
    v[3].bytes = std::make_shared<const std::vector<std::byte>>(std::move(bytes));
    v[3].elem_type = type;
    v[3].count = count;
    runner.run(*find_call("glVertexPointer"), v, "test");
  };
  auto bytes_of = [](const auto& array) {
    std::vector<std::byte> out(sizeof(array));
    std::memcpy(out.data(), &array, sizeof(array));
    return out;
  };
  const GLfloat a[2] = {2.5f, 2.5f}, b[2] = {6.5f, 6.5f};
  pointer_call(2, GL_FLOAT, bytes_of(a), 2);
  std::vector<Value> cap(1);
  cap[0].i = GL_VERTEX_ARRAY;
  runner.run(*find_call("glEnableClientState"), cap, "test");
  std::vector<Value> mask(1);
  mask[0].i = GL_CLIENT_VERTEX_ARRAY_BIT;
  runner.run(*find_call("glPushClientAttrib"), mask, "test");
  pointer_call(2, GL_FLOAT, bytes_of(b), 2);
  runner.run(*find_call("glPopClientAttrib"), {}, "test");
  std::vector<Value> draw(3);
  draw[0].i = GL_POINTS;
  draw[1].i = 0;
  draw[2].i = 1;
  runner.run(*find_call("glDrawArrays"), draw, "test");
  EXPECT_EQ(pixel(c, 2, 2)[0], 255u);
  EXPECT_EQ(pixel(c, 6, 6)[0], 0u);
}

// The calls print with their own bit names (PushClientAttrib's bits share values with
// PushAttrib's).
TEST(AttribStack, CallsPrintTheirBitNames) {
  Call push{find_call("glPushAttrib"), std::vector<Value>(1)};
  push.args[0].i = GL_FOG_BIT | GL_LIST_BIT;
  EXPECT_EQ(format_call(push), "glPushAttrib(GL_FOG_BIT | GL_LIST_BIT)");
  push.args[0].i = static_cast<std::int64_t>(GL_ALL_ATTRIB_BITS);
  EXPECT_EQ(format_call(push), "glPushAttrib(GL_ALL_ATTRIB_BITS)");
  Call client{find_call("glPushClientAttrib"), std::vector<Value>(1)};
  client.args[0].i = GL_CLIENT_VERTEX_ARRAY_BIT;
  EXPECT_EQ(format_call(client), "glPushClientAttrib(GL_CLIENT_VERTEX_ARRAY_BIT)");
  client.args[0].i = static_cast<std::int64_t>(GL_CLIENT_ALL_ATTRIB_BITS);
  EXPECT_EQ(format_call(client), "glPushClientAttrib(GL_CLIENT_ALL_ATTRIB_BITS)");
}
