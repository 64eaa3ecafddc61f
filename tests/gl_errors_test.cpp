// Every GL error case of the spine's calls (§2.5 and the command descriptions):
// the erroneous call sets the named error and has no effect.
#include <gtest/gtest.h>

#include <functional>
#include <string>

#include "test_util.hpp"

using namespace passim;

namespace {
struct ErrorCase {
  const char* what;
  std::function<void(Context&)> call;
  GLenum error;
};

Context make() { return Context(test::small_config(8, 8)); }
}  // namespace

TEST(GlErrors, EachCaseSetsTheNamedError) {
  const float f4[4] = {0, 0, 0, 0};
  const double d16[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
  const ErrorCase cases[] = {
      {"glEnable bad cap", [](Context& c) { c.glEnable(GL_TRIANGLES); }, GL_INVALID_ENUM},
      {"glDisable bad cap", [](Context& c) { c.glDisable(0x1234); }, GL_INVALID_ENUM},
      {"glIsEnabled bad cap", [](Context& c) { c.glIsEnabled(GL_FLOAT); }, GL_INVALID_ENUM},
      {"glGetIntegerv bad pname", [](Context& c) { GLint v[16]; c.glGetIntegerv(GL_FLOAT, v); }, GL_INVALID_ENUM},
      {"glHint bad target", [](Context& c) { c.glHint(GL_FLOAT, GL_NICEST); }, GL_INVALID_ENUM},
      {"glHint bad mode", [](Context& c) { c.glHint(GL_FOG_HINT, GL_FLOAT); }, GL_INVALID_ENUM},
      {"glClear bad bit", [](Context& c) { c.glClear(GL_COLOR_BUFFER_BIT | 0x8); }, GL_INVALID_VALUE},
      {"glDrawBuffer bad enum", [](Context& c) { c.glDrawBuffer(GL_FLOAT); }, GL_INVALID_ENUM},
      {"glDrawBuffer missing back buffer", [](Context& c) { c.glDrawBuffer(GL_BACK); }, GL_INVALID_OPERATION},
      {"glDrawBuffer missing right buffer", [](Context& c) { c.glDrawBuffer(GL_RIGHT); }, GL_INVALID_OPERATION},
      {"glDrawBuffer missing aux buffer", [](Context& c) { c.glDrawBuffer(GL_AUX0); }, GL_INVALID_OPERATION},
      {"glReadBuffer GL_NONE", [](Context& c) { c.glReadBuffer(GL_NONE); }, GL_INVALID_ENUM},
      {"glReadBuffer missing back", [](Context& c) { c.glReadBuffer(GL_BACK); }, GL_INVALID_OPERATION},
      {"glScissor negative", [](Context& c) { c.glScissor(0, 0, -1, 4); }, GL_INVALID_VALUE},
      {"glViewport negative", [](Context& c) { c.glViewport(0, 0, 4, -1); }, GL_INVALID_VALUE},
      {"glAlphaFunc bad func", [](Context& c) { c.glAlphaFunc(GL_ADD, 0.5f); }, GL_INVALID_ENUM},
      {"glStencilFunc bad func", [](Context& c) { c.glStencilFunc(GL_KEEP, 0, 1); }, GL_INVALID_ENUM},
      {"glStencilOp bad op", [](Context& c) { c.glStencilOp(GL_KEEP, GL_ADD, GL_KEEP); }, GL_INVALID_ENUM},
      {"glDepthFunc bad func", [](Context& c) { c.glDepthFunc(GL_ONE); }, GL_INVALID_ENUM},
      {"glBlendFunc SRC_COLOR as source", [](Context& c) { c.glBlendFunc(GL_SRC_COLOR, GL_ZERO); }, GL_INVALID_ENUM},
      {"glBlendFunc DST_COLOR as destination", [](Context& c) { c.glBlendFunc(GL_ONE, GL_DST_COLOR); }, GL_INVALID_ENUM},
      {"glBlendFunc SATURATE as destination", [](Context& c) { c.glBlendFunc(GL_ONE, GL_SRC_ALPHA_SATURATE); }, GL_INVALID_ENUM},
      {"glBlendEquation bad mode", [](Context& c) { c.glBlendEquation(GL_ONE); }, GL_INVALID_ENUM},
      {"glLogicOp bad op", [](Context& c) { c.glLogicOp(GL_ONE); }, GL_INVALID_ENUM},
      {"glMatrixMode bad mode", [](Context& c) { c.glMatrixMode(GL_FLOAT); }, GL_INVALID_ENUM},
      {"glPopMatrix underflow", [](Context& c) { c.glPopMatrix(); }, GL_STACK_UNDERFLOW},
      {"glPushMatrix projection overflow", [](Context& c) { c.glMatrixMode(GL_PROJECTION); c.glPushMatrix(); c.glPushMatrix(); }, GL_STACK_OVERFLOW},
      {"glFrustum near 0", [](Context& c) { c.glFrustum(-1, 1, -1, 1, 0, 10); }, GL_INVALID_VALUE},
      {"glFrustum far negative", [](Context& c) { c.glFrustum(-1, 1, -1, 1, 1, -10); }, GL_INVALID_VALUE},
      {"glFrustum left == right", [](Context& c) { c.glFrustum(1, 1, -1, 1, 1, 10); }, GL_INVALID_VALUE},
      {"glOrtho near == far", [](Context& c) { c.glOrtho(-1, 1, -1, 1, 2, 2); }, GL_INVALID_VALUE},
      {"glClipPlane bad plane", [&](Context& c) { c.glClipPlane(GL_CLIP_PLANE0 + 6, d16); }, GL_INVALID_ENUM},
      {"glBegin bad mode", [](Context& c) { c.glBegin(GL_POLYGON + 1); }, GL_INVALID_ENUM},
      {"glBegin inside Begin", [](Context& c) { c.glBegin(GL_TRIANGLES); c.glBegin(GL_TRIANGLES); }, GL_INVALID_OPERATION},
      {"glEnd without Begin", [](Context& c) { c.glEnd(); }, GL_INVALID_OPERATION},
      {"glEnable inside Begin", [](Context& c) { c.glBegin(GL_TRIANGLES); c.glEnable(GL_BLEND); }, GL_INVALID_OPERATION},
      {"glClear inside Begin", [](Context& c) { c.glBegin(GL_POINTS); c.glClear(GL_COLOR_BUFFER_BIT); }, GL_INVALID_OPERATION},
      {"glGetError inside Begin", [](Context& c) { c.glBegin(GL_POINTS); c.glGetError(); }, GL_INVALID_OPERATION},
      {"glEnableClientState bad array", [](Context& c) { c.glEnableClientState(GL_FLOAT); }, GL_INVALID_ENUM},
      {"glVertexPointer size 1", [](Context& c) { c.glVertexPointer(1, GL_FLOAT, 0, nullptr); }, GL_INVALID_VALUE},
      {"glVertexPointer bad type", [](Context& c) { c.glVertexPointer(3, GL_UNSIGNED_BYTE, 0, nullptr); }, GL_INVALID_ENUM},
      {"glVertexPointer negative stride", [](Context& c) { c.glVertexPointer(3, GL_FLOAT, -4, nullptr); }, GL_INVALID_VALUE},
      {"glNormalPointer bad type", [](Context& c) { c.glNormalPointer(GL_UNSIGNED_INT, 0, nullptr); }, GL_INVALID_ENUM},
      {"glColorPointer size 2", [](Context& c) { c.glColorPointer(2, GL_FLOAT, 0, nullptr); }, GL_INVALID_VALUE},
      {"glTexCoordPointer size 5", [](Context& c) { c.glTexCoordPointer(5, GL_FLOAT, 0, nullptr); }, GL_INVALID_VALUE},
      {"glDrawArrays bad mode", [](Context& c) { c.glDrawArrays(GL_FLOAT, 0, 3); }, GL_INVALID_ENUM},
      {"glDrawArrays negative count", [](Context& c) { c.glDrawArrays(GL_TRIANGLES, 0, -1); }, GL_INVALID_VALUE},
      {"glDrawElements bad type", [](Context& c) { const GLint i[3] = {0, 1, 2}; c.glDrawElements(GL_TRIANGLES, 3, GL_INT, i); }, GL_INVALID_ENUM},
      {"glDrawElements negative count", [](Context& c) { const GLuint i[1] = {0}; c.glDrawElements(GL_TRIANGLES, -1, GL_UNSIGNED_INT, i); }, GL_INVALID_VALUE},
      {"glEdgeFlagPointer negative stride", [](Context& c) { c.glEdgeFlagPointer(-1, nullptr); }, GL_INVALID_VALUE},
      {"glInterleavedArrays bad format", [](Context& c) { c.glInterleavedArrays(GL_RGBA, 0, nullptr); }, GL_INVALID_ENUM},
      {"glInterleavedArrays negative stride", [](Context& c) { c.glInterleavedArrays(GL_V3F, -4, nullptr); }, GL_INVALID_VALUE},
      {"glInterleavedArrays inside Begin", [](Context& c) { c.glBegin(GL_POINTS); c.glInterleavedArrays(GL_V3F, 0, nullptr); }, GL_INVALID_OPERATION},
      {"glDrawRangeElements end < start", [](Context& c) { const GLubyte i[1] = {0}; c.glDrawRangeElements(GL_POINTS, 2, 1, 1, GL_UNSIGNED_BYTE, i); }, GL_INVALID_VALUE},
      {"glDrawRangeElements negative count", [](Context& c) { const GLubyte i[1] = {0}; c.glDrawRangeElements(GL_POINTS, 0, 1, -1, GL_UNSIGNED_BYTE, i); }, GL_INVALID_VALUE},
      {"glDrawRangeElements bad mode", [](Context& c) { const GLubyte i[1] = {0}; c.glDrawRangeElements(GL_POLYGON + 1, 0, 1, 1, GL_UNSIGNED_BYTE, i); }, GL_INVALID_ENUM},
      {"glDrawRangeElements bad type", [](Context& c) { const GLshort i[1] = {0}; c.glDrawRangeElements(GL_POINTS, 0, 1, 1, GL_SHORT, i); }, GL_INVALID_ENUM},
      {"glDrawRangeElements inside Begin", [](Context& c) { const GLubyte i[1] = {0}; c.glBegin(GL_POINTS); c.glDrawRangeElements(GL_POINTS, 0, 1, 1, GL_UNSIGNED_BYTE, i); }, GL_INVALID_OPERATION},
      {"glRects inside Begin", [](Context& c) { c.glBegin(GL_POINTS); c.glRects(0, 0, 1, 1); }, GL_INVALID_OPERATION},
      {"glRectiv inside Begin", [](Context& c) { const GLint a[2] = {0, 0}, b[2] = {1, 1}; c.glBegin(GL_POINTS); c.glRectiv(a, b); }, GL_INVALID_OPERATION},
      {"glRectdv inside Begin", [](Context& c) { const GLdouble a[2] = {0, 0}, b[2] = {1, 1}; c.glBegin(GL_POINTS); c.glRectdv(a, b); }, GL_INVALID_OPERATION},
      {"glRasterPos3s inside Begin", [](Context& c) { c.glBegin(GL_POINTS); c.glRasterPos3s(0, 0, 0); }, GL_INVALID_OPERATION},
      {"glRasterPos4iv inside Begin", [](Context& c) { const GLint v[4] = {0, 0, 0, 1}; c.glBegin(GL_POINTS); c.glRasterPos4iv(v); }, GL_INVALID_OPERATION},
      {"glNewList 0", [](Context& c) { c.glNewList(0, GL_COMPILE); }, GL_INVALID_VALUE},
      {"glNewList bad mode", [](Context& c) { c.glNewList(1, GL_FLOAT); }, GL_INVALID_ENUM},
      {"glNewList while compiling", [](Context& c) { c.glNewList(1, GL_COMPILE); c.glNewList(2, GL_COMPILE); }, GL_INVALID_OPERATION},
      {"glEndList without NewList", [](Context& c) { c.glEndList(); }, GL_INVALID_OPERATION},
      {"glGenLists negative", [](Context& c) { c.glGenLists(-1); }, GL_INVALID_VALUE},
      {"glDeleteLists negative", [](Context& c) { c.glDeleteLists(1, -1); }, GL_INVALID_VALUE},
      {"glCallLists negative", [](Context& c) { const GLuint l[1] = {1}; c.glCallLists(-1, GL_UNSIGNED_INT, l); }, GL_INVALID_VALUE},
      {"glCallLists bad type", [](Context& c) { const GLuint l[1] = {1}; c.glCallLists(1, GL_DOUBLE, l); }, GL_INVALID_ENUM},
      {"glShadeModel bad mode", [](Context& c) { c.glShadeModel(GL_FLOAT); }, GL_INVALID_ENUM},
      {"glLightf bad light", [](Context& c) { c.glLightf(GL_LIGHT0 + 8, GL_SPOT_EXPONENT, 1); }, GL_INVALID_ENUM},
      {"glLightf vector pname", [](Context& c) { c.glLightf(GL_LIGHT0, GL_POSITION, 1); }, GL_INVALID_ENUM},
      {"glLightf spot exponent 129", [](Context& c) { c.glLightf(GL_LIGHT0, GL_SPOT_EXPONENT, 129); }, GL_INVALID_VALUE},
      {"glLightf spot cutoff 91", [](Context& c) { c.glLightf(GL_LIGHT0, GL_SPOT_CUTOFF, 91); }, GL_INVALID_VALUE},
      {"glLightf negative attenuation", [](Context& c) { c.glLightf(GL_LIGHT0, GL_LINEAR_ATTENUATION, -1); }, GL_INVALID_VALUE},
      {"glLightfv bad pname", [&](Context& c) { c.glLightfv(GL_LIGHT0, GL_SHININESS + 1, f4); }, GL_INVALID_ENUM},
      {"glLightModeli bad colour control", [](Context& c) { c.glLightModeli(GL_LIGHT_MODEL_COLOR_CONTROL, GL_FLOAT); }, GL_INVALID_ENUM},
      {"glLightModelf vector pname", [](Context& c) { c.glLightModelf(GL_LIGHT_MODEL_AMBIENT, 1); }, GL_INVALID_ENUM},
      {"glMaterialf bad face", [](Context& c) { c.glMaterialf(GL_LEFT, GL_SHININESS, 1); }, GL_INVALID_ENUM},
      {"glMaterialf shininess 200", [](Context& c) { c.glMaterialf(GL_FRONT, GL_SHININESS, 200); }, GL_INVALID_VALUE},
      {"glMaterialf vector pname", [](Context& c) { c.glMaterialf(GL_FRONT, GL_AMBIENT, 1); }, GL_INVALID_ENUM},
      {"glMaterialfv spot direction", [&](Context& c) { c.glMaterialfv(GL_FRONT, GL_SPOT_DIRECTION, f4); }, GL_INVALID_ENUM},
      {"glColorMaterial bad mode", [](Context& c) { c.glColorMaterial(GL_FRONT, GL_POSITION); }, GL_INVALID_ENUM},
      {"glCullFace bad mode", [](Context& c) { c.glCullFace(GL_LEFT); }, GL_INVALID_ENUM},
      {"glFrontFace bad mode", [](Context& c) { c.glFrontFace(GL_FRONT); }, GL_INVALID_ENUM},
      {"glPolygonMode bad mode", [](Context& c) { c.glPolygonMode(GL_FRONT, GL_TRIANGLES); }, GL_INVALID_ENUM},
      {"glPointSize 0", [](Context& c) { c.glPointSize(0); }, GL_INVALID_VALUE},
      {"glLineWidth negative", [](Context& c) { c.glLineWidth(-1); }, GL_INVALID_VALUE},
      {"glPushGroupMarkerEXT negative length", [](Context& c) { c.glPushGroupMarkerEXT(-1, "x"); }, GL_INVALID_VALUE},
  };
  for (const ErrorCase& ec : cases) {
    Context ctx = make();
    ec.call(ctx);
    // Errors are read outside Begin/End (glGetError itself is an error inside).
    if (std::string(ec.what).find("inside Begin") != std::string::npos) ctx.glEnd();
    EXPECT_EQ(ctx.glGetError(), ec.error) << ec.what;
    EXPECT_EQ(ctx.glGetError(), static_cast<GLenum>(GL_NO_ERROR)) << ec.what << ": the flag is cleared by glGetError";
  }
}

TEST(GlErrors, ErroneousCallHasNoEffect) {
  Context ctx(test::small_config(8, 8));
  ctx.glDepthFunc(GL_GREATER);
  ctx.glDepthFunc(GL_ONE);  // invalid
  GLint v = 0;
  ctx.glGetIntegerv(GL_DEPTH_FUNC, &v);
  EXPECT_EQ(static_cast<GLenum>(v), static_cast<GLenum>(GL_GREATER));
  ctx.glViewport(1, 2, 3, 4);
  ctx.glViewport(0, 0, -1, 5);  // invalid
  GLint vp[4];
  ctx.glGetIntegerv(GL_VIEWPORT, vp);
  EXPECT_EQ(vp[0], 1);
  EXPECT_EQ(vp[3], 4);
}

TEST(GlErrors, FirstErrorIsKeptUntilRead) {
  Context ctx(test::small_config(8, 8));
  ctx.glEnable(0x1234);            // INVALID_ENUM
  ctx.glScissor(0, 0, -1, -1);     // INVALID_VALUE, recorded in the log only
  EXPECT_EQ(ctx.glGetError(), static_cast<GLenum>(GL_INVALID_ENUM));
  EXPECT_EQ(ctx.glGetError(), static_cast<GLenum>(GL_NO_ERROR));
  ASSERT_EQ(ctx.error_log().size(), 2u);
  EXPECT_EQ(ctx.error_log()[1].call, "glScissor");
}

TEST(GlErrors, StackDepthsAndLimits) {
  Context ctx(test::small_config(8, 8));
  GLint max_mv = 0;
  ctx.glGetIntegerv(GL_MAX_MODELVIEW_STACK_DEPTH, &max_mv);
  EXPECT_GE(max_mv, 32);
  for (int k = 1; k < max_mv; ++k) ctx.glPushMatrix();
  EXPECT_EQ(ctx.glGetError(), static_cast<GLenum>(GL_NO_ERROR));
  ctx.glPushMatrix();
  EXPECT_EQ(ctx.glGetError(), static_cast<GLenum>(GL_STACK_OVERFLOW));
  GLint depth = 0;
  ctx.glGetIntegerv(GL_MODELVIEW_STACK_DEPTH, &depth);
  EXPECT_EQ(depth, max_mv);
}

TEST(GlErrors, GetStringNamesTheImplementationAndRejectsOtherNames) {
  // §6.1.5: VENDOR, RENDERER, VERSION and EXTENSIONS; any other name is INVALID_ENUM and a
  // call between Begin and End INVALID_OPERATION, both returning NULL.
  Context ctx(test::small_config(8, 8));
  auto text = [&](GLenum name) {
    const GLubyte* s = ctx.glGetString(name);
    return s ? std::string(reinterpret_cast<const char*>(s)) : std::string("(null)");
  };
  EXPECT_EQ(text(GL_VENDOR), "passim");
  EXPECT_EQ(text(GL_RENDERER), "ideal");  // the machine profile modelled
  EXPECT_EQ(text(GL_VERSION).rfind("1.2", 0), 0u);  // "<major>.<minor>" first (§6.1.5)
  EXPECT_NE(text(GL_EXTENSIONS).find("GL_ARB_imaging"), std::string::npos);
  EXPECT_EQ(ctx.glGetError(), static_cast<GLenum>(GL_NO_ERROR));
  EXPECT_EQ(text(GL_TEXTURE_2D), "(null)");
  EXPECT_EQ(ctx.glGetError(), static_cast<GLenum>(GL_INVALID_ENUM));
  ctx.glBegin(GL_POINTS);
  EXPECT_EQ(text(GL_VENDOR), "(null)");
  ctx.glEnd();
  EXPECT_EQ(ctx.glGetError(), static_cast<GLenum>(GL_INVALID_OPERATION));
}
