#include "roadload/recording/read_ahead.hpp"

namespace roadload::recording {

ReadAhead::ReadAhead(RecordingReader& reader) : reader_(reader), thread_([this] { read(); }) {}

ReadAhead::~ReadAhead() {
  released_.store(kStop, std::memory_order_release);
  released_.notify_one();
  thread_.join();
}

// Returns whether the reader has more.
bool ReadAhead::fill(Batch& b, std::size_t& interfaces_seen) {
  b.size = 0;
  b.last = false;
  try {
    while (b.size < kBatch && reader_.next_into(b.records[b.size])) ++b.size;
  } catch (...) {
    failure_ = std::current_exception();
  }
  b.last = b.size < kBatch;
  // Names are only ever added: a copy when the count grew keeps the consumer's table whole.
  const InterfaceTable& table = reader_.interfaces();
  b.new_interfaces = table.size() != interfaces_seen;
  if (b.new_interfaces) {
    b.interfaces = table;
    interfaces_seen = table.size();
  }
  return !b.last;
}

void ReadAhead::read() {
  std::size_t interfaces_seen = 0;
  for (std::size_t n = 0;; ++n) {
    for (std::size_t r = released_.load(std::memory_order_acquire); r < kStop && n - r >= kBatches;
         r = released_.load(std::memory_order_acquire)) {
      released_.wait(r, std::memory_order_acquire);
    }
    if (released_.load(std::memory_order_acquire) >= kStop) return;
    const bool more = fill(batches_[n % kBatches], interfaces_seen);
    filled_.store(n + 1, std::memory_order_release);
    filled_.notify_one();
    if (!more) return;
  }
}

const Record* ReadAhead::next() {
  for (;;) {
    if (current_ != nullptr && at_ < current_->size) return &current_->records[at_++];
    if (ended_) return nullptr;
    if (current_ != nullptr && current_->last) {
      ended_ = true;
      if (failure_) std::rethrow_exception(failure_);
      return nullptr;
    }
    std::size_t taken = released_.load(std::memory_order_relaxed);
    if (current_ != nullptr) {
      released_.store(++taken, std::memory_order_release);
      released_.notify_one();
    }
    for (std::size_t f = filled_.load(std::memory_order_acquire); f == taken; f = filled_.load(std::memory_order_acquire)) {
      filled_.wait(f, std::memory_order_acquire);
    }
    current_ = &batches_[taken % kBatches];
    at_ = 0;
    if (current_->new_interfaces) interfaces_ = current_->interfaces;
  }
}

}  // namespace roadload::recording
