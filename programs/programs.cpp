// The pass programs of the seeds (docs/programs.md). Each is GL 1.2 + ARB_imaging
// code against Context; the constants the paper gives for 8 bits are derived here from
// the plane widths.
#include "programs/programs.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/type_ptr.hpp>
#include <map>
#include <random>
#include <sstream>

namespace passim {

const std::vector<ProgramInfo>& program_list() {
  static const std::vector<ProgramInfo> list = {
      {"shadow-map", "Brabec & Seidel §2",
       "depth -> colour through EYE_LINEAR texgen and a 1D ramp; the map copied to a 2D texture; a camera ramp "
       "pass, a projective pass subtracting in the blend unit, a copy turning values > 0 into 'shadowed' "
       "(footnote 1); the lit image attenuated by the mask"},
      {"pcf", "Brabec & Seidel §3",
       "NxN percentage-closer filtering (N = 2, 3, 4): N² jittered (stratified, Figure 3) colour-masked "
       "shadow-map passes packed four to an RGBA map, z replicated to four channels, the subtraction, the count "
       "through the colour table and colour matrix (Figure 4), maps summed in the accumulation buffer for N > 2"},
      {"fast-pcf", "Brabec & Seidel §4",
       "one shadow-map pass into all four channels, the 3x3 packing convolution on the copy to texture, the "
       "(ds/2, dt/2) offset: 2x2; '4x4' as four phases (lower-left, lower-right, upper-left, upper-right "
       "kernels) summed in the accumulation buffer"},
      {"mdsm", "Multiple-depth shadow maps §4",
       "n-SM (n = 1, 2, 3): the map's depth plus the maximum / minimum over its 3x3 neighbourhood, built with "
       "shifted glCopyPixels under glBlendEquation(MAX / MIN); the n-shadow test by subtraction and counting; "
       "PCF(k, n) with k = N² lookups summed in the accumulation buffer"},
      {"hw-shadow", "dedicated hardware (SGIX_shadow)",
       "the baseline: the depth plane copied to a DEPTH_COMPONENT texture, compared with r by the texture unit "
       "(TEXTURE_LEQUAL_R_SGIX), NEAREST or LINEAR (--linear)"},
      {"reeves", "Reeves, Salesin & Cook 1987 (software reference)",
       "percentage-closer filtering in double precision over an NxN-texel footprint (default 3x3), N² samples "
       "--sampling random (a), gaussian (b) or jittered (c); bias; outside the map lit",
       true},
      {"shader-pcf", "ogldev tutorial 42 (software reference)",
       "the tutorial's 3x3 loop of shadow-compare lookups one texel apart; its light factor 0.5 + F/18 is "
       "1 − attenuation/2 here",
       true},
      {"mdsm-ref", "Multiple-depth shadow maps §4.2 (software reference)",
       "the n-shadow test and PCF(k, n) in double: depths, 3x3 maximum and minimum of an unquantised map",
       true},
  };
  return list;
}

const CapturedImage& ProgramRun::image(const std::string& name) const {
  for (const CapturedImage& img : result.images)
    if (img.name == name) return img;
  throw std::out_of_range("no image named " + name);
}

double uniform01(std::mt19937& rng) { return static_cast<double>(rng() >> 8) / 16777216.0; }

int count_levels(const CapturedImage& image) {
  std::vector<std::uint32_t> v(image.codes.begin(), image.codes.end());
  std::sort(v.begin(), v.end());
  v.erase(std::unique(v.begin(), v.end()), v.end());
  int levels = 0;
  for (std::size_t k = 0; k < v.size(); ++k)
    if (k == 0 || v[k] - v[k - 1] > 1) ++levels;
  return levels;
}

namespace {

// The smallest sized internal format of Table 3.16 that holds `bits` (4, 8, 12, 16).
int sized_width(int bits) { return bits <= 4 ? 4 : bits <= 8 ? 8 : bits <= 12 ? 12 : 16; }
GLenum intensity_format(int bits) {
  const int w = sized_width(bits);
  return w == 4 ? GL_INTENSITY4 : w == 8 ? GL_INTENSITY8 : w == 12 ? GL_INTENSITY12 : GL_INTENSITY16;
}
GLenum rgba_format(int bits) {
  const int w = sized_width(bits);
  return w == 4 ? GL_RGBA4 : w == 8 ? GL_RGBA8 : w == 12 ? GL_RGBA12 : GL_RGBA16;
}
GLenum depth_format(int bits) {
  return bits <= 16 ? GL_DEPTH_COMPONENT16 : bits <= 24 ? GL_DEPTH_COMPONENT24 : GL_DEPTH_COMPONENT32;
}

// The share of full shadow each of k shadowed channels carries in the counting copy:
// shares sum to the largest code, as the paper's 64 + 64 + 64 + 63 = 255 (footnote 2).
std::vector<int> channel_shares(int k, int max_code) {
  const int share = (max_code + k - 1) / k;
  std::vector<int> s(static_cast<std::size_t>(k), share);
  s.back() = max_code - share * (k - 1);
  return s;
}


class Program {
 public:
  Program(ProgramRun& run, Context& gl, TraceWriter* writer)
      : run_(run), o_(run.options), gl_(gl), writer_(writer), scene_(run.scene) {
    bits_ = o_.color_bits;
    texture_bits_ = o_.texture_bits > 0 ? o_.texture_bits : bits_;
    table_bits_ = o_.table_bits > 0 ? o_.table_bits : bits_;
    max_code_ = (1 << bits_) - 1;
    map_ = run.map_size;
    width_ = o_.width;
    height_ = o_.height;
  }

