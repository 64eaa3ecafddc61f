// Context: the OpenGL 1.2 (+ ARB_imaging) entry points with the spec's error
// semantics (§2.5: an erroneous call has no effect and sets an error flag).
// Each entry point validates, then updates state or hands work to a stage. The entry points
// are grouped below as the spec's state groups are, each group in its own file
// (pipeline/context_<group>.cpp, named beside each group); the state is the structs of
// pipeline/state.hpp, grouped as chapter 6's tables group it (docs/architecture.md).
#pragma once
#include <array>
#include <functional>
#include <stdexcept>
#include <type_traits>
#include <map>
#include <memory>
#include <set>
#include <string>
#include <vector>

#include "pipeline/attrib_stack.hpp"
#include "pipeline/calls.hpp"
#include "pipeline/counters.hpp"
#include "pipeline/framebuffer.hpp"
#include "pipeline/gl.hpp"
#include "pipeline/memory_budget.hpp"
#include "pipeline/profile.hpp"
#include "pipeline/state.hpp"
#include "pipeline/texture.hpp"
#include "stages/row_splitter.hpp"
#include "client/pixel_unpack.hpp"
#include "stages/fog.hpp"
#include "stages/pixel_transfer.hpp"
#include "stages/rasterizer.hpp"
#include "stages/vertex.hpp"

// §2.7's immediate-mode calls come in families, one member per component count n and type:
// glVertex{234}{sifd}[v], glTexCoord{1234}{sifd}[v], glNormal3{bsifd}[v], glColor{34}{b s i f d
// ub us ui}[v], glRasterPos{234}{sifd}[v], glRect{sifd}[v]. A family's types are listed once
// here, each as M(name, n, suffix, C type, scalar kind, array kind) (the call table's letters,
// pipeline/calls.hpp), and the members are declared (below), defined (context_vertices.cpp) and
// given their rows (calls.cpp) from these lists.
#define PASSIM_COORDINATE_TYPES(M, name, n) \
  M(name, n, s, GLshort, h, S) M(name, n, i, GLint, i, I) M(name, n, f, GLfloat, f, F) M(name, n, d, GLdouble, d, D)
#define PASSIM_NORMAL_TYPES(M, name, n) M(name, n, b, GLbyte, g, G) PASSIM_COORDINATE_TYPES(M, name, n)
#define PASSIM_COLOR_TYPES(M, name, n) \
  PASSIM_NORMAL_TYPES(M, name, n) M(name, n, ub, GLubyte, c, B) M(name, n, us, GLushort, w, H) M(name, n, ui, GLuint, u, U)
// A scalar form's parameters and arguments by component count.
#define PASSIM_COMPONENT_PARAMS_1(T) T a
#define PASSIM_COMPONENT_PARAMS_2(T) T a, T b
#define PASSIM_COMPONENT_PARAMS_3(T) T a, T b, T c
#define PASSIM_COMPONENT_PARAMS_4(T) T a, T b, T c, T d
#define PASSIM_COMPONENT_ARGS_1 a
#define PASSIM_COMPONENT_ARGS_2 a, b
#define PASSIM_COMPONENT_ARGS_3 a, b, c
#define PASSIM_COMPONENT_ARGS_4 a, b, c, d
#define PASSIM_DECLARE_SCALAR(name, n, suffix, T, ...) void name##n##suffix(PASSIM_COMPONENT_PARAMS_##n(T));
#define PASSIM_DECLARE_VECTOR(name, n, suffix, T, ...) void name##n##suffix##v(const T* v);
#define PASSIM_DECLARE_CALLS(name, n, suffix, T, ...) \
  PASSIM_DECLARE_SCALAR(name, n, suffix, T) PASSIM_DECLARE_VECTOR(name, n, suffix, T)
// glRect{sifd}v takes two corners.
#define PASSIM_DECLARE_RECT_VECTOR(name, n, suffix, T, ...) void name##suffix##v(const T* v1, const T* v2);

namespace passim {

struct FragmentStagesSetup;
struct LaneStages;
struct SpanBuffers;
class FragmentSink;
struct FragmentOpsInput;

// Receives every call the application makes (outermost calls only), for recording.
class CallSink {
 public:
  virtual ~CallSink() = default;
  virtual void on_call(const Call& call) = 0;
};

// Thrown for conditions that are not GL errors but make a run meaningless
// (a broken counter balance, an out-of-range client array read from a trace).
struct InternalError : std::runtime_error {
  using std::runtime_error::runtime_error;
};
struct ClientDataError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

class Context {
 public:
  // The planes are charged to a memory budget of `memory_limit` bytes first (BudgetExceeded
  // when they do not fit; memory_budget.hpp).
  explicit Context(const FramebufferConfig& config, const MachineProfile& profile = machine_profiles().front(),
                   std::uint64_t memory_limit = kDefaultMemoryBudget);
  ~Context();
  Context(const Context&) = delete;
  Context& operator=(const Context&) = delete;

  // ---- errors, enables and queries (§2.5, §2.11, §6.1): context_state.cpp ----
  GLenum glGetError();
  void glEnable(GLenum cap);
  void glDisable(GLenum cap);
  GLboolean glIsEnabled(GLenum cap);
  const GLubyte* glGetString(GLenum name);
  void glGetIntegerv(GLenum pname, GLint* params);
  void glGetFloatv(GLenum pname, GLfloat* params);
  void glGetDoublev(GLenum pname, GLdouble* params);
  void glGetBooleanv(GLenum pname, GLboolean* params);
  void glHint(GLenum target, GLenum mode);
  void glFlush();
  void glFinish();

  // ---- attribute stacks (§6.1.14): context_attrib.cpp ----
  void glPushAttrib(GLbitfield mask);
  void glPopAttrib();
  void glPushClientAttrib(GLbitfield mask);
  void glPopClientAttrib();

  // ---- framebuffer control, clears and accumulation (§4.2): context_framebuffer.cpp ----
  void glClear(GLbitfield mask);
  void glClearColor(GLfloat r, GLfloat g, GLfloat b, GLfloat a);
  void glClearDepth(GLdouble depth);
  void glClearStencil(GLint s);
  void glClearAccum(GLfloat r, GLfloat g, GLfloat b, GLfloat a);
  void glAccum(GLenum op, GLfloat value);
  void glColorMask(GLboolean r, GLboolean g, GLboolean b, GLboolean a);
  void glDepthMask(GLboolean flag);
  void glStencilMask(GLuint mask);
  void glDrawBuffer(GLenum mode);
  void glReadBuffer(GLenum mode);

