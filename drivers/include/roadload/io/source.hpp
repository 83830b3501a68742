#pragma once
// What the daemon sees of a device: a source of stamped samples that it polls from one thread.
// Live implementations (SocketCAN, spidev + gpiod, gpsd) and replay implementations (a recording)
// sit behind the same interface, so roadloadd runs unchanged on a truck and on a recording.
//
// A source never throws in the data path and never allocates after open(): bad input, overflows
// and device errors are counted in its status and the read goes on. Setup errors (no such device,
// no permission) are returned by the implementation's open() with what was tried.
#include <cstddef>
#include <cstdint>
#include <span>

#include "roadload/time.hpp"

namespace roadload::io {

enum class SourceState : std::uint8_t {
  up,       // delivering
  waiting,  // open but nothing yet (no fix, no traffic)
  down,     // the device went away or failed; the source retries on its own
  ended,    // a replay reached its end
};

const char* to_string(SourceState s);

// Counters only grow; the daemon prints differences. `detail` is a short source-specific text for
// the status line (bus state, fitted rate, fix mode), NUL-terminated, rewritten as things change.
struct SourceStatus {
  SourceState state = SourceState::waiting;
  std::uint64_t items = 0;             // samples or frames delivered
  std::uint64_t dropped = 0;           // lost before delivery and known to be lost (kernel queue, FIFO overflow)
  std::uint64_t errors = 0;            // device or bus errors (error frames, bad transfers, malformed input)
  std::uint64_t restarts = 0;          // times the source went down and came back
  std::uint64_t clock_steps = 0;       // wall-clock steps seen under kernel stamps (CAN)
  std::uint64_t userspace_stamps = 0;  // items whose kernel stamp was unusable, stamped at read
  StampSource stamps = StampSource::kernel;
  char detail[96] = {};
};

template <typename Sample>
class Source {
 public:
  virtual ~Source() = default;
  // Waits at most `timeout` for input and fills `out` from its front; returns how many. Zero on a
  // timeout, while down, or once ended (check status().state).
  virtual std::size_t read(std::span<Sample> out, Nanoseconds timeout) = 0;
  // Called from the reading thread only; the daemon copies it out for the status thread.
  virtual const SourceStatus& status() const = 0;
  virtual const char* name() const = 0;
};

}  // namespace roadload::io
