// The speed peer's section-2 shadow-map frame (../shared/peers/osmesa-bench/osmesa_bench.c,
// `shadow_frameA`), transcribed call for call so that passim and the peer time the same
// work: the same scene (a 16x16 ground, a 48x36 sphere and a 48x32 torus in one display list,
// 6,944 triangles), the same cameras, textures and five passes — the light pass at 512x512
// with the distance ramp by EYE_LINEAR texgen and a 1D INTENSITY8 ramp, the copy to the shadow
// texture, the camera ramp pass, the projective REVERSE_SUBTRACT pass, and the lit pass
// writing G and B. The float arithmetic is the peer's, operation for operation, so the
// vertices and matrices are the same bits.
//
// `G` is anything with the GL calls as methods: passim's Context, or the outside check's
// forwarder to Mesa (tests/osmesa_check.cpp compares the two images of the frame).
#pragma once
#include <cmath>
#include <cstring>
#include <vector>

#include "pipeline/gl.hpp"

namespace passim::peer {

// Column-major 4x4 float matrices, as the peer computes them.
struct Mat {
  float m[16];
};

inline Mat mat_identity() {
  Mat r;
  std::memset(&r, 0, sizeof r);
  r.m[0] = r.m[5] = r.m[10] = r.m[15] = 1.0f;
  return r;
}

inline Mat mat_mul(Mat a, Mat b) {  // a * b
  Mat r;
  for (int c = 0; c < 4; c++)
    for (int rr = 0; rr < 4; rr++) {
      float s = 0.0f;
      for (int k = 0; k < 4; k++) s += a.m[k * 4 + rr] * b.m[c * 4 + k];
      r.m[c * 4 + rr] = s;
    }
  return r;
}

inline Mat mat_perspective(float fovy_deg, float aspect, float n, float f) {
  Mat r;
  const float t = 1.0f / std::tan(fovy_deg * static_cast<float>(M_PI) / 360.0f);
  std::memset(&r, 0, sizeof r);
  r.m[0] = t / aspect;
  r.m[5] = t;
  r.m[10] = (f + n) / (n - f);
  r.m[11] = -1.0f;
  r.m[14] = 2.0f * f * n / (n - f);
  return r;
}

inline void norm3(float v[3]) {
  const float l = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
  if (l > 0) {
    v[0] /= l;
    v[1] /= l;
    v[2] /= l;
  }
}

inline Mat mat_lookat(float ex, float ey, float ez, float cx, float cy, float cz, float ux, float uy, float uz) {
  float f[3] = {cx - ex, cy - ey, cz - ez}, up[3] = {ux, uy, uz}, s[3], u[3];
  norm3(f);
  s[0] = f[1] * up[2] - f[2] * up[1];
  s[1] = f[2] * up[0] - f[0] * up[2];
  s[2] = f[0] * up[1] - f[1] * up[0];
  norm3(s);
  u[0] = s[1] * f[2] - s[2] * f[1];
  u[1] = s[2] * f[0] - s[0] * f[2];
  u[2] = s[0] * f[1] - s[1] * f[0];
  Mat r = mat_identity();
  r.m[0] = s[0];
  r.m[4] = s[1];
  r.m[8] = s[2];
  r.m[1] = u[0];
  r.m[5] = u[1];
  r.m[9] = u[2];
  r.m[2] = -f[0];
  r.m[6] = -f[1];
  r.m[10] = -f[2];
  r.m[12] = -(s[0] * ex + s[1] * ey + s[2] * ez);
  r.m[13] = -(u[0] * ex + u[1] * ey + u[2] * ez);
  r.m[14] = (f[0] * ex + f[1] * ey + f[2] * ez);
  return r;
}

inline Mat mat_bias() {  // [-1, 1] -> [0, 1]
  Mat r = mat_identity();
  r.m[0] = r.m[5] = r.m[10] = 0.5f;
  r.m[12] = r.m[13] = r.m[14] = 0.5f;
  return r;
}

inline void mat_row(const Mat& a, int row, float out[4]) {
  for (int c = 0; c < 4; c++) out[c] = a.m[c * 4 + row];
}

// A mesh: per vertex nx ny nz x y z.
using Mesh = std::vector<float>;

inline void mesh_vert(Mesh& m, float nx, float ny, float nz, float x, float y, float z) {
  m.insert(m.end(), {nx, ny, nz, x, y, z});
}

inline void sphere_pt(float r, float cx, float cy, float cz, int i, int j, int slices, int stacks, float out[6]) {
  const float th = static_cast<float>(M_PI) * static_cast<float>(j) / static_cast<float>(stacks);
  const float ph = 2.0f * static_cast<float>(M_PI) * static_cast<float>(i) / static_cast<float>(slices);
  const float nx = std::sin(th) * std::cos(ph), ny = std::cos(th), nz = std::sin(th) * std::sin(ph);
  out[0] = nx;
  out[1] = ny;
  out[2] = nz;
  out[3] = cx + r * nx;
  out[4] = cy + r * ny;
  out[5] = cz + r * nz;
}

inline void gen_sphere(Mesh& m, float cx, float cy, float cz, float r, int slices, int stacks) {
  for (int j = 0; j < stacks; j++)
    for (int i = 0; i < slices; i++) {
      float a[6], b[6], c[6], d[6];
      sphere_pt(r, cx, cy, cz, i, j, slices, stacks, a);
      sphere_pt(r, cx, cy, cz, i + 1, j, slices, stacks, b);
      sphere_pt(r, cx, cy, cz, i + 1, j + 1, slices, stacks, c);
      sphere_pt(r, cx, cy, cz, i, j + 1, slices, stacks, d);
      if (j != 0) {
        mesh_vert(m, a[0], a[1], a[2], a[3], a[4], a[5]);
        mesh_vert(m, b[0], b[1], b[2], b[3], b[4], b[5]);
        mesh_vert(m, c[0], c[1], c[2], c[3], c[4], c[5]);
      }
      if (j != stacks - 1) {
        mesh_vert(m, a[0], a[1], a[2], a[3], a[4], a[5]);
        mesh_vert(m, c[0], c[1], c[2], c[3], c[4], c[5]);
        mesh_vert(m, d[0], d[1], d[2], d[3], d[4], d[5]);
      }
    }
}

inline void torus_pt(float R, float r, float cx, float cy, float cz, float tilt, int i, int j, int nmaj, int nmin,
                     float out[6]) {
  const float u = 2.0f * static_cast<float>(M_PI) * static_cast<float>(i) / static_cast<float>(nmaj);
  const float v = 2.0f * static_cast<float>(M_PI) * static_cast<float>(j) / static_cast<float>(nmin);
  const float nx = std::cos(v) * std::cos(u), ny = std::sin(v), nz = std::cos(v) * std::sin(u);
  const float x = (R + r * std::cos(v)) * std::cos(u), y = r * std::sin(v), z = (R + r * std::cos(v)) * std::sin(u);
  const float ct = std::cos(tilt), st = std::sin(tilt);
  out[0] = nx;
  out[1] = ny * ct - nz * st;
  out[2] = ny * st + nz * ct;
  out[3] = cx + x;
  out[4] = cy + y * ct - z * st;
  out[5] = cz + y * st + z * ct;
}

inline void gen_torus(Mesh& m, float cx, float cy, float cz, float R, float r, float tilt, int nmaj, int nmin) {
  for (int i = 0; i < nmaj; i++)
    for (int j = 0; j < nmin; j++) {
      float a[6], b[6], c[6], d[6];
      torus_pt(R, r, cx, cy, cz, tilt, i, j, nmaj, nmin, a);
      torus_pt(R, r, cx, cy, cz, tilt, i + 1, j, nmaj, nmin, b);
      torus_pt(R, r, cx, cy, cz, tilt, i + 1, j + 1, nmaj, nmin, c);
      torus_pt(R, r, cx, cy, cz, tilt, i, j + 1, nmaj, nmin, d);
      mesh_vert(m, a[0], a[1], a[2], a[3], a[4], a[5]);
      mesh_vert(m, c[0], c[1], c[2], c[3], c[4], c[5]);
      mesh_vert(m, b[0], b[1], b[2], b[3], b[4], b[5]);
      mesh_vert(m, a[0], a[1], a[2], a[3], a[4], a[5]);
      mesh_vert(m, d[0], d[1], d[2], d[3], d[4], d[5]);
      mesh_vert(m, c[0], c[1], c[2], c[3], c[4], c[5]);
    }
}

inline void gen_ground(Mesh& m, float half, int n) {
  const float s = 2.0f * half / static_cast<float>(n);
  for (int j = 0; j < n; j++)
    for (int i = 0; i < n; i++) {
      const float x0 = -half + s * static_cast<float>(i), x1 = x0 + s, z0 = -half + s * static_cast<float>(j),
                  z1 = z0 + s;
      mesh_vert(m, 0, 1, 0, x0, 0, z0);
      mesh_vert(m, 0, 1, 0, x0, 0, z1);
      mesh_vert(m, 0, 1, 0, x1, 0, z1);
      mesh_vert(m, 0, 1, 0, x0, 0, z0);
      mesh_vert(m, 0, 1, 0, x1, 0, z1);
      mesh_vert(m, 0, 1, 0, x1, 0, z0);
    }
}

// The peer's frame A on `gl`, whose window is width x height (at least 512 x 512).
template <class G>
class ShadowFrame {
 public:
  ShadowFrame(G& gl, int width, int height) : gl_(gl), W(width), H(height) {}

