// A bus's frames wait in the kernel's queue while the writer's ring is full, instead of being
// taken and dropped: a reader catching up on a backlog outruns the disk. Once the ring has been
// full for longer than a disk stall, the frames come out of the queue that late, or the queue
// overflowed, the reader takes whole batches again so that the estimator is fed, and the
// recording counts what it loses. An accelerometer's FIFO is always read in full.
#include <gtest/gtest.h>

#include <atomic>
#include <memory>
#include <type_traits>
#include <utility>

#include "roadload/firmware/daemon.hpp"

namespace roadload::firmware {
namespace {

// The kernel's socket queue: `backlog` items ready at once, 1 us apart from `first`; each read
// takes what it is asked for.
template <typename T>
class Backlog final : public io::Source<T> {
 public:
  Backlog(std::size_t backlog, CaptureTime first) : left_(backlog), next_(first) { status_.state = io::SourceState::up; }
  std::size_t read(std::span<T> out, Nanoseconds) override {
    const std::size_t n = std::min(out.size(), left_);
    for (std::size_t i = 0; i < n; ++i) {
      out[i] = T{};
      out[i].t = next_;
      next_ += Nanoseconds{1000};
    }
    left_ -= n;
    status_.items += n;
    return n;
  }
  const io::SourceStatus& status() const override { return status_; }
  const char* name() const override { return "backlog"; }
  std::size_t left() const { return left_; }
  void overflow(std::uint64_t frames) { status_.dropped += frames; }  // the kernel's queue was full
  CaptureTime next() const { return next_; }

 private:
  std::size_t left_;
  CaptureTime next_;
  io::SourceStatus status_;
};

template <typename C>
constexpr std::size_t ring_capacity() {
  return std::remove_reference_t<decltype(std::declval<C&>().to_writer())>::capacity();
}

// Time moves only when the test moves it.
class ManualClock final : public io::WaitClock {
 public:
  CaptureTime now() const override { return t; }
  void sleep_until(CaptureTime, Nanoseconds) override {}
  CaptureTime t = capture_time_from_ns(10'000'000'000);
};

// A channel over a backlog of `extra` items more than its ring holds, stamped from `first`.
template <typename C, typename T>
struct Fixture {
  Fixture(std::size_t extra, CaptureTime first, SourceKind kind) {
    auto source = std::make_unique<Backlog<T>>(ring_capacity<C>() + extra, first);
    queue = source.get();
    channel = std::make_unique<C>(std::move(source), kind, "src");
    channel->begin(false, clock);
  }
  void read(int times) {
    for (int i = 0; i < times; ++i) channel->read_once(stop, clock, Nanoseconds{0});
  }
  ManualClock clock;
  const std::atomic<bool> stop{false};
  Backlog<T>* queue = nullptr;
  std::unique_ptr<C> channel;
};

TEST(ChannelBacklog, FramesWaitInTheKernelWhileTheWritersRingIsFull) {
  constexpr std::size_t ring = ring_capacity<CanChannel>();
  Fixture<CanChannel, CanFrame> f(5000, capture_time_from_ns(9'900'000'000), SourceKind::can);
  f.read(200);
  EXPECT_EQ(f.channel->to_writer().size(), ring);
  EXPECT_EQ(f.queue->left(), 5000u);
  EXPECT_EQ(f.channel->report().ring_dropped, 0u);

  // Room again: reads are held to it, and deliver through the last frame taken, not through the
  // read's start: older frames still wait in the queue.
  CanFrame frame;
  for (int i = 0; i < 10; ++i) f.channel->to_writer().try_pop(frame);
  f.read(1);
  EXPECT_EQ(f.queue->left(), 4990u);
  EXPECT_EQ(f.channel->to_writer().size(), ring);
  EXPECT_EQ(f.channel->delivered_through(), f.queue->next() - Nanoseconds{1000});

  // Full for as long as a stalled disk: whole batches again, and the ring counts what it drops.
  f.read(1);
  f.clock.t += std::chrono::seconds(1);
  f.read(1);
  EXPECT_LT(f.queue->left(), 4990u);
  EXPECT_EQ(f.channel->report().ring_dropped, 4990u - f.queue->left());
}

TEST(ChannelBacklog, FramesThatWaitedLongerThanAStallAreReadInFull) {
  // The queue's frames were stamped 0.6 s before the reads: the disk is slower than the bus.
  Fixture<CanChannel, CanFrame> f(5000, capture_time_from_ns(9'400'000'000), SourceKind::can);
  f.read(200);
  EXPECT_EQ(f.queue->left(), 0u);
  EXPECT_EQ(f.channel->report().ring_dropped, 5000u);
}

TEST(ChannelBacklog, AKernelQueueThatOverflowedIsReadInFull) {
  // A socket buffer smaller than a stall's worth of the bus: the kernel drops before the frames
  // are old, and holding back would starve the estimate.
  Fixture<CanChannel, CanFrame> f(5000, capture_time_from_ns(9'900'000'000), SourceKind::can);
  f.read(200);
  CanFrame frame;
  for (int i = 0; i < 10; ++i) f.channel->to_writer().try_pop(frame);
  f.queue->overflow(100);
  f.read(2);
  EXPECT_EQ(f.queue->left(), 5000u - 10 - 1024);
  EXPECT_EQ(f.channel->report().ring_dropped, 1024u);
}

TEST(ChannelBacklog, AnAccelerometersFifoIsReadInFullAndTheRingDrops) {
  Fixture<AccelChannel, AccelSample> f(5000, capture_time_from_ns(9'900'000'000), SourceKind::accelerometer);
  f.read(200);
  EXPECT_EQ(f.queue->left(), 0u);
  EXPECT_EQ(f.channel->to_writer().size(), ring_capacity<AccelChannel>());
  EXPECT_EQ(f.channel->report().ring_dropped, 5000u);
}

}  // namespace
}  // namespace roadload::firmware
