#pragma once
// Runs fn(0) ... fn(count - 1) on `jobs` threads, each index once; returns when all are done.
// Simulations are independent and take seconds each: a shared counter is all the scheduling needed.
#include <algorithm>
#include <atomic>
#include <cstddef>
#include <thread>
#include <vector>

namespace roadload::gap {

template <typename Fn>
void parallel_for(std::size_t count, unsigned jobs, const Fn& fn) {
  std::atomic<std::size_t> next{0};
  auto worker = [&] {
    for (std::size_t i = next++; i < count; i = next++) fn(i);
  };
  std::vector<std::thread> threads;
  for (unsigned j = 1; j < std::max(1u, jobs); ++j) threads.emplace_back(worker);
  worker();
  for (auto& t : threads) t.join();
}

}  // namespace roadload::gap
