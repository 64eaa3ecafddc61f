// The imaging subset, part 1: a colour table (GL_COLOR_TABLE) and a 2D convolution
// (GL_CONVOLUTION_2D, border mode GL_REDUCE) applied by glDrawPixels. Mesa's llvmpipe does
// not implement ARB_imaging, so the test computes this program's expected image from the
// spec (tests/apitrace_test.cpp); the image Mesa drew is kept only as the record of the run
// (tests/data/apitrace/README.md).
#include "harness.hpp"

// The input image: 16x12 RGBA (the test repeats this formula).
static GLubyte input(int x, int y, int c) {
  switch (c) {
    case 0: return static_cast<GLubyte>(15 * x + 3 * y);
    case 1: return static_cast<GLubyte>(20 * y + x);
    case 2: return static_cast<GLubyte>((37 * x * y + 11) % 256);
    default: return 255;
  }
}

int main() {
  GlWindow w = open_window(48, 32, {GLX_RGBA, GLX_DOUBLEBUFFER, GLX_RED_SIZE, 8, GLX_GREEN_SIZE, 8,
                                     GLX_BLUE_SIZE, 8});
  window_coordinates(w);
  glClearColor(0.0f, 0.0f, 0.0f, 1.0f);
  glClear(GL_COLOR_BUFFER_BIT);

  static GLubyte image[12][16][4];
  for (int y = 0; y < 12; ++y)
    for (int x = 0; x < 16; ++x)
      for (int c = 0; c < 4; ++c) image[y][x][c] = input(x, y, c);

  // Colour table: 256 RGBA entries, R inverted, G squared, B halved plus 64, A kept.
  static GLubyte table[256][4];
  for (int i = 0; i < 256; ++i) {
    table[i][0] = static_cast<GLubyte>(255 - i);
    table[i][1] = static_cast<GLubyte>(i * i / 255);
    table[i][2] = static_cast<GLubyte>(64 + i / 2);
    table[i][3] = static_cast<GLubyte>(i);
  }
  glColorTable(GL_COLOR_TABLE, GL_RGBA8, 256, GL_RGBA, GL_UNSIGNED_BYTE, table);
  glEnable(GL_COLOR_TABLE);
  glRasterPos2i(1, 1);
  glDrawPixels(16, 12, GL_RGBA, GL_UNSIGNED_BYTE, image);
  glDisable(GL_COLOR_TABLE);

  // 3x3 convolution with unequal weights per channel (rows bottom first). Tenths, not
  // sixteenths: the sums never land on a half code, where the rounding of the last bit
  // would decide (the test checks that no expected value is that close to a tie).
  static const GLfloat kernel[3][3][4] = {
      {{0.1f, 0.0f, 0.3f, 0.0f}, {0.1f, 0.0f, 0.0f, 0.0f}, {0.1f, 0.0f, 0.0f, 0.0f}},
      {{0.1f, 0.6f, 0.0f, 0.0f}, {0.2f, 0.3f, 0.3f, 1.0f}, {0.1f, 0.0f, 0.0f, 0.0f}},
      {{0.1f, 0.0f, 0.0f, 0.0f}, {0.1f, 0.0f, 0.0f, 0.0f}, {0.1f, 0.0f, 0.3f, 0.0f}}};
  glConvolutionFilter2D(GL_CONVOLUTION_2D, GL_RGBA, 3, 3, GL_RGBA, GL_FLOAT, kernel);
  glEnable(GL_CONVOLUTION_2D);
  glRasterPos2i(20, 1);
  glDrawPixels(16, 12, GL_RGBA, GL_UNSIGNED_BYTE, image);
  glDisable(GL_CONVOLUTION_2D);

  // Both: the colour table, then the filter (the order of §3.6.3).
  glEnable(GL_COLOR_TABLE);
  glEnable(GL_CONVOLUTION_2D);
  glRasterPos2i(1, 16);
  glDrawPixels(16, 12, GL_RGBA, GL_UNSIGNED_BYTE, image);
  glDisable(GL_CONVOLUTION_2D);
  glDisable(GL_COLOR_TABLE);

  save_reference(w, "imaging_table_convolution.png");
  glXSwapBuffers(w.display, w.window);
  close_window(w);
  return 0;
}
