// Every GL error case of the spine's calls (§2.5 and the command descriptions):
// the erroneous call sets the named error and has no effect.
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <set>
#include <string>

#include "test_util.hpp"

using namespace passim;

namespace {
struct ErrorCase {
  const char* what;
  std::function<void(Context&)> call;
  GLenum error;
  // The rules that depend on the framebuffer or the budget need a context of another kind.
  bool color_only = false;         // no depth, stencil or accumulation buffer
  std::uint64_t memory_limit = 0;  // 0: the default budget
};

Context make(const ErrorCase& ec) {
  FramebufferConfig config = test::small_config(8, 8);
  if (ec.color_only) config.depth_bits = config.stencil_bits = config.accum_bits = 0;
  return Context(config, machine_profiles().front(), ec.memory_limit ? ec.memory_limit : kDefaultMemoryBudget);
}
}  // namespace

namespace {
// The negative cases: each erroneous call with the error the spec names for it.
const std::vector<ErrorCase>& error_cases() {
  static const float f4[4] = {0, 0, 0, 0};
  static const double d16[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
  static const std::vector<ErrorCase> cases = {
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
      {"glPushAttrib overflow", [](Context& c) { for (int k = 0; k <= 16; ++k) c.glPushAttrib(GL_ALL_ATTRIB_BITS); }, GL_STACK_OVERFLOW},
      {"glPopAttrib underflow", [](Context& c) { c.glPopAttrib(); }, GL_STACK_UNDERFLOW},
      {"glPushClientAttrib overflow", [](Context& c) { for (int k = 0; k <= 16; ++k) c.glPushClientAttrib(GL_CLIENT_ALL_ATTRIB_BITS); }, GL_STACK_OVERFLOW},
      {"glPopClientAttrib underflow", [](Context& c) { c.glPopClientAttrib(); }, GL_STACK_UNDERFLOW},
      {"glPushMatrix projection overflow", [](Context& c) { c.glMatrixMode(GL_PROJECTION); c.glPushMatrix(); c.glPushMatrix(); }, GL_STACK_OVERFLOW},
      {"glFrustum near 0", [](Context& c) { c.glFrustum(-1, 1, -1, 1, 0, 10); }, GL_INVALID_VALUE},
      {"glFrustum far negative", [](Context& c) { c.glFrustum(-1, 1, -1, 1, 1, -10); }, GL_INVALID_VALUE},
      {"glFrustum left == right", [](Context& c) { c.glFrustum(1, 1, -1, 1, 1, 10); }, GL_INVALID_VALUE},
      {"glOrtho near == far", [](Context& c) { c.glOrtho(-1, 1, -1, 1, 2, 2); }, GL_INVALID_VALUE},
      {"glClipPlane bad plane", [](Context& c) { c.glClipPlane(GL_CLIP_PLANE0 + 6, d16); }, GL_INVALID_ENUM},
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
      {"glLightfv bad pname", [](Context& c) { c.glLightfv(GL_LIGHT0, GL_SHININESS + 1, f4); }, GL_INVALID_ENUM},
      {"glLightModeli bad colour control", [](Context& c) { c.glLightModeli(GL_LIGHT_MODEL_COLOR_CONTROL, GL_FLOAT); }, GL_INVALID_ENUM},
      {"glLightModelf vector pname", [](Context& c) { c.glLightModelf(GL_LIGHT_MODEL_AMBIENT, 1); }, GL_INVALID_ENUM},
      {"glMaterialf bad face", [](Context& c) { c.glMaterialf(GL_LEFT, GL_SHININESS, 1); }, GL_INVALID_ENUM},
      {"glMaterialf shininess 200", [](Context& c) { c.glMaterialf(GL_FRONT, GL_SHININESS, 200); }, GL_INVALID_VALUE},
      {"glMaterialf vector pname", [](Context& c) { c.glMaterialf(GL_FRONT, GL_AMBIENT, 1); }, GL_INVALID_ENUM},
      {"glMaterialfv spot direction", [](Context& c) { c.glMaterialfv(GL_FRONT, GL_SPOT_DIRECTION, f4); }, GL_INVALID_ENUM},
      {"glColorMaterial bad mode", [](Context& c) { c.glColorMaterial(GL_FRONT, GL_POSITION); }, GL_INVALID_ENUM},
      {"glCullFace bad mode", [](Context& c) { c.glCullFace(GL_LEFT); }, GL_INVALID_ENUM},
      {"glFrontFace bad mode", [](Context& c) { c.glFrontFace(GL_FRONT); }, GL_INVALID_ENUM},
      {"glPolygonMode bad mode", [](Context& c) { c.glPolygonMode(GL_FRONT, GL_TRIANGLES); }, GL_INVALID_ENUM},
      {"glPointSize 0", [](Context& c) { c.glPointSize(0); }, GL_INVALID_VALUE},
      {"glLineWidth negative", [](Context& c) { c.glLineWidth(-1); }, GL_INVALID_VALUE},
      {"glPushGroupMarkerEXT negative length", [](Context& c) { c.glPushGroupMarkerEXT(-1, "x"); }, GL_INVALID_VALUE},
      // The rules of the remaining calls, one case each (GlErrors.EveryErrorRuleHasANegativeTest).
      {"glInsertEventMarkerEXT negative length", [](Context& c) { c.glInsertEventMarkerEXT(-1, "x"); }, GL_INVALID_VALUE},
      {"glDisableClientState bad array", [](Context& c) { c.glDisableClientState(GL_FLOAT); }, GL_INVALID_ENUM},
      {"glNormalPointer negative stride", [](Context& c) { c.glNormalPointer(GL_FLOAT, -1, nullptr); }, GL_INVALID_VALUE},
      {"glColorPointer bad type", [](Context& c) { c.glColorPointer(4, GL_BITMAP, 0, nullptr); }, GL_INVALID_ENUM},
      {"glTexCoordPointer bad type", [](Context& c) { c.glTexCoordPointer(2, GL_UNSIGNED_BYTE, 0, nullptr); }, GL_INVALID_ENUM},
      {"glAccum bad op", [](Context& c) { c.glAccum(GL_ADD + 1, 1); }, GL_INVALID_ENUM},
      {"glLighti vector pname", [](Context& c) { c.glLighti(GL_LIGHT0, GL_AMBIENT, 1); }, GL_INVALID_ENUM},
      {"glLightfv unknown pname", [](Context& c) { const GLfloat v[4] = {0, 0, 0, 0}; c.glLightfv(GL_LIGHT0, GL_FLOAT, v); }, GL_INVALID_ENUM},
      {"glLightModelf bad pname", [](Context& c) { c.glLightModelf(GL_FLOAT, 1); }, GL_INVALID_ENUM},
      {"glLightModeli ambient", [](Context& c) { c.glLightModeli(GL_LIGHT_MODEL_AMBIENT, 1); }, GL_INVALID_ENUM},
      {"glLightModelfv unknown pname", [](Context& c) { const GLfloat v[4] = {0, 0, 0, 0}; c.glLightModelfv(GL_FLOAT, v); }, GL_INVALID_ENUM},
      {"glMaterialfv unknown pname", [](Context& c) { const GLfloat v[4] = {0, 0, 0, 0}; c.glMaterialfv(GL_FRONT, GL_FLOAT, v); }, GL_INVALID_ENUM},
      {"glColorMaterial bad face", [](Context& c) { c.glColorMaterial(GL_LEFT, GL_AMBIENT); }, GL_INVALID_ENUM},
      {"glPixelStorei bad pname", [](Context& c) { c.glPixelStorei(GL_FLOAT, 1); }, GL_INVALID_ENUM},
      {"glPixelStorei alignment 3", [](Context& c) { c.glPixelStorei(GL_UNPACK_ALIGNMENT, 3); }, GL_INVALID_VALUE},
      {"glPixelStorei negative row length", [](Context& c) { c.glPixelStorei(GL_UNPACK_ROW_LENGTH, -1); }, GL_INVALID_VALUE},
      {"glPixelTransferf bad pname", [](Context& c) { c.glPixelTransferf(GL_FLOAT, 1); }, GL_INVALID_ENUM},
      {"glPixelMapfv bad map", [](Context& c) { const GLfloat v[1] = {0}; c.glPixelMapfv(GL_FLOAT, 1, v); }, GL_INVALID_ENUM},
      {"glPixelMapfv size 0", [](Context& c) { const GLfloat v[1] = {0}; c.glPixelMapfv(GL_PIXEL_MAP_R_TO_R, 0, v); }, GL_INVALID_VALUE},
      {"glPixelMapfv index map size 3", [](Context& c) { const GLfloat v[3] = {0, 0, 0}; c.glPixelMapfv(GL_PIXEL_MAP_I_TO_I, 3, v); }, GL_INVALID_VALUE},
      {"glBitmap negative width", [](Context& c) { c.glBitmap(-1, 1, 0, 0, 0, 0, nullptr); }, GL_INVALID_VALUE},
      {"glDrawPixels negative width", [](Context& c) { c.glDrawPixels(-1, 1, GL_RGBA, GL_UNSIGNED_BYTE, nullptr); }, GL_INVALID_VALUE},
      {"glDrawPixels bad type", [](Context& c) { c.glDrawPixels(1, 1, GL_RGBA, GL_RGBA, nullptr); }, GL_INVALID_ENUM},
      {"glDrawPixels bad format", [](Context& c) { c.glDrawPixels(1, 1, GL_FLOAT, GL_UNSIGNED_BYTE, nullptr); }, GL_INVALID_ENUM},
      {"glReadPixels negative width", [](Context& c) { GLubyte b[4]; c.glReadPixels(0, 0, -1, 1, GL_RGBA, GL_UNSIGNED_BYTE, b); }, GL_INVALID_VALUE},
      {"glReadPixels bad type", [](Context& c) { GLubyte b[4]; c.glReadPixels(0, 0, 1, 1, GL_RGBA, GL_RGBA, b); }, GL_INVALID_ENUM},
      {"glReadPixels COLOR_INDEX in RGBA mode", [](Context& c) { GLubyte b[4]; c.glReadPixels(0, 0, 1, 1, GL_COLOR_INDEX, GL_UNSIGNED_BYTE, b); }, GL_INVALID_OPERATION},
      {"glReadPixels bad format", [](Context& c) { GLubyte b[4]; c.glReadPixels(0, 0, 1, 1, GL_FLOAT, GL_UNSIGNED_BYTE, b); }, GL_INVALID_ENUM},
      {"glCopyPixels bad type", [](Context& c) { c.glCopyPixels(0, 0, 1, 1, GL_RGBA); }, GL_INVALID_ENUM},
      {"glCopyPixels negative width", [](Context& c) { c.glCopyPixels(0, 0, -1, 1, GL_COLOR); }, GL_INVALID_VALUE},
      {"glPolygonMode bad face", [](Context& c) { c.glPolygonMode(GL_LEFT, GL_FILL); }, GL_INVALID_ENUM},
      {"glGetFloatv bad pname", [](Context& c) { GLfloat v[16]; c.glGetFloatv(GL_FLOAT, v); }, GL_INVALID_ENUM},
      {"glGetDoublev bad pname", [](Context& c) { GLdouble v[16]; c.glGetDoublev(GL_FLOAT, v); }, GL_INVALID_ENUM},
      {"glGetBooleanv bad pname", [](Context& c) { GLboolean v[16]; c.glGetBooleanv(GL_FLOAT, v); }, GL_INVALID_ENUM},
      {"glGenTextures negative n", [](Context& c) { c.glGenTextures(-1, nullptr); }, GL_INVALID_VALUE},
      {"glDeleteTextures negative n", [](Context& c) { c.glDeleteTextures(-1, nullptr); }, GL_INVALID_VALUE},
      {"glBindTexture bad target", [](Context& c) { c.glBindTexture(GL_FLOAT, 1); }, GL_INVALID_ENUM},
      {"glBindTexture 1D name as 2D", [](Context& c) { c.glBindTexture(GL_TEXTURE_1D, 5); c.glBindTexture(GL_TEXTURE_2D, 5); }, GL_INVALID_OPERATION},
      {"glTexImage2D 1D target", [](Context& c) { c.glTexImage2D(GL_TEXTURE_1D, 0, GL_RGBA8, 1, 1, 0, GL_RGBA, GL_UNSIGNED_BYTE, nullptr); }, GL_INVALID_ENUM},
      {"glTexImage2D negative level", [](Context& c) { c.glTexImage2D(GL_TEXTURE_2D, -1, GL_RGBA8, 1, 1, 0, GL_RGBA, GL_UNSIGNED_BYTE, nullptr); }, GL_INVALID_VALUE},
      {"glTexImage2D bad internal format", [](Context& c) { c.glTexImage2D(GL_TEXTURE_2D, 0, 0x1234, 1, 1, 0, GL_RGBA, GL_UNSIGNED_BYTE, nullptr); }, GL_INVALID_VALUE},
      {"glTexImage2D border 2", [](Context& c) { c.glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, 1, 1, 2, GL_RGBA, GL_UNSIGNED_BYTE, nullptr); }, GL_INVALID_VALUE},
      {"glTexImage2D width 3", [](Context& c) { c.glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, 3, 1, 0, GL_RGBA, GL_UNSIGNED_BYTE, nullptr); }, GL_INVALID_VALUE},
      {"glTexImage2D bad format", [](Context& c) { c.glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, 1, 1, 0, GL_FLOAT, GL_UNSIGNED_BYTE, nullptr); }, GL_INVALID_ENUM},
      {"glTexImage2D bad type", [](Context& c) { c.glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, 1, 1, 0, GL_RGBA, GL_RGBA, nullptr); }, GL_INVALID_ENUM},
      {"glTexImage2D depth data into RGBA", [](Context& c) { c.glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, 1, 1, 0, GL_DEPTH_COMPONENT, GL_FLOAT, nullptr); }, GL_INVALID_OPERATION},
      {"glTexSubImage2D bad target", [](Context& c) { GLubyte b[4] = {}; c.glTexSubImage2D(GL_TEXTURE_1D, 0, 0, 0, 1, 1, GL_RGBA, GL_UNSIGNED_BYTE, b); }, GL_INVALID_ENUM},
      {"glTexSubImage2D bad format", [](Context& c) { GLubyte b[4] = {}; c.glTexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, 1, 1, GL_FLOAT, GL_UNSIGNED_BYTE, b); }, GL_INVALID_ENUM},
      {"glTexSubImage2D negative level", [](Context& c) { GLubyte b[4] = {}; c.glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, 1, 1, 0, GL_RGBA, GL_UNSIGNED_BYTE, nullptr); c.glTexSubImage2D(GL_TEXTURE_2D, -1, 0, 0, 1, 1, GL_RGBA, GL_UNSIGNED_BYTE, b); }, GL_INVALID_VALUE},
      {"glTexSubImage2D outside the level", [](Context& c) { GLubyte b[16] = {}; c.glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, 1, 1, 0, GL_RGBA, GL_UNSIGNED_BYTE, nullptr); c.glTexSubImage2D(GL_TEXTURE_2D, 0, 1, 0, 1, 1, GL_RGBA, GL_UNSIGNED_BYTE, b); }, GL_INVALID_VALUE},
      {"glTexSubImage2D depth into RGBA", [](Context& c) { GLfloat b[1] = {}; c.glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, 1, 1, 0, GL_RGBA, GL_UNSIGNED_BYTE, nullptr); c.glTexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, 1, 1, GL_DEPTH_COMPONENT, GL_FLOAT, b); }, GL_INVALID_OPERATION},
      {"glCopyTexImage2D internal format 4", [](Context& c) { c.glCopyTexImage2D(GL_TEXTURE_2D, 0, 4, 0, 0, 1, 1, 0); }, GL_INVALID_VALUE},
      {"glCopyTexSubImage2D bad target", [](Context& c) { c.glCopyTexSubImage2D(GL_TEXTURE_1D, 0, 0, 0, 0, 0, 1, 1); }, GL_INVALID_ENUM},
      {"glGetTexImage bad target", [](Context& c) { GLubyte b[4]; c.glGetTexImage(GL_FLOAT, 0, GL_RGBA, GL_UNSIGNED_BYTE, b); }, GL_INVALID_ENUM},
      {"glGetTexImage bad format", [](Context& c) { GLubyte b[4]; c.glGetTexImage(GL_TEXTURE_2D, 0, GL_FLOAT, GL_UNSIGNED_BYTE, b); }, GL_INVALID_ENUM},
      {"glGetTexImage undefined level", [](Context& c) { GLubyte b[4]; c.glGetTexImage(GL_TEXTURE_2D, 0, GL_RGBA, GL_UNSIGNED_BYTE, b); }, GL_INVALID_VALUE},
      {"glGetTexImage depth of RGBA", [](Context& c) { GLfloat b[1]; c.glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, 1, 1, 0, GL_RGBA, GL_UNSIGNED_BYTE, nullptr); c.glGetTexImage(GL_TEXTURE_2D, 0, GL_DEPTH_COMPONENT, GL_FLOAT, b); }, GL_INVALID_OPERATION},
      {"glTexParameteri bad target", [](Context& c) { c.glTexParameteri(GL_FLOAT, GL_TEXTURE_MAG_FILTER, GL_LINEAR); }, GL_INVALID_ENUM},
      {"glTexParameteri mag filter mipmap", [](Context& c) { c.glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR_MIPMAP_LINEAR); }, GL_INVALID_ENUM},
      {"glTexParameteri bad wrap", [](Context& c) { c.glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_LINEAR); }, GL_INVALID_ENUM},
      {"glTexParameteri negative base level", [](Context& c) { c.glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_BASE_LEVEL, -1); }, GL_INVALID_VALUE},
      {"glTexParameteri negative max level", [](Context& c) { c.glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAX_LEVEL, -1); }, GL_INVALID_VALUE},
      {"glTexParameteri bad compare operator", [](Context& c) { c.glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_COMPARE_OPERATOR_SGIX, GL_LEQUAL); }, GL_INVALID_ENUM},
      {"glTexParameteri bad compare mode", [](Context& c) { c.glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_COMPARE_MODE, GL_LEQUAL); }, GL_INVALID_ENUM},
      {"glTexParameteri bad compare func", [](Context& c) { c.glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_COMPARE_FUNC, GL_NEVER); }, GL_INVALID_ENUM},
      {"glTexParameteri bad depth texture mode", [](Context& c) { c.glTexParameteri(GL_TEXTURE_2D, GL_DEPTH_TEXTURE_MODE, GL_RGBA); }, GL_INVALID_ENUM},
      {"glTexParameteri bad pname", [](Context& c) { c.glTexParameteri(GL_TEXTURE_2D, GL_FLOAT, 0); }, GL_INVALID_ENUM},
      {"glGetTexParameterfv bad target", [](Context& c) { GLfloat v[4]; c.glGetTexParameterfv(GL_FLOAT, GL_TEXTURE_MAG_FILTER, v); }, GL_INVALID_ENUM},
      {"glGetTexParameterfv bad pname", [](Context& c) { GLfloat v[4]; c.glGetTexParameterfv(GL_TEXTURE_2D, GL_FLOAT, v); }, GL_INVALID_ENUM},
      {"glGetTexLevelParameteriv bad target", [](Context& c) { GLint v[1]; c.glGetTexLevelParameteriv(GL_FLOAT, 0, GL_TEXTURE_WIDTH, v); }, GL_INVALID_ENUM},
      {"glGetTexLevelParameteriv negative level", [](Context& c) { GLint v[1]; c.glGetTexLevelParameteriv(GL_TEXTURE_2D, -1, GL_TEXTURE_WIDTH, v); }, GL_INVALID_VALUE},
      {"glGetTexLevelParameteriv bad pname", [](Context& c) { GLint v[1]; c.glGetTexLevelParameteriv(GL_TEXTURE_2D, 0, GL_FLOAT, v); }, GL_INVALID_ENUM},
      {"glTexEnvi bad target", [](Context& c) { c.glTexEnvi(GL_FLOAT, GL_TEXTURE_ENV_MODE, GL_REPLACE); }, GL_INVALID_ENUM},
      {"glTexEnvi bad pname", [](Context& c) { c.glTexEnvi(GL_TEXTURE_ENV, GL_FLOAT, GL_REPLACE); }, GL_INVALID_ENUM},
      {"glTexGeni bad coord", [](Context& c) { c.glTexGeni(GL_FLOAT, GL_TEXTURE_GEN_MODE, GL_EYE_LINEAR); }, GL_INVALID_ENUM},
      {"glTexGeni bad mode", [](Context& c) { c.glTexGeni(GL_S, GL_TEXTURE_GEN_MODE, GL_LINEAR); }, GL_INVALID_ENUM},
      {"glTexGeni sphere map for R", [](Context& c) { c.glTexGeni(GL_R, GL_TEXTURE_GEN_MODE, GL_SPHERE_MAP); }, GL_INVALID_ENUM},
      {"glTexGeni bad pname", [](Context& c) { c.glTexGeni(GL_S, GL_FLOAT, GL_EYE_LINEAR); }, GL_INVALID_ENUM},
      {"glFogi bad mode", [](Context& c) { c.glFogi(GL_FOG_MODE, GL_NEAREST); }, GL_INVALID_ENUM},
      {"glFogf negative density", [](Context& c) { c.glFogf(GL_FOG_DENSITY, -1); }, GL_INVALID_VALUE},
      {"glFogi bad pname", [](Context& c) { c.glFogi(GL_FLOAT, 0); }, GL_INVALID_ENUM},
      // Framebuffer-dependent rules: a colour-only framebuffer.
      {"glAccum without an accumulation buffer", [](Context& c) { c.glAccum(GL_LOAD, 1); }, GL_INVALID_OPERATION, true},
      {"glDrawPixels stencil without stencil", [](Context& c) { const GLubyte b[1] = {0}; c.glDrawPixels(1, 1, GL_STENCIL_INDEX, GL_UNSIGNED_BYTE, b); }, GL_INVALID_OPERATION, true},
      {"glDrawPixels depth without depth", [](Context& c) { const GLubyte b[1] = {0}; c.glDrawPixels(1, 1, GL_DEPTH_COMPONENT, GL_UNSIGNED_BYTE, b); }, GL_INVALID_OPERATION, true},
      {"glReadPixels stencil without stencil", [](Context& c) { GLubyte b[1]; c.glReadPixels(0, 0, 1, 1, GL_STENCIL_INDEX, GL_UNSIGNED_BYTE, b); }, GL_INVALID_OPERATION, true},
      {"glReadPixels depth without depth", [](Context& c) { GLubyte b[1]; c.glReadPixels(0, 0, 1, 1, GL_DEPTH_COMPONENT, GL_UNSIGNED_BYTE, b); }, GL_INVALID_OPERATION, true},
      {"glCopyPixels depth without depth", [](Context& c) { c.glCopyPixels(0, 0, 1, 1, GL_DEPTH); }, GL_INVALID_OPERATION, true},
      {"glCopyTexImage2D depth without depth", [](Context& c) { c.glCopyTexImage2D(GL_TEXTURE_2D, 0, GL_DEPTH_COMPONENT, 0, 0, 4, 4, 0); }, GL_INVALID_OPERATION, true},
      {"glReadPixels bad format", [](Context& c) { GLubyte b[4]; c.glReadPixels(0, 0, 1, 1, GL_TEXTURE_2D, GL_UNSIGNED_BYTE, b); }, GL_INVALID_ENUM},
      // Sizes past the implementation or the budget (§2.5: OUT_OF_MEMORY).
      {"glReadPixels rectangle past the budget", [](Context& c) { GLubyte b[4]; c.glReadPixels(0, 0, 100000, 100000, GL_RGBA, GL_UNSIGNED_BYTE, b); }, GL_OUT_OF_MEMORY},
      {"glTexImage2D past max_texture_texels", [](Context& c) { c.glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA, 65536, 65536, 0, GL_RGBA, GL_UNSIGNED_BYTE, nullptr); }, GL_OUT_OF_MEMORY},
      {"glTexImage2D level past the budget", [](Context& c) { c.glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA, 256, 256, 0, GL_RGBA, GL_UNSIGNED_BYTE, nullptr); }, GL_OUT_OF_MEMORY, false, 64 * 1024},
      {"display list past the budget", [](Context& c) {
         static const std::vector<GLubyte> image(128 * 128 * 4, 0);
         c.glNewList(1, GL_COMPILE);
         c.glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA, 128, 128, 0, GL_RGBA, GL_UNSIGNED_BYTE, image.data());
         c.glEndList(); }, GL_OUT_OF_MEMORY, false, 64 * 1024},
      {"glGetTexImage pack rows past int", [](Context& c) {
         c.glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA, 2, 2, 0, GL_RGBA, GL_UNSIGNED_BYTE, nullptr);
         c.glPixelStorei(GL_PACK_SKIP_ROWS, 2147483647);
         GLubyte b[16];
         c.glGetTexImage(GL_TEXTURE_2D, 0, GL_RGBA, GL_UNSIGNED_BYTE, b); }, GL_INVALID_VALUE},
      // Enumerants of the wrong kind where a parameter's count alone would accept them.
      {"glGetString bad name", [](Context& c) { c.glGetString(GL_TEXTURE_2D); }, GL_INVALID_ENUM},
      {"glMaterialfv light pname", [](Context& c) { c.glMaterialfv(GL_FRONT, GL_POSITION, f4); }, GL_INVALID_ENUM},
      {"glTexGenfv env pname", [](Context& c) { c.glTexGenfv(GL_S, GL_TEXTURE_ENV_COLOR, f4); }, GL_INVALID_ENUM},
      {"glTexEnvi bad mode", [](Context& c) { c.glTexEnvi(GL_TEXTURE_ENV, GL_TEXTURE_ENV_MODE, GL_LINEAR); }, GL_INVALID_ENUM},
      {"glTexParameteri bad min filter", [](Context& c) { c.glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_REPEAT); }, GL_INVALID_ENUM},
      {"glTexSubImage2D bad target", [](Context& c) { const GLubyte b[4] = {0, 0, 0, 0}; c.glTexSubImage2D(GL_TEXTURE_1D, 0, 0, 0, 1, 1, GL_RGBA, GL_UNSIGNED_BYTE, b); }, GL_INVALID_ENUM},
      {"glCopyTexSubImage2D bad target", [](Context& c) { c.glCopyTexSubImage2D(GL_TEXTURE_1D, 0, 0, 0, 0, 0, 1, 1); }, GL_INVALID_ENUM},
      // Colour tables (§3.6.3, ARB_imaging).
      {"glColorTable bad target", [](Context& c) { c.glColorTable(GL_TEXTURE_2D, GL_RGBA, 4, GL_RGBA, GL_UNSIGNED_BYTE, nullptr); }, GL_INVALID_ENUM},
      {"glColorTable depth internal format", [](Context& c) { c.glColorTable(GL_COLOR_TABLE, GL_DEPTH_COMPONENT, 4, GL_RGBA, GL_UNSIGNED_BYTE, nullptr); }, GL_INVALID_ENUM},
      {"glColorTable internal format 3", [](Context& c) { c.glColorTable(GL_COLOR_TABLE, 3, 4, GL_RGBA, GL_UNSIGNED_BYTE, nullptr); }, GL_INVALID_ENUM},
      {"glColorTable stencil format", [](Context& c) { c.glColorTable(GL_COLOR_TABLE, GL_RGBA, 4, GL_STENCIL_INDEX, GL_UNSIGNED_BYTE, nullptr); }, GL_INVALID_ENUM},
      {"glColorTable width 3", [](Context& c) { c.glColorTable(GL_COLOR_TABLE, GL_RGBA, 3, GL_RGBA, GL_UNSIGNED_BYTE, nullptr); }, GL_INVALID_VALUE},
      {"glColorTable too large", [](Context& c) { c.glColorTable(GL_COLOR_TABLE, GL_RGBA, 1 << 30, GL_RGBA, GL_UNSIGNED_BYTE, nullptr); }, GL_TABLE_TOO_LARGE},
      {"glColorSubTable bad target", [](Context& c) { const GLubyte b[4] = {0, 0, 0, 0}; c.glColorSubTable(GL_TEXTURE_2D, 0, 1, GL_RGBA, GL_UNSIGNED_BYTE, b); }, GL_INVALID_ENUM},
      {"glColorSubTable depth format", [](Context& c) { const GLubyte b[4] = {0, 0, 0, 0}; c.glColorSubTable(GL_COLOR_TABLE, 0, 1, GL_DEPTH_COMPONENT, GL_UNSIGNED_BYTE, b); }, GL_INVALID_ENUM},
      {"glColorSubTable past the table", [](Context& c) {
         c.glColorTable(GL_COLOR_TABLE, GL_RGBA, 4, GL_RGBA, GL_UNSIGNED_BYTE, nullptr);
         const GLubyte b[8] = {};
         c.glColorSubTable(GL_COLOR_TABLE, 3, 2, GL_RGBA, GL_UNSIGNED_BYTE, b); }, GL_INVALID_VALUE},
      {"glCopyColorTable bad target", [](Context& c) { c.glCopyColorTable(GL_TEXTURE_2D, GL_RGBA, 0, 0, 4); }, GL_INVALID_ENUM},
      {"glCopyColorTable width 3", [](Context& c) { c.glCopyColorTable(GL_COLOR_TABLE, GL_RGBA, 0, 0, 3); }, GL_INVALID_VALUE},
      {"glCopyColorTable too large", [](Context& c) { c.glCopyColorTable(GL_COLOR_TABLE, GL_RGBA, 0, 0, 1 << 30); }, GL_TABLE_TOO_LARGE},
      {"glCopyColorSubTable bad target", [](Context& c) { c.glCopyColorSubTable(GL_TEXTURE_2D, 0, 0, 0, 1); }, GL_INVALID_ENUM},
      {"glCopyColorSubTable past the table", [](Context& c) { c.glCopyColorSubTable(GL_COLOR_TABLE, 0, 0, 0, 1); }, GL_INVALID_VALUE},
      {"glGetColorTable bad format", [](Context& c) { GLubyte b[4]; c.glGetColorTable(GL_COLOR_TABLE, GL_DEPTH_COMPONENT, GL_UNSIGNED_BYTE, b); }, GL_INVALID_ENUM},
      {"glColorTableParameterfv bad target", [](Context& c) { c.glColorTableParameterfv(GL_TEXTURE_2D, GL_COLOR_TABLE_SCALE, f4); }, GL_INVALID_ENUM},
      {"glColorTableParameterfv bad pname", [](Context& c) { c.glColorTableParameterfv(GL_COLOR_TABLE, GL_COLOR_TABLE_WIDTH, f4); }, GL_INVALID_ENUM},
      {"glGetColorTableParameteriv bad target", [](Context& c) { GLint v[4]; c.glGetColorTableParameteriv(GL_TEXTURE_2D, GL_COLOR_TABLE_WIDTH, v); }, GL_INVALID_ENUM},
      {"glGetColorTableParameteriv bad pname", [](Context& c) { GLint v[4]; c.glGetColorTableParameteriv(GL_COLOR_TABLE, GL_TEXTURE_WIDTH, v); }, GL_INVALID_ENUM},
      // Convolution filters (§3.6.3).
      {"glConvolutionFilter1D bad target", [](Context& c) { c.glConvolutionFilter1D(GL_CONVOLUTION_2D, GL_RGBA, 3, GL_RGBA, GL_FLOAT, nullptr); }, GL_INVALID_ENUM},
      {"glConvolutionFilter1D colour-index format", [](Context& c) { c.glConvolutionFilter1D(GL_CONVOLUTION_1D, GL_RGBA, 3, GL_COLOR_INDEX, GL_FLOAT, nullptr); }, GL_INVALID_ENUM},
      {"glConvolutionFilter1D too wide", [](Context& c) { c.glConvolutionFilter1D(GL_CONVOLUTION_1D, GL_RGBA, 1000, GL_RGBA, GL_FLOAT, nullptr); }, GL_INVALID_VALUE},
      {"glConvolutionFilter2D bad target", [](Context& c) { c.glConvolutionFilter2D(GL_CONVOLUTION_1D, GL_RGBA, 3, 3, GL_RGBA, GL_FLOAT, nullptr); }, GL_INVALID_ENUM},
      {"glConvolutionFilter2D negative height", [](Context& c) { c.glConvolutionFilter2D(GL_CONVOLUTION_2D, GL_RGBA, 3, -1, GL_RGBA, GL_FLOAT, nullptr); }, GL_INVALID_VALUE},
      {"glSeparableFilter2D bad target", [](Context& c) { c.glSeparableFilter2D(GL_CONVOLUTION_2D, GL_RGBA, 3, 3, GL_RGBA, GL_FLOAT, nullptr, nullptr); }, GL_INVALID_ENUM},
      {"glSeparableFilter2D too tall", [](Context& c) { c.glSeparableFilter2D(GL_SEPARABLE_2D, GL_RGBA, 3, 1000, GL_RGBA, GL_FLOAT, nullptr, nullptr); }, GL_INVALID_VALUE},
      {"glCopyConvolutionFilter2D bad target", [](Context& c) { c.glCopyConvolutionFilter2D(GL_SEPARABLE_2D, GL_RGBA, 0, 0, 3, 3); }, GL_INVALID_ENUM},
      {"glCopyConvolutionFilter2D too wide", [](Context& c) { c.glCopyConvolutionFilter2D(GL_CONVOLUTION_2D, GL_RGBA, 0, 0, 1000, 3); }, GL_INVALID_VALUE},
      {"glCopyConvolutionFilter1D bad target", [](Context& c) { c.glCopyConvolutionFilter1D(GL_CONVOLUTION_2D, GL_RGBA, 0, 0, 3); }, GL_INVALID_ENUM},
      {"glCopyConvolutionFilter1D negative width", [](Context& c) { c.glCopyConvolutionFilter1D(GL_CONVOLUTION_1D, GL_RGBA, 0, 0, -1); }, GL_INVALID_VALUE},
      {"glGetConvolutionFilter separable target", [](Context& c) { GLfloat b[4]; c.glGetConvolutionFilter(GL_SEPARABLE_2D, GL_RGBA, GL_FLOAT, b); }, GL_INVALID_ENUM},
      {"glGetSeparableFilter 2D target", [](Context& c) { GLfloat b[4]; c.glGetSeparableFilter(GL_CONVOLUTION_2D, GL_RGBA, GL_FLOAT, b, b, nullptr); }, GL_INVALID_ENUM},
      {"glConvolutionParameteri bad target", [](Context& c) { c.glConvolutionParameteri(GL_TEXTURE_2D, GL_CONVOLUTION_BORDER_MODE, GL_REDUCE); }, GL_INVALID_ENUM},
      {"glConvolutionParameteri bad border mode", [](Context& c) { c.glConvolutionParameteri(GL_CONVOLUTION_2D, GL_CONVOLUTION_BORDER_MODE, GL_CLAMP); }, GL_INVALID_ENUM},
      {"glConvolutionParameterfv bad pname", [](Context& c) { c.glConvolutionParameterfv(GL_CONVOLUTION_2D, GL_COLOR_TABLE_SCALE, f4); }, GL_INVALID_ENUM},
      // Histogram and minmax (§3.6.3).
      {"glHistogram bad target", [](Context& c) { c.glHistogram(GL_MINMAX, 16, GL_RGBA, GL_FALSE); }, GL_INVALID_ENUM},
      {"glHistogram width 3", [](Context& c) { c.glHistogram(GL_HISTOGRAM, 3, GL_RGBA, GL_FALSE); }, GL_INVALID_VALUE},
      {"glHistogram intensity format", [](Context& c) { c.glHistogram(GL_HISTOGRAM, 16, GL_INTENSITY, GL_FALSE); }, GL_INVALID_ENUM},
      {"glHistogram too large", [](Context& c) { c.glHistogram(GL_HISTOGRAM, 1 << 30, GL_RGBA, GL_FALSE); }, GL_TABLE_TOO_LARGE},
      {"glResetHistogram bad target", [](Context& c) { c.glResetHistogram(GL_MINMAX); }, GL_INVALID_ENUM},
      {"glGetHistogram bad target", [](Context& c) { GLuint b[4]; c.glGetHistogram(GL_MINMAX, GL_FALSE, GL_RGBA, GL_UNSIGNED_INT, b); }, GL_INVALID_ENUM},
      {"glGetHistogram depth format", [](Context& c) { GLuint b[4]; c.glGetHistogram(GL_HISTOGRAM, GL_FALSE, GL_DEPTH_COMPONENT, GL_UNSIGNED_INT, b); }, GL_INVALID_ENUM},
      {"glMinmax bad target", [](Context& c) { c.glMinmax(GL_HISTOGRAM, GL_RGBA, GL_FALSE); }, GL_INVALID_ENUM},
      {"glMinmax depth format", [](Context& c) { c.glMinmax(GL_MINMAX, GL_DEPTH_COMPONENT, GL_FALSE); }, GL_INVALID_ENUM},
      {"glResetMinmax bad target", [](Context& c) { c.glResetMinmax(GL_HISTOGRAM); }, GL_INVALID_ENUM},
      {"glGetMinmax bad target", [](Context& c) { GLfloat b[8]; c.glGetMinmax(GL_HISTOGRAM, GL_FALSE, GL_RGBA, GL_FLOAT, b); }, GL_INVALID_ENUM},
      {"glGetMinmax bad type", [](Context& c) { GLfloat b[8]; c.glGetMinmax(GL_MINMAX, GL_FALSE, GL_RGBA, GL_RGBA, b); }, GL_INVALID_ENUM},
  };
  return cases;
}
}  // namespace

