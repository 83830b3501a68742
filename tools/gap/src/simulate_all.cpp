// Simulations on several threads, straight into features, with a count and the time left for
// the user while a library of tens of them runs.
#include <chrono>
#include <cmath>
#include <mutex>

#include "roadload/gap/engine.hpp"
#include "roadload/gap/parallel.hpp"

namespace roadload::gap {

std::vector<RecordedRun> simulate_all(const std::vector<SimTask>& tasks, const j1939::Database& db, unsigned jobs,
                                      const std::function<void(const std::string&)>& progress) {
  using Clock = std::chrono::steady_clock;
  constexpr std::chrono::seconds kEvery{5};
  std::vector<RecordedRun> out(tasks.size());
  std::mutex mutex;
  std::size_t done = 0;
  const Clock::time_point start = Clock::now();
  Clock::time_point said = start;
  parallel_for(tasks.size(), jobs, [&](std::size_t i) {
    out[i] = simulate_run(tasks[i].scenario, tasks[i].seed, db, *tasks[i].layout);
    if (!progress) return;
    std::lock_guard lock(mutex);
    ++done;
    const Clock::time_point now = Clock::now();
    if (now - said < kEvery || done == tasks.size()) return;
    said = now;
    const double elapsed_s = std::chrono::duration<double>(now - start).count();
    const double left_s = elapsed_s / static_cast<double>(done) * static_cast<double>(tasks.size() - done);
    progress("  simulated " + std::to_string(done) + " of " + std::to_string(tasks.size()) + ", about " +
             std::to_string(static_cast<long>(std::lround(left_s))) + " s left");
  });
  return out;
}

}  // namespace roadload::gap
