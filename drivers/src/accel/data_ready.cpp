#include "roadload/accel/data_ready.hpp"

#include <gpiod.h>

#include <algorithm>
#include <cerrno>
#include <cstring>

#include "roadload/io/posix_time.hpp"

namespace roadload::accel {

Parsed<std::unique_ptr<GpiodLine>> GpiodLine::open(const std::string& chip, unsigned line_offset, const std::string& consumer) {
  gpiod_chip* c = gpiod_chip_open_lookup(chip.c_str());
  if (c == nullptr) return ParseError{chip, 0, "gpiod_chip_open_lookup", std::strerror(errno)};
  gpiod_line* l = gpiod_chip_get_line(c, line_offset);
  if (l == nullptr) {
    ParseError e{chip, 0, "line " + std::to_string(line_offset), std::strerror(errno)};
    gpiod_chip_close(c);
    return e;
  }
  if (gpiod_line_request_rising_edge_events(l, consumer.c_str()) != 0) {
    ParseError e{chip, 0, "line " + std::to_string(line_offset), std::string("rising-edge events: ") + std::strerror(errno)};
    gpiod_chip_close(c);
    return e;
  }
  return std::unique_ptr<GpiodLine>(new GpiodLine(c, l));
}

GpiodLine::~GpiodLine() {
  gpiod_line_release(line_);
  gpiod_chip_close(chip_);
}

int GpiodLine::wait(Nanoseconds timeout, std::int64_t& edge_mono_ns) {
  const timespec ts = io::to_timespec(std::max(timeout, Nanoseconds{0}));
  const int ready = gpiod_line_event_wait(line_, &ts);
  if (ready < 0 && errno == EINTR) return 0;  // a signal for the daemon: the caller loops
  if (ready <= 0) return ready;
  gpiod_line_event event{};
  if (gpiod_line_event_read(line_, &event) != 0) return -1;
  edge_mono_ns = io::from_timespec(event.ts).count();
  return 1;
}

std::int64_t GpiodLine::now_ns() const { return io::read_clock(CLOCK_MONOTONIC).count(); }

}  // namespace roadload::accel