TEST(GlErrors, EachCaseSetsTheNamedError) {
  for (const ErrorCase& ec : error_cases()) {
    Context ctx = make(ec);
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

// Every place in the GL machine's sources that raises a GL error (a `set_error(` line of
// pipeline/*.cpp: one rule, or a few the line decides between) should be reached by a
// negative case above. The sites no case reaches are printed, and there may be none
// (docs/status.md gives the counts): a new rule without a case makes this test fail.
TEST(GlErrors, EveryErrorRuleHasANegativeTest) {
  // Only the cases count: not the calls of other tests that ran before in this process.
  Context::forget_error_sites_reached();
  for (const ErrorCase& ec : error_cases()) {
    Context ctx = make(ec);
    ec.call(ctx);
  }
  const auto reached = Context::error_sites_reached();
  std::set<std::pair<std::string, int>> sites;
  for (const auto& entry : std::filesystem::directory_iterator(PASSIM_SOURCE_DIR "/pipeline")) {
    if (entry.path().extension() != ".cpp") continue;
    std::ifstream in(entry.path());
    std::string line;
    for (int n = 1; std::getline(in, line); ++n) {
      const std::size_t at = line.find("set_error(");
      const std::size_t comment = line.find("//");
      if (at == std::string::npos || (comment != std::string::npos && comment < at)) continue;
      if (line.find("void Context::set_error(") != std::string::npos) continue;  // the definition
      sites.emplace(entry.path().filename().string(), n);
    }
  }
  std::size_t unreached = 0;
  std::string list;
  for (const auto& site : sites)
    if (!reached.count(site)) {
      ++unreached;
      list += "  " + site.first + ":" + std::to_string(site.second) + "\n";
    }
  constexpr std::size_t kUnreachedAtMost = 0;
  std::printf("%zu error sites, %zu reached by the negative cases, %zu not yet:\n%s", sites.size(),
              sites.size() - unreached, unreached, list.c_str());
  EXPECT_GT(sites.size(), 150u) << "the scan of pipeline/*.cpp found too few sites";
  EXPECT_LE(unreached, kUnreachedAtMost) << list;
}
