#pragma once
// Counts heap allocations made while a scope is open. The test binary replaces the global
// operator new (allocation_counter.cpp), so "no heap in the hot path" is a test that can fail.
#include <cstddef>

namespace roadload::test {

class CountAllocations {
 public:
  CountAllocations();
  ~CountAllocations();
  CountAllocations(const CountAllocations&) = delete;
  CountAllocations& operator=(const CountAllocations&) = delete;
  std::size_t count() const;
};

}  // namespace roadload::test
