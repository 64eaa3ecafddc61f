// Progress of long work on stderr (docs/studies.md, "Progress"): on a terminal one line,
// rewritten in place, with the steps done, the time taken and an estimate of the time left;
// into a file or a pipe a plain line now and then (never a bare carriage return); nothing at
// all when quiet. Short work (under a second) says nothing.
#pragma once
#include <chrono>
#include <string>

namespace passim {

class Progress {
 public:
  // `what` starts each line ("passim study"); `total` steps make the whole; `unit` names a step
  // ("%": the steps are percent, and the line says "37 % done").
  Progress(std::string what, int total, bool quiet, std::string unit = "steps");
  ~Progress();
  // `done` of the total steps are finished; `detail` says which one is next or was last.
  void step(int done, const std::string& detail = "");
  // Ends the line on a terminal (the next output starts on a fresh line).
  void finish();
  // The estimate alone: seconds left after `done` of `total` steps in `elapsed` seconds
  // (the mean step so far times the steps left).
  static double seconds_left(double elapsed, int done, int total);
  // "7 s", "2 min 05 s", "1 h 02 min".
  static std::string duration(double seconds);

 private:
  std::string what_, unit_;
  int total_;
  bool quiet_, tty_, shown_ = false;
  std::chrono::steady_clock::time_point start_, last_;
};

}  // namespace passim
