// A plain-GLX window for the recorded test programs (tests/data/apitrace/README.md).
// Each program opens one window with the visual attributes it asks for, draws, reads
// its own result back with glReadPixels and saves it as the reference image
// (OpenImageIO, top row first), then exits. Run under apitrace by record.sh.
#pragma once
// OpenImageIO first: X11 defines macros (None, Status) its headers use as names.
#include <OpenImageIO/imageio.h>

#include <GL/gl.h>
#include <GL/glext.h>
#include <GL/glx.h>
#include <X11/Xlib.h>

#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

struct GlWindow {
  Display* display = nullptr;
  ::Window window = 0;
  GLXContext context = nullptr;
  int width = 0, height = 0;
};

// attributes: a glXChooseVisual list without the terminating None.
inline GlWindow open_window(int width, int height, std::vector<int> attributes) {
  GlWindow w;
  w.width = width;
  w.height = height;
  w.display = XOpenDisplay(nullptr);
  if (!w.display) { std::fprintf(stderr, "no X display\n"); std::exit(1); }
  attributes.push_back(None);
  XVisualInfo* visual = glXChooseVisual(w.display, DefaultScreen(w.display), attributes.data());
  if (!visual) { std::fprintf(stderr, "no visual with those attributes\n"); std::exit(1); }
  XSetWindowAttributes swa{};
  swa.colormap = XCreateColormap(w.display, RootWindow(w.display, visual->screen), visual->visual, AllocNone);
  swa.event_mask = StructureNotifyMask;
  w.window = XCreateWindow(w.display, RootWindow(w.display, visual->screen), 0, 0, width, height, 0,
                           visual->depth, InputOutput, visual->visual, CWColormap | CWEventMask, &swa);
  XMapWindow(w.display, w.window);
  for (XEvent e;;) {  // wait until mapped so the drawable has its size
    XNextEvent(w.display, &e);
    if (e.type == MapNotify) break;
  }
  w.context = glXCreateContext(w.display, visual, nullptr, True);
  glXMakeCurrent(w.display, w.window, w.context);
  XFree(visual);
  return w;
}

// Viewport and projections for drawing in window coordinates: object (x, y) = pixel (x, y).
inline void window_coordinates(const GlWindow& w) {
  glViewport(0, 0, w.width, w.height);
  glMatrixMode(GL_PROJECTION);
  glLoadIdentity();
  glOrtho(0, w.width, 0, w.height, -1, 1);
  glMatrixMode(GL_MODELVIEW);
  glLoadIdentity();
}

// Reads the current read buffer as RGBA8 and writes it (top row first) to `file`.
inline void save_reference(const GlWindow& w, const char* file) {
  std::vector<unsigned char> pixels(static_cast<size_t>(w.width) * w.height * 4);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadPixels(0, 0, w.width, w.height, GL_RGBA, GL_UNSIGNED_BYTE, pixels.data());
  auto out = OIIO::ImageOutput::create(file);
  OIIO::ImageSpec spec(w.width, w.height, 4, OIIO::TypeDesc::UINT8);
  spec.attribute("oiio:UnassociatedAlpha", 1);  // the bytes as read, not divided by alpha
  const auto row = static_cast<OIIO::stride_t>(w.width) * 4;
  if (!out || !out->open(file, spec) ||
      !out->write_image(OIIO::TypeDesc::UINT8, pixels.data() + (w.height - 1) * row, OIIO::AutoStride, -row)) {
    std::fprintf(stderr, "cannot write %s\n", file);
    std::exit(1);
  }
  out->close();
}

inline void close_window(GlWindow& w) {
  glXMakeCurrent(w.display, None, nullptr);
  glXDestroyContext(w.display, w.context);
  XDestroyWindow(w.display, w.window);
  XCloseDisplay(w.display);
}
