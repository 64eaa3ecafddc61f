// The pixel path on a single-buffered window: glDrawPixels (RGBA and RGB, unsigned byte,
// with unpack alignment and row length), glPixelZoom (magnify, mirror) and glCopyPixels
// with zoom, ended by glFlush: no glXSwapBuffers, so the replay snapshots at the flush
// (tests/data/apitrace/README.md).
#include "harness.hpp"

int main() {
  GlWindow w = open_window(80, 64, {GLX_RGBA, GLX_RED_SIZE, 8, GLX_GREEN_SIZE, 8, GLX_BLUE_SIZE, 8});
  window_coordinates(w);
  glClearColor(26 / 255.0f, 51 / 255.0f, 77 / 255.0f, 1.0f);  // whole codes (A1: Mesa rounds 0.3 to 76)
  glClear(GL_COLOR_BUFFER_BIT);

  // A 12x10 RGBA image, rows padded to 16 pixels (GL_UNPACK_ROW_LENGTH).
  static GLubyte image[10][16][4];
  for (int y = 0; y < 10; ++y)
    for (int x = 0; x < 16; ++x) {
      image[y][x][0] = static_cast<GLubyte>(20 * x);
      image[y][x][1] = static_cast<GLubyte>(25 * y);
      image[y][x][2] = static_cast<GLubyte>((x * y * 7) & 255);
      image[y][x][3] = 255;
    }
  glPixelStorei(GL_UNPACK_ROW_LENGTH, 16);
  glRasterPos2i(2, 2);
  glDrawPixels(12, 10, GL_RGBA, GL_UNSIGNED_BYTE, image);
  glPixelZoom(2.0f, 3.0f);
  glRasterPos2i(20, 2);
  glDrawPixels(12, 10, GL_RGBA, GL_UNSIGNED_BYTE, image);
  glPixelStorei(GL_UNPACK_ROW_LENGTH, 0);

  // 7x5 RGB with 3-byte rows: unpack alignment 1; drawn mirrored in x.
  static GLubyte rgb[5][7][3];
  for (int y = 0; y < 5; ++y)
    for (int x = 0; x < 7; ++x) {
      rgb[y][x][0] = static_cast<GLubyte>(255 - 30 * x);
      rgb[y][x][1] = static_cast<GLubyte>(40 * y);
      rgb[y][x][2] = 200;
    }
  glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  glPixelZoom(-2.0f, 2.0f);
  glRasterPos2i(78, 40);
  glDrawPixels(7, 5, GL_RGB, GL_UNSIGNED_BYTE, rgb);

  // glCopyPixels: the first image, enlarged, then a plain copy. (Whole zoom factors: with
  // 1.5, Mesa picks source columns from pixel corners, not centres as §3.6.4 says, see
  // docs/arithmetic.md "Against Mesa".)
  glPixelZoom(2.0f, 2.0f);
  glRasterPos2i(2, 36);
  glCopyPixels(2, 2, 12, 10, GL_COLOR);
  glPixelZoom(1.0f, 1.0f);
  glRasterPos2i(50, 52);
  glCopyPixels(20, 2, 24, 10, GL_COLOR);
  glFlush();

  save_reference(w, "pixels_zoom.png");
  close_window(w);
  return 0;
}