  // ---- per-fragment operations (§4.1): context_fragment.cpp ----
  void glScissor(GLint x, GLint y, GLsizei width, GLsizei height);
  void glAlphaFunc(GLenum func, GLclampf ref);
  void glStencilFunc(GLenum func, GLint ref, GLuint mask);
  void glStencilOp(GLenum fail, GLenum zfail, GLenum zpass);
  void glDepthFunc(GLenum func);
  void glBlendFunc(GLenum sfactor, GLenum dfactor);
  void glBlendEquation(GLenum mode);
  void glBlendColor(GLclampf r, GLclampf g, GLclampf b, GLclampf a);
  void glLogicOp(GLenum opcode);

  // ---- coordinate transformation (§2.10): context_transform.cpp ----
  void glViewport(GLint x, GLint y, GLsizei width, GLsizei height);
  void glDepthRange(GLclampd near_val, GLclampd far_val);
  void glMatrixMode(GLenum mode);
  void glLoadIdentity();
  void glLoadMatrixf(const GLfloat* m);
  void glLoadMatrixd(const GLdouble* m);
  void glMultMatrixf(const GLfloat* m);
  void glMultMatrixd(const GLdouble* m);
  void glPushMatrix();
  void glPopMatrix();
  void glTranslatef(GLfloat x, GLfloat y, GLfloat z);
  void glTranslated(GLdouble x, GLdouble y, GLdouble z);
  void glRotatef(GLfloat angle, GLfloat x, GLfloat y, GLfloat z);
  void glRotated(GLdouble angle, GLdouble x, GLdouble y, GLdouble z);
  void glScalef(GLfloat x, GLfloat y, GLfloat z);
  void glScaled(GLdouble x, GLdouble y, GLdouble z);
  void glFrustum(GLdouble l, GLdouble r, GLdouble b, GLdouble t, GLdouble n, GLdouble f);
  void glOrtho(GLdouble l, GLdouble r, GLdouble b, GLdouble t, GLdouble n, GLdouble f);
  void glClipPlane(GLenum plane, const GLdouble* equation);
  // GLU helpers (computed with GLM, applied with glMultMatrixd semantics).
  void gluPerspective(GLdouble fovy, GLdouble aspect, GLdouble z_near, GLdouble z_far);
  void gluLookAt(GLdouble ex, GLdouble ey, GLdouble ez, GLdouble cx, GLdouble cy, GLdouble cz, GLdouble ux,
                 GLdouble uy, GLdouble uz);

  // ---- vertices, Begin/End, rectangles (§2.6-2.9): context_vertices.cpp ----
  void glBegin(GLenum mode);
  void glEnd();
  // §2.7's immediate-mode families, every member in its scalar and vector form (glVertex2s(GLshort,
  // GLshort) and glVertex2sv(const GLshort*)), declared from the family's types (above the class).
  PASSIM_COORDINATE_TYPES(PASSIM_DECLARE_CALLS, glVertex, 2)
  PASSIM_COORDINATE_TYPES(PASSIM_DECLARE_CALLS, glVertex, 3)
  PASSIM_COORDINATE_TYPES(PASSIM_DECLARE_CALLS, glVertex, 4)
  PASSIM_COORDINATE_TYPES(PASSIM_DECLARE_CALLS, glTexCoord, 1)
  PASSIM_COORDINATE_TYPES(PASSIM_DECLARE_CALLS, glTexCoord, 2)
  PASSIM_COORDINATE_TYPES(PASSIM_DECLARE_CALLS, glTexCoord, 3)
  PASSIM_COORDINATE_TYPES(PASSIM_DECLARE_CALLS, glTexCoord, 4)
  PASSIM_NORMAL_TYPES(PASSIM_DECLARE_CALLS, glNormal, 3)
  PASSIM_COLOR_TYPES(PASSIM_DECLARE_CALLS, glColor, 3)
  PASSIM_COLOR_TYPES(PASSIM_DECLARE_CALLS, glColor, 4)
  // §2.6.2: the flag current vertices take (polygon mode LINE and POINT draw the flagged edges).
  void glEdgeFlag(GLboolean flag);
  void glEdgeFlagv(const GLboolean* flag);
  // §2.9: Begin(POLYGON), the four corners counter-clockwise from (x1, y1), End.
  void glRects(GLshort x1, GLshort y1, GLshort x2, GLshort y2);
  void glRecti(GLint x1, GLint y1, GLint x2, GLint y2);
  void glRectf(GLfloat x1, GLfloat y1, GLfloat x2, GLfloat y2);
  void glRectd(GLdouble x1, GLdouble y1, GLdouble x2, GLdouble y2);
  PASSIM_COORDINATE_TYPES(PASSIM_DECLARE_RECT_VECTOR, glRect, 2)

  // ---- vertex arrays (§2.8): context_arrays.cpp ----
  void glEnableClientState(GLenum array);
  void glDisableClientState(GLenum array);
  void glVertexPointer(GLint size, GLenum type, GLsizei stride, const void* pointer);
  void glNormalPointer(GLenum type, GLsizei stride, const void* pointer);
  void glColorPointer(GLint size, GLenum type, GLsizei stride, const void* pointer);
  void glTexCoordPointer(GLint size, GLenum type, GLsizei stride, const void* pointer);
  void glEdgeFlagPointer(GLsizei stride, const void* pointer);
  // Table 2.5's formats: the arrays it enables and their pointers into one block.
  void glInterleavedArrays(GLenum format, GLsizei stride, const void* pointer);
  void glArrayElement(GLint i);
  void glDrawArrays(GLenum mode, GLint first, GLsizei count);
  void glDrawElements(GLenum mode, GLsizei count, GLenum type, const void* indices);
  void glDrawRangeElements(GLenum mode, GLuint start, GLuint end, GLsizei count, GLenum type, const void* indices);

  // ---- display lists (§5.4): context_lists.cpp ----
  void glNewList(GLuint list, GLenum mode);
  void glEndList();
  void glCallList(GLuint list);
  void glCallLists(GLsizei n, GLenum type, const void* lists);
  GLuint glGenLists(GLsizei range);
  void glDeleteLists(GLuint list, GLsizei range);
  GLboolean glIsList(GLuint list);
  void glListBase(GLuint base);

  // ---- lighting (§2.13): context_lighting.cpp ----
  void glShadeModel(GLenum mode);
  void glLightf(GLenum light, GLenum pname, GLfloat param);
  void glLighti(GLenum light, GLenum pname, GLint param);
  void glLightfv(GLenum light, GLenum pname, const GLfloat* params);
  void glLightModelf(GLenum pname, GLfloat param);
  void glLightModeli(GLenum pname, GLint param);
  void glLightModelfv(GLenum pname, const GLfloat* params);
  void glMaterialf(GLenum face, GLenum pname, GLfloat param);
  void glMaterialfv(GLenum face, GLenum pname, const GLfloat* params);
  void glColorMaterial(GLenum face, GLenum mode);

