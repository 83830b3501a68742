#pragma once
// One source, read on a thread of its own or in turn with others on a shared one (SharedReader): it
// reads batches from the device (or a replay) and pushes each item into two rings, one drained by
// the writer and one by the estimator, so a slow disk stalls neither the estimator nor acquisition
// for long: a bus's frames wait in the kernel's queue while the writer's ring is full, at most
// about kDiskStall (read_size). What either ring refuses is counted. The status is published under
// a mutex at most every 20 ms, and at the end, for the status thread; the items themselves pass
// through the rings, which take no lock.
#include <array>
#include <atomic>
#include <chrono>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>

#include "roadload/firmware/spsc_ring.hpp"
#include "roadload/firmware/status_report.hpp"
#include "roadload/firmware/thread_name.hpp"
#include "roadload/io/replay_clock.hpp"
#include "roadload/io/source.hpp"

namespace roadload::firmware {

// Frame length in bits without stuffing, as can-utils' canbusload counts by default.
std::uint32_t can_frame_bits(const CanFrame& f);

template <typename T, std::size_t RingCapacity>
class Channel {
 public:
  Channel(std::unique_ptr<io::Source<T>> source, SourceKind kind, std::string name)
      : source_(std::move(source)), kind_(kind), name_(std::move(name)) {}
  ~Channel() { join(); }
  Channel(const Channel&) = delete;
  Channel& operator=(const Channel&) = delete;

  // Reads on a thread of its own until `stop` or the end of a replay. Without an estimator its ring
  // stays empty rather than filling up and counting drops.
  void start(const std::atomic<bool>& stop, bool feed_estimator, const io::WaitClock& clock) {
    begin(feed_estimator, clock);
    thread_ = std::thread([this, &stop, &clock] {
      name_this_thread(name_);
      while (!stop.load(std::memory_order_relaxed) && read_once(stop, clock, kReadTimeout)) {
      }
      finish(stop, clock);
    });
  }
  void join() {
    if (thread_.joinable()) thread_.join();
  }

  // For a thread that reads several channels in turn (SharedReader): begin(), then read_once()
  // until it returns false or the thread stops, then finish(), all on that thread.
  void begin(bool feed_estimator, const io::WaitClock& clock) {
    feed_estimator_ = feed_estimator;
    replay_ = is_replay();
    dropped_seen_ = source_->status().dropped;
    // Nothing is delivered before the first read: a replay's items stamped before start() are
    // still to come, and a live device's socket may hold frames stamped before it.
    delivered_through_ns_.store(to_ns(CaptureTime{}), std::memory_order_relaxed);
    heard_ns_.store(to_ns(clock.now()), std::memory_order_relaxed);
    published_at_ = CaptureTime{};
  }
  // One read, waiting at most `timeout` for the device; false once the source has ended.
  bool read_once(const std::atomic<bool>& stop, const io::WaitClock& clock, Nanoseconds timeout) {
    // One clock reading a read: under User-Mode Linux each is a system call, and a bus read in
    // full batches makes thousands of reads a second.
    const CaptureTime asked = clock.now();
    heard_ns_.store(to_ns(asked), std::memory_order_release);
    const auto got = read_what_fits(asked, timeout);
    if (!got) return true;
    const std::size_t n = got->n;
    pass_on(n, stop, clock);
    // A read that was not cut short by the size asked for returned everything stamped before it
    // began; a full one only what it holds.
    CaptureTime through = n > 0 ? batch_[n - 1].t : asked;
    if (!got->full && asked > through) through = asked;
    delivered_through_ns_.store(to_ns(through), std::memory_order_release);
    if (asked - published_at_ >= kPublishPeriod) {
      publish();
      published_at_ = asked;
    }
    return source_->status().state != io::SourceState::ended;
  }
  // On the way out, what the device already holds (frames queued in the socket) is still taken,
  // as the writer makes room for it.
  void finish(const std::atomic<bool>& stop, const io::WaitClock& clock) {
    for (int i = 0; i < kDrainReads && source_->status().state != io::SourceState::ended; ++i) {
      const auto got = read_what_fits(clock.now(), Nanoseconds{0});
      if (!got) continue;
      if (got->n == 0) break;
      pass_on(got->n, stop, clock);
    }
    publish();
    delivered_through_ns_.store(to_ns(CaptureTime::max()), std::memory_order_release);
    finished_.store(true, std::memory_order_release);
  }

  SpscRing<T, RingCapacity>& to_writer() { return to_writer_; }
  SpscRing<T, RingCapacity>& to_estimator() { return to_estimator_; }
  const std::string& name() const { return name_; }
  SourceKind kind() const { return kind_; }
  // The source itself, before start() or after join() only.
  io::Source<T>& source() { return *source_; }

  // A copy of the latest published status and the bits seen (CAN), for the status thread.
  SourceReport report() {
    SourceReport r;
    r.name = name_;
    r.kind = kind_;
    {
      std::lock_guard lock(mutex_);
      r.status = published_;
    }
    r.ring_dropped = to_writer_.dropped() + to_estimator_.dropped();
    return r;
  }
  std::uint64_t bits() const { return bits_.load(std::memory_order_relaxed); }
  // A replay at its end; a live source never finishes.
  bool finished() const { return finished_.load(std::memory_order_acquire); }
  bool is_replay() const { return source_->status().stamps == StampSource::recording; }
  // A replay waits for room in its rings rather than drop (set by start()).
  bool waits_for_room() const { return replay_; }
  // Every item stamped at or before this is in the rings: a thread the scheduler starved, or a
  // device read late, holds this back, and the estimator waits for it rather than take its items
  // out of order. After the end of a replay, the end of time.
  CaptureTime delivered_through() const { return capture_time_from_ns(delivered_through_ns_.load(std::memory_order_acquire)); }
  // When its last read began (start() counts as one): a read waits at most its timeout (100 ms), so
  // a thread not heard from for long is hung or starved, however old or new the stamps it delivered.
  CaptureTime heard_at() const { return capture_time_from_ns(heard_ns_.load(std::memory_order_acquire)); }

