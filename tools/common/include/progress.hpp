#pragma once
// Progress of a long run on standard error: a terminal gets one line redrawn each percent with the
// time gone and the time left; a log file a line each tenth.
#include <chrono>
#include <string>

namespace roadload::cli {

class Progress {
 public:
  // `silent_s`: nothing is printed before this much wall time, so a short run stays quiet and
  // only a long one (a gateway's hour of driving) tells how far it is.
  Progress(std::string what, bool quiet, double silent_s = 0);
  // `fraction` of the run done, 0..1.
  void update(double fraction);
  // Ends a terminal's line.
  void finish();
  double wall_s() const;

 private:
  std::string what_;
  bool quiet_, tty_;
  double silent_s_;
  bool spoke_ = false;
  int last_tenth_ = 0;
  std::chrono::steady_clock::time_point start_;
};

}  // namespace roadload::cli