  // One whole frame: the shadow map(s) generated, tested, counted, composed. The
  // frame's textures are deleted at its end, as an application redrawing would.
  void frame() {
    run_.result.images.clear();
    captures_.clear();
    const std::string& p = o_.program;
    if (p == "shadow-map") shadow_map();
    else if (p == "pcf") pcf();
    else if (p == "fast-pcf") fast_pcf();
    else if (p == "mdsm") mdsm();
    else hw_shadow();
    final_image();
    gl_.glDeleteTextures(static_cast<GLsizei>(frame_textures_.size()), frame_textures_.data());
    frame_textures_.clear();
  }

  // The state every frame starts from: the scene's display list, texgen, the ramp.
  void setup() {
    gl_.glDrawBuffer(GL_BACK);
    gl_.glReadBuffer(GL_BACK);
    gl_.glShadeModel(GL_SMOOTH);
    gl_.glEnable(GL_DEPTH_TEST);
    gl_.glDepthFunc(GL_LESS);
    gl_.glColorMaterial(GL_FRONT_AND_BACK, GL_AMBIENT_AND_DIFFUSE);
    gl_.glEnable(GL_COLOR_MATERIAL);
    gl_.glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    scene_list_ = gl_.glGenLists(1);
    gl_.glNewList(scene_list_, GL_COMPILE);
    draw_scene(gl_, scene_);
    gl_.glEndList();
    // Texgen: (s, t, r, q) = eye coordinates (x, y, z, w); the planes are set under an
    // identity modelview, so they stay the eye's own axes (§2.10.4). The texture matrix
    // then maps them where each pass needs them.
    gl_.glMatrixMode(GL_MODELVIEW);
    gl_.glLoadIdentity();
    const GLenum coords[4] = {GL_S, GL_T, GL_R, GL_Q};
    for (int k = 0; k < 4; ++k) {
      GLdouble plane[4] = {0, 0, 0, 0};
      plane[k] = 1.0;
      gl_.glTexGeni(coords[k], GL_TEXTURE_GEN_MODE, GL_EYE_LINEAR);
      gl_.glTexGendv(coords[k], GL_EYE_PLANE, plane);
    }
    if (o_.program != "hw-shadow") make_ramp();
    run_.bias_depth = o_.program == "hw-shadow" ? o_.bias / std::ldexp(1.0, o_.depth_bits)
                                                : o_.bias / std::ldexp(1.0, bits_);
  }

