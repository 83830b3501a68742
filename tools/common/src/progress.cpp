#include "progress.hpp"

#include <unistd.h>

#include <cstdio>

namespace roadload::cli {

Progress::Progress(std::string what, bool quiet, double silent_s)
    : what_(std::move(what)),
      quiet_(quiet),
      tty_(isatty(STDERR_FILENO) == 1),
      silent_s_(silent_s),
      start_(std::chrono::steady_clock::now()) {}

double Progress::wall_s() const { return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count(); }

void Progress::update(double fraction) {
  if (quiet_) return;
  const double wall = wall_s();
  if (wall < silent_s_) return;
  spoke_ = true;
  const double left = fraction > 0 ? wall * (1.0 - fraction) / fraction : 0.0;
  if (tty_) {
    std::fprintf(stderr, "\r%s: %3.0f %%  %.0f s, about %.0f s left ", what_.c_str(), fraction * 100.0, wall, left);
  } else if (static_cast<int>(fraction * 10.0 + 1e-9) > last_tenth_) {
    last_tenth_ = static_cast<int>(fraction * 10.0 + 1e-9);
    std::fprintf(stderr, "%s: %3d %%  %.0f s, about %.0f s left\n", what_.c_str(), last_tenth_ * 10, wall, left);
  }
}

void Progress::finish() {
  if (!quiet_ && tty_ && spoke_) std::fputc('\n', stderr);
}

}  // namespace roadload::cli