  // ---- points, lines and polygons (§3.3-3.5): context_rasterization.cpp ----
  void glCullFace(GLenum mode);
  void glFrontFace(GLenum mode);
  void glPolygonMode(GLenum face, GLenum mode);
  void glPolygonOffset(GLfloat factor, GLfloat units);
  void glPointSize(GLfloat size);
  void glLineWidth(GLfloat width);
  void glLineStipple(GLint factor, GLushort pattern);

  // ---- passes, EXT_debug_marker: context.cpp ----
  void glPushGroupMarkerEXT(GLsizei length, const GLchar* marker);
  void glPopGroupMarkerEXT();
  void glInsertEventMarkerEXT(GLsizei length, const GLchar* marker);

  // ---- pixel storage (§3.6.1): context_pixels.cpp ----
  void glPixelStorei(GLenum pname, GLint param);
  void glPixelStoref(GLenum pname, GLfloat param);

  // ---- texture objects, images, parameters (§3.8, SGIX_depth_texture, SGIX_shadow, ARB_shadow):
  //      context_texture.cpp; environment and coordinate generation: context_texture_env.cpp ----
  void glGenTextures(GLsizei n, GLuint* textures);
  void glDeleteTextures(GLsizei n, const GLuint* textures);
  void glBindTexture(GLenum target, GLuint texture);
  GLboolean glIsTexture(GLuint texture);
  void glTexImage1D(GLenum target, GLint level, GLint internalformat, GLsizei width, GLint border, GLenum format,
                    GLenum type, const void* pixels);
  void glTexImage2D(GLenum target, GLint level, GLint internalformat, GLsizei width, GLsizei height, GLint border,
                    GLenum format, GLenum type, const void* pixels);
  void glTexSubImage1D(GLenum target, GLint level, GLint xoffset, GLsizei width, GLenum format, GLenum type,
                       const void* pixels);
  void glTexSubImage2D(GLenum target, GLint level, GLint xoffset, GLint yoffset, GLsizei width, GLsizei height,
                       GLenum format, GLenum type, const void* pixels);
  // The GLU helpers (docs/arithmetic.md A28): every level from the image halved in its own
  // type as SGI's GLU 1.3 does; 0, or GLU_INVALID_ENUM / GLU_INVALID_VALUE (then no level
  // is specified). Power-of-two sizes only (GLU would first scale others with gluScaleImage).
  GLint gluBuild1DMipmaps(GLenum target, GLint internalformat, GLsizei width, GLenum format, GLenum type,
                          const void* data);
  GLint gluBuild2DMipmaps(GLenum target, GLint internalformat, GLsizei width, GLsizei height, GLenum format,
                          GLenum type, const void* data);
  void glCopyTexImage1D(GLenum target, GLint level, GLenum internalformat, GLint x, GLint y, GLsizei width,
                        GLint border);
  void glCopyTexImage2D(GLenum target, GLint level, GLenum internalformat, GLint x, GLint y, GLsizei width,
                        GLsizei height, GLint border);
  void glCopyTexSubImage1D(GLenum target, GLint level, GLint xoffset, GLint x, GLint y, GLsizei width);
  void glCopyTexSubImage2D(GLenum target, GLint level, GLint xoffset, GLint yoffset, GLint x, GLint y, GLsizei width,
                           GLsizei height);
  void glGetTexImage(GLenum target, GLint level, GLenum format, GLenum type, void* pixels);
  void glTexParameteri(GLenum target, GLenum pname, GLint param);
  void glTexParameterf(GLenum target, GLenum pname, GLfloat param);
  void glTexParameterfv(GLenum target, GLenum pname, const GLfloat* params);
  void glGetTexParameterfv(GLenum target, GLenum pname, GLfloat* params);
  void glGetTexParameteriv(GLenum target, GLenum pname, GLint* params);
  void glGetTexLevelParameteriv(GLenum target, GLint level, GLenum pname, GLint* params);
  void glTexEnvi(GLenum target, GLenum pname, GLint param);
  void glTexEnvf(GLenum target, GLenum pname, GLfloat param);
  void glTexEnvfv(GLenum target, GLenum pname, const GLfloat* params);
  void glTexGeni(GLenum coord, GLenum pname, GLint param);
  void glTexGenf(GLenum coord, GLenum pname, GLfloat param);
  void glTexGenfv(GLenum coord, GLenum pname, const GLfloat* params);
  void glTexGendv(GLenum coord, GLenum pname, const GLdouble* params);

  // ---- fog (§3.10): context_texture_env.cpp ----
  void glFogf(GLenum pname, GLfloat param);
  void glFogi(GLenum pname, GLint param);
  void glFogfv(GLenum pname, const GLfloat* params);

  // ---- raster position, pixel maps and transfer, pixel rectangles (§2.12, §3.6, §4.3):
  //      context_pixels.cpp ----
  void glRasterPos2i(GLint x, GLint y);
  void glRasterPos2f(GLfloat x, GLfloat y);
  void glRasterPos3f(GLfloat x, GLfloat y, GLfloat z);
  void glRasterPos4f(GLfloat x, GLfloat y, GLfloat z, GLfloat w);
  void glRasterPos2d(GLdouble x, GLdouble y);
  void glRasterPos3d(GLdouble x, GLdouble y, GLdouble z);
  // The rest of §2.12's family, beside Vertex's in context_vertices.cpp.
  PASSIM_DECLARE_SCALAR(glRasterPos, 2, s, GLshort)
  PASSIM_DECLARE_SCALAR(glRasterPos, 3, s, GLshort)
  PASSIM_DECLARE_SCALAR(glRasterPos, 4, s, GLshort)
  PASSIM_DECLARE_SCALAR(glRasterPos, 3, i, GLint)
  PASSIM_DECLARE_SCALAR(glRasterPos, 4, i, GLint)
  PASSIM_DECLARE_SCALAR(glRasterPos, 4, d, GLdouble)
  PASSIM_COORDINATE_TYPES(PASSIM_DECLARE_VECTOR, glRasterPos, 2)
  PASSIM_COORDINATE_TYPES(PASSIM_DECLARE_VECTOR, glRasterPos, 3)
  PASSIM_COORDINATE_TYPES(PASSIM_DECLARE_VECTOR, glRasterPos, 4)
  void glPixelZoom(GLfloat xfactor, GLfloat yfactor);
  void glPixelTransferf(GLenum pname, GLfloat param);
  void glPixelTransferi(GLenum pname, GLint param);
  void glPixelMapfv(GLenum map, GLsizei mapsize, const GLfloat* values);
  void glPixelMapusv(GLenum map, GLsizei mapsize, const GLushort* values);
  void glPixelMapuiv(GLenum map, GLsizei mapsize, const GLuint* values);
  void glDrawPixels(GLsizei width, GLsizei height, GLenum format, GLenum type, const void* pixels);
  void glReadPixels(GLint x, GLint y, GLsizei width, GLsizei height, GLenum format, GLenum type, void* pixels);
  void glCopyPixels(GLint x, GLint y, GLsizei width, GLsizei height, GLenum type);
  // §3.7: fragments of the raster colour where bits are set, at ⌊raster position − origin⌋;
  // then the raster position moves by (xmove, ymove).
  void glBitmap(GLsizei width, GLsizei height, GLfloat xorig, GLfloat yorig, GLfloat xmove, GLfloat ymove,
                const GLubyte* bitmap);

