// Blending equations (GL_FUNC_ADD, GL_FUNC_SUBTRACT, GL_FUNC_REVERSE_SUBTRACT, GL_MIN,
// GL_MAX), a constant blend colour, colour masks and a smooth-shaded background, drawn
// with client-side vertex arrays (apitrace records them as fake pointer calls carrying the
// data). Colours are whole 8-bit codes and each blend has one product at most, so the
// spec's arithmetic has one answer and Mesa's 8-bit blender must give it too
// (tests/data/apitrace/README.md).
#include "harness.hpp"

int main() {
  GlWindow w = open_window(64, 64, {GLX_RGBA, GLX_DOUBLEBUFFER, GLX_RED_SIZE, 8, GLX_GREEN_SIZE, 8,
                                     GLX_BLUE_SIZE, 8, GLX_ALPHA_SIZE, 8});
  window_coordinates(w);
  glClearColor(0.25f, 0.5f, 0.75f, 0.5f);
  glClear(GL_COLOR_BUFFER_BIT);

  // A smooth-shaded background band, drawn from client arrays.
  const GLfloat band[] = {0, 0, 64, 0, 64, 64, 0, 64};
  const GLubyte band_colors[] = {255, 0, 0, 255, 0, 255, 0, 128, 0, 0, 255, 64, 255, 255, 255, 0};
  glEnableClientState(GL_VERTEX_ARRAY);
  glEnableClientState(GL_COLOR_ARRAY);
  glVertexPointer(2, GL_FLOAT, 0, band);
  glColorPointer(4, GL_UNSIGNED_BYTE, 0, band_colors);
  glDrawArrays(GL_QUADS, 0, 4);
  glDisableClientState(GL_COLOR_ARRAY);

  glEnable(GL_BLEND);
  glBlendColor(51 / 255.0f, 102 / 255.0f, 153 / 255.0f, 204 / 255.0f);
  struct Blend {
    GLenum equation, source, destination;
  };
  const Blend blends[] = {{GL_FUNC_ADD, GL_ONE, GL_ONE},
                          {GL_FUNC_SUBTRACT, GL_ONE, GL_ONE},
                          {GL_FUNC_REVERSE_SUBTRACT, GL_ONE, GL_ONE},
                          {GL_MIN, GL_ONE, GL_ONE},
                          {GL_MAX, GL_ONE, GL_ONE},
                          {GL_FUNC_ADD, GL_CONSTANT_COLOR, GL_ZERO},
                          {GL_FUNC_ADD, GL_ZERO, GL_ONE_MINUS_CONSTANT_ALPHA},
                          {GL_FUNC_REVERSE_SUBTRACT, GL_ZERO, GL_CONSTANT_ALPHA}};
  const GLfloat quad[] = {0, 0, 7, 0, 7, 40, 0, 40};
  for (int i = 0; i < 8; ++i) {
    glBlendEquation(blends[i].equation);
    glBlendFunc(blends[i].source, blends[i].destination);
    glPushMatrix();
    glTranslatef(1.0f + 8.0f * i, 4.0f, 0.0f);
    glColor4ub(230, static_cast<GLubyte>(60 + 20 * i), 25, 178);
    glVertexPointer(2, GL_FLOAT, 0, quad);
    glDrawArrays(GL_QUADS, 0, 4);
    glPopMatrix();
  }
  glBlendEquation(GL_FUNC_ADD);
  glDisable(GL_BLEND);

  // Colour masks: each strip writes only some channels.
  const GLboolean masks[4][4] = {{GL_TRUE, GL_FALSE, GL_FALSE, GL_TRUE}, {GL_FALSE, GL_TRUE, GL_FALSE, GL_FALSE},
                                 {GL_FALSE, GL_FALSE, GL_TRUE, GL_TRUE}, {GL_TRUE, GL_TRUE, GL_FALSE, GL_FALSE}};
  for (int i = 0; i < 4; ++i) {
    glColorMask(masks[i][0], masks[i][1], masks[i][2], masks[i][3]);
    glColor4f(1.0f, 0.0f, 1.0f, 0.0f);
    glRectf(2.0f + 15.0f * i, 46.0f, 14.0f + 15.0f * i, 62.0f);
  }
  glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
  glDisableClientState(GL_VERTEX_ARRAY);

  save_reference(w, "blend_masks.png");
  glXSwapBuffers(w.display, w.window);
  close_window(w);
  return 0;
}
