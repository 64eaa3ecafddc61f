// The accumulation buffer (GL_ACCUM, GL_LOAD, GL_MULT, GL_ADD, GL_RETURN) on a visual that
// asks for one: four jittered, smooth-shaded drawings averaged, as the papers' filters
// average shadow tests. Each drawing is saved too (accum_scene0..3.png): Debian 12's Mesa
// accumulates in linear sRGB space (docs/arithmetic.md "Against Mesa"), so the test's
// reference for the accumulation is computed from the spec on Mesa's own drawings
// (tests/data/apitrace/README.md).
#include <string>

#include "harness.hpp"

static void draw_scene(float dx, float dy) {
  glClear(GL_COLOR_BUFFER_BIT);
  glPushMatrix();
  glTranslatef(dx, dy, 0.0f);
  glBegin(GL_TRIANGLES);
  glColor4ub(250, 40, 10, 255);
  glVertex2f(6.0f, 6.0f);
  glColor4ub(20, 230, 60, 255);
  glVertex2f(58.0f, 12.0f);
  glColor4ub(30, 50, 240, 255);
  glVertex2f(28.0f, 58.0f);
  glEnd();
  glColor4ub(255, 255, 255, 255);
  glRecti(40, 40, 60, 44);
  glPopMatrix();
}

int main() {
  GlWindow w = open_window(64, 64, {GLX_RGBA, GLX_DOUBLEBUFFER, GLX_RED_SIZE, 8, GLX_GREEN_SIZE, 8, GLX_BLUE_SIZE, 8,
                                     GLX_ACCUM_RED_SIZE, 16, GLX_ACCUM_GREEN_SIZE, 16, GLX_ACCUM_BLUE_SIZE, 16});
  window_coordinates(w);
  glClearColor(16 / 255.0f, 32 / 255.0f, 48 / 255.0f, 1.0f);
  glClearAccum(0.0f, 0.0f, 0.0f, 0.0f);
  glClear(GL_ACCUM_BUFFER_BIT);

  const float jitter[4][2] = {{0.25f, 0.25f}, {-0.25f, 0.25f}, {0.25f, -0.25f}, {-0.25f, -0.25f}};
  for (int i = 0; i < 4; ++i) {
    draw_scene(jitter[i][0], jitter[i][1]);
    save_reference(w, ("accum_scene" + std::to_string(i) + ".png").c_str());
    glAccum(i == 0 ? GL_LOAD : GL_ACCUM, 0.25f);
  }
  glAccum(GL_MULT, 0.75f);
  glAccum(GL_ADD, 0.125f);
  glAccum(GL_RETURN, 1.0f);

  save_reference(w, "accum.png");
  glXSwapBuffers(w.display, w.window);
  close_window(w);
  return 0;
}