  // ---- the imaging subset (ARB_imaging): context_imaging.cpp ----
  void glColorTable(GLenum target, GLenum internalformat, GLsizei width, GLenum format, GLenum type,
                    const void* table);
  void glColorSubTable(GLenum target, GLsizei start, GLsizei count, GLenum format, GLenum type, const void* data);
  void glCopyColorTable(GLenum target, GLenum internalformat, GLint x, GLint y, GLsizei width);
  void glColorTableParameterfv(GLenum target, GLenum pname, const GLfloat* params);
  void glGetColorTableParameteriv(GLenum target, GLenum pname, GLint* params);
  void glCopyColorSubTable(GLenum target, GLsizei start, GLint x, GLint y, GLsizei width);
  // §3.6.3 / §6.1.4: the table or filter as stored, packed like ReadPixels without pixel transfer.
  void glGetColorTable(GLenum target, GLenum format, GLenum type, void* table);
  void glGetConvolutionFilter(GLenum target, GLenum format, GLenum type, void* image);
  void glGetSeparableFilter(GLenum target, GLenum format, GLenum type, void* row, void* column, void* span);
  void glCopyConvolutionFilter1D(GLenum target, GLenum internalformat, GLint x, GLint y, GLsizei width);
  void glConvolutionFilter1D(GLenum target, GLenum internalformat, GLsizei width, GLenum format, GLenum type,
                             const void* image);
  void glConvolutionFilter2D(GLenum target, GLenum internalformat, GLsizei width, GLsizei height, GLenum format,
                             GLenum type, const void* image);
  void glSeparableFilter2D(GLenum target, GLenum internalformat, GLsizei width, GLsizei height, GLenum format,
                           GLenum type, const void* row, const void* column);
  void glCopyConvolutionFilter2D(GLenum target, GLenum internalformat, GLint x, GLint y, GLsizei width,
                                 GLsizei height);
  void glConvolutionParameteri(GLenum target, GLenum pname, GLint param);
  void glConvolutionParameterfv(GLenum target, GLenum pname, const GLfloat* params);
  void glHistogram(GLenum target, GLsizei width, GLenum internalformat, GLboolean sink);
  void glResetHistogram(GLenum target);
  void glGetHistogram(GLenum target, GLboolean reset, GLenum format, GLenum type, void* values);
  void glMinmax(GLenum target, GLenum internalformat, GLboolean sink);
  void glResetMinmax(GLenum target);
  void glGetMinmax(GLenum target, GLboolean reset, GLenum format, GLenum type, void* values);

  // ---- window system (what glXSwapBuffers does): context.cpp ----
  void swap_buffers();

  // ---- passim: inspection, recording, counters ----
  const Framebuffer& framebuffer() const { return fb_; }
  const FramebufferConfig& config() const { return fb_.config; }
  // The what-if study's stage removal (not GL state; see PixelTransferState::Removed).
  void remove_stages(const PixelTransferState::Removed& removed) { transfer_.removed = removed; }
  const MachineProfile& profile() const { return profile_; }
  // The run's memory budget: what the GL holds for the application is charged to it.
  MemoryBudget& memory() { return memory_; }
  const MemoryBudget& memory() const { return memory_; }
  const std::vector<Pass>& passes() const { return passes_; }
  Counters total_counters() const;
  const std::vector<GlErrorRecord>& error_log() const { return error_log_; }
  // The places in the GL machine's sources (file name, line) whose error rules have raised an
  // error in this process, in any context: what the negative tests have reached.
  static std::set<std::pair<std::string, int>> error_sites_reached();
  static void forget_error_sites_reached();  // so that a test counts only what its own calls reach
  const std::vector<std::string>& warnings() const { return warnings_; }
  // Raises InternalError if any pass broke the fragment balance.
  void check_balance() const;
  void set_call_sink(CallSink* sink) { sink_ = sink; }
  // Called at the end of every pass (each glPopGroupMarkerEXT, with the index of the pass that
  // ended) once its work has reached the planes: where the cross-check compares two runs.
  using PassEndObserver = std::function<void(const Context&, std::size_t pass)>;
  void set_pass_end_observer(PassEndObserver observer) { pass_end_ = std::move(observer); }
  // "file:line" attached to GL errors raised from now on (trace replay).
  void set_source_location(std::string where) { where_ = std::move(where); }
  // The colour buffer a name (GL_FRONT/GL_BACK...) reads from; nullptr when absent.
  const ColorPlane* color_buffer(GLenum which) const;
  // The buffer glReadPixels reads (GL_READ_BUFFER), without a GL call (which a recorder would record).
  GLenum read_buffer() const { return pixel_.read_buffer; }
  GLenum draw_buffer() const { return fb_control_.draw_buffer; }  // GL_DRAW_BUFFER, likewise
  // The trace replayer tells how many bytes lie behind the data it just gave a pointer call
  // (for bounds checks): the arrays now pointing into [data, data + bytes) take it as theirs
  // (a pointer call sets one, InterleavedArrays several) and are returned. None when the call
  // raised an error and had no effect, so the replayer keeps the earlier data alive.
  std::vector<GLenum> adopt_client_array_data(const void* data, std::size_t bytes);
  const PixelStore& unpack_store() const { return pixel_store_.unpack; }
  const PixelStore& pack_store() const { return pixel_store_.pack; }
  // The elements the image queries write with the state as it is (the call table's {state}
  // outputs, sized before the call runs); 0 where the call would raise an error and write nothing.
  std::uint64_t state_output_elements(GLenum pname) const;  // glGet{Integer,Float,Double,Boolean}v
  std::uint64_t tex_image_output_elements(GLenum target, GLint level, GLenum format, GLenum type) const;
  std::uint64_t color_table_output_elements(GLenum target, GLenum format, GLenum type) const;
  // `part`: 0 the filter's image, 1 a separable filter's row, 2 its column.
  std::uint64_t filter_output_elements(GLenum target, GLenum format, GLenum type, int part) const;
  std::uint64_t histogram_output_elements(GLenum format, GLenum type) const;
  std::uint64_t minmax_output_elements(GLenum format, GLenum type) const;
  // The client attribute stack's depth (a trace replayer keeps the array data it saved alive).
  std::size_t client_attrib_depth() const { return client_attrib_stack_.size(); }
  // The groups the top entry of the client stack saved (0 when it is empty).
  GLbitfield client_attrib_top_mask() const { return client_attrib_stack_.empty() ? 0 : client_attrib_stack_.back().mask; }
  // The texture object bound to a target (GL_TEXTURE_1D/2D); nullptr for another target.
  const TextureObject* bound_texture(GLenum target) const;
  // Bits of each fragment colour channel (A26: alpha carried at RGB precision when the
  // framebuffer has fewer than 2 alpha bits).
  const std::array<int, 4>& fragment_color_bits() const { return fragment_bits_; }
  // Threads of rasterization and fragment processing (1 = this thread only). Any number
  // gives the same bits and counters (docs/threads.md); at most kMaxThreads.
  void set_threads(int threads);
  int threads() const;
  static constexpr int kMaxThreads = 64;

