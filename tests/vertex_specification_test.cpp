// §2.7-2.9's vertex specification: every immediate-mode variant against values worked out by
// hand from Table 2.6 and §2.7, Rect against its polygon (§2.9), InterleavedArrays against
// Table 2.5, DrawRangeElements against DrawElements (§2.8), the edge flag (§2.6.2); and each
// through display lists, the recorder and the .pass reader.
#include <gtest/gtest.h>

#include <array>
#include <cstdint>
#include <cstring>
#include <functional>
#include <limits>
#include <string>
#include <vector>

#include "pipeline/calls.hpp"
#include "test_util.hpp"
#include "trace_io/trace.hpp"

namespace passim {
namespace {

constexpr double u8 = 255.0, u16 = 65535.0, u32 = 4294967295.0;  // 2^b − 1

std::array<double, 4> query4(Context& c, GLenum pname) {
  GLdouble v[16] = {0, 0, 0, 0};
  c.glGetDoublev(pname, v);
  return {v[0], v[1], v[2], v[3]};
}

void expect_near4(const std::array<double, 4>& got, const std::array<double, 4>& want, const std::string& what,
                  int n = 4) {
  for (int k = 0; k < n; ++k) EXPECT_DOUBLE_EQ(got[k], want[k]) << what << " component " << k;
}

struct StateCase {
  const char* what;
  std::function<void(Context&)> call;
  GLenum query;
  std::array<double, 4> want;
  int components = 4;
};

// Table 2.6: unsigned c → c / (2^b − 1), signed c → (2c + 1) / (2^b − 1); the expected values
// are those fractions worked out by hand.
TEST(VertexSpecification, ColourComponentsFollowTable26) {
  const StateCase cases[] = {
      {"glColor3b", [](Context& c) { c.glColor3b(-128, 127, 0); }, GL_CURRENT_COLOR, {-1.0, 1.0, 1 / u8, 1.0}},
      {"glColor4bv", [](Context& c) { const GLbyte v[4] = {-1, 63, -64, 127}; c.glColor4bv(v); }, GL_CURRENT_COLOR,
       {-1 / u8, 127 / u8, -127 / u8, 1.0}},
      {"glColor3s", [](Context& c) { c.glColor3s(-32768, 32767, -1); }, GL_CURRENT_COLOR, {-1.0, 1.0, -1 / u16, 1.0}},
      {"glColor4sv", [](Context& c) { const GLshort v[4] = {0, 16383, -16384, 32767}; c.glColor4sv(v); },
       GL_CURRENT_COLOR, {1 / u16, 32767 / u16, -32767 / u16, 1.0}},
      {"glColor3i", [](Context& c) { c.glColor3i(std::numeric_limits<GLint>::min(), std::numeric_limits<GLint>::max(), 0); },
       GL_CURRENT_COLOR, {-1.0, 1.0, 1 / u32, 1.0}},
      {"glColor4iv", [](Context& c) { const GLint v[4] = {-1, 1, 1073741823, 2147483647}; c.glColor4iv(v); },
       GL_CURRENT_COLOR, {-1 / u32, 3 / u32, 2147483647 / u32, 1.0}},
      {"glColor3ub", [](Context& c) { c.glColor3ub(255, 0, 51); }, GL_CURRENT_COLOR, {1.0, 0.0, 0.2, 1.0}},
      {"glColor4ubv", [](Context& c) { const GLubyte v[4] = {0, 255, 102, 1}; c.glColor4ubv(v); }, GL_CURRENT_COLOR,
       {0.0, 1.0, 0.4, 1 / u8}},
      {"glColor3us", [](Context& c) { c.glColor3us(65535, 0, 13107); }, GL_CURRENT_COLOR, {1.0, 0.0, 0.2, 1.0}},
      {"glColor4usv", [](Context& c) { const GLushort v[4] = {32768, 1, 65535, 0}; c.glColor4usv(v); },
       GL_CURRENT_COLOR, {32768 / u16, 1 / u16, 1.0, 0.0}},
      {"glColor3ui", [](Context& c) { c.glColor3ui(4294967295u, 0, 858993459u); }, GL_CURRENT_COLOR,
       {1.0, 0.0, 0.2, 1.0}},
      {"glColor4uiv", [](Context& c) { const GLuint v[4] = {0, 4294967295u, 1, 2147483648u}; c.glColor4uiv(v); },
       GL_CURRENT_COLOR, {0.0, 1.0, 1 / u32, 2147483648.0 / u32}},
      {"glColor3fv", [](Context& c) { const GLfloat v[3] = {0.25f, 0.5f, 0.75f}; c.glColor3fv(v); }, GL_CURRENT_COLOR,
       {0.25, 0.5, 0.75, 1.0}},
      {"glColor4d", [](Context& c) { c.glColor4d(0.125, 0.25, 0.5, 0.0625); }, GL_CURRENT_COLOR,
       {0.125, 0.25, 0.5, 0.0625}},
      // Normals as colours are (Table 2.6); texture coordinates and raster positions directly.
      {"glNormal3b", [](Context& c) { c.glNormal3b(-128, 127, 0); }, GL_CURRENT_NORMAL, {-1.0, 1.0, 1 / u8, 0}, 3},
      {"glNormal3sv", [](Context& c) { const GLshort v[3] = {-32768, 32767, 0}; c.glNormal3sv(v); }, GL_CURRENT_NORMAL,
       {-1.0, 1.0, 1 / u16, 0}, 3},
      {"glNormal3i", [](Context& c) { c.glNormal3i(0, 2147483647, -2147483647 - 1); }, GL_CURRENT_NORMAL,
       {1 / u32, 1.0, -1.0, 0}, 3},
      {"glNormal3bv", [](Context& c) { const GLbyte v[3] = {0, -1, 1}; c.glNormal3bv(v); }, GL_CURRENT_NORMAL,
       {1 / u8, -1 / u8, 3 / u8, 0}, 3},
      {"glTexCoord1s", [](Context& c) { c.glTexCoord1s(7); }, GL_CURRENT_TEXTURE_COORDS, {7, 0, 0, 1}},
      {"glTexCoord2iv", [](Context& c) { const GLint v[2] = {-3, 4}; c.glTexCoord2iv(v); }, GL_CURRENT_TEXTURE_COORDS,
       {-3, 4, 0, 1}},
      {"glTexCoord3s", [](Context& c) { c.glTexCoord3s(1, -2, 3); }, GL_CURRENT_TEXTURE_COORDS, {1, -2, 3, 1}},
      {"glTexCoord4i", [](Context& c) { c.glTexCoord4i(5, 6, 7, 8); }, GL_CURRENT_TEXTURE_COORDS, {5, 6, 7, 8}},
      {"glTexCoord1dv", [](Context& c) { const GLdouble v[1] = {0.5}; c.glTexCoord1dv(v); }, GL_CURRENT_TEXTURE_COORDS,
       {0.5, 0, 0, 1}},
      {"glTexCoord4sv", [](Context& c) { const GLshort v[4] = {-1, 2, -3, 4}; c.glTexCoord4sv(v); },
       GL_CURRENT_TEXTURE_COORDS, {-1, 2, -3, 4}},
      // Window coordinates under test::window_projection: (x, y) as given, object z 0 → 0.5;
      // w = 2 divides x and y.
      {"glRasterPos2s", [](Context& c) { c.glRasterPos2s(3, 5); }, GL_CURRENT_RASTER_POSITION, {3, 5, 0.5, 0}, 3},
      {"glRasterPos3iv", [](Context& c) { const GLint v[3] = {1, 2, 0}; c.glRasterPos3iv(v); },
       GL_CURRENT_RASTER_POSITION, {1, 2, 0.5, 0}, 3},
      {"glRasterPos4s", [](Context& c) { c.glRasterPos4s(2, 4, 0, 2); }, GL_CURRENT_RASTER_POSITION, {1, 2, 0.5, 0}, 3},
      {"glRasterPos4dv", [](Context& c) { const GLdouble v[4] = {6, 2, 0, 2}; c.glRasterPos4dv(v); },
       GL_CURRENT_RASTER_POSITION, {3, 1, 0.5, 0}, 3},
      {"glRasterPos2fv", [](Context& c) { const GLfloat v[2] = {6.5f, 7.25f}; c.glRasterPos2fv(v); },
       GL_CURRENT_RASTER_POSITION, {6.5, 7.25, 0.5, 0}, 3},
  };
  for (const StateCase& sc : cases) {
    Context ctx(test::small_config(8, 8));
    test::window_projection(ctx);
    sc.call(ctx);
    EXPECT_EQ(ctx.glGetError(), static_cast<GLenum>(GL_NO_ERROR)) << sc.what;
    expect_near4(query4(ctx, sc.query), sc.want, sc.what, sc.components);
  }
}

// Every vector form of every family does what its scalar form does, through the call table (so
// every row is checked to exist and to take its components in order).
TEST(VertexSpecification, EveryVectorFormEqualsItsScalarForm) {
  const char* families[] = {"glVertex", "glTexCoord", "glNormal", "glColor", "glRasterPos"};
  const char* types[] = {"b", "s", "i", "f", "d", "ub", "us", "ui"};
  int checked = 0;
  for (const char* family : families) {
    for (int n = 1; n <= 4; ++n) {
      for (const char* t : types) {
        const std::string scalar = std::string(family) + std::to_string(n) + t;
        const CallInfo* s = find_call(scalar);
        const CallInfo* v = find_call(scalar + "v");
        ASSERT_EQ(s == nullptr, v == nullptr) << scalar;
        if (!s) continue;
        ASSERT_EQ(s->params.size(), static_cast<std::size_t>(n)) << scalar;
        ASSERT_EQ(v->params.size(), 1u) << scalar;
        // Components 3, 2, 1, 5 (every type holds them), at a window position inside 8x8.
        const std::int64_t values[4] = {3, 2, 1, 5};
        std::vector<Value> scalar_args(static_cast<std::size_t>(n));
        const GLenum type = param_element_type(*v, 0, {});
        std::vector<std::byte> bytes(static_cast<std::size_t>(n * type_size(type)));
        for (int k = 0; k < n; ++k) {
          scalar_args[static_cast<std::size_t>(k)].i = values[k];
          scalar_args[static_cast<std::size_t>(k)].d = static_cast<double>(values[k]);
          auto put = [&](auto x) { std::memcpy(bytes.data() + k * sizeof x, &x, sizeof x); };
          switch (type) {
            case GL_BYTE: put(static_cast<std::int8_t>(values[k])); break;
            case GL_UNSIGNED_BYTE: put(static_cast<std::uint8_t>(values[k])); break;
            case GL_SHORT: put(static_cast<std::int16_t>(values[k])); break;
            case GL_UNSIGNED_SHORT: put(static_cast<std::uint16_t>(values[k])); break;
            case GL_INT: put(static_cast<std::int32_t>(values[k])); break;
            case GL_UNSIGNED_INT: put(static_cast<std::uint32_t>(values[k])); break;
            case GL_FLOAT: put(static_cast<float>(values[k])); break;
            default: put(static_cast<double>(values[k])); break;
          }
        }
        std::vector<Value> vector_args(1, detail::array_value(bytes.data(), type, static_cast<std::size_t>(n)));
        auto run = [&](const CallInfo& info, const std::vector<Value>& args) {
          auto ctx = std::make_unique<Context>(test::small_config(8, 8));
          test::window_projection(*ctx);
          // The current values (RasterPos is not allowed between Begin and End), then a point.
          const bool vertex = std::string(family) == "glVertex";
          if (!vertex) info.invoke(*ctx, args);
          ctx->glBegin(GL_POINTS);
          if (vertex) info.invoke(*ctx, args);
          else ctx->glVertex2f(3.5f, 2.5f);
          ctx->glEnd();
          return ctx;
        };
        const auto a = run(*s, scalar_args), b = run(*v, vector_args);
        EXPECT_EQ(a->glGetError(), static_cast<GLenum>(GL_NO_ERROR)) << scalar;
        for (GLenum q : {GL_CURRENT_COLOR, GL_CURRENT_NORMAL, GL_CURRENT_TEXTURE_COORDS, GL_CURRENT_RASTER_POSITION})
          EXPECT_EQ(query4(*a, q), query4(*b, q)) << scalar << " " << enum_name(q);
        EXPECT_EQ(a->framebuffer().color[0].rgba, b->framebuffer().color[0].rgba) << scalar;
        if (std::string(family) == "glVertex") {  // the point (3, 2) lands on pixel (3, 2)
          EXPECT_EQ(test::pixel(*a, 3, 2)[0], n == 4 ? 0u : 255u) << scalar;  // w = 5 moves it to (0, 0)
        }
        ++checked;
      }
    }
  }
  // glVertex{234}{sifd}, glTexCoord{1234}{sifd}, glNormal3{bsifd}, glColor{34}{8 types},
  // glRasterPos{234}{sifd}: 12 + 16 + 5 + 16 + 12.
  EXPECT_EQ(checked, 61);
}

// §2.7: integer vertex coordinates are converted directly: each form draws the fragments
// glVertex2f draws, and a homogeneous w divides (glVertex4sv(16, 0, 0, 2) is (8, 0)).
TEST(VertexSpecification, IntegerVerticesDrawWhatFloatVerticesDraw) {
  auto draw = [](const std::function<void(Context&)>& vertices) {
    auto ctx = std::make_unique<Context>(test::small_config(8, 8));
    test::window_projection(*ctx);
    ctx->glColor3ub(255, 255, 255);
    ctx->glBegin(GL_TRIANGLES);
    vertices(*ctx);
    ctx->glEnd();
    return ctx;
  };
  const auto reference = draw([](Context& c) { c.glVertex2f(0, 0); c.glVertex2f(8, 0); c.glVertex2f(0, 8); });
  const std::function<void(Context&)> forms[] = {
      [](Context& c) { c.glVertex2s(0, 0); c.glVertex3s(8, 0, 0); c.glVertex4s(0, 8, 0, 1); },
      [](Context& c) { c.glVertex4i(0, 0, 0, 1); c.glVertex3i(8, 0, 0); c.glVertex2i(0, 8); },
      [](Context& c) {
        const GLshort a[2] = {0, 0}, b[4] = {16, 0, 0, 2};
        const GLint d[3] = {0, 8, 0};
        c.glVertex2sv(a); c.glVertex4sv(b); c.glVertex3iv(d);
      },
      [](Context& c) {
        const GLint a[4] = {0, 0, 0, 1};
        const GLdouble b[4] = {8, 0, 0, 1};
        const GLshort d[3] = {0, 8, 0};
        c.glVertex4iv(a); c.glVertex4dv(b); c.glVertex3sv(d);
      },
  };
  for (std::size_t k = 0; k < std::size(forms); ++k) {
    const auto ctx = draw(forms[k]);
    EXPECT_EQ(ctx->framebuffer().color[0].rgba, reference->framebuffer().color[0].rgba) << "form " << k;
  }
  // The triangle covers pixel (0, 0) and not (7, 7).
  EXPECT_EQ(test::pixel(*reference, 0, 0)[0], 255u);
  EXPECT_EQ(test::pixel(*reference, 7, 7)[0], 0u);
}

// §2.9: Rect(x1, y1, x2, y2) is the polygon (x1, y1) (x2, y1) (x2, y2) (x1, y2): for every type
// and form, the same fragments as that polygon: the 4 x 5 pixels whose centres lie inside.
TEST(VertexSpecification, RectIsItsPolygon) {
  auto draw = [](const std::function<void(Context&)>& f) {
    auto ctx = std::make_unique<Context>(test::small_config(8, 8));
    test::window_projection(*ctx);
    ctx->glColor3ub(255, 255, 255);
    f(*ctx);
    return ctx;
  };
  const auto polygon = draw([](Context& c) {
    c.glBegin(GL_POLYGON);
    c.glVertex2i(1, 2);
    c.glVertex2i(5, 2);
    c.glVertex2i(5, 7);
    c.glVertex2i(1, 7);
    c.glEnd();
  });
  int lit = 0;
  for (int y = 0; y < 8; ++y)
    for (int x = 0; x < 8; ++x) {
      const bool inside = x >= 1 && x <= 4 && y >= 2 && y <= 6;
      EXPECT_EQ(test::pixel(*polygon, x, y)[0], inside ? 255u : 0u) << x << "," << y;
      lit += inside;
    }
  EXPECT_EQ(lit, 20);
  const GLshort s1[2] = {1, 2}, s2[2] = {5, 7};
  const GLint i1[2] = {1, 2}, i2[2] = {5, 7};
  const GLfloat f1[2] = {1, 2}, f2[2] = {5, 7};
  const GLdouble d1[2] = {1, 2}, d2[2] = {5, 7};
  const std::pair<const char*, std::function<void(Context&)>> rects[] = {
      {"glRects", [](Context& c) { c.glRects(1, 2, 5, 7); }},
      {"glRecti", [](Context& c) { c.glRecti(1, 2, 5, 7); }},
      {"glRectf", [](Context& c) { c.glRectf(1, 2, 5, 7); }},
      {"glRectd", [](Context& c) { c.glRectd(1, 2, 5, 7); }},
      {"glRectsv", [&](Context& c) { c.glRectsv(s1, s2); }},
      {"glRectiv", [&](Context& c) { c.glRectiv(i1, i2); }},
      {"glRectfv", [&](Context& c) { c.glRectfv(f1, f2); }},
      {"glRectdv", [&](Context& c) { c.glRectdv(d1, d2); }},
      {"glRects reversed", [](Context& c) { c.glRects(5, 7, 1, 2); }},  // clockwise: the same pixels
  };
  for (const auto& [what, f] : rects) {
    const auto ctx = draw(f);
    EXPECT_EQ(ctx->glGetError(), static_cast<GLenum>(GL_NO_ERROR)) << what;
    EXPECT_EQ(ctx->framebuffer().color[0].rgba, polygon->framebuffer().color[0].rgba) << what;
  }
}

// Table 2.5, worked out by hand with f = 4 (a float) and c = 4 (four unsigned bytes, already a
// multiple of f): the arrays each format enables, their offsets pc, pn, pv and the stride s.
struct InterleavedRow {
  GLenum format;
  int st, sc;
  bool ub, en;
  int sv, pc, pn, pv, s;
};
const InterleavedRow kTable25[] = {
    {GL_V2F, 0, 0, false, false, 2, 0, 0, 0, 8},
    {GL_V3F, 0, 0, false, false, 3, 0, 0, 0, 12},
    {GL_C4UB_V2F, 0, 4, true, false, 2, 0, 4, 4, 12},
    {GL_C4UB_V3F, 0, 4, true, false, 3, 0, 4, 4, 16},
    {GL_C3F_V3F, 0, 3, false, false, 3, 0, 12, 12, 24},
    {GL_N3F_V3F, 0, 0, false, true, 3, 0, 0, 12, 24},
    {GL_C4F_N3F_V3F, 0, 4, false, true, 3, 0, 16, 28, 40},
    {GL_T2F_V3F, 2, 0, false, false, 3, 8, 8, 8, 20},
    {GL_T4F_V4F, 4, 0, false, false, 4, 16, 16, 16, 32},
    {GL_T2F_C4UB_V3F, 2, 4, true, false, 3, 8, 12, 12, 24},
    {GL_T2F_C3F_V3F, 2, 3, false, false, 3, 8, 20, 20, 32},
    {GL_T2F_N3F_V3F, 2, 0, false, true, 3, 8, 8, 20, 32},
    {GL_T2F_C4F_N3F_V3F, 2, 4, false, true, 3, 8, 24, 36, 48},
    {GL_T4F_C4F_N3F_V4F, 4, 4, false, true, 4, 16, 32, 44, 60},
};

// Element 1 of a two-element block laid out by the table's offsets (stride `stride`): texture
// coordinates 0.5, 1.5, ..., colour (51, 102, 153, 204)/255 or 0.25, 0.5, 0.75, 0.125, normal
// (0, 0.6, 0.8), vertex (3.5, 5.5, 0, 1).
std::vector<std::byte> interleaved_block(const InterleavedRow& r, int stride) {
  std::vector<std::byte> block(static_cast<std::size_t>(2 * stride), std::byte{0xEE});
  std::byte* e = block.data() + stride;
  auto floats = [](std::byte* at, std::initializer_list<float> v) { std::memcpy(at, v.begin(), 4 * v.size()); };
  const float tex[4] = {0.5f, 1.5f, 2.5f, 3.5f};
  std::memcpy(e, tex, static_cast<std::size_t>(4 * r.st));
  if (r.ub) {
    const std::uint8_t c[4] = {51, 102, 153, 204};
    std::memcpy(e + r.pc, c, 4);
  } else if (r.sc > 0) {
    const float c[4] = {0.25f, 0.5f, 0.75f, 0.125f};
    std::memcpy(e + r.pc, c, static_cast<std::size_t>(4 * r.sc));
  }
  if (r.en) floats(e + r.pn, {0.0f, 0.6f, 0.8f});
  const float v[4] = {3.5f, 5.5f, 0.0f, 1.0f};
  std::memcpy(e + r.pv, v, static_cast<std::size_t>(4 * r.sv));
  return block;
}

TEST(VertexSpecification, InterleavedArraysFollowTable25) {
  for (const InterleavedRow& r : kTable25) {
    for (const int extra : {0, 12}) {  // stride 0 (the table's s), or s + 12 given
      const std::string what = enum_name(r.format) + (extra ? " stride s+12" : " stride 0");
      const int stride = r.s + extra;
      const std::vector<std::byte> block = interleaved_block(r, stride);
      Context ctx(test::small_config(8, 8));
      test::window_projection(ctx);
      const GLubyte flags[2] = {1, 1};
      ctx.glEdgeFlagPointer(0, flags);
      ctx.glEnableClientState(GL_EDGE_FLAG_ARRAY);  // InterleavedArrays disables it
      ctx.glColor4f(1, 1, 1, 1);
      ctx.glTexCoord4f(9, 9, 9, 9);
      ctx.glNormal3f(9, 9, 9);
      ctx.glInterleavedArrays(r.format, extra ? stride : 0, block.data());
      ASSERT_EQ(ctx.glGetError(), static_cast<GLenum>(GL_NO_ERROR)) << what;
      EXPECT_EQ(ctx.glIsEnabled(GL_TEXTURE_COORD_ARRAY), r.st > 0 ? GL_TRUE : GL_FALSE) << what;
      EXPECT_EQ(ctx.glIsEnabled(GL_COLOR_ARRAY), r.sc > 0 ? GL_TRUE : GL_FALSE) << what;
      EXPECT_EQ(ctx.glIsEnabled(GL_NORMAL_ARRAY), r.en ? GL_TRUE : GL_FALSE) << what;
      EXPECT_EQ(ctx.glIsEnabled(GL_VERTEX_ARRAY), GL_TRUE) << what;
      EXPECT_EQ(ctx.glIsEnabled(GL_EDGE_FLAG_ARRAY), GL_FALSE) << what;
      // ArrayElement outside Begin/End sets the current values (its Vertex does nothing).
      ctx.glArrayElement(1);
      const std::array<double, 4> tex = r.st == 4 ? std::array<double, 4>{0.5, 1.5, 2.5, 3.5}
                                      : r.st == 2 ? std::array<double, 4>{0.5, 1.5, 0, 1}
                                                  : std::array<double, 4>{9, 9, 9, 9};
      expect_near4(query4(ctx, GL_CURRENT_TEXTURE_COORDS), tex, what + " texcoord");
      const std::array<double, 4> colour = r.ub        ? std::array<double, 4>{0.2, 0.4, 0.6, 0.8}
                                           : r.sc == 4 ? std::array<double, 4>{0.25, 0.5, 0.75, 0.125}
                                           : r.sc == 3 ? std::array<double, 4>{0.25, 0.5, 0.75, 1}
                                                       : std::array<double, 4>{1, 1, 1, 1};
      expect_near4(query4(ctx, GL_CURRENT_COLOR), colour, what + " colour");
      const std::array<double, 4> normal = r.en ? std::array<double, 4>{0, 0.6f, 0.8f, 0} : std::array<double, 4>{9, 9, 9, 0};
      expect_near4(query4(ctx, GL_CURRENT_NORMAL), normal, what + " normal", 3);
      // The vertex, at pv: a point on pixel (3, 5) and nowhere else.
      ctx.glBegin(GL_POINTS);
      ctx.glArrayElement(1);
      ctx.glEnd();
      EXPECT_NE(test::pixel(ctx, 3, 5)[0], 0u) << what;
      int lit = 0;
      for (int y = 0; y < 8; ++y)
        for (int x = 0; x < 8; ++x) lit += test::pixel(ctx, x, y)[0] != 0;
      EXPECT_EQ(lit, 1) << what;
    }
  }
}

// A draw from interleaved arrays records as the arrays' pointer calls with the enables
// InterleavedArrays set, and compiles into a list as its data (§5.4: InterleavedArrays itself
// is executed at once): both give the image the immediate draw gives.
TEST(VertexSpecification, InterleavedArraysRecordAndCompile) {
  // Three elements of GL_T2F_V3F: texture coordinates (s, t), then the vertex (x, y, z).
  const float t2f_v3f[3][5] = {{0, 0, 0, 0, 0}, {1, 0, 8, 0, 0}, {0, 1, 0, 8, 0}};
  auto draw = [&](Context& c) {
    test::window_projection(c);
    c.glColor3ub(200, 100, 50);
    c.glInterleavedArrays(GL_T2F_V3F, 0, t2f_v3f);
    c.glDrawArrays(GL_TRIANGLES, 0, 3);
  };
  Context direct(test::small_config(8, 8));
  draw(direct);
  EXPECT_EQ(test::pixel(direct, 0, 0)[0], 200u);

  Context recorded(test::small_config(8, 8));
  test::Recording rec(recorded);
  draw(recorded);
  const std::string text = rec.text.str();
  EXPECT_NE(text.find("glEnableClientState(GL_TEXTURE_COORD_ARRAY)"), std::string::npos) << text;
  EXPECT_NE(text.find("glDisableClientState(GL_EDGE_FLAG_ARRAY)"), std::string::npos) << text;
  EXPECT_EQ(text.find("glInterleavedArrays"), std::string::npos) << text;
  const ReplayResult replay = replay_trace_text(text, "interleaved.pass", ".");
  EXPECT_EQ(replay.context->framebuffer().color[0].rgba, direct.framebuffer().color[0].rgba) << text;

  Context listed(test::small_config(8, 8));
  test::window_projection(listed);
  listed.glColor3ub(200, 100, 50);
  listed.glNewList(1, GL_COMPILE);
  listed.glInterleavedArrays(GL_T2F_V3F, 0, t2f_v3f);
  listed.glDrawArrays(GL_TRIANGLES, 0, 3);
  listed.glEndList();
  listed.glDisableClientState(GL_VERTEX_ARRAY);  // the list holds the data, not the arrays
  listed.glCallList(1);
  EXPECT_EQ(listed.glGetError(), static_cast<GLenum>(GL_NO_ERROR));
  EXPECT_EQ(listed.framebuffer().color[0].rgba, direct.framebuffer().color[0].rgba);
}

// §2.8: DrawRangeElements draws what DrawElements draws with the same indices.
TEST(VertexSpecification, DrawRangeElementsDrawsWhatDrawElementsDraws) {
  const GLshort vertices[4][2] = {{0, 0}, {8, 0}, {8, 8}, {0, 8}};
  const GLubyte colours[4][3] = {{255, 0, 0}, {0, 255, 0}, {0, 0, 255}, {255, 255, 255}};
  const GLushort indices[6] = {0, 1, 2, 2, 3, 0};
  auto draw = [&](const std::function<void(Context&)>& f) {
    auto ctx = std::make_unique<Context>(test::small_config(8, 8));
    test::window_projection(*ctx);
    ctx->glEnableClientState(GL_VERTEX_ARRAY);
    ctx->glEnableClientState(GL_COLOR_ARRAY);
    ctx->glVertexPointer(2, GL_SHORT, 0, vertices);
    ctx->glColorPointer(3, GL_UNSIGNED_BYTE, 0, colours);
    f(*ctx);
    return ctx;
  };
  const auto elements = draw([&](Context& c) { c.glDrawElements(GL_TRIANGLES, 6, GL_UNSIGNED_SHORT, indices); });
  const auto range = draw([&](Context& c) { c.glDrawRangeElements(GL_TRIANGLES, 0, 3, 6, GL_UNSIGNED_SHORT, indices); });
  EXPECT_EQ(range->glGetError(), static_cast<GLenum>(GL_NO_ERROR));
  EXPECT_EQ(range->framebuffer().color[0].rgba, elements->framebuffer().color[0].rgba);
  EXPECT_NE(test::pixel(*range, 0, 0), test::pixel(*range, 7, 7));  // smooth colours: something was drawn

  // Recorded (with the arrays' data), then replayed from the text; compiled into a list.
  Context recorded(test::small_config(8, 8));
  {
    test::Recording rec(recorded);
    test::window_projection(recorded);
    recorded.glEnableClientState(GL_VERTEX_ARRAY);
    recorded.glEnableClientState(GL_COLOR_ARRAY);
    recorded.glVertexPointer(2, GL_SHORT, 0, vertices);
    recorded.glColorPointer(3, GL_UNSIGNED_BYTE, 0, colours);
    recorded.glDrawRangeElements(GL_TRIANGLES, 0, 3, 6, GL_UNSIGNED_SHORT, indices);
    const std::string text = rec.text.str();
    EXPECT_NE(text.find("glDrawRangeElements(GL_TRIANGLES, 0, 3, 6, GL_UNSIGNED_SHORT, {0, 1, 2, 2, 3, 0})"),
              std::string::npos)
        << text;
    const ReplayResult replay = replay_trace_text(text, "range.pass", ".");
    EXPECT_EQ(replay.context->framebuffer().color[0].rgba, elements->framebuffer().color[0].rgba);
    recorded.set_call_sink(nullptr);
  }
  const auto listed = draw([&](Context& c) {
    c.glNewList(1, GL_COMPILE);
    c.glDrawRangeElements(GL_TRIANGLES, 0, 3, 6, GL_UNSIGNED_SHORT, indices);
    c.glEndList();
    c.glCallList(1);
  });
  EXPECT_EQ(listed->framebuffer().color[0].rgba, elements->framebuffer().color[0].rgba);
  // An error draws nothing.
  const auto rejected = draw([&](Context& c) { c.glDrawRangeElements(GL_TRIANGLES, 3, 0, 6, GL_UNSIGNED_SHORT, indices); });
  EXPECT_EQ(rejected->glGetError(), static_cast<GLenum>(GL_INVALID_VALUE));
  EXPECT_EQ(test::pixel(*rejected, 0, 0)[0], 0u);
}

// §2.6.2: EdgeFlag sets the current flag (any nonzero value is TRUE), allowed between Begin and
// End; the edge-flag array (§2.8) sets it per element, also from a list and a recording.
TEST(VertexSpecification, EdgeFlagIsStoredFromCallsAndArrays) {
  auto flag = [](Context& c) {
    GLboolean b = 2;
    c.glGetBooleanv(GL_EDGE_FLAG, &b);
    return b;
  };
  Context ctx(test::small_config(8, 8));
  EXPECT_EQ(flag(ctx), GL_TRUE);  // Table 6.5's initial value
  ctx.glBegin(GL_POLYGON);
  ctx.glEdgeFlag(GL_FALSE);
  ctx.glEnd();
  EXPECT_EQ(ctx.glGetError(), static_cast<GLenum>(GL_NO_ERROR));
  EXPECT_EQ(flag(ctx), GL_FALSE);
  const GLboolean two[1] = {2};
  ctx.glEdgeFlagv(two);
  EXPECT_EQ(flag(ctx), GL_TRUE);

  const GLboolean flags[3] = {1, 0, 1};
  ctx.glEdgeFlagPointer(0, flags);
  ctx.glEnableClientState(GL_EDGE_FLAG_ARRAY);
  EXPECT_EQ(ctx.glIsEnabled(GL_EDGE_FLAG_ARRAY), GL_TRUE);
  ctx.glArrayElement(1);
  EXPECT_EQ(flag(ctx), GL_FALSE);
  ctx.glArrayElement(2);
  EXPECT_EQ(flag(ctx), GL_TRUE);
  ctx.glNewList(1, GL_COMPILE);
  ctx.glArrayElement(1);  // compiled as glEdgeFlag(GL_FALSE)
  ctx.glEndList();
  EXPECT_EQ(flag(ctx), GL_TRUE);
  ctx.glCallList(1);
  EXPECT_EQ(flag(ctx), GL_FALSE);

  Context recorded(test::small_config(8, 8));
  test::Recording rec(recorded);
  recorded.glEdgeFlagPointer(0, flags);
  recorded.glEnableClientState(GL_EDGE_FLAG_ARRAY);
  recorded.glArrayElement(2);  // outside Begin/End: the pointer call with the data, then the call
  recorded.glBegin(GL_POINTS);
  recorded.glArrayElement(1);
  recorded.glEnd();
  const std::string text = rec.text.str();
  EXPECT_NE(text.find("glEdgeFlagPointer(0, {1, 0, 1})"), std::string::npos) << text;
  // Inside Begin/End no pointer call may be written: the element is recorded as its calls.
  EXPECT_NE(text.find("glEdgeFlag(GL_FALSE)"), std::string::npos) << text;
  EXPECT_EQ(text.find("glArrayElement(1)"), std::string::npos) << text;
  const ReplayResult replay = replay_trace_text(text, "edge.pass", ".");
  EXPECT_EQ(flag(*replay.context), GL_FALSE);
}

}  // namespace
}  // namespace passim
