// The ADXL355 driver against the register-level model (tests/support/adxl355_model.hpp) in virtual
// time: configuration and its errors, conversion, completeness, timing against the part's true
// sampling instants, a slow reader, FIFO overflow, SPI failures, a broken FIFO set, a power cycle,
// and no heap in the hot path. The part runs 2 % fast (as real parts may) at a nominal 4000 Hz,
// its data-ready edges stamped 0-200 µs late.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <memory>
#include <optional>
#include <vector>

#include "adxl355_model.hpp"
#include "allocation_counter.hpp"
#include "roadload/accel/adxl355_source.hpp"

namespace roadload::accel {
namespace {

using test::Adxl355Model;
using test::Adxl355ModelConfig;
using test::ModelSample;

constexpr std::int64_t kUs = 1'000;
constexpr std::int64_t kMs = 1'000'000;
constexpr char kDevice[] = "/dev/spidev0.0";

// x ramps so that every sample differs from the one before; z carries gravity.
std::array<double, 3> ramp(double t_s) { return {0.5 * std::fmod(t_s, 20.0) - 5.0, -0.25, adxl355::kStandardGravity}; }

Adxl355ModelConfig fast_part(std::int64_t latency_max_ns = 200 * kUs) {
  Adxl355ModelConfig c;
  c.rate_offset_ppm = 20'000;
  c.latency_max_ns = latency_max_ns;
  return c;
}

struct Rig {
  explicit Rig(Adxl355ModelConfig config, test::AccelSignal signal = ramp, Adxl355Settings part = {})
      : model(config, std::move(signal)) {
    auto s = Adxl355Source::open(model, model, {part, 3, kDevice});
    if (s) {
      source = std::move(s.value());
    } else {
      error = s.error();
    }
    got.reserve(1 << 17);
  }

  // Reads for `ns` of virtual time as the daemon does: 10 ms timeouts, 64 samples at most, and
  // `busy_ns` of other work after each read.
  void run(std::int64_t ns, std::int64_t busy_ns = 0) {
    const std::int64_t end = model.now_ns() + ns;
    while (model.now_ns() < end) {
      const std::size_t n = source->read(buf, Nanoseconds{10 * kMs});
      got.insert(got.end(), buf.begin(), buf.begin() + static_cast<std::ptrdiff_t>(n));
      if (busy_ns > 0) model.advance(Nanoseconds{busy_ns});
    }
  }

  // Reads as roadloadd's shared reader does: never waiting, every `every_ns`.
  void poll(std::int64_t ns, std::int64_t every_ns) {
    const std::int64_t end = model.now_ns() + ns;
    while (model.now_ns() < end) {
      const std::size_t n = source->read(buf, Nanoseconds{0});
      got.insert(got.end(), buf.begin(), buf.begin() + static_cast<std::ptrdiff_t>(n));
      model.advance(Nanoseconds{every_ns});
    }
  }

