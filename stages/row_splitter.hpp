// Work over the rows of an image or window, split as the caller chooses (on several
// threads: Context::rows_on_lanes).
#pragma once
#include <functional>

namespace passim {

// A splitter must call body(first, end) once for each range of a partition of [0, rows).
// The functions that take one compute every row alone from inputs no row writes, so any
// partition gives the same bits.
using RowSplitter = std::function<void(int rows, const std::function<void(int first, int end)>& body)>;

}  // namespace passim