  // Figure 1: a 1D ramp of 2^bits texels, texel i = i / (2^bits − 1), sampled NEAREST, so
  // an encoded depth s becomes the code floor(s·2^bits) exactly (the ramp's INTENSITY
  // format replicates it into all four channels).
  void make_ramp() {
    const int n = 1 << bits_;
    std::vector<float> texels(static_cast<std::size_t>(n));
    for (int i = 0; i < n; ++i) texels[static_cast<std::size_t>(i)] = static_cast<float>(static_cast<double>(i) / max_code_);
    gl_.glGenTextures(1, &ramp_);
    gl_.glBindTexture(GL_TEXTURE_1D, ramp_);
    gl_.glTexImage1D(GL_TEXTURE_1D, 0, static_cast<GLint>(intensity_format(texture_bits_)), n, 0, GL_LUMINANCE, GL_FLOAT,
                     texels.data());
    gl_.glTexParameteri(GL_TEXTURE_1D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    gl_.glTexParameteri(GL_TEXTURE_1D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    gl_.glTexParameteri(GL_TEXTURE_1D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    gl_.glTexEnvi(GL_TEXTURE_ENV, GL_TEXTURE_ENV_MODE, GL_REPLACE);
  }

  // ---------------------------------------------------------------- views and regions
  double aspect() const { return static_cast<double>(width_) / height_; }

  void use_region(int w, int h) {
    gl_.glViewport(0, 0, w, h);
    gl_.glScissor(0, 0, w, h);
    gl_.glEnable(GL_SCISSOR_TEST);
  }

  // The light's view; the image plane moved by (jx, jy) texels (Figure 3's jitter).
  void light_view(double jx = 0.0, double jy = 0.0) {
    use_region(map_, map_);
    gl_.glMatrixMode(GL_PROJECTION);
    gl_.glLoadIdentity();
    if (jx != 0.0 || jy != 0.0) gl_.glTranslated(2.0 * jx / map_, 2.0 * jy / map_, 0.0);
    gl_.gluPerspective(scene_.light.fovy_degrees, 1.0, scene_.light.near_plane, scene_.light.far_plane);
    gl_.glMatrixMode(GL_MODELVIEW);
    gl_.glLoadIdentity();
    look_at(scene_.light);
  }

  void camera_view() {
    use_region(width_, height_);
    gl_.glMatrixMode(GL_PROJECTION);
    gl_.glLoadIdentity();
    gl_.gluPerspective(scene_.camera.fovy_degrees, aspect(), scene_.camera.near_plane, scene_.camera.far_plane);
    gl_.glMatrixMode(GL_MODELVIEW);
    gl_.glLoadIdentity();
    look_at(scene_.camera);
  }

  void look_at(const View& v) {
    gl_.gluLookAt(v.eye.x, v.eye.y, v.eye.z, v.center.x, v.center.y, v.center.z, v.up.x, v.up.y, v.up.z);
  }

  // Window coordinates for pixel rectangles: the raster position at pixel (x, y).
  void window_raster_pos(int x, int y) {
    gl_.glMatrixMode(GL_PROJECTION);
    gl_.glLoadIdentity();
    const FramebufferConfig& c = gl_.config();
    gl_.glOrtho(0.0, c.width, 0.0, c.height, -1.0, 1.0);
    gl_.glMatrixMode(GL_MODELVIEW);
    gl_.glLoadIdentity();
    gl_.glRasterPos2i(x, y);
  }

  void load_texture_matrix(const glm::dmat4& m) {
    gl_.glMatrixMode(GL_TEXTURE);
    gl_.glLoadMatrixd(glm::value_ptr(m));
    gl_.glMatrixMode(GL_MODELVIEW);
  }

  // The row that encodes depth: s = (−z_eye − near) / (far − near) in the light's eye
  // space, minus `bias` (§2: "a mapping from r to any of the colour channels").
  glm::dmat4 ramp_matrix(double bias) const {
    const double n = scene_.light.near_plane, f = scene_.light.far_plane, a = 1.0 / (f - n);
    glm::dmat4 m(1.0);
    m[0][0] = 0.0;
    m[2][0] = -a;
    m[3][0] = -n * a - bias;
    return m;
  }

  // Camera eye coordinates -> light eye coordinates (the paper's "additional 4x4
  // texture matrix which transforms points from camera to light source space").
  glm::dmat4 camera_to_light() const {
    return scene_.light.view_matrix() * glm::inverse(scene_.camera.view_matrix());
  }

  // Camera eye coordinates -> the light's texture space [0,1]² (+ window depth in r),
  // offset by (ds, dt) texels.
  glm::dmat4 projective_matrix(double ds, double dt, double r_bias = 0.0) const {
    glm::dmat4 m = glm::translate(glm::dmat4(1.0), glm::dvec3(ds / map_, dt / map_, -r_bias));
    m = m * glm::translate(glm::dmat4(1.0), glm::dvec3(0.5)) * glm::scale(glm::dmat4(1.0), glm::dvec3(0.5));
    return m * scene_.light.projection_matrix(1.0) * camera_to_light();
  }

  // The scene drawn with texture `tex` on `target`, coordinates from texgen through
  // `texture_matrix`.
  void draw_textured(GLenum target, GLuint tex, const glm::dmat4& texture_matrix) {
    load_texture_matrix(texture_matrix);
    texgen(true);
    gl_.glBindTexture(target, tex);
    gl_.glEnable(target);
    gl_.glCallList(scene_list_);
    gl_.glDisable(target);
    texgen(false);
  }

  void texgen(bool on) {
    for (GLenum c : {GL_TEXTURE_GEN_S, GL_TEXTURE_GEN_T, GL_TEXTURE_GEN_R, GL_TEXTURE_GEN_Q})
      on ? gl_.glEnable(c) : gl_.glDisable(c);
  }

  // ---------------------------------------------------------------- passes
  void begin(const std::string& label) { gl_.glPushGroupMarkerEXT(static_cast<GLsizei>(label.size()), label.c_str()); }
  void end() { gl_.glPopGroupMarkerEXT(); }

  void capture(std::string name, const std::string& plane, int w, int h, bool intermediate = true) {
    if ((intermediate && !o_.intermediates) || (!o_.images && !writer_)) return;
    // A pass that repeats (one per map or phase) numbers its captures: mask, mask1, ...
    const int seen = captures_[name]++;
    if (seen > 0) name += std::to_string(seen);
    const CaptureRegion region{0, 0, w, h};
    run_.result.images.push_back(capture_plane(gl_, name, plane, GL_BACK, region));
    if (writer_) writer_->output(name, plane, plane == "depth" ? "" : "GL_BACK", region);
  }

  // The scene from the light with depth encoded through the ramp, into the channels
  // the colour mask leaves open. `clear_color` clears the colour too (to the far value).
  void light_ramp_pass(const std::string& label, double jx, double jy, bool clear_color, int channel = -1) {
    begin(label);
    light_view(jx, jy);
    if (clear_color) {
      gl_.glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
      gl_.glClearColor(1.0f, 1.0f, 1.0f, 1.0f);  // unrendered map texels: farthest depth
    }
    gl_.glClear(clear_color ? (GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT) : GL_DEPTH_BUFFER_BIT);
    if (channel >= 0) gl_.glColorMask(channel == 0, channel == 1, channel == 2, channel == 3);
    gl_.glDisable(GL_CULL_FACE);  // the map holds the nearest surface, front or back
    gl_.glDisable(GL_LIGHTING);
    draw_textured(GL_TEXTURE_1D, ramp_, ramp_matrix(0.0));
    gl_.glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    end();
  }

  // A 2D texture of the map region's colour, sampled NEAREST (the copy keeps the codes).
  GLuint copy_map_to_texture(GLenum internal_format, const std::string& label) {
    begin(label);
    GLuint tex = 0;
    gl_.glGenTextures(1, &tex);
    frame_textures_.push_back(tex);
    gl_.glBindTexture(GL_TEXTURE_2D, tex);
    gl_.glCopyTexImage2D(GL_TEXTURE_2D, 0, internal_format, 0, 0, map_, map_, 0);
    gl_.glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    gl_.glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    gl_.glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    gl_.glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    end();
    return tex;
  }

  // §2 second pass: the scene from the camera, each pixel coloured with its own depth in
  // the light's space (less the bias), in all four channels.
  void camera_ramp_pass() {
    begin("camera depth");
    camera_view();
    gl_.glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    gl_.glClearColor(0.0f, 0.0f, 0.0f, 0.0f);
    gl_.glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    gl_.glEnable(GL_CULL_FACE);
    gl_.glCullFace(GL_BACK);
    gl_.glDisable(GL_LIGHTING);
    gl_.glDepthFunc(GL_LESS);
    draw_textured(GL_TEXTURE_1D, ramp_, ramp_matrix(run_.bias_depth) * camera_to_light());
    end();
    capture("camera-depth", "color", width_, height_);
  }

  // §2 third pass: the map projected onto the scene and subtracted from the camera
  // depth in the blend unit: dst − src, clamped at 0, > 0 where the map holds a nearer
  // surface. (ds, dt) offsets the lookup in texels.
  void shadow_test_pass(GLuint map, double ds, double dt, const std::string& label = "shadow test") {
    begin(label);
    camera_view();
    gl_.glDepthFunc(GL_EQUAL);
    gl_.glDepthMask(GL_FALSE);
    gl_.glEnable(GL_BLEND);
    gl_.glBlendEquation(GL_FUNC_REVERSE_SUBTRACT);
    gl_.glBlendFunc(GL_ONE, GL_ONE);
    draw_textured(GL_TEXTURE_2D, map, projective_matrix(ds, dt));
    gl_.glDisable(GL_BLEND);
    gl_.glBlendEquation(GL_FUNC_ADD);
    gl_.glDepthMask(GL_TRUE);
    gl_.glDepthFunc(GL_LESS);
    end();
    capture("mask", "color", width_, height_);
  }

  // A framebuffer-to-framebuffer copy of the camera region onto itself, writing only
  // the channels `mask` leaves open.
  void copy_in_place(const std::array<GLboolean, 4>& mask) {
    gl_.glDisable(GL_DEPTH_TEST);
    gl_.glDisable(GL_SCISSOR_TEST);
    window_raster_pos(0, 0);
    gl_.glColorMask(mask[0], mask[1], mask[2], mask[3]);
    gl_.glCopyPixels(0, 0, width_, height_, GL_COLOR);
    gl_.glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    gl_.glEnable(GL_DEPTH_TEST);
  }

  // Footnote 1: values > 0 become 1 (alpha scaled by 2^bits, clamped).
  void threshold_copy() {
    begin("threshold");
    gl_.glPixelTransferf(GL_ALPHA_SCALE, static_cast<GLfloat>(max_code_ + 1));
    copy_in_place({GL_FALSE, GL_FALSE, GL_FALSE, GL_TRUE});
    gl_.glPixelTransferf(GL_ALPHA_SCALE, 1.0f);
    end();
  }

  // Figure 4: the colour table sends 0 to 0 and any other code to its channel's share
  // (the paper's 64, 64, 64, 63 at 8 bits); the colour matrix sums the channels into
  // alpha. `k` channels take part; the others count nothing.
  void count_copy(int k) {
    begin("count");
    const int n = 1 << bits_;
    const std::vector<int> shares = channel_shares(k, max_code_);
    std::vector<float> table(static_cast<std::size_t>(4 * n), 0.0f);
    for (int i = 1; i < n; ++i)
      for (int c = 0; c < k; ++c)
        table[static_cast<std::size_t>(4 * i + c)] = static_cast<float>(static_cast<double>(shares[static_cast<std::size_t>(c)]) / max_code_);
    gl_.glColorTable(GL_COLOR_TABLE, rgba_format(table_bits_), n, GL_RGBA, GL_FLOAT, table.data());
    gl_.glEnable(GL_COLOR_TABLE);
    const GLdouble sum_all[16] = {1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1};
    gl_.glMatrixMode(GL_COLOR);
    gl_.glLoadMatrixd(sum_all);
    gl_.glMatrixMode(GL_MODELVIEW);
    copy_in_place({GL_FALSE, GL_FALSE, GL_FALSE, GL_TRUE});
    gl_.glMatrixMode(GL_COLOR);
    gl_.glLoadIdentity();
    gl_.glMatrixMode(GL_MODELVIEW);
    gl_.glDisable(GL_COLOR_TABLE);
    end();
  }

  // Sums `phases` results in the accumulation buffer, each with its weight.
  void accumulate(int phase, double weight) {
    begin("accumulate");
    use_region(width_, height_);
    gl_.glAccum(phase == 0 ? GL_LOAD : GL_ACCUM, static_cast<GLfloat>(weight));
    end();
  }
  void accumulation_return() {
    begin("accumulate");
    use_region(width_, height_);
    gl_.glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_TRUE);
    gl_.glAccum(GL_RETURN, 1.0f);
    gl_.glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    end();
  }

  // ---------------------------------------------------------------- programs
  void shadow_map() {
    run_.samples.push_back({0, 0, 0.5, 0.5});
    light_ramp_pass("shadow map", 0.0, 0.0, true);
    capture("shadowmap", "color", map_, map_, false);
    const GLuint map = copy_map_to_texture(intensity_format(texture_bits_), "copy to texture");
    camera_ramp_pass();
    shadow_test_pass(map, 0.0, 0.0);
    threshold_copy();
  }

  // §3: N×N strata per texel, each sampled once (jittered within its stratum), four to
  // an RGBA map (one channel per pass); each map tested and counted, maps summed.
  void pcf() {
    const int n = o_.filter, strata = n * n, maps = (strata + 3) / 4;
    std::mt19937 rng(o_.seed);
    std::vector<GLuint> textures;
    const char* channel_names = "RGBA";
    for (int m = 0; m < maps; ++m) {
      for (int c = 0; c < 4 && 4 * m + c < strata; ++c) {
        const int s = 4 * m + c, a = s % n, b = s / n;
        const double xi = o_.jitter ? uniform01(rng) : 0.5, eta = o_.jitter ? uniform01(rng) : 0.5;
        const double dx = (a + xi) / n, dy = (b + eta) / n;  // the sample inside its texel
        run_.samples.push_back({m, c, dx, dy});
        light_ramp_pass(fmt::format("shadow map {} {}", m, channel_names[c]), 0.5 - dx, 0.5 - dy, c == 0, c);
      }
      capture(maps == 1 ? "shadowmap" : fmt::format("shadowmap{}", m), "color", map_, map_, false);
      textures.push_back(copy_map_to_texture(rgba_format(texture_bits_), "copy to texture"));
    }
    for (int m = 0; m < maps; ++m) {
      const int k = std::min(4, strata - 4 * m);
      camera_ramp_pass();
      shadow_test_pass(textures[static_cast<std::size_t>(m)], 0.0, 0.0);
      count_copy(k);
      if (maps > 1) accumulate(m, static_cast<double>(k) / strata);
    }
    if (maps > 1) accumulation_return();
  }

  // §4: the packing kernel for the 2x2 block whose lower-left texel is at (n0, m0) of
  // the 3x3 filter: R from the lower left, G lower right, B upper left, A upper right.
  // Phase (0, 0) is the paper's C (its equation (1) read as P_{m+i, n+j}).
  std::vector<float> packing_kernel(int n0, int m0) const {
    std::vector<float> k(3 * 3 * 4, 0.0f);
    auto set = [&](int n, int m, int c) { k[static_cast<std::size_t>((m * 3 + n) * 4 + c)] = 1.0f; };
    set(n0, m0, 0), set(n0 + 1, m0, 1), set(n0, m0 + 1, 2), set(n0 + 1, m0 + 1, 3);
    return k;
  }

  void fast_pcf() {
    light_ramp_pass("shadow map", 0.0, 0.0, true);
    capture("shadowmap", "color", map_, map_, false);
    // Phases: the 2x2 blocks of the 3x3 window (lower-left only for 2x2).
    std::vector<std::pair<int, int>> phases = {{0, 0}};
    if (o_.filter == 4) phases = {{0, 0}, {1, 0}, {0, 1}, {1, 1}};
    std::vector<GLuint> textures;
    for (auto [n0, m0] : phases) {
      const std::vector<float> kernel = packing_kernel(n0, m0);
      gl_.glConvolutionFilter2D(GL_CONVOLUTION_2D, GL_RGBA, 3, 3, GL_RGBA, GL_FLOAT, kernel.data());
      gl_.glConvolutionParameteri(GL_CONVOLUTION_2D, GL_CONVOLUTION_BORDER_MODE, GL_REPLICATE_BORDER);
      gl_.glEnable(GL_CONVOLUTION_2D);
      textures.push_back(copy_map_to_texture(rgba_format(texture_bits_), "copy to texture (packing convolution)"));
      gl_.glDisable(GL_CONVOLUTION_2D);
    }
    for (int c = 0; c < 4; ++c)  // the packed texel's samples, relative to the lookup texel
      run_.samples.push_back({0, c, -0.5 + (c % 2), -0.5 + (c / 2)});
    const int count = static_cast<int>(phases.size());
    for (int p = 0; p < count; ++p) {
      camera_ramp_pass();
      // Figure 6: offset (ds/2, dt/2) for the packed texel's new centre.
      shadow_test_pass(textures[static_cast<std::size_t>(p)], 0.5, 0.5);
      count_copy(4);
      if (count > 1) accumulate(p, 1.0 / count);
    }
    if (count > 1) accumulation_return();
  }

  // One shifted copy of the map region onto itself under the current blend equation:
  // each texel combined with its neighbour at (dx, dy).
  void shifted_copy(int dx, int dy) {
    window_raster_pos(std::max(0, -dx), std::max(0, -dy));
    gl_.glCopyPixels(std::max(0, dx), std::max(0, dy), map_ - std::abs(dx), map_ - std::abs(dy), GL_COLOR);
  }

  // The extra depths of an n-SM: the 3x3 neighbourhood's maximum (channel G) or minimum
  // (channel B), separably: two horizontal then two vertical shifted copies.
  void neighbourhood(GLenum equation, int channel, const std::string& label) {
    begin(label);
    gl_.glDisable(GL_DEPTH_TEST);
    gl_.glDisable(GL_SCISSOR_TEST);
    gl_.glColorMask(channel == 0, channel == 1, channel == 2, channel == 3);
    gl_.glEnable(GL_BLEND);
    gl_.glBlendEquation(equation);
    gl_.glBlendFunc(GL_ONE, GL_ONE);
    shifted_copy(1, 0), shifted_copy(-1, 0), shifted_copy(0, 1), shifted_copy(0, -1);
    gl_.glBlendEquation(GL_FUNC_ADD);
    gl_.glDisable(GL_BLEND);
    gl_.glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    gl_.glEnable(GL_DEPTH_TEST);
    end();
  }

  void mdsm() {
    const int n = o_.depths, side = o_.filter, k = side * side;
    light_ramp_pass("shadow map", 0.0, 0.0, true);
    if (n >= 2) neighbourhood(GL_MAX, 1, "maximum depths");
    if (n >= 3) neighbourhood(GL_MIN, 2, "minimum depths");
    capture("shadowmap", "color", map_, map_, false);
    const GLuint map = copy_map_to_texture(rgba_format(texture_bits_), "copy to texture");
    run_.samples.push_back({0, 0, 0.5, 0.5});
    for (int j = 0; j < side; ++j)
      for (int i = 0; i < side; ++i) {
        // Lookups one texel apart, centred on the pixel's projection.
        const double ds = i - 0.5 * (side - 1), dt = j - 0.5 * (side - 1);
        camera_ramp_pass();
        shadow_test_pass(map, ds, dt);
        count_copy(n);
        if (k > 1) accumulate(j * side + i, 1.0 / k);
      }
    if (k > 1) accumulation_return();
  }

  void hw_shadow() {
    begin("shadow map");
    light_view();
    gl_.glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
    gl_.glClear(GL_DEPTH_BUFFER_BIT);
    gl_.glDisable(GL_CULL_FACE);
    gl_.glDisable(GL_LIGHTING);
    gl_.glCallList(scene_list_);
    gl_.glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    end();
    capture("shadowmap", "depth", map_, map_, false);
    run_.samples.push_back({0, 0, 0.5, 0.5});
    const GLuint map = copy_map_to_texture(depth_format(o_.depth_bits), "copy to texture");
    const GLint filter = o_.linear ? GL_LINEAR : GL_NEAREST;
    gl_.glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, filter);
    gl_.glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, filter);
    gl_.glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_COMPARE_SGIX, GL_TRUE);
    // LEQUAL_R: 1 where the texel is at or before r, i.e. where the point is shadowed.
    gl_.glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_COMPARE_OPERATOR_SGIX, GL_TEXTURE_LEQUAL_R_SGIX);
    gl_.glTexParameteri(GL_TEXTURE_2D, GL_DEPTH_TEXTURE_MODE, GL_INTENSITY);
    begin("shadow test");
    camera_view();
    gl_.glClearColor(0.0f, 0.0f, 0.0f, 0.0f);
    gl_.glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    gl_.glEnable(GL_CULL_FACE);
    gl_.glCullFace(GL_BACK);
    draw_textured(GL_TEXTURE_2D, map, projective_matrix(0.0, 0.0, run_.bias_depth));
    end();
  }

