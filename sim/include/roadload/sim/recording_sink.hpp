#pragma once
// Hands a simulation's samples to a RecordingWriter: the simulated truck's log in the project's
// recording format, on the simulated truck's single bus.
#include "roadload/recording/writer.hpp"
#include "roadload/sim/simulation.hpp"

namespace roadload::sim {

class RecordingSink final : public SampleSink {
 public:
  explicit RecordingSink(recording::RecordingWriter& w) : w_(w) {}
  void frame(const CanFrame& f) override { w_.write(f, "can0"); }
  void accel(const AccelSample& s) override { w_.write(s); }
  void gnss(const GnssFix& s) override { w_.write(s); }
  void weather(const WeatherSample& s) override { w_.write(s); }

 private:
  recording::RecordingWriter& w_;
};

}  // namespace roadload::sim