  Adxl355Model model;
  std::unique_ptr<Adxl355Source> source;
  std::optional<ParseError> error;
  std::array<AccelSample, 64> buf{};
  std::vector<AccelSample> got;
};

struct Comparison {
  std::size_t compared = 0;
  std::size_t wrong_values = 0;
  double worst_us = 0;  // over samples taken at or after `from_ns`
};

// Delivered samples against the ones the part kept (not lost in its FIFO), in order.
Comparison compare(const Rig& rig, std::int64_t from_ns) {
  std::vector<const ModelSample*> kept;
  for (const ModelSample& s : rig.model.samples()) {
    if (!s.lost) kept.push_back(&s);
  }
  Comparison c;
  c.compared = std::min(kept.size(), rig.got.size());
  for (std::size_t i = 0; i < c.compared; ++i) {
    const ModelSample& m = *kept[i];
    const AccelSample& a = rig.got[i];
    const double v[3] = {a.x_mps2, a.y_mps2, a.z_mps2};
    bool same = a.sensor == 3;
    for (std::size_t k = 0; k < 3; ++k) same = same && std::abs(v[k] - m.raw[k] * m.mps2_per_lsb) < 1e-9;
    c.wrong_values += same ? 0u : 1u;
    if (m.t_ns >= from_ns) c.worst_us = std::max(c.worst_us, std::abs(static_cast<double>(to_ns(a.t) - m.t_ns)) / 1e3);
  }
  return c;
}

TEST(Adxl355Driver, RejectsWrongDeviceIdNamingTheRegisterAndValue) {
  Adxl355Model model({}, ramp);
  model.set_id(adxl355::kPartId, 0xE9);  // an ADXL359
  auto s = Adxl355Source::open(model, model, {{}, 0, kDevice});
  ASSERT_FALSE(s.ok());
  EXPECT_EQ(s.error().file, kDevice);
  EXPECT_EQ(s.error().field, "PARTID (0x02)");
  EXPECT_EQ(s.error().message, "read 0xE9, expected 0xED: not an ADXL355");

  Adxl355Model absent({}, ramp);
  absent.set_id(adxl355::kDevIdAd, 0xFF);  // nothing drives MISO
  auto none = Adxl355Source::open(absent, absent, {{}, 0, kDevice});
  ASSERT_FALSE(none.ok());
  EXPECT_EQ(none.error().to_string(), "/dev/spidev0.0: DEVID_AD (0x00): read 0xFF, expected 0xAD: not an ADXL355");
}

TEST(Adxl355Driver, RejectsRangesAndRatesThePartDoesNotHave) {
  Adxl355Model model({}, ramp);
  auto range = Adxl355Source::open(model, model, {{16, 4000}, 0, kDevice});
  ASSERT_FALSE(range.ok());
  EXPECT_EQ(range.error().field, "range_g");
  auto rate = Adxl355Source::open(model, model, {{2, 3000}, 0, kDevice});
  ASSERT_FALSE(rate.ok());
  EXPECT_EQ(rate.error().field, "odr_hz");
}

TEST(Adxl355Driver, ConfiguresRangeRateAndMeasurementWithDataReadyOn) {
  Rig rig({}, ramp, {4, 1000});
  ASSERT_TRUE(rig.source) << rig.error->to_string();
  EXPECT_EQ(rig.model.reg(adxl355::kRange) & adxl355::kRangeMask, 2);
  EXPECT_EQ(rig.model.reg(adxl355::kRange) & ~adxl355::kRangeMask, 0x80);  // reset's other bits kept
  EXPECT_EQ(rig.model.reg(adxl355::kFilter), 2);                           // 1000 Hz, high-pass off
  EXPECT_EQ(rig.model.reg(adxl355::kPowerCtl), 0);                         // measuring, DRDY on
  rig.run(200 * kMs);
  EXPECT_NEAR(rig.source->sample_clock().rate_hz(), 1000.0, 1.0);
  EXPECT_EQ(rig.source->status().state, io::SourceState::up);
}

TEST(Adxl355Driver, ValuesConvertedWithTheRangesScaleWithinOneLsb) {
  for (const int range_g : {2, 4, 8}) {
    const std::array<double, 3> truth{1.2345, -3.21, 2.0 * range_g};  // z near full scale
    Rig rig({}, [&](double) { return truth; }, {range_g, 4000});
    ASSERT_TRUE(rig.source) << rig.error->to_string();
    rig.run(50 * kMs);
    ASSERT_GT(rig.got.size(), 150u);
    const double lsb = adxl355::kStandardGravity / (adxl355::kLsbPerG2g / (range_g / 2));
    double worst = 0;
    for (const AccelSample& a : rig.got) {
      worst = std::max({worst, std::abs(a.x_mps2 - truth[0]), std::abs(a.y_mps2 - truth[1]), std::abs(a.z_mps2 - truth[2])});
    }
    EXPECT_LE(worst, lsb) << range_g << " g";
  }
}

TEST(Adxl355Driver, EverySampleDeliveredInOrderWithNoneLostWhileTheReaderKeepsUp) {
  Rig rig(fast_part());
  ASSERT_TRUE(rig.source) << rig.error->to_string();
  rig.run(2'000 * kMs);
  const Comparison c = compare(rig, 0);
  EXPECT_EQ(c.wrong_values, 0u);
  EXPECT_EQ(rig.model.fifo_lost(), 0u);
  EXPECT_GE(c.compared + 40, rig.model.samples().size()) << "the last reads' samples may still be queued";
  EXPECT_EQ(rig.source->status().items, rig.got.size());
  EXPECT_EQ(rig.source->status().dropped, 0u);
  EXPECT_EQ(rig.source->status().errors, 0u);
  for (std::size_t i = 1; i < rig.got.size(); ++i) {
    if (rig.got[i].t <= rig.got[i - 1].t) {
      ADD_FAILURE() << "sample " << i << " not after the one before";
      break;
    }
  }
}

TEST(Adxl355Driver, SampleTimesWithin50usOfTrueInstantsDespiteOscillatorOffsetAndLatency) {
  Rig rig(fast_part());
  ASSERT_TRUE(rig.source) << rig.error->to_string();
  const std::int64_t warm = rig.model.now_ns() + 250 * kMs;  // the fit's window fills first
  rig.run(5'000 * kMs);
  const Comparison c = compare(rig, warm);
  std::printf(
      "adxl355: worst sample time error %.1f us over %zu samples (+2 %% oscillator, 0-200 us latency), "
      "rate %.2f Hz fitted, %.2f Hz true\n",
      c.worst_us, c.compared, rig.source->sample_clock().rate_hz(), rig.model.rate_hz());
  EXPECT_LT(c.worst_us, 50.0);
  EXPECT_NEAR(rig.source->sample_clock().rate_hz(), rig.model.rate_hz(), 0.5);
  EXPECT_NE(std::string(rig.source->status().detail).find("adxl355 4080."), std::string::npos) << rig.source->status().detail;
}

TEST(Adxl355Driver, ReaderTakingTwelveEdgesPerReadLosesNothingAndKeepsTime) {
  Rig rig(fast_part());
  ASSERT_TRUE(rig.source) << rig.error->to_string();
  const std::int64_t warm = rig.model.now_ns() + 250 * kMs;
  rig.run(2'000 * kMs, 3 * kMs);  // 3 ms between reads: 12 edges queued, under the kernel's 16
  const Comparison c = compare(rig, warm);
  std::printf("adxl355: reading every 3 ms, worst time error %.1f us over %zu samples\n", c.worst_us, c.compared);
  EXPECT_EQ(c.wrong_values, 0u);
  EXPECT_GE(c.compared + 60, rig.model.samples().size());
  EXPECT_EQ(rig.source->status().dropped, 0u);
  EXPECT_EQ(rig.source->status().errors, 0u);
  EXPECT_LT(c.worst_us, 50.0);
}

TEST(Adxl355Driver, FifoOverflowReportedAsTheSamplesTheModelLostAndTimingRecovers) {
  Rig rig(fast_part());
  ASSERT_TRUE(rig.source) << rig.error->to_string();
  const std::int64_t warm = rig.model.now_ns() + 250 * kMs;
  rig.run(500 * kMs);
  for (const std::int64_t stall_ms : {10, 20, 37, 55, 100, 250}) {
    rig.model.advance(Nanoseconds{stall_ms * kMs});  // the reader stalls; the FIFO holds 8 ms
    rig.run(300 * kMs);
    EXPECT_EQ(rig.source->status().dropped, rig.model.fifo_lost()) << "after a " << stall_ms << " ms stall";
  }
  EXPECT_GT(rig.model.fifo_lost(), 1500u);
  EXPECT_GT(rig.model.events_dropped(), 0u);
  const Comparison c = compare(rig, warm);
  std::printf("adxl355: %llu samples lost in 6 stalls, all counted; worst time error %.1f us over %zu samples\n",
              static_cast<unsigned long long>(rig.model.fifo_lost()), c.worst_us, c.compared);
  EXPECT_EQ(c.wrong_values, 0u);
  EXPECT_LT(c.worst_us, 50.0);
  EXPECT_EQ(rig.source->status().errors, 0u);
}

TEST(Adxl355Driver, SpiFailureIsCountedAndReadingResumes) {
  Rig rig(fast_part());
  ASSERT_TRUE(rig.source) << rig.error->to_string();
  rig.run(200 * kMs);
  rig.model.fail_transfers(3);
  rig.run(200 * kMs);
  EXPECT_EQ(rig.source->status().errors, 3u);
  EXPECT_EQ(rig.source->status().restarts, 1u);
  EXPECT_EQ(rig.source->status().state, io::SourceState::up);
  EXPECT_EQ(rig.source->status().dropped, 0u) << "the FIFO kept the samples while the bus was down";
  EXPECT_EQ(compare(rig, 0).wrong_values, 0u);

  // An outage longer than the FIFO: the samples it lost are counted, then reading goes on.
  rig.model.fail_transfers(400);
  rig.run(400 * kMs);
  EXPECT_EQ(rig.source->status().errors, 403u);
  EXPECT_EQ(rig.source->status().restarts, 2u);
  EXPECT_GT(rig.model.fifo_lost(), 0u);
  EXPECT_EQ(rig.source->status().dropped, rig.model.fifo_lost());
  const Comparison c = compare(rig, 0);
  EXPECT_EQ(c.wrong_values, 0u);
  EXPECT_GE(c.compared + 40, rig.model.samples().size() - rig.model.fifo_lost());
}

TEST(Adxl355Driver, BrokenFifoSetIsCountedAndNeverDeliveredAsData) {
  Rig rig(fast_part());
  ASSERT_TRUE(rig.source) << rig.error->to_string();
  rig.run(100 * kMs);
  rig.model.lose_next_x_entry();  // y and z of one sample arrive without their x
  rig.run(100 * kMs);
  EXPECT_EQ(rig.source->status().errors, 1u);
  EXPECT_EQ(rig.source->status().dropped, 1u);
  const Comparison c = compare(rig, rig.model.samples().front().t_ns + 250 * kMs);
  EXPECT_EQ(c.wrong_values, 0u);
  EXPECT_GT(c.compared, 700u);
}

TEST(Adxl355Driver, PowerCycledPartIsConfiguredAgain) {
  Rig rig(fast_part());
  ASSERT_TRUE(rig.source) << rig.error->to_string();
  rig.run(100 * kMs);
  const std::size_t before = rig.got.size();
  rig.model.power_cycle();  // registers back to defaults: standby, no data-ready edges
  rig.run(300 * kMs);
  EXPECT_EQ(rig.source->status().restarts, 1u);
  EXPECT_EQ(rig.model.reg(adxl355::kPowerCtl), 0);
  EXPECT_GT(rig.got.size(), before + 1000);
  EXPECT_EQ(compare(rig, 0).wrong_values, 0u);
}

TEST(Adxl355Driver, AReaderThatNeverWaitsLosesNothingAndFindsAPowerCycledPart) {
  Rig rig(fast_part());
  ASSERT_TRUE(rig.source) << rig.error->to_string();
  rig.poll(200 * kMs, 3 * kMs);
  EXPECT_EQ(rig.source->status().dropped, 0u);
  EXPECT_EQ(rig.source->status().errors, 0u);
  const std::size_t before = rig.got.size();
  rig.model.power_cycle();
  rig.poll(300 * kMs, 3 * kMs);
  EXPECT_EQ(rig.source->status().restarts, 1u);
  EXPECT_GT(rig.got.size(), before + 1000);
  EXPECT_EQ(compare(rig, 0).wrong_values, 0u);
}

TEST(Adxl355Driver, APartThatIsGoneIsCheckedTenTimesASecondHoweverOftenItIsPolled) {
  Rig rig(fast_part());
  ASSERT_TRUE(rig.source) << rig.error->to_string();
  rig.poll(100 * kMs, 3 * kMs);
  rig.model.power_cycle();            // no more edges
  rig.model.fail_transfers(100'000);  // and no answer on the bus
  rig.poll(50 * kMs, 3 * kMs);        // the edges queued before it, then the first check
  const std::uint64_t before = rig.source->status().errors;
  rig.poll(1'000 * kMs, 3 * kMs);
  EXPECT_EQ(rig.source->status().state, io::SourceState::down);
  const std::uint64_t checks = rig.source->status().errors - before;  // each failed check counts an error
  EXPECT_GE(checks, 9u);
  EXPECT_LE(checks, 11u);
}

TEST(Adxl355Driver, NoHeapAllocationPerReadAfterTheFirst) {
  Rig rig(fast_part());
  ASSERT_TRUE(rig.source) << rig.error->to_string();
  rig.run(300 * kMs);
  const std::size_t before = rig.got.size();
  std::size_t allocations = 0;
  {
    test::CountAllocations count;
    rig.run(300 * kMs);
    rig.model.advance(Nanoseconds{30 * kMs});  // an overflow and its resync, too
    rig.run(300 * kMs);
    allocations = count.count();
  }
  EXPECT_GT(rig.got.size(), before + 2000);
  EXPECT_EQ(allocations, 0u);
}

}  // namespace
}  // namespace roadload::accel
