#pragma once
// A source that hands out samples held in memory, a batch at a time, and can hold back at a gate:
// the tests let the daemon settle, open an allocation counter, then let the rest through.
#include <algorithm>
#include <atomic>
#include <chrono>
#include <thread>
#include <vector>

#include "roadload/io/replay_clock.hpp"
#include "roadload/io/source.hpp"

namespace roadload::firmware::test {

// The drive's time runs `speedup` times faster than the wall clock from `start`, shared by every
// source of a test so that streams arrive together, as devices would deliver them.
struct Pace {
  std::chrono::steady_clock::time_point start;
  CaptureTime drive_start{};
  double speedup = 20;
  // When set, the drive's clock starts at what this points to instead: a test can build its
  // daemon first and start the drive after, however long the build takes.
  const std::chrono::steady_clock::time_point* start_at = nullptr;
  CaptureTime now() const {
    const auto wall = std::chrono::steady_clock::now() - (start_at != nullptr ? *start_at : start);
    return drive_start + Nanoseconds{static_cast<std::int64_t>(static_cast<double>(wall.count()) * speedup)};
  }
};

template <typename T>
class MemorySource final : public io::Source<T> {
 public:
  // Items after index `gate_at` wait until `gate` is open. With kernel stamps it stands for a
  // device, which the daemon does not wait for, rather than a replay.
  MemorySource(std::vector<T> items, const std::atomic<bool>& gate, std::size_t gate_at, const char* name, Pace pace,
               StampSource stamps = StampSource::recording)
      : items_(std::move(items)), gate_(gate), gate_at_(gate_at), name_(name), pace_(pace) {
    status_.state = io::SourceState::up;
    status_.stamps = stamps;
  }

  std::size_t read(std::span<T> out, Nanoseconds timeout) override {
    if (next_ == items_.size()) {
      status_.state = io::SourceState::ended;
      return 0;
    }
    std::size_t limit = std::min(items_.size(), next_ + out.size());
    if (!gate_.load()) limit = std::min(limit, gate_at_);
    std::size_t n = take(out, limit);
    // Nothing due: wait a little, as a device's read would. A backlog is handed out at once, so a
    // thread the scheduler kept waiting catches up instead of falling a sleep further behind.
    if (n == 0 && timeout > Nanoseconds{0}) {
      std::this_thread::sleep_for(std::min<Nanoseconds>(timeout, std::chrono::microseconds(500)));
      n = take(out, limit);
    }
    status_.items += n;
    return n;
  }
  const io::SourceStatus& status() const override { return status_; }
  const char* name() const override { return name_; }

 private:
  std::size_t take(std::span<T> out, std::size_t limit) {
    const CaptureTime due = pace_.now();
    std::size_t n = 0;
    while (next_ < limit && items_[next_].t <= due) out[n++] = items_[next_++];
    return n;
  }

  std::vector<T> items_;
  const std::atomic<bool>& gate_;
  std::size_t gate_at_;
  const char* name_;
  Pace pace_;
  std::size_t next_ = 0;
  io::SourceStatus status_;
};

// The drive's own time at the test's pace: the daemon's horizons and intervals pass as they would
// on a truck, only faster.
class PaceClock final : public io::WaitClock {
 public:
  explicit PaceClock(const Pace& pace) : pace_(pace) {}
  CaptureTime now() const override { return pace_.now(); }
  void sleep_until(CaptureTime t, Nanoseconds limit) override {
    const auto wait = std::min(t - now(), limit);
    if (wait.count() > 0)
      std::this_thread::sleep_for(
          std::chrono::nanoseconds(static_cast<std::int64_t>(static_cast<double>(wait.count()) / pace_.speedup)));
  }

 private:
  Pace pace_;
};

}  // namespace roadload::firmware::test
