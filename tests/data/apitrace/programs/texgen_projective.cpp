// Texture-coordinate generation (GL_OBJECT_LINEAR and GL_EYE_LINEAR for s, t and q) and a
// projective texture matrix, as a shadow-map pass sets them up, on a perspective floor and
// a tilted quad. The texture is a gentle ramp (neighbouring texels differ by one code), so
// where two implementations pick neighbouring texels at a boundary they differ by one step
// at most, while a wrong texgen or projection shows as many steps
// (tests/data/apitrace/README.md).
#include "harness.hpp"

int main() {
  GlWindow w = open_window(96, 72, {GLX_RGBA, GLX_DOUBLEBUFFER, GLX_RED_SIZE, 8, GLX_GREEN_SIZE, 8,
                                     GLX_BLUE_SIZE, 8, GLX_DEPTH_SIZE, 16});
  // 64x64 RGB ramp: R follows s, G follows t, B their sum.
  static GLubyte texels[64][64][3];
  for (int t = 0; t < 64; ++t)
    for (int s = 0; s < 64; ++s) {
      texels[t][s][0] = static_cast<GLubyte>(64 + s);
      texels[t][s][1] = static_cast<GLubyte>(96 + t);
      texels[t][s][2] = static_cast<GLubyte>(32 + (s + t) / 2);
    }
  GLuint name = 0;
  glGenTextures(1, &name);
  glBindTexture(GL_TEXTURE_2D, name);
  glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  glTexImage2D(GL_TEXTURE_2D, 0, GL_RGB8, 64, 64, 0, GL_RGB, GL_UNSIGNED_BYTE, texels);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  glTexEnvi(GL_TEXTURE_ENV, GL_TEXTURE_ENV_MODE, GL_REPLACE);

  glViewport(0, 0, 96, 72);
  glClearColor(0.0f, 0.0f, 0.0f, 1.0f);
  glClearDepth(1.0);
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  glEnable(GL_DEPTH_TEST);
  glMatrixMode(GL_PROJECTION);
  glLoadIdentity();
  glFrustum(-0.8, 0.8, -0.6, 0.6, 1.0, 20.0);
  glMatrixMode(GL_MODELVIEW);
  glLoadIdentity();
  glTranslatef(0.0f, -0.6f, -3.0f);
  glRotatef(25.0f, 1.0f, 0.0f, 0.0f);

  // Eye-linear planes are given with the modelview current: here, the identity.
  glPushMatrix();
  glLoadIdentity();
  const GLfloat s_plane[] = {1, 0, 0, 0}, t_plane[] = {0, 1, 0, 0}, r_plane[] = {0, 0, 1, 0}, q_plane[] = {0, 0, 0, 1};
  for (GLenum c : {GL_S, GL_T, GL_R, GL_Q}) glTexGeni(c, GL_TEXTURE_GEN_MODE, GL_EYE_LINEAR);
  glTexGenfv(GL_S, GL_EYE_PLANE, s_plane);
  glTexGenfv(GL_T, GL_EYE_PLANE, t_plane);
  glTexGenfv(GL_R, GL_EYE_PLANE, r_plane);
  glTexGenfv(GL_Q, GL_EYE_PLANE, q_plane);
  glPopMatrix();
  glEnable(GL_TEXTURE_GEN_S);
  glEnable(GL_TEXTURE_GEN_T);
  glEnable(GL_TEXTURE_GEN_R);
  glEnable(GL_TEXTURE_GEN_Q);

  // The texture matrix projects eye space from a "light": bias * scale * frustum * view.
  glMatrixMode(GL_TEXTURE);
  glLoadIdentity();
  glTranslatef(0.5f, 0.5f, 0.0f);
  glScalef(0.5f, 0.5f, 1.0f);
  glFrustum(-0.7, 0.7, -0.7, 0.7, 1.0, 10.0);
  glTranslatef(0.3f, -0.2f, -0.5f);
  glMatrixMode(GL_MODELVIEW);
  glEnable(GL_TEXTURE_2D);

  glBegin(GL_QUADS);  // the floor
  glVertex3f(-2.0f, 0.0f, 1.0f);
  glVertex3f(2.0f, 0.0f, 1.0f);
  glVertex3f(2.0f, 0.0f, -3.0f);
  glVertex3f(-2.0f, 0.0f, -3.0f);
  glEnd();

  // A tilted quad with object-linear s and t instead.
  glTexGeni(GL_S, GL_TEXTURE_GEN_MODE, GL_OBJECT_LINEAR);
  glTexGeni(GL_T, GL_TEXTURE_GEN_MODE, GL_OBJECT_LINEAR);
  const GLfloat s_object[] = {0.4f, 0.0f, 0.1f, 0.5f}, t_object[] = {0.0f, 0.45f, 0.0f, 0.3f};
  glTexGenfv(GL_S, GL_OBJECT_PLANE, s_object);
  glTexGenfv(GL_T, GL_OBJECT_PLANE, t_object);
  glDisable(GL_TEXTURE_GEN_R);
  glDisable(GL_TEXTURE_GEN_Q);
  glMatrixMode(GL_TEXTURE);
  glLoadIdentity();
  glMatrixMode(GL_MODELVIEW);
  glPushMatrix();
  glTranslatef(0.4f, 0.5f, -0.5f);
  glRotatef(-30.0f, 0.0f, 1.0f, 0.0f);
  glBegin(GL_QUADS);
  glVertex3f(-0.5f, -0.4f, 0.0f);
  glVertex3f(0.5f, -0.4f, 0.0f);
  glVertex3f(0.5f, 0.6f, 0.0f);
  glVertex3f(-0.5f, 0.6f, 0.0f);
  glEnd();
  glPopMatrix();

  save_reference(w, "texgen_projective.png");
  glXSwapBuffers(w.display, w.window);
  close_window(w);
  return 0;
}
