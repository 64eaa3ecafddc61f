// Side-by-side figures of program runs (like the paper's Figure 7): each run's final
// image reduced, with the inset region outlined, above the inset magnified.
#pragma once
#include <filesystem>
#include <string>
#include <vector>

#include "programs/programs.hpp"

namespace passim {

struct FigureColumn {
  std::string title;
  const CapturedImage* image = nullptr;  // a colour ("rgb") capture
};

struct InsetRegion {
  int x = 0, y = 0, width = 100, height = 75;  // window coordinates (row 0 at the bottom)
};

// One row pair per group of columns (e.g. 8 bits, then 12 bits): each full image at
// `scale`, with the inset region outlined in red, and under it the inset magnified to
// the same width. Written as an 8-bit PNG (temporary file + rename).
void write_figure(const std::filesystem::path& file, const std::vector<std::vector<FigureColumn>>& rows,
                  const InsetRegion& inset, int scale_down = 2);

}  // namespace passim