 private:
  static constexpr std::size_t kBatch = 1024;  // a CAN source's recvmmsg fills one in one call
  static constexpr Nanoseconds kReadTimeout{100'000'000};
  // A lock and a copy of the status after every read cost more than the reads of a device read
  // every 2 ms; status lines are at least 100 ms apart.
  static constexpr Nanoseconds kPublishPeriod{20'000'000};
  static constexpr int kDrainReads = 1024;
  static constexpr Nanoseconds kDiskStall{500'000'000};

  // A bus's frames wait in the kernel's socket queue until the writer's ring has room for them
  // (a reader catching up on a backlog fills the ring faster than the disk empties it), unless the
  // disk is stalled or slower than the bus: the ring full for kDiskStall, the frames last read
  // stamped kDiskStall before the read, or the kernel dropping frames (a socket buffer smaller
  // than kDiskStall of the bus). Then whole batches are read again, so that the estimator
  // is fed and the socket's queue (a second or so of a full bus) does not overflow, and the
  // recording counts what it loses. An accelerometer's FIFO holds a few milliseconds: it is read
  // in full and what a ring cannot take is dropped.
  std::size_t read_size(CaptureTime now) {
    if constexpr (!std::is_same_v<T, CanFrame>) {
      return kBatch;
    } else {
      if (replay_ || behind_) return kBatch;
      const std::size_t room = to_writer_.capacity() - to_writer_.size();
      if (room > 0) {
        full_since_.reset();
        return std::min(room, kBatch);
      }
      if (!full_since_) full_since_ = now;
      return now - *full_since_ >= kDiskStall ? kBatch : 0;
    }
  }
  void note_lag(CaptureTime asked, std::size_t n) {
    if constexpr (std::is_same_v<T, CanFrame>) {
      const std::uint64_t dropped = source_->status().dropped;
      behind_ = (n > 0 && asked - batch_[n - 1].t >= kDiskStall) || dropped != dropped_seen_;
      dropped_seen_ = dropped;
    }
  }
  // One read of as many items as read_size allows into batch_, or, when none fit, a 1 ms wait for
  // room instead (nullopt). `full`: the read filled what it asked for, so more may be waiting.
  struct Read {
    std::size_t n;
    bool full;
  };
  std::optional<Read> read_what_fits(CaptureTime now, Nanoseconds timeout) {
    const std::size_t want = read_size(now);
    if (want == 0) {
      std::this_thread::sleep_for(std::chrono::milliseconds(1));
      return std::nullopt;
    }
    const std::size_t n = source_->read(std::span<T>(batch_).first(want), timeout);
    note_lag(now, n);
    return Read{n, n == want};
  }

  // A device cannot wait, so a full ring drops and counts (a bus's thread reads only what the
  // writer's ring has room for, read_size); a replay can, so it waits for room. A
  // replay waiting on the consumer is not a hung source: it stays heard from.
  void push(SpscRing<T, RingCapacity>& ring, const T& item, const std::atomic<bool>& stop, const io::WaitClock& clock) {
    if (!replay_) {
      ring.try_push(item);
      return;
    }
    while (!ring.try_push(item, false)) {
      if (stop.load(std::memory_order_relaxed)) {
        ring.try_push(item);
        return;
      }
      heard_ns_.store(to_ns(clock.now()), std::memory_order_release);
      std::this_thread::sleep_for(std::chrono::milliseconds(1));
    }
  }

  // A replay's stream is in time order, so each item handed on delivers everything stamped before
  // it: a replay that waits for room mid-batch then holds the others back only to what it has
  // handed on, and the oldest item of its full ring is always within their reach.
  void pass_on(std::size_t n, const std::atomic<bool>& stop, const io::WaitClock& clock) {
    for (std::size_t i = 0; i < n; ++i) {
      push(to_writer_, batch_[i], stop, clock);
      if (feed_estimator_) push(to_estimator_, batch_[i], stop, clock);
      if (replay_) delivered_through_ns_.store(to_ns(batch_[i].t), std::memory_order_release);
      if constexpr (std::is_same_v<T, CanFrame>) bits_seen_ += can_frame_bits(batch_[i]);
    }
    bits_.store(bits_seen_, std::memory_order_relaxed);
  }

  void publish() {
    std::lock_guard lock(mutex_);
    published_ = source_->status();
  }

  std::unique_ptr<io::Source<T>> source_;
  std::array<T, kBatch> batch_{};
  SourceKind kind_;
  std::string name_;
  SpscRing<T, RingCapacity> to_writer_;
  SpscRing<T, RingCapacity> to_estimator_;
  std::mutex mutex_;
  io::SourceStatus published_;
  std::atomic<std::uint64_t> bits_{0};
  std::uint64_t bits_seen_ = 0;  // the source thread's own count
  std::atomic<bool> finished_{false};
  CaptureTime published_at_{};  // the reading thread's own
  std::atomic<std::int64_t> delivered_through_ns_{0};
  std::atomic<std::int64_t> heard_ns_{0};
  bool feed_estimator_ = true;
  bool replay_ = false;
  std::optional<CaptureTime> full_since_;  // the writer's ring full since (CAN)
  bool behind_ = false;                    // the last frames read were kDiskStall old (CAN)
  std::uint64_t dropped_seen_ = 0;         // the kernel's drops as of the last read (CAN)
  std::thread thread_;
};

}  // namespace roadload::firmware
