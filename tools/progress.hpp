#pragma once
// Progress of a long run on standard error: a terminal gets one line redrawn each percent with the
// time gone and the time left; a log file a line each tenth.
#include <chrono>
#include <string>

namespace roadload::cli {

class Progress {
 public:
  Progress(std::string what, bool quiet);
  // `fraction` of the run done, 0..1.
  void update(double fraction);
  // Ends a terminal's line.
  void finish();
  double wall_s() const;

 private:
  std::string what_;
  bool quiet_, tty_;
  int last_tenth_ = 0;
  std::chrono::steady_clock::time_point start_;
};

}  // namespace roadload::cli
