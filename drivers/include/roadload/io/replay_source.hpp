#pragma once
// The replay implementation of every sensor source: one stream of a recording folder handed out on
// the daemon's capture clock through a ReplayTiming. Paced, a sample is handed out no earlier than
// its capture time, so the daemon sees the drive as a truck would deliver it; unpaced, as fast as
// it is read. The recording's malformed lines are counted as errors, as a live device's would be.
#include <cstdio>
#include <memory>
#include <string>
#include <type_traits>

#include "roadload/io/replay_clock.hpp"
#include "roadload/io/source.hpp"
#include "roadload/recording/reader.hpp"

namespace roadload::io {

template <typename Sample>
class ReplaySource final : public Source<Sample> {
 public:
  static constexpr unsigned kMask = std::is_same_v<Sample, AccelSample> ? recording::kAccelStream
                                    : std::is_same_v<Sample, GnssFix>       ? recording::kGnssStream
                                    : std::is_same_v<Sample, WeatherSample> ? recording::kWeatherStream
                                                                          : recording::kCanStream;

  static Parsed<std::unique_ptr<ReplaySource>> open(const std::string& folder, const ReplayTiming& timing,
                                                    WaitClock& clock, const char* name) {
    auto reader = recording::RecordingReader::open(folder, kMask);
    if (!reader) return reader.error();
    return std::unique_ptr<ReplaySource>(new ReplaySource(std::move(reader.value()), timing, clock, name));
  }

  std::size_t read(std::span<Sample> out, Nanoseconds timeout) override {
    std::size_t n = 0;
    const CaptureTime give_up = clock_.now() + timeout;
    while (n < out.size()) {
      if (!has_pending_ && !pull()) break;
      if (timing_.paced()) {
        const CaptureTime now = clock_.now();
        if (pending_.t > now) {
          if (n > 0 || now >= give_up) break;
          clock_.sleep_until(pending_.t, give_up - now);
          continue;
        }
      }
      out[n++] = pending_;
      has_pending_ = false;
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
    std::snprintf(status_.detail, sizeof status_.detail, "replay x%.3g", timing.rate);
  }

  bool pull() {
    while (const recording::Record* r = reader_.next()) {
      if (const auto* s = std::get_if<Sample>(r)) {
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
};

}  // namespace roadload::io
