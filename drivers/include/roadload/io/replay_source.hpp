#pragma once
// The replay implementation of every sensor source: one stream of a recording folder handed out on
// the daemon's capture clock through a ReplayTiming. Paced, a sample is handed out no earlier than
// its capture time, in batches of what came due within kPaceBatch, as a device's FIFO or a
// socket's queue is read, so the daemon sees the drive as a truck would deliver it; unpaced, as
// fast as it is read. The recording's malformed lines are counted as errors, as a live device's would be.
// Faults a bench replay asks for are applied here as the device would show them: a GNSS outage
// withholds fixes and leaves the source waiting for one; an accelerometer FIFO overflow loses a
// FIFO's worth of each sensor's samples and counts them as dropped.
#include <algorithm>
#include <array>
#include <cstdio>
#include <memory>
#include <string>
#include <type_traits>

#include "roadload/io/replay_clock.hpp"
#include "roadload/io/replay_faults.hpp"
#include "roadload/io/source.hpp"
#include "roadload/recording/reader.hpp"

namespace roadload::io {

template <typename Sample>
class ReplaySource final : public Source<Sample> {
 public:
  static constexpr unsigned kMask = std::is_same_v<Sample, AccelSample>     ? recording::kAccelStream
                                    : std::is_same_v<Sample, GnssFix>       ? recording::kGnssStream
                                    : std::is_same_v<Sample, WeatherSample> ? recording::kWeatherStream
                                                                            : recording::kCanStream;

  static Parsed<std::unique_ptr<ReplaySource>> open(const std::string& folder, const ReplayTiming& timing, WaitClock& clock,
                                                    const char* name, const ReplayFaults& faults = {}) {
    auto reader = recording::RecordingReader::open(folder, kMask);
    if (!reader) return reader.error();
    auto src = std::unique_ptr<ReplaySource>(new ReplaySource(std::move(reader.value()), timing, clock, name));
    // Fault times count from the replay's origin (its first CAN frame) on the recording's timeline.
    if constexpr (std::is_same_v<Sample, GnssFix>) {
      for (const FaultWindow& w : faults.gnss_outages)
        src->withheld_.push_back({timing.recorded_origin + w.at, timing.recorded_origin + w.at + w.length});
    }
    if constexpr (std::is_same_v<Sample, AccelSample>) {
      for (const Nanoseconds at : faults.accel_overflows) src->overflows_.push_back(timing.recorded_origin + at);
      std::sort(src->overflows_.begin(), src->overflows_.end());
    }
    return src;
  }

  // A wake-up per sample (32,000 a second for eight accelerometers at 4 kHz) cost a replay under
  // UML three quarters of a core; a wake-up per 4 ms is a FIFO's read cadence. Stamps are unchanged.
  static constexpr Nanoseconds kPaceBatch{4'000'000};

  std::size_t read(std::span<Sample> out, Nanoseconds timeout) override {
    std::size_t n = 0;
    // The clock is read again only for a sample not yet due at the last reading: on a kernel where
    // reading it is a system call (UML's vDSO makes one), a reading per sample would cap the replay.
    CaptureTime now = clock_.now();
    const CaptureTime give_up = now + timeout;
    while (n < out.size()) {
      if (!has_pending_ && !pull()) break;
      if (timing_.paced() && pending_.t > now) {
        now = clock_.now();
        if (pending_.t > now) {
          if (n > 0 || now >= give_up) break;
          clock_.sleep_until(pending_.t + kPaceBatch, give_up - now);
          now = clock_.now();
          continue;
        }
      }
      out[n++] = pending_;
      has_pending_ = false;
      if (status_.state == SourceState::waiting) set_state(SourceState::up, "");
    }
    status_.items += n;
    status_.errors = reader_.errors().count();
    return n;
  }

  const SourceStatus& status() const override { return status_; }
  const char* name() const override { return name_; }

 private:
  ReplaySource(recording::RecordingReader reader, const ReplayTiming& timing, WaitClock& clock, const char* name)
      : reader_(std::move(reader)), timing_(timing), clock_(clock), name_(name) {
    status_.state = SourceState::up;
    status_.stamps = StampSource::recording;
    set_state(SourceState::up, "");
  }

  void set_state(SourceState state, const char* why) {
    status_.state = state;
    std::snprintf(status_.detail, sizeof status_.detail, "replay x%.3g%s", timing_.rate, why);
  }

  // A GNSS fix inside an outage is withheld; an accelerometer sample lost to a FIFO overflow is
  // counted as dropped.
  bool faulted(const Sample& s) {
    for (const auto& [from, to] : withheld_) {
      if (s.t >= from && s.t < to) {
        set_state(SourceState::waiting, ", no fix (outage replayed)");
        return true;
      }
    }
    if constexpr (std::is_same_v<Sample, AccelSample>) {
      while (next_overflow_ < overflows_.size() && s.t >= overflows_[next_overflow_]) {
        ++next_overflow_;
        fifo_loss_.fill(kAccelFifoSamples);
      }
      if (s.sensor < fifo_loss_.size() && fifo_loss_[s.sensor] > 0) {
        --fifo_loss_[s.sensor];
        ++status_.dropped;
        return true;
      }
    }
    return false;
  }

  bool pull() {
    while (const recording::Record* r = reader_.next()) {
      if (const auto* s = std::get_if<Sample>(r)) {
        if (faulted(*s)) continue;
        pending_ = *s;
        pending_.t = timing_.capture(s->t);
        has_pending_ = true;
        return true;
      }
    }
    status_.state = SourceState::ended;
    return false;
  }

  recording::RecordingReader reader_;
  ReplayTiming timing_;
  WaitClock& clock_;
  const char* name_;
  Sample pending_{};
  bool has_pending_ = false;
  SourceStatus status_;
  std::vector<std::pair<CaptureTime, CaptureTime>> withheld_;
  std::vector<CaptureTime> overflows_;
  std::size_t next_overflow_ = 0;
  std::array<std::size_t, 16> fifo_loss_{};  // samples still to lose, per sensor index
};

}  // namespace roadload::io
