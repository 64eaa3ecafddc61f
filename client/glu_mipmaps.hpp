// The mipmap chain of the gluBuild1DMipmaps / gluBuild2DMipmaps helper (docs/arithmetic.md
// A28): each level is the previous one halved in the application's own pixel type, as the
// SGI OpenGL Sample Implementation's GLU 1.3 (mipmap.c, halveImage_<type>) halves it.
#pragma once
#include <cstddef>
#include <vector>

#include "pipeline/gl.hpp"

namespace passim {

// Halves a width x height image of `components` elements per pixel (element values as
// stored, not normalised; rows bottom first) to max(1, width/2) x max(1, height/2).
// Both sides > 1: each element from its 2x2 box; one side 1: from its pair.
//   UNSIGNED_BYTE/SHORT, BYTE/SHORT: box (a+b+c+d+2)/4, pair (a+b)/2, integer division
//     (truncation toward zero for the signed types);
//   UNSIGNED_INT: box (a+b+c+d)/4 + 0.5 in double, pair (a+b)/2 in double, truncated;
//   INT: box ((float)a+(float)b+(float)c+(float)d)/4 + 0.5, pair ((float)a+(float)b)/2
//     with a and b read as unsigned (as the sample implementation does), truncated;
//   FLOAT: box (a+b+c+d)/4, pair (a+b)/2, in float.
std::vector<double> glu_halve_image(const std::vector<double>& image, int width, int height, int components,
                                    GLenum type);

// The elements as client data of `type`, tightly packed (alignment 1, native byte order).
std::vector<std::byte> pack_elements(const std::vector<double>& elements, GLenum type);

}  // namespace passim