  // Call-table plumbing (used by PASSIM_ENTRY; see calls.cpp).
  struct CallScope {
    explicit CallScope(Context& c) : ctx(c) { ++ctx.call_depth_; }
    // Primitives queued to the raster lanes are run when the outermost call that drew them
    // returns, unless it left a Begin/End open (the rest of it follows).
    ~CallScope() {
      if (--ctx.call_depth_ == 0 && ctx.raster_queued_ && !ctx.in_begin_) ctx.run_raster_queue();
    }
    bool outermost() const { return ctx.call_depth_ == 1; }
    Context& ctx;
  };
  template <class... A>
  bool intercept(const CallInfo& info, const A&... args);

 private:
  bool intercept_values(const CallInfo& info, std::vector<Value>&& values);
  // `site_file`, `site_line`: where the rule that raised it is written (for the test that every
  // rule has a negative test, GlErrors.EveryErrorRuleHasANegativeTest).
  // (__builtin_FILE/LINE rather than std::source_location, which clang 14 with libstdc++ 12 —
  // the fuzz build — lacks.)
  void set_error(GLenum error, const char* site_file = __builtin_FILE(), int site_line = __builtin_LINE());
  // §2.5: a call whose working buffers — `pixels` pixels of a rectangle as the pixel path holds
  // them — would pass what is left of the memory budget raises OUT_OF_MEMORY (false: the call
  // must then do nothing).
  bool rectangle_fits_in_memory(std::int64_t width, std::int64_t height);
  static constexpr std::uint64_t kRectangleBytesPerPixel = 48;  // reals (32) + codes (8) + a copy (8)
  // The scalar (glXxxi/f) and vector (glXxxfv) forms of a parameter call: a scalar call with a
  // vector-valued pname is INVALID_ENUM; both hand the setter four doubles.
  template <class Setter>
  void scalar_parameter(bool vector_pname, double value, Setter&& set) {
    if (vector_pname) return set_error(GL_INVALID_ENUM);
    const double v[4] = {value, 0.0, 0.0, 0.0};
    set(v);
  }
  template <class T, class Setter>
  void vector_parameter(const T* params, int n, Setter&& set) {
    double v[4] = {0.0, 0.0, 0.0, 0.0};
    for (int k = 0; k < n && k < 4; ++k) v[k] = static_cast<double>(params[k]);
    set(v);
  }
  bool set_capability(GLenum cap, bool value);
  // Every capability Enable accepts (§2.11 and the tables' "enable" attributes), in one order.
  std::vector<GLenum> capabilities() const;
  // The attribute groups' saving and restoring (context_attrib.cpp).
  void save_attribs(ServerAttribs& saved);
  void restore_attribs(const ServerAttribs& saved);
  bool get_state(GLenum pname, std::vector<double>& out, bool& is_color) const;
  std::vector<Mat4>& current_stack();
  void mult_matrix(const Mat4& m);
  void submit_vertex(const Vec4& object_position);
  ProcessedVertex process_vertex(const Vec4& object_position, Counters& counters);
  // process_vertex in two parts: what it changes (the normal matrix computed, the vertex
  // material recorded), once per run of vertices, and then, reading state only, a vertex with
  // the given current normal.
  void prepare_vertex_processing();
  bool sphere_map_texgen() const;  // s or t generated by SPHERE_MAP (needs the normal)
  ProcessedVertex transform_vertex(const Vec4& object_position, const Vec3& normal) const;
  // The lighting and texgen evaluations of `vertices` vertices (counted by state alone).
  void count_vertex_processing(Counters& counters, std::uint64_t vertices) const;
  double vertex_color(double c, int bits) const;
  void light_pending_vertex(ProcessedVertex& v, int face) const;
  void emit_primitive_vertex(const ProcessedVertex& v);
  void flush_polygon();
  // `edge_flags`: whether the vertices' edge flags apply (§2.6.2; false for strips and fans).
  void draw_polygon(const ProcessedVertex* const* vertices, int count, const ProcessedVertex& provoking,
                    bool edge_flags = true);
  // §3.5.5 for a polygon drawn as lines or points: the polygon offset of its first triangle.
  double polygon_mode_offset(const std::vector<RasterVertex>& window, const RasterTarget& target) const;
  // draw_polygon's work before rasterization (NaN checks, clipping, window coordinates, facing
  // and culling, lighting the face drawn), reading state only and counting primitives into
  // `counters`: false when nothing is drawn.
  struct PolygonWork;
  bool assemble_polygon(const ProcessedVertex* const* vertices, int count, const ProcessedVertex& provoking,
                        PolygonWork& work, Counters& counters) const;
  // A polygon's facing from the signed area of its window vertices (§3.5.1, eq. 3.6), and
  // whether culling (§3.5.1) drops it (counted into `counters`).
  struct Facing {
    bool drawn = false, front = false;
    int face = 0;  // the colours it takes: 1 for a back face with two-sided lighting (§2.13.1)
  };
  Facing polygon_facing(const RasterVertex* window, std::size_t count, Counters& counters) const;
  // polygon_facing of the triangle (a, b, c), the same sums in the same order.
  Facing triangle_facing(const RasterVertex& a, const RasterVertex& b, const RasterVertex& c, Counters& counters) const;
  Facing facing_of_area(double area, Counters& counters) const;
  void note_polygon_warnings(unsigned warnings);
  // A drawn polygon's triangle options: the stage setup's, shading and polygon offset.
  TriangleOptions polygon_options(const TriangleOptions& setup_options, const Vec4& flat_color) const;
  void draw_point(const ProcessedVertex& v);
  // A line segment from a to b (§3.4): clipped, lit (front colours), rasterized.
  void draw_line(const ProcessedVertex& a, const ProcessedVertex& b);
  // A segment's window end points rasterized with the current line state, the stipple counter
  // carried on; depth_offset is added to window z (polygon offset of a polygon drawn as lines).
  // open_end: b was made by clipping (A31).
  void rasterize_line_segment(const RasterVertex& a, const RasterVertex& b, const Vec4& flat_color,
                              double depth_offset, bool open_end = false);
  void array_element_impl(int i);
  void check_array_bounds(std::int64_t max_index) const;
  void compile_array_element(int i, std::vector<Call>& out) const;
  void execute_list(GLuint list);
  // A glBegin(GL_TRIANGLES) ... glEnd block of a display list holding only glNormal3d and
  // glVertex4d calls (what a compiled DrawArrays of vertex and normal arrays holds): its
  // distinct vertices are transformed once each and its triangles assembled, on every raster
  // lane when there are lanes (draw_triangle_batch), then queued or drawn in order: the same
  // primitives, bits and counters as its calls one by one (vertex processing reads state
  // only, so equal inputs give equal vertices).
  struct TriangleBatch {
    std::size_t begin_call = 0, end_call = 0;  // indices of its glBegin and glEnd in the list
    // The distinct vertices: position and current normal, or (inherits) the current normal
    // at glBegin, for the vertices before the block's first glNormal3d.
    std::vector<Vec4> positions;
    std::vector<Vec3> normals;
    std::vector<std::uint8_t> inherits;
    std::vector<std::uint32_t> vertices;  // each vertex in call order: its distinct vertex
    bool sets_normal = false;             // then the current normal after it is last_normal
    Vec3 last_normal{0.0};
  };
  void find_triangle_batches(GLuint list);
  void draw_triangle_batch(const TriangleBatch& batch, const std::vector<Call>& calls);
  void set_light_param(GLenum light, GLenum pname, const double* v);
  void set_material_param(GLenum face, GLenum pname, const double* v);
  void set_light_model_param(GLenum pname, const double* v);
  void update_fragment_bits();
  Counters& counters();
  // The colour buffers a DrawBuffer/ReadBuffer mode names; empty when one is missing.
  std::vector<ColorBufferId> buffers_named(GLenum mode) const;
  const Mat4& normal_matrix();
  Vec4 array_value_at(const ClientArray& a, int i, bool normalise) const;
  void record_client_arrays(int max_index);
  void warn_once(const std::string& message);
  void apply_color_material();
  RasterVertex to_window(const ProcessedVertex& v, int face) const;
  // Texturing.
  TextureObject* texture_for(GLenum target);
  // `overwritten`: the caller stores every texel of the level next (a copy), so its storage
  // is sized but not cleared.
  void tex_image(GLenum target, int dims, GLint level, GLint internalformat, GLsizei width, GLsizei height,
                 GLint border, GLenum format, GLenum type, const void* pixels, bool overwritten = false);
  void tex_sub_image(GLenum target, int dims, GLint level, GLint xoffset, GLint yoffset, GLsizei width,
                     GLsizei height, GLenum format, GLenum type, const void* pixels);
  void copy_tex_image(GLenum target, int dims, GLint level, GLenum internalformat, GLint x, GLint y, GLsizei width,
                      GLsizei height, GLint border);
  void copy_tex_sub_image(GLenum target, int dims, GLint level, GLint xoffset, GLint yoffset, GLint x, GLint y,
                          GLsizei width, GLsizei height);
  GLint build_mipmaps(GLenum target, int dims, GLint internalformat, int width, int height, GLenum format,
                      GLenum type, const void* data);
  void store_texels(TextureLevel& level, int x0, int y0, int width, int height, const std::vector<Rgba>& rgba,
                    const std::vector<double>* depth);
  // Copies to a colour texture read through the transfer operations: whole, or in bands of
  // rows on every raster lane when the transfer has nothing that needs neighbouring or
  // earlier rows (no convolution, histogram or minmax) — the same texels and counters.
  // The source is width × height at (x, y); the texels stored are store_width × store_height
  // at (x0, y0) (smaller after a REDUCE convolution). Nothing is stored when the transfer
  // consumed the image (a histogram or minmax sink).
  void copy_color_texels(int dims, int x, int y, int width, int height, TextureLevel& level, int x0, int y0,
                         int store_width, int store_height);
  TextureLevel* sub_image_level(GLenum target, int dims, GLint level, GLint xoffset, GLint yoffset, GLsizei width,
                                GLsizei height);
  void read_for_texture(bool depth, int dims, int x, int y, int width, int height, std::vector<Rgba>& rgba,
                        std::vector<double>& values);
  // The size an image has after a REDUCE convolution for `dims` (unchanged otherwise).
  void reduced_size(int dims, int& width, int& height) const;
  // `split`: the conversion by ranges of rows (rows_on_lanes), or whole.
  void read_framebuffer_rgba(int x, int y, int width, int height, std::vector<Rgba>& out,
                             const RowSplitter* split = nullptr) const;
  // A rectangle of the read buffer kept as its codes (8 bytes a pixel rather than 32), for
  // conversion a band of rows at a time (§4.3.2: code k reads as k/(2^n − 1), A = 1 without
  // alpha bits; pixels outside the window are undefined: they read as 0 here).
  struct SourceCodes {
    int width = 0, height = 0;
    int i_lo = 0, i_hi = 0, j_lo = 0, j_hi = 0;  // the part inside the window
    const std::uint16_t* first = nullptr;        // codes of pixel (i_lo, j_lo), 4 per pixel
    std::size_t stride = 0;                      // codes from one row to the next (rows bottom first)
    const double* values[4] = {};                // code -> value per channel; nullptr: no bits (1)
    int bits[4] = {0, 0, 0, 0};                  // the read buffer's channel widths
    void to_reals(int first_row, int rows, Rgba* out) const;
    // A table of per-code results (entry i: 4 values, for a pixel whose component k has code
    // min(i, 2^bits_k − 1); then one entry for a pixel outside the window): the reals such a
    // table is made from (transfer_table), and its entries looked up per pixel, component k
    // of the output from the entry of the pixel's own component k. Row j of the rows goes to
    // out + (j − first_row)·out_stride, 4 values a pixel.
    std::size_t table_entries() const;
    std::vector<Rgba> table_reals() const;
    template <class Code>
    void through_table(int first_row, int rows, const Code* table, Code* out, std::size_t out_stride) const;
  };
  // transfer_per_component's steps for every code of `source` (SourceCodes::table_reals),
  // counting nothing; or an empty vector when the transfer is not per component or the
  // table would hold more entries than `pixels`, the pixels it is for.
  std::vector<Rgba> transfer_table(const SourceCodes& source, int dims, std::uint64_t pixels);
  // `copy`: the codes are copied there (A22: a copy that draws reads its whole source first);
  // null: they are read in place, and the read buffer must not change while they are used.
  SourceCodes read_framebuffer_codes(int x, int y, int width, int height, std::vector<std::uint16_t>* copy) const;
  // The attributes every pixel-rectangle and bitmap fragment takes from the raster position.
  struct RasterFragments {
    std::uint16_t codes[4];
    std::uint32_t z;
    double s, t, r, fog;
    bool extras;  // texture coordinates and fog are read by an enabled stage
    // Fragments [first, first + count) of the span; `colour` / `depth` false leaves those
    // for the caller (a rectangle's own colours or depths).
    void put(FragmentSpan& span, int first, int count = 1, bool colour = true, bool depth = true) const;
  };
  RasterFragments raster_fragments(const TriangleOptions& options) const;
  void read_framebuffer_depth(int x, int y, int width, int height, std::vector<double>& out) const;
  void set_tex_parameter(GLenum target, GLenum pname, const double* v);
  void set_tex_env(GLenum target, GLenum pname, const double* v);
  void set_tex_gen(GLenum coord, GLenum pname, const double* v);
  // The stage setup of a primitive drawn now (and its options' texture and fog parts);
  // prepare_fragment_stages connects this thread's stages to it, fragment_sink() their first.
  FragmentStagesSetup fragment_stages_setup(TriangleOptions& options);
  // fragment_stages_setup for a point or polygon, worked out once for every primitive drawn
  // until a call that may change state (any call a Begin/End or a draw call does not allow:
  // PASSIM_ENTRY forgets it) and, on one thread, connected once. `options` becomes the
  // default options with the texture and fog parts fragment_stages_setup sets.
  const FragmentStagesSetup& primitive_stages_setup(TriangleOptions& options);
  FragmentOpsInput fragment_ops_input() const;
  void prepare_fragment_stages(TriangleOptions& options);
  FragmentSink& fragment_sink();
  void set_fog(GLenum pname, const double* v);
  void set_raster_position(const Vec4& object);
  void set_pixel_map(GLenum map, GLsizei mapsize, const double* values);
  void define_color_table(int index, GLenum internalformat, int width, int start, const std::vector<Rgba>& rgba);
  bool check_table_format(GLenum internalformat);
  ConvolutionFilter* filter_for(GLenum target);
  bool check_filter_format(GLenum internalformat, GLenum format, GLenum type);
  void define_filter(ConvolutionFilter& f, GLenum internalformat, int width, int height, std::vector<Rgba>&& taps);
  void set_convolution_parameter(GLenum target, GLenum pname, const double* v);
  // Rasterizes a pixel rectangle at the raster position with the zoom rule; colours from
  // `rgba` (after transfer) or, for depth rectangles, the raster colour with `depth` values.
  // first_column, first_row: where the rectangle starts in the one the call named (a copy
  // clipped to the window, visible_groups); its groups are placed as that one's.
  void draw_pixel_rectangle(int width, int height, const std::vector<Rgba>* rgba, const std::vector<double>* depth,
                            int first_column = 0, int first_row = 0);
  // A20: the window pixels a width x height rectangle drawn at the raster position with the
  // pixel zoom covers. The columns are the same in every row: window column x_first + c shows
  // source column source_column[c] (increasing x; contiguous, since the groups tile
  // [xr, xr + zx·width)); source row j covers window rows rows[j][0] … rows[j][1].
  struct RectanglePlacement {
    int x_first = 0;
    std::vector<int> source_column;
    bool identity = false;  // source_column[c] == c for every source column (zoom 1, all inside)
    std::vector<std::array<int, 2>> rows;
  };
  RectanglePlacement place_rectangle(int width, int height, int first_column = 0, int first_row = 0) const;
  // Rows [first_row, first_row + rows) of a rectangle placed by `placement`; `rgba` or `depth`
  // holds those rows' values (width per row). `raster` comes from prepare_rectangle_fragments,
  // called once per rectangle (it configures the fragment stages).
  RasterFragments prepare_rectangle_fragments();
  // `codes`, in place of `rgba`: the rows' colours as fragment codes already, 4 a pixel.
  void draw_pixel_rows(const RasterFragments& raster, const RectanglePlacement& placement, int width, int first_row,
                       int rows, const Rgba* rgba, const double* depth, const std::uint16_t* codes = nullptr);
  // draw_pixel_rows into the given stages, counters and span buffers (a lane's).
  void draw_pixel_rows(const RasterFragments& raster, const RectanglePlacement& placement, int width, int first_row,
                       int rows, const Rgba* rgba, const double* depth, const std::uint16_t* codes,
                       FragmentSink& sink, Counters& counters, SpanBuffers& spans) const;
  // glCopyPixels's colour source drawn through a transfer_table: each pixel's fragment codes
  // looked up, band by band (on the raster lanes when there are any).
  void copy_pixels_through_table(const SourceCodes& source, const RectanglePlacement& placement, int width,
                                 int height, const std::vector<Rgba>& table_reals);
  // Whether glCopyPixels must copy its source before drawing (A22): unless the read buffer is
  // not drawn, or no source row's window rows hold another source row, drawing a band could
  // change rows a later (or another lane's) band has yet to read.
  bool copy_source_needed(const RectanglePlacement& placement, int y, int height) const;
  // glCopyPixels's bands of rows (no convolution, histogram or minmax), converted,
  // transferred and drawn on every raster lane: the same pixels and counters.
  void copy_bands_on_lanes(const SourceCodes& source, const RectanglePlacement& placement, int width, int height,
                           int band_rows);
  // body(lane, first, end) for the bands [first, end) of band_rows rows that cover [0, rows),
  // each run by whichever raster lane claims it next (the calling thread among them). Only
  // between primitives: nothing may be rasterizing.
  void bands_on_lanes(int rows, int band_rows, const std::function<void(int lane, int first, int end)>& body);
  // Work over ranges of rows split into bands of 16 on the raster lanes (bands_on_lanes; for
  // the per-pixel steps of pixel transfer and the convolution); null on one thread.
  const RowSplitter* rows_on_lanes();
  // The bands of `source` (band_rows rows each) converted and transferred on every raster
  // lane, each band handed to use(lane, reals, first row, rows) on the lane that made it; the
  // lanes' stages connected to `setup` first when given; their counters added to the pass.
  // For transfers without a convolution, histogram or minmax (per pixel, no order).
  using TransferredBandUse = std::function<void(LaneStages& lane, const Rgba* band, int first_row, int rows)>;
  // The lanes' own stages (connected to `setup` when given) and counters (added to the pass's
  // after), scratch_->pixel_lanes, for body(lane, first, end) over bands of rows as
  // bands_on_lanes runs them.
  void bands_on_pixel_lanes(int height, int band_rows, const FragmentStagesSetup* setup,
                            const std::function<void(int lane, int first, int end)>& body);
  void transfer_bands_on_lanes(const SourceCodes& source, int width, int height, int dims, int band_rows,
                               const FragmentStagesSetup* setup, const TransferredBandUse& use);
  // §4.3.1: stencil indices written at the rectangle's pixels through the scissor test and the
  // stencil writemask only.
  void draw_stencil_rectangle(int width, int height, const std::vector<double>& indices, int first_column = 0,
                              int first_row = 0);
  void read_framebuffer_stencil(int x, int y, int width, int height, std::vector<double>& out) const;

