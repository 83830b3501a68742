// A bus's frames wait in the kernel's queue while the writer's ring is full, instead of being
// taken and dropped: a reader catching up on a backlog outruns the disk. Once the ring has been
// full for longer than a disk stall, the reader takes frames again so that the estimator is fed,
// and the recording counts what it loses. An accelerometer's FIFO is always read in full.
#include <gtest/gtest.h>

#include <atomic>
#include <memory>
#include <type_traits>
#include <utility>

#include "roadload/firmware/daemon.hpp"

namespace roadload::firmware {
namespace {

// The kernel's socket queue: `backlog` frames ready at once, each read takes what it is asked for.
template <typename T>
class Backlog final : public io::Source<T> {
 public:
  explicit Backlog(std::size_t backlog) : left_(backlog) { status_.state = io::SourceState::up; }
  std::size_t read(std::span<T> out, Nanoseconds) override {
    const std::size_t n = std::min(out.size(), left_);
    for (std::size_t i = 0; i < n; ++i) out[i] = T{};
    left_ -= n;
    status_.items += n;
    return n;
  }
  const io::SourceStatus& status() const override { return status_; }
  const char* name() const override { return "backlog"; }
  std::size_t left() const { return left_; }

 private:
  std::size_t left_;
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
  CaptureTime t = capture_time_from_ns(1'000'000'000);
};

TEST(ChannelBacklog, FramesWaitInTheKernelWhileTheWritersRingIsFull) {
  constexpr std::size_t ring = ring_capacity<CanChannel>();
  auto source = std::make_unique<Backlog<CanFrame>>(ring + 5000);
  Backlog<CanFrame>& backlog = *source;
  CanChannel channel(std::move(source), SourceKind::can, "can0");
  ManualClock clock;
  const std::atomic<bool> stop{false};
  channel.begin(false, clock);
  for (int i = 0; i < 200; ++i) channel.read_once(stop, clock, Nanoseconds{0});
  EXPECT_EQ(channel.to_writer().size(), ring);
  EXPECT_EQ(backlog.left(), 5000u);
  EXPECT_EQ(channel.report().ring_dropped, 0u);

  // Full for long enough to be a stalled disk: frames are taken again, and the ring counts.
  channel.read_once(stop, clock, Nanoseconds{0});
  clock.t += std::chrono::seconds(1);
  channel.read_once(stop, clock, Nanoseconds{0});
  EXPECT_LT(backlog.left(), 5000u);
  EXPECT_EQ(channel.report().ring_dropped, 5000u - backlog.left());

  // Room again: reads are held to it.
  CanFrame f;
  for (int i = 0; i < 10; ++i) channel.to_writer().try_pop(f);
  const std::size_t before = backlog.left();
  channel.read_once(stop, clock, Nanoseconds{0});
  EXPECT_EQ(before - backlog.left(), 10u);
  EXPECT_EQ(channel.to_writer().size(), ring);
}

TEST(ChannelBacklog, AnAccelerometersFifoIsReadInFullAndTheRingDrops) {
  constexpr std::size_t ring = ring_capacity<AccelChannel>();
  auto source = std::make_unique<Backlog<AccelSample>>(ring + 5000);
  Backlog<AccelSample>& fifo = *source;
  AccelChannel channel(std::move(source), SourceKind::accelerometer, "accel");
  ManualClock clock;
  const std::atomic<bool> stop{false};
  channel.begin(false, clock);
  for (int i = 0; i < 200; ++i) channel.read_once(stop, clock, Nanoseconds{0});
  EXPECT_EQ(fifo.left(), 0u);
  EXPECT_EQ(channel.to_writer().size(), ring);
  EXPECT_EQ(channel.report().ring_dropped, 5000u);
}

}  // namespace
}  // namespace roadload::firmware
