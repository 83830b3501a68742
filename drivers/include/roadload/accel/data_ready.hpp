#pragma once
// The accelerometer's data-ready pin as the kernel reports it: rising edges, each stamped by the
// kernel at the interrupt. libgpiod 1.6 (the GPIO v1 uAPI) stamps line events in CLOCK_MONOTONIC
// on Linux >= 5.7, the capture clock, so the stamps are used as they are.
//
// The kernel queues at most kKernelQueue events per line and drops new ones while the queue is
// full, so a reader that drains that many at once must assume later edges went missing.
#include <cstdint>
#include <memory>
#include <string>

#include "roadload/parse_error.hpp"
#include "roadload/time.hpp"

struct gpiod_chip;
struct gpiod_line;

namespace roadload::accel {

class DataReadyLine {
 public:
  static constexpr int kKernelQueue = 16;  // events per line in the v1 uAPI's kfifo

  virtual ~DataReadyLine() = default;
  // Waits at most `timeout` (zero: only looks) for the oldest queued rising edge and consumes it.
  // 1: an edge, its kernel stamp in `edge_mono_ns` (CLOCK_MONOTONIC ns); 0: timeout; -1: error.
  virtual int wait(Nanoseconds timeout, std::int64_t& edge_mono_ns) = 0;
  // The clock the edges are stamped in, read now (CLOCK_MONOTONIC ns).
  virtual std::int64_t now_ns() const = 0;
};

class GpiodLine final : public DataReadyLine {
 public:
  // `chip` as gpiod_chip_open_lookup takes it: "gpiochip0", "/dev/gpiochip0", a label or a number.
  static Parsed<std::unique_ptr<GpiodLine>> open(const std::string& chip, unsigned line_offset, const std::string& consumer);
  ~GpiodLine() override;
  GpiodLine(const GpiodLine&) = delete;
  GpiodLine& operator=(const GpiodLine&) = delete;

  int wait(Nanoseconds timeout, std::int64_t& edge_mono_ns) override;
  std::int64_t now_ns() const override;

 private:
  GpiodLine(gpiod_chip* chip, gpiod_line* line) : chip_(chip), line_(line) {}
  gpiod_chip* chip_;
  gpiod_line* line_;
};

}  // namespace roadload::accel
