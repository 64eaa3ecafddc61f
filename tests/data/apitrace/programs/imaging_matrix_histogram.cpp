// The imaging subset, part 2: the colour matrix (glMatrixMode(GL_COLOR)), histogram and
// minmax on glDrawPixels, read back with glGetHistogram and glGetMinmax. Mesa's llvmpipe
// does not implement ARB_imaging: the test computes the expected image, histogram and
// minmax from the spec (tests/apitrace_test.cpp; tests/data/apitrace/README.md).
#include "harness.hpp"

static GLubyte input(int x, int y, int c) {  // 16x12 RGBA (the test repeats this formula)
  switch (c) {
    case 0: return static_cast<GLubyte>(16 * x + y);
    case 1: return static_cast<GLubyte>(21 * y);
    case 2: return static_cast<GLubyte>((29 * x + 13 * y) % 256);
    default: return static_cast<GLubyte>(255 - 10 * x);
  }
}

int main() {
  GlWindow w = open_window(40, 16, {GLX_RGBA, GLX_DOUBLEBUFFER, GLX_RED_SIZE, 8, GLX_GREEN_SIZE, 8,
                                     GLX_BLUE_SIZE, 8, GLX_ALPHA_SIZE, 8});
  window_coordinates(w);
  glClearColor(0.0f, 0.0f, 0.0f, 0.0f);
  glClear(GL_COLOR_BUFFER_BIT);

  static GLubyte image[12][16][4];
  for (int y = 0; y < 12; ++y)
    for (int x = 0; x < 16; ++x)
      for (int c = 0; c < 4; ++c) image[y][x][c] = input(x, y, c);

  // Colour matrix (column-major): R' = (G + 2B)/3, G' = R, B' = 0.3 R + 0.6 A, A' = A. Thirds
  // and tenths keep every expected value away from a half code (the test checks this).
  const GLfloat m[16] = {0.0f, 1.0f, 0.3f, 0.0f,  1.0f / 3, 0.0f, 0.0f, 0.0f,
                         2.0f / 3, 0.0f, 0.0f, 0.0f,  0.0f, 0.0f, 0.6f, 1.0f};
  glMatrixMode(GL_COLOR);
  glLoadMatrixf(m);
  glMatrixMode(GL_MODELVIEW);

  glHistogram(GL_HISTOGRAM, 32, GL_RGBA, GL_FALSE);
  glMinmax(GL_MINMAX, GL_RGBA, GL_FALSE);
  glEnable(GL_HISTOGRAM);
  glEnable(GL_MINMAX);
  glRasterPos2i(2, 2);
  glDrawPixels(16, 12, GL_RGBA, GL_UNSIGNED_BYTE, image);
  glDisable(GL_HISTOGRAM);
  glDisable(GL_MINMAX);

  static GLuint histogram[32][4];
  static GLfloat minmax[2][4];
  glGetHistogram(GL_HISTOGRAM, GL_FALSE, GL_RGBA, GL_UNSIGNED_INT, histogram);
  glGetMinmax(GL_MINMAX, GL_FALSE, GL_RGBA, GL_FLOAT, minmax);

  // The identity matrix again: the plain image beside it.
  glMatrixMode(GL_COLOR);
  glLoadIdentity();
  glMatrixMode(GL_MODELVIEW);
  glRasterPos2i(22, 2);
  glDrawPixels(16, 12, GL_RGBA, GL_UNSIGNED_BYTE, image);

  save_reference(w, "imaging_matrix_histogram.png");
  glXSwapBuffers(w.display, w.window);
  close_window(w);
  return 0;
}