  MemoryBudget memory_;  // before fb_: the planes are charged before they are allocated
  Framebuffer fb_;
  MachineProfile profile_;
  std::array<int, 4> fragment_bits_{};

  // state (§6.2)
  TransformState transform_;
  ViewportState viewport_;
  CurrentState current_;
  LightingState lighting_;
  PolygonState polygon_;
  FragmentOpsState fragment_;
  FramebufferControlState fb_control_;
  PixelState pixel_;
  ClientArrayState arrays_;
  std::map<GLenum, bool> unmodelled_caps_;  // enables accepted and stored, not yet modelled
  bool texturing_enabled_ = false;
  TextureState textures_;
  PixelStoreState pixel_store_;
  FogState fog_;
  RasterPosState raster_;
  PixelTransferState transfer_;
  double zoom_x_ = 1.0, zoom_y_ = 1.0;
  HintState hints_;
  std::vector<ServerAttribs> attrib_stack_;         // §6.1.14
  std::vector<ClientAttribs> client_attrib_stack_;
  std::vector<ColorBufferId> draw_buffer_ids_;
  Mat4 normal_matrix_{1.0};
  bool normal_matrix_dirty_ = true;

  // errors
  GLenum error_ = GL_NO_ERROR;
  std::vector<GlErrorRecord> error_log_;
  std::vector<std::string> warnings_;
  std::string where_;
  const char* current_call_ = "";

