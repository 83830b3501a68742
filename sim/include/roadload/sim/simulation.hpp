#pragma once
// One simulated drive: the plant stepped in virtual time, every sensor sampled on its own clock,
// samples handed to a sink in time order per stream, ground truth alongside.
#include <cstdint>
#include <functional>
#include <memory>
#include <vector>

#include "roadload/can_frame.hpp"
#include "roadload/j1939/database.hpp"
#include "roadload/recording/metadata.hpp"
#include "roadload/samples.hpp"
#include "roadload/sim/plant.hpp"
#include "roadload/sim/scenario.hpp"
#include "roadload/sim/truth.hpp"

namespace roadload::sim {

class SampleSink {
 public:
  virtual ~SampleSink() = default;
  virtual void frame(const CanFrame& f) = 0;
  virtual void accel(const AccelSample& s) = 0;
  virtual void gnss(const GnssFix& s) = 0;
  virtual void weather(const WeatherSample& s) = 0;
};

struct RunSummary {
  double simulated_s = 0;
  double distance_m = 0;
  std::uint64_t frames = 0, accel_samples = 0, gnss_fixes = 0, weather_samples = 0;
  EnergyLedger ledger;
};

class Simulation {
 public:
  Simulation(const Scenario& scenario, std::uint64_t seed, const j1939::Database& db);
  ~Simulation();
  Simulation(const Simulation&) = delete;
  Simulation& operator=(const Simulation&) = delete;

  // What meta.toml says: sensors, vehicle, clock. Never the effects.
  recording::Metadata metadata() const;
  // Each accelerometer's output step by sensor id, for a recording that stores counts.
  std::vector<double> accel_steps_mps2() const;
  // truth.toml: the scenario, seed and effects.
  std::string truth_toml() const;

  // `progress` gets the fraction done now and then.
  RunSummary run(SampleSink& sink, TruthRecorder* truth, const std::function<void(double)>& progress = {});

  const TruckPlant& plant() const;
  const Route& route() const;

 private:
  struct Parts;
  std::unique_ptr<Parts> p_;
};

}  // namespace roadload::sim