  // The lit image attenuated by the shadow fraction in alpha: an ambient pass, then
  // the light's diffuse term scaled by (1 − alpha) in the blend unit, on the depths the
  // camera passes left (depth test EQUAL).
  void final_image() {
    begin("final");
    camera_view();
    gl_.glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_FALSE);
    gl_.glClearColor(0.15f, 0.15f, 0.2f, 0.0f);
    gl_.glClear(GL_COLOR_BUFFER_BIT);
    gl_.glEnable(GL_CULL_FACE);
    gl_.glCullFace(GL_BACK);
    gl_.glDepthFunc(GL_EQUAL);
    gl_.glDepthMask(GL_FALSE);
    const GLfloat pos[4] = {static_cast<GLfloat>(scene_.light.eye.x), static_cast<GLfloat>(scene_.light.eye.y),
                            static_cast<GLfloat>(scene_.light.eye.z), 1.0f};
    const GLfloat zero[4] = {0, 0, 0, 1}, ambient[4] = {0.3f, 0.3f, 0.3f, 1}, diffuse[4] = {0.8f, 0.8f, 0.8f, 1};
    gl_.glLightfv(GL_LIGHT0, GL_POSITION, pos);
    gl_.glLightfv(GL_LIGHT0, GL_AMBIENT, zero);
    gl_.glLightfv(GL_LIGHT0, GL_SPECULAR, zero);
    gl_.glEnable(GL_LIGHT0);
    gl_.glEnable(GL_LIGHTING);
    gl_.glLightfv(GL_LIGHT0, GL_DIFFUSE, zero);
    gl_.glLightModelfv(GL_LIGHT_MODEL_AMBIENT, ambient);
    gl_.glCallList(scene_list_);
    gl_.glLightfv(GL_LIGHT0, GL_DIFFUSE, diffuse);
    gl_.glLightModelfv(GL_LIGHT_MODEL_AMBIENT, zero);
    gl_.glEnable(GL_BLEND);
    gl_.glBlendFunc(GL_ONE_MINUS_DST_ALPHA, GL_ONE);
    gl_.glCallList(scene_list_);
    gl_.glDisable(GL_BLEND);
    gl_.glDisable(GL_LIGHTING);
    gl_.glDepthMask(GL_TRUE);
    gl_.glDepthFunc(GL_LESS);
    gl_.glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    end();
    capture("final", "rgb", width_, height_, false);
    capture("attenuation", "alpha", width_, height_, false);
  }

  ProgramRun& run_;
  const ProgramOptions& o_;
  Context& gl_;
  TraceWriter* writer_;  // null when not recording
  const Scene& scene_;
  int bits_ = 8, texture_bits_ = 8, table_bits_ = 8, max_code_ = 255, map_ = 512, width_ = 800, height_ = 600;
  GLuint scene_list_ = 0, ramp_ = 0;
  std::map<std::string, int> captures_;
  std::vector<GLuint> frame_textures_;
};