  // primitive assembly
  bool in_begin_ = false;
  bool drawing_arrays_ = false;  // inside glDrawArrays / glDrawElements (the profile's quad split)
  GLenum begin_mode_ = GL_POINTS;
  std::vector<ProcessedVertex> prim_vertices_;
  std::vector<std::array<Material, 2>> vertex_materials_;  // materials in force for this Begin/End's vertices
  bool materials_dirty_ = true;
  std::uint64_t prim_vertex_count_ = 0;
  std::uint64_t line_stipple_counter_ = 0;  // §3.4.2 s: reset at Begin and per separate segment

  // display lists
  std::map<GLuint, std::vector<Call>> lists_;
  // Names GenLists handed out that hold no list yet: runs [first, last] (a huge range is one run).
  std::map<GLuint, GLuint> empty_lists_;
  bool list_name_used(GLuint name) const;
  // Bytes a list or call holds (charged to the memory budget).
  static std::uint64_t list_bytes(const std::vector<Call>& calls);
  static std::uint64_t call_bytes(const Call& call);
  std::uint64_t compiling_bytes_ = 0;  // charged for the list being compiled
  // Lists executed since the outermost CallList (the cap on lists that call lists).
  std::uint64_t lists_executed_ = 0;
  static constexpr std::uint64_t kMaxListExecutions = std::uint64_t{1} << 20;
  GLuint list_base_ = 0;
  std::map<GLuint, std::vector<TriangleBatch>> list_batches_;  // of lists that have some
  GLuint compiling_list_ = 0;
  GLenum compile_mode_ = 0;
  std::vector<Call> compiling_calls_;
  int list_nesting_ = 0;

