#include "roadload/accel/adxl355_source.hpp"

#include <cstdio>

// A part that went down (SPI failed) or silent (no data-ready edge: power cycle, reset) is checked
// and, if it lost its settings, started again.
namespace roadload::accel {
namespace {

// How often a part with no edges coming is checked. With edges coming, its FIFO is filling and
// holds only 32 sets (8 ms at 4 kHz): it is checked at every read.
constexpr std::int64_t kIdleCheckNs = 100'000'000;

}  // namespace

// Silence is measured from the last edge, not by a read's wait: roadloadd's reader polls every
// part without waiting, and must still notice one that stopped.
bool Adxl355Source::healthy(int edges) {
  const std::int64_t now_ns = line_.now_ns();
  if (edges > 0) last_edge_ns_ = now_ns;
  const bool silent = edges == 0 && static_cast<double>(now_ns - last_edge_ns_) > 4 * period_ns_;
  if (status_.state != io::SourceState::down && !silent) return true;
  if (edges == 0 && now_ns - checked_ns_ < kIdleCheckNs) return false;
  checked_ns_ = now_ns;
  return recover();
}

bool Adxl355Source::recover() {
  const bool was_down = status_.state == io::SourceState::down;
  const Adxl355::Fault f = part_.check();
  if (f == Adxl355::Fault::spi) {
    go_down("SPI transfer failed");
    return false;
  }
  if (f != Adxl355::Fault::none) {
    // The part answers but lost its settings: start it again, on a new grid.
    if (part_.prepare() != Adxl355::Fault::none || start_measuring() != Adxl355::Fault::none) {
      go_down("the part does not start");
      return false;
    }
  }
  if (was_down || f != Adxl355::Fault::none) ++status_.restarts;
  if (was_down) status_.state = io::SourceState::up;
  return true;
}

void Adxl355Source::go_down(const char* why) {
  ++status_.errors;
  status_.state = io::SourceState::down;
  std::snprintf(status_.detail, sizeof status_.detail, "adxl355 down: %s", why);
}

}  // namespace roadload::accel
