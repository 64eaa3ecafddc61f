// The figures of studies, reports and the demo, drawn by matplotlib through passim's Python
// package (python/passim/figures.py): `python3 -m passim.figures ...`, with the package found
// beside this executable (build/python) or where `cmake --install` put it.
#pragma once
#include <string>
#include <vector>

namespace passim {

struct FigureRun {
  bool ok = false;
  std::string message;  // why not, when not: python3 or matplotlib missing, or the script's error
  std::vector<std::string> files;  // the files written
};

// Runs `python3 -m passim.figures` with `args`. The interpreter: $PASSIM_PYTHON3, else the one
// the build found (Debian's /usr/bin/python3), else python3 on the PATH.
FigureRun draw_figures(const std::vector<std::string>& args);

}  // namespace passim