  // recording
  CallSink* sink_ = nullptr;
  int call_depth_ = 0;
  bool raster_queued_ = false;  // primitives wait in the raster lanes
  void run_raster_queue();
  // primitive_stages_setup's memo (in Scratch) is valid until PASSIM_ENTRY of a
  // state-changing call.
  bool primitive_setup_valid_ = false;

  // passes
  PassEndObserver pass_end_;
  std::vector<Pass> passes_;
  std::vector<std::size_t> marker_stack_;  // indices into passes_
  std::size_t current_pass_ = SIZE_MAX;

  // stages' scratch (span buffers and the like)
  struct Scratch;
  std::unique_ptr<Scratch> scratch_;
};

}  // namespace passim

namespace passim {
namespace detail {

Value array_value(const void* data, GLenum type, std::size_t count);

// Argument `values.size()` of a call as the call table records it: numbers exactly, strings,
// and client memory as the elements its row's length rule says the call reads.
template <class T>
Value to_value(const CallInfo& info, const std::vector<Value>& values, const T& v, const PixelStore& unpack) {
  Value out;
  if constexpr (std::is_floating_point_v<T>) {
    out.d = static_cast<double>(v);
  } else if constexpr (std::is_integral_v<T>) {
    out.i = static_cast<std::int64_t>(v);
  } else if constexpr (std::is_same_v<T, const char*>) {
    out.set_str(v ? v : "");
  } else if constexpr (std::is_pointer_v<T> && std::is_const_v<std::remove_pointer_t<T>>) {
    const std::size_t k = values.size();
    out = array_value(v, param_element_type(info, k, values),
                      v ? static_cast<std::size_t>(param_elements_needed(info, k, values, unpack)) : 0);
  }
  return out;  // an output pointer: nothing to record
}

}  // namespace detail

template <class... A>
bool Context::intercept(const CallInfo& info, const A&... args) {
  // Fast path: nothing records and no list is being compiled.
  if (!sink_ && compiling_list_ == 0) return false;
  std::vector<Value> values;
  values.reserve(sizeof...(A));
  (values.push_back(detail::to_value(info, values, args, pixel_store_.unpack)), ...);
  return intercept_values(info, std::move(values));
}

}  // namespace passim

// Opening of every entry point: finds the call's table row once, records or
// compiles the outermost call, and rejects calls not allowed between Begin/End.
// Returns from the entry point (with `ret`) when the call must not execute now.
#define PASSIM_ENTRY_RET(ret, ...)                                                           \
  static const ::passim::CallInfo& passim_call_info_ = ::passim::call_info_or_die(__func__); \
  ::passim::Context::CallScope passim_call_scope_(*this);                                    \
  if (passim_call_scope_.outermost()) {                                                      \
    current_call_ = __func__;                                                                \
    if (intercept(passim_call_info_ __VA_OPT__(, ) __VA_ARGS__)) return ret;                 \
  }                                                                                          \
  if (!passim_call_info_.keeps_raster_queue) {                                               \
    if (raster_queued_) run_raster_queue();                                                  \
    primitive_setup_valid_ = false;                                                          \
  }                                                                                          \
  if (in_begin_ && !passim_call_info_.allowed_in_begin_end) {                                \
    set_error(GL_INVALID_OPERATION);                                                         \
    return ret;                                                                              \
  }
#define PASSIM_ENTRY(...) PASSIM_ENTRY_RET(, __VA_ARGS__)