bool is_power_of_two(int v) { return v > 0 && (v & (v - 1)) == 0; }

// Checks the settings against the program and the machine profile; fills the defaults.
void validate(ProgramOptions& o, const MachineProfile& profile, int map) {
  const MachineLimits& l = profile.limits;
  auto known = std::find_if(program_list().begin(), program_list().end(),
                            [&](const ProgramInfo& p) { return p.name == o.program; });
  if (known == program_list().end())
    throw ProgramError(fmt::format("unknown program '{}' (passim program --list shows them)", o.program));
  if (known->reference) throw ProgramError(fmt::format("'{}' is a software reference (run_reference)", o.program));
  if (o.color_bits < 4 || o.color_bits > 16)
    throw ProgramError(fmt::format("--bits {}: the programs run at colour widths 4 to 16", o.color_bits));
  if (o.depth_bits < 1 || o.depth_bits > 32) throw ProgramError(fmt::format("--depth-bits {}: 1 to 32", o.depth_bits));
  for (const auto& [value, what] : {std::pair{o.texture_bits, "--texture-bits"}, std::pair{o.table_bits, "--table-bits"}})
    if (value != 0 && value != 4 && value != 8 && value != 12 && value != 16)
      throw ProgramError(fmt::format("{} {}: a sized internal format, 4, 8, 12 or 16", what, value));
  if (o.width < 1 || o.height < 1 || o.width > l.max_framebuffer_size || o.height > l.max_framebuffer_size)
    throw ProgramError(fmt::format("--size {}x{}: each side must be 1 to {} (profile {}, largest framebuffer)", o.width,
                                   o.height, l.max_framebuffer_size, profile.name));
  if (!is_power_of_two(map) || map > l.max_texture_size)
    throw ProgramError(fmt::format("--map {}: a power of two up to {} (profile {}, MAX_TEXTURE_SIZE)", map,
                                   l.max_texture_size, profile.name));
  if (map > l.max_framebuffer_size)
    throw ProgramError(fmt::format("--map {}: larger than the framebuffer can be ({})", map, l.max_framebuffer_size));
  if (std::isnan(o.bias))
    o.bias = o.program == "hw-shadow" ? std::ldexp(1.0, o.depth_bits - 12) : std::ldexp(1.0, o.color_bits - 8);
  if (!std::isfinite(o.bias)) throw ProgramError("--bias must be a finite number of steps");
  const std::string& p = o.program;
  const bool ramp = p != "hw-shadow";
  if (ramp && (1 << o.color_bits) > l.max_texture_size)
    throw ProgramError(fmt::format(
        "--bits {}: the depth ramp needs a 1D texture of 2^{} = {} texels; profile {} allows {} (MAX_TEXTURE_SIZE)",
        o.color_bits, o.color_bits, 1 << o.color_bits, profile.name, l.max_texture_size));
  const bool counts = p == "pcf" || p == "fast-pcf" || p == "mdsm";
  if (counts && (1 << o.color_bits) > l.max_color_table_width)
    throw ProgramError(fmt::format(
        "--bits {}: the counting colour table needs 2^{} = {} entries; profile {} allows {} (MAX_COLOR_TABLE_WIDTH)",
        o.color_bits, o.color_bits, 1 << o.color_bits, profile.name, l.max_color_table_width));
  if (p == "fast-pcf" && (l.max_convolution_width < 3 || l.max_convolution_height < 3))
    throw ProgramError(fmt::format("fast-pcf needs a 3x3 convolution; profile {} allows {}x{}", profile.name,
                                   l.max_convolution_width, l.max_convolution_height));
  if (p == "shadow-map" || p == "hw-shadow") {
    if (o.filter != 0 && o.filter != 1)
      throw ProgramError(fmt::format("{} has no filter (--filter {}x{}); pcf, fast-pcf and mdsm have", p, o.filter, o.filter));
    o.filter = 1;
  } else if (p == "pcf") {
    if (o.filter == 0) o.filter = 2;
    if (o.filter < 2 || o.filter > 4) throw ProgramError(fmt::format("pcf --filter {0}x{0}: 2x2, 3x3 or 4x4", o.filter));
  } else if (p == "fast-pcf") {
    if (o.filter == 0) o.filter = 2;
    if (o.filter != 2 && o.filter != 4) throw ProgramError(fmt::format("fast-pcf --filter {0}x{0}: 2x2 or 4x4", o.filter));
  } else if (p == "mdsm") {
    if (o.filter == 0) o.filter = 2;
    if (o.filter < 1 || o.filter > 3) throw ProgramError(fmt::format("mdsm --filter {0}x{0}: 1x1, 2x2 or 3x3 (k = 1, 4, 9)", o.filter));
    if (o.depths < 1 || o.depths > 3) throw ProgramError(fmt::format("mdsm --depths {}: 1, 2 or 3", o.depths));
  }
  const bool accumulates = (p == "pcf" && o.filter > 2) || (p == "fast-pcf" && o.filter == 4) || (p == "mdsm" && o.filter > 1);
  if (accumulates && o.accum_bits < 0) throw ProgramError("--accum-bits must be positive");
  if (o.accum_bits < 0 || o.accum_bits > 32) throw ProgramError(fmt::format("--accum-bits {}: 2 to 32", o.accum_bits));
}

}  // namespace

