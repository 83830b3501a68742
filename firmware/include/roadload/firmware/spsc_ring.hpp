#pragma once
// A single-producer single-consumer ring of fixed capacity: one acquisition thread pushes, one
// consumer (estimator or writer) pops; neither blocks, locks or allocates. A full ring refuses the
// push and counts it, so a stalled consumer costs samples, reported, and never blocks the producer
// (which may choose to wait: Channel::read_size).
// Each side caches the other's index and reloads it only when the ring looks full or empty, so the
// two threads touch shared cache lines once per batch rather than once per item.
#include <array>
#include <atomic>
#include <cstddef>
#include <cstdint>
#include <type_traits>

namespace roadload::firmware {

template <typename T, std::size_t Capacity>
class SpscRing {
  static_assert(Capacity >= 2 && (Capacity & (Capacity - 1)) == 0, "capacity must be a power of two");
  static_assert(std::is_trivially_copyable_v<T>, "items are copied in and out");

 public:
  using value_type = T;
  static constexpr std::size_t capacity() { return Capacity; }

  // Producer side. A refused item is counted as dropped unless the producer means to retry it.
  bool try_push(const T& item, bool count_drop = true) {
    const std::uint64_t head = head_.load(std::memory_order_relaxed);
    if (head - tail_seen_ == Capacity) {
      tail_seen_ = tail_.load(std::memory_order_acquire);
      if (head - tail_seen_ == Capacity) {
        if (count_drop) dropped_.fetch_add(1, std::memory_order_relaxed);
        return false;
      }
    }
    slots_[head & (Capacity - 1)] = item;
    head_.store(head + 1, std::memory_order_release);
    return true;
  }

  // Consumer side.
  bool try_pop(T& out) {
    const std::uint64_t tail = tail_.load(std::memory_order_relaxed);
    if (tail == head_seen_) {
      head_seen_ = head_.load(std::memory_order_acquire);
      if (tail == head_seen_) return false;
    }
    out = slots_[tail & (Capacity - 1)];
    tail_.store(tail + 1, std::memory_order_release);
    return true;
  }

  // Consumer side: the oldest item without taking it, or null when empty.
  const T* peek() {
    const std::uint64_t tail = tail_.load(std::memory_order_relaxed);
    if (tail == head_seen_) {
      head_seen_ = head_.load(std::memory_order_acquire);
      if (tail == head_seen_) return nullptr;
    }
    return &slots_[tail & (Capacity - 1)];
  }

  // Either side, approximately.
  std::size_t size() const {
    return static_cast<std::size_t>(head_.load(std::memory_order_acquire) - tail_.load(std::memory_order_acquire));
  }
  std::uint64_t dropped() const { return dropped_.load(std::memory_order_relaxed); }
  std::uint64_t pushed() const { return head_.load(std::memory_order_relaxed); }

 private:
  alignas(64) std::atomic<std::uint64_t> head_{0};
  std::uint64_t tail_seen_ = 0;  // producer's copy
  alignas(64) std::atomic<std::uint64_t> tail_{0};
  std::uint64_t head_seen_ = 0;  // consumer's copy
  alignas(64) std::atomic<std::uint64_t> dropped_{0};
  alignas(64) std::array<T, Capacity> slots_{};
};

}  // namespace roadload::firmware
