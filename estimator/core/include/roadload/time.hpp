#pragma once
// Time as a type: every sample of a drive is stamped in one monotonic capture clock.
// A bare double of seconds from an unknown clock cannot be passed where a CaptureTime is expected.
#include <chrono>
#include <cstdint>

namespace roadload {

// The capture clock has no now(): the estimator never reads clocks; drivers map their
// kernel stamps into it and the simulator advances it in virtual time.
struct CaptureClock {
  using rep = std::int64_t;
  using period = std::nano;
  using duration = std::chrono::duration<rep, period>;
  using time_point = std::chrono::time_point<CaptureClock, duration>;
  static constexpr bool is_steady = true;
};

using Nanoseconds = CaptureClock::duration;
using CaptureTime = CaptureClock::time_point;
// A configured duration as TOML gives it, in seconds, exactly as written: read once at the file's
// edge, carried as this type everywhere after.
using Seconds = std::chrono::duration<double>;

inline constexpr std::int64_t kNsPerS = 1'000'000'000;

constexpr CaptureTime capture_time_from_ns(std::int64_t ns) { return CaptureTime{Nanoseconds{ns}}; }
constexpr std::int64_t to_ns(CaptureTime t) { return t.time_since_epoch().count(); }
constexpr double to_seconds(Nanoseconds d) { return static_cast<double>(d.count()) * 1e-9; }

// Where a stamp came from, as chrony keeps it: a kernel stamp is trusted more than a userspace one.
enum class StampSource : std::uint8_t {
  hardware,   // taken by the device or NIC
  kernel,     // taken by the kernel at interrupt or socket receive
  userspace,  // read in the daemon after the fact
  recording,  // read back from a recording; its origin is in the recording's metadata
  simulated,  // virtual time of the simulator
};

}  // namespace roadload