struct ProgramSession::State {
  ProgramRun run;
  std::ostringstream trace;
  std::unique_ptr<TraceWriter> writer;
  std::unique_ptr<Program> program;
  int frames = 0;
};

ProgramSession::ProgramSession(const ProgramOptions& options, bool record) : state_(std::make_unique<State>()) {
  ProgramRun& run = state_->run;
  run.options = options;
  run.scene = make_scene(options.scene);
  const MachineProfile* profile = find_profile(options.profile);
  if (!profile) throw ProgramError(fmt::format("unknown machine profile '{}' (passim info lists them)", options.profile));
  run.map_size = options.map_size > 0 ? options.map_size : run.scene.default_map_size;
  validate(run.options, *profile, run.map_size);
  run.triangles = run.scene.triangles();
  const ProgramOptions& o = run.options;

  TraceSettings& s = run.result.settings;
  s.profile = profile->name;
  s.framebuffer.width = std::max(o.width, run.map_size);
  s.framebuffer.height = std::max(o.height, run.map_size);
  s.framebuffer.color_bits = {o.color_bits, o.color_bits, o.color_bits, o.color_bits};
  s.framebuffer.depth_bits = o.depth_bits;
  s.framebuffer.stencil_bits = 0;
  s.framebuffer.accum_bits = o.accum_bits > 0 ? o.accum_bits : FramebufferConfig::default_accum_bits(s.framebuffer.color_bits);
  s.framebuffer.double_buffer = true;
  const std::string invalid = s.framebuffer.validate(profile->limits.max_framebuffer_size);
  if (!invalid.empty()) throw ProgramError(invalid);

  run.result.context = std::make_unique<Context>(s.framebuffer, s.machine());
  run.result.context->set_threads(options.threads);
  run.result.context->set_pass_end_observer(options.pass_end);
  if (o.remove_color_tables || o.remove_convolution || o.remove_color_matrix) {
    // A trace cannot say this (it is not GL state): such a session records nothing.
    if (record) throw ProgramError("a program with removed stages cannot be recorded as a trace");
    run.result.context->remove_stages({o.remove_color_tables, o.remove_convolution, o.remove_color_matrix});
  }
  if (record) {
    state_->trace << "# passim program " << o.program << " on scene " << run.scene.name << " (" << run.triangles
                  << " triangles)\n";
    state_->writer = std::make_unique<TraceWriter>(state_->trace);
    state_->writer->write_header(s);
    run.result.context->set_call_sink(state_->writer.get());
  }
  state_->program = std::make_unique<Program>(run, *run.result.context, state_->writer.get());
  state_->program->setup();
}

ProgramSession::~ProgramSession() = default;

void ProgramSession::frame() {
  if (state_->writer && state_->frames > 0)
    throw std::logic_error("a recorded program session runs one frame (its @output names would repeat)");
  state_->program->frame();
  ++state_->frames;
  const Context& ctx = *state_->run.result.context;
  ctx.check_balance();  // every run checks it (InternalError), programs as replays
  if (!ctx.error_log().empty()) {
    const GlErrorRecord& e = ctx.error_log().front();
    throw std::logic_error(fmt::format("program {} raised GL error {} in {}", state_->run.options.program,
                                       enum_name(e.error), e.call));
  }
}

const ProgramRun& ProgramSession::run() const { return state_->run; }

ProgramRun ProgramSession::finish() {
  state_->program.reset();
  state_->run.result.context->set_call_sink(nullptr);
  state_->run.trace = state_->trace.str();
  return std::move(state_->run);
}

ProgramRun run_program(const ProgramOptions& options) {
  ProgramSession session(options, true);
  session.frame();
  return session.finish();
}

}  // namespace passim