  // What the peer's main() does before its tests: the viewport, DITHER off, the cameras, the
  // scene's display list, the textures; then frame A's own set-up (DITHER off again).
  void setup() {
    gl_.glViewport(0, 0, W, H);
    gl_.glDisable(GL_DITHER);
    setup_cameras();
    build_scene();
    make_textures();
    gl_.glDisable(GL_DITHER);
  }

  // shadow_frame() with frame_variant 0.
  void frame() {
    // pass 1: the shadow map from the light, 512x512
    gl_.glViewport(0, 0, 512, 512);
    gl_.glEnable(GL_SCISSOR_TEST);
    gl_.glScissor(0, 0, 512, 512);
    gl_.glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    gl_.glClearColor(1, 1, 1, 1);
    gl_.glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    gl_.glDisable(GL_SCISSOR_TEST);
    gl_.glDisable(GL_LIGHTING);
    gl_.glDisable(GL_BLEND);
    gl_.glEnable(GL_DEPTH_TEST);
    gl_.glDepthFunc(GL_LESS);
    gl_.glDepthMask(GL_TRUE);
    gl_.glEnable(GL_CULL_FACE);
    load_mat(GL_PROJECTION, light_proj_);
    set_light_ramp_plane(light_view_);
    gl_.glEnable(GL_TEXTURE_GEN_S);
    gl_.glBindTexture(GL_TEXTURE_1D, tex_ramp1d_);
    gl_.glEnable(GL_TEXTURE_1D);
    gl_.glTexEnvi(GL_TEXTURE_ENV, GL_TEXTURE_ENV_MODE, GL_REPLACE);
    gl_.glColorMask(GL_TRUE, GL_FALSE, GL_FALSE, GL_FALSE);
    gl_.glCallList(scene_list_);
    // pass 2: the copy to the shadow texture
    gl_.glBindTexture(GL_TEXTURE_2D, tex_shadow_);
    gl_.glCopyTexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, 0, 0, 512, 512);
    // pass 3: the camera pass with the light-distance ramp
    gl_.glViewport(0, 0, W, H);
    gl_.glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    gl_.glClearColor(0, 0, 0, 0);
    gl_.glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    load_mat(GL_PROJECTION, cam_proj_);
    set_light_ramp_plane(cam_view_);
    gl_.glColorMask(GL_TRUE, GL_FALSE, GL_FALSE, GL_FALSE);
    gl_.glCallList(scene_list_);
    // pass 4: the projective shadow-map subtraction
    gl_.glDisable(GL_TEXTURE_1D);
    gl_.glDisable(GL_TEXTURE_GEN_S);
    load_mat(GL_MODELVIEW, cam_view_);  // the planes given in world space
    eye_plane(GL_S, 1, 0, 0, 0);
    eye_plane(GL_T, 0, 1, 0, 0);
    eye_plane(GL_R, 0, 0, 1, 0);
    eye_plane(GL_Q, 0, 0, 0, 1);
    const Mat tm = mat_mul(mat_bias(), mat_mul(light_proj_, light_view_));
    load_mat(GL_TEXTURE, tm);
    gl_.glEnable(GL_TEXTURE_GEN_S);
    gl_.glEnable(GL_TEXTURE_GEN_T);
    gl_.glEnable(GL_TEXTURE_GEN_R);
    gl_.glEnable(GL_TEXTURE_GEN_Q);
    gl_.glBindTexture(GL_TEXTURE_2D, tex_shadow_);
    gl_.glEnable(GL_TEXTURE_2D);
    gl_.glDepthFunc(GL_LEQUAL);
    gl_.glDepthMask(GL_FALSE);
    gl_.glEnable(GL_BLEND);
    gl_.glBlendEquation(GL_FUNC_REVERSE_SUBTRACT);
    gl_.glBlendFunc(GL_ONE, GL_ONE);
    gl_.glMatrixMode(GL_MODELVIEW);
    gl_.glCallList(scene_list_);
    gl_.glDisable(GL_BLEND);
    gl_.glBlendEquation(GL_FUNC_ADD);
    gl_.glDisable(GL_TEXTURE_2D);
    gl_.glDisable(GL_TEXTURE_GEN_S);
    gl_.glDisable(GL_TEXTURE_GEN_T);
    gl_.glDisable(GL_TEXTURE_GEN_R);
    gl_.glDisable(GL_TEXTURE_GEN_Q);
    load_mat(GL_TEXTURE, mat_identity());
    // pass 5: the lit scene, writing G and B only (the R mask survives)
    load_mat(GL_MODELVIEW, cam_view_);
    const float pos[4] = {light_pos_[0], light_pos_[1], light_pos_[2], 1.0f};
    gl_.glLightfv(GL_LIGHT0, GL_POSITION, pos);
    gl_.glEnable(GL_LIGHT0);
    gl_.glEnable(GL_LIGHTING);
    gl_.glColorMaterial(GL_FRONT_AND_BACK, GL_AMBIENT_AND_DIFFUSE);
    gl_.glEnable(GL_COLOR_MATERIAL);
    gl_.glDepthFunc(GL_LEQUAL);
    gl_.glColorMask(GL_FALSE, GL_TRUE, GL_TRUE, GL_FALSE);
    gl_.glCallList(scene_list_);
    gl_.glDepthMask(GL_TRUE);
    gl_.glDisable(GL_LIGHTING);
    gl_.glDisable(GL_COLOR_MATERIAL);
    gl_.glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
  }

