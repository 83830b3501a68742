// Cost of one CRR filter step (predict + speed update) at the default state size, against the
// predict alone as the reference. Prints figures; goal: a step under 1 microsecond.
#include <chrono>
#include <cmath>
#include <cstdio>

#include "roadload/crr_filter.hpp"
#include "roadload/drive_analyzer.hpp"
#include "vehicles.hpp"

namespace {

using Clock = std::chrono::steady_clock;

template <typename F>
double ns_per_call(long n, F&& f) {
  const auto t0 = Clock::now();
  for (long i = 0; i < n; ++i) f(i);
  return std::chrono::duration<double, std::nano>(Clock::now() - t0).count() / static_cast<double>(n);
}

}  // namespace

int main() {
  constexpr long kSteps = 2'000'000;
  roadload::CrrFilterConfig cfg = roadload::analyzer_config(roadload::shipped::mnroad_vehicle()).filter;
  cfg.max_step = roadload::Nanoseconds{1'000'000'000};
  roadload::model::ForceInputs in;
  in.tractive_n = 4000;
  in.air_density_kgpm3 = 1.18;
  in.headwind_mps = 2;
  in.effective_mass_kg = 37200;
  in.usable = true;
  double sink = 0;

  roadload::CrrFilter f(cfg);
  f.start(roadload::capture_time_from_ns(0), 20.0);
  const double predict = ns_per_call(kSteps, [&](long i) {
    in.t = roadload::capture_time_from_ns((i + 1) * 100'000'000);
    in.grade_rad = 0.001 * static_cast<double>(i % 7);
    f.predict_to(in);
    sink += f.speed_mps();
  });

  roadload::CrrFilter g(cfg);
  g.start(roadload::capture_time_from_ns(0), 20.0);
  const double step = ns_per_call(kSteps, [&](long i) {
    in.t = roadload::capture_time_from_ns((i + 1) * 100'000'000);
    in.grade_rad = 0.001 * static_cast<double>(i % 7);
    g.predict_to(in);
    g.update_speed(in.t, g.speed_mps() + 0.01 * std::sin(static_cast<double>(i)), 0.03);
    sink += g.crr();
  });
  std::printf(
      "crr filter (%d states): predict %.1f ns, predict + speed update %.1f ns per step (%.2fx the predict); "
      "goal < 1000 ns: %s   [checksum %.3g]\n",
      roadload::CrrState::count, predict, step, step / predict, step < 1000 ? "met" : "NOT met", sink);
  return 0;
}