  int triangles() const { return scene_triangles_; }

 private:
  void load_mat(GLenum mode, const Mat& m) {
    gl_.glMatrixMode(mode);
    gl_.glLoadMatrixf(m.m);
  }
  void eye_plane(GLenum coord, float a, float b, float c, float d) {
    const float p[4] = {a, b, c, d};
    gl_.glTexGeni(coord, GL_TEXTURE_GEN_MODE, GL_EYE_LINEAR);
    gl_.glTexGenfv(coord, GL_EYE_PLANE, p);
  }
  // s = (distance along the light's axis − near)/(far − near), a world-space plane given while
  // the modelview holds the view.
  void set_light_ramp_plane(const Mat& view_at_spec) {
    float r2[4];
    mat_row(light_view_, 2, r2);
    const float inv = 1.0f / (light_far_ - light_near_);
    const float p[4] = {-r2[0] * inv, -r2[1] * inv, -r2[2] * inv, (-r2[3] - light_near_) * inv};
    load_mat(GL_MODELVIEW, view_at_spec);
    gl_.glTexGeni(GL_S, GL_TEXTURE_GEN_MODE, GL_EYE_LINEAR);
    gl_.glTexGenfv(GL_S, GL_EYE_PLANE, p);
  }
  void setup_cameras() {
    cam_view_ = mat_lookat(0.0f, 6.0f, 12.0f, 0.0f, 1.0f, 0.0f, 0.0f, 1.0f, 0.0f);
    cam_proj_ = mat_perspective(45.0f, static_cast<float>(W) / static_cast<float>(H), 1.0f, 40.0f);
    light_view_ = mat_lookat(light_pos_[0], light_pos_[1], light_pos_[2], 0.0f, 0.5f, 0.0f, 0.0f, 1.0f, 0.0f);
    light_proj_ = mat_perspective(70.0f, 1.0f, light_near_, light_far_);
  }
  void emit_mesh(const Mesh& m) {
    gl_.glBegin(GL_TRIANGLES);
    for (std::size_t k = 0; k < m.size(); k += 6) {
      gl_.glNormal3fv(&m[k]);
      gl_.glVertex3fv(&m[k + 3]);
    }
    gl_.glEnd();
  }
  void build_scene() {
    Mesh ground, sphere, torus;
    gen_ground(ground, 8.0f, 16);
    gen_sphere(sphere, -2.0f, 1.6f, 0.0f, 1.6f, 48, 36);
    gen_torus(torus, 2.4f, 1.5f, 0.8f, 1.6f, 0.5f, 1.1f, 48, 32);
    scene_triangles_ = static_cast<int>((ground.size() + sphere.size() + torus.size()) / 18);
    scene_list_ = gl_.glGenLists(1);
    gl_.glNewList(scene_list_, GL_COMPILE);
    gl_.glColor3f(0.55f, 0.75f, 0.45f);
    emit_mesh(ground);
    gl_.glColor3f(0.85f, 0.35f, 0.30f);
    emit_mesh(sphere);
    gl_.glColor3f(0.35f, 0.45f, 0.90f);
    emit_mesh(torus);
    gl_.glEndList();
  }
  // The textures frame A uses, made as the peer makes them (the ramp and the shadow texture;
  // the peer's other textures are made too, so the names are the same).
  void make_textures() {
    GLubyte ramp[256];
    for (int i = 0; i < 256; i++) ramp[i] = static_cast<GLubyte>(i);
    gl_.glGenTextures(1, &tex_ramp1d_);
    gl_.glBindTexture(GL_TEXTURE_1D, tex_ramp1d_);
    gl_.glTexImage1D(GL_TEXTURE_1D, 0, GL_INTENSITY8, 256, 0, GL_LUMINANCE, GL_UNSIGNED_BYTE, ramp);
    gl_.glTexParameteri(GL_TEXTURE_1D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    gl_.glTexParameteri(GL_TEXTURE_1D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    gl_.glTexParameteri(GL_TEXTURE_1D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    std::vector<GLubyte> img(512 * 512 * 4);
    for (int y = 0; y < 512; y++)
      for (int x = 0; x < 512; x++) {
        GLubyte* p = img.data() + (y * 512 + x) * 4;
        p[0] = static_cast<GLubyte>(x ^ y);
        p[1] = static_cast<GLubyte>(x);
        p[2] = static_cast<GLubyte>(y);
        p[3] = 255;
      }
    GLuint tex_proj2d = 0;
    gl_.glGenTextures(1, &tex_proj2d);
    gl_.glBindTexture(GL_TEXTURE_2D, tex_proj2d);
    gl_.glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, 512, 512, 0, GL_RGBA, GL_UNSIGNED_BYTE, img.data());
    texture_parameters_2d();
    GLuint copies[3] = {0, 0, 0};
    const GLenum formats[3] = {GL_RGBA8, GL_LUMINANCE8, GL_RGBA8};
    for (int i = 0; i < 3; i++) {
      gl_.glGenTextures(1, &copies[i]);
      gl_.glBindTexture(GL_TEXTURE_2D, copies[i]);
      gl_.glTexImage2D(GL_TEXTURE_2D, 0, static_cast<GLint>(formats[i]), 512, 512, 0, GL_RGBA, GL_UNSIGNED_BYTE,
                       nullptr);
      texture_parameters_2d();
    }
    tex_shadow_ = copies[2];
    gl_.glBindTexture(GL_TEXTURE_2D, 0);
    gl_.glBindTexture(GL_TEXTURE_1D, 0);
  }
  void texture_parameters_2d() {
    gl_.glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    gl_.glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    gl_.glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    gl_.glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  }

  G& gl_;
  const int W, H;
  Mat cam_view_{}, cam_proj_{}, light_view_{}, light_proj_{};
  const float light_pos_[3] = {6.0f, 12.0f, 6.0f};
  const float light_near_ = 6.0f, light_far_ = 26.0f;
  GLuint scene_list_ = 0, tex_ramp1d_ = 0, tex_shadow_ = 0;
  int scene_triangles_ = 0;
};

}  // namespace passim::peer
