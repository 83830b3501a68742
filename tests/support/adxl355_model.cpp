#include "adxl355_model.hpp"

#include <algorithm>
#include <cmath>

#include "roadload/accel/adxl355.hpp"

namespace roadload::test {

namespace {

using namespace accel::adxl355;

constexpr std::int32_t kTemp25C = 1885;  // TEMP2:TEMP1 at 25 °C (Linux's adxl355 driver)
constexpr std::uint32_t kEmptyEntry = kEntryEmpty;

std::uint32_t entry(std::int32_t raw, bool x) { return (static_cast<std::uint32_t>(raw) & 0xFFFFFu) << 4 | (x ? kEntryX : 0u); }

}  // namespace

Adxl355Model::Adxl355Model(Adxl355ModelConfig config, AccelSignal signal)
    : config_(config), signal_(std::move(signal)), rng_(config.seed), now_(config.start_ns), last_stamp_(config.start_ns) {
  log_.reserve(config_.log_capacity);
  reset();
  busy_until_ = now_;  // powered up long ago
}

void Adxl355Model::set_id(std::uint8_t reg, std::uint8_t value) { ids_[reg] = value; }

void Adxl355Model::power_cycle() {
  reset();
  busy_until_ = now_;
}

void Adxl355Model::advance(Nanoseconds d) { pass(d.count()); }

bool Adxl355Model::transfer(std::span<const std::uint8_t> tx, std::span<std::uint8_t> rx) {
  if (tx.empty() || tx.size() != rx.size()) return false;
  const auto duration = config_.transfer_overhead_ns + std::llround(static_cast<double>(tx.size()) * 8e9 / config_.spi_clock_hz);
  if (fail_transfers_ > 0) {
    --fail_transfers_;
    pass(duration);
    return false;
  }
  // The part sees the whole transfer at chip select; its duration passes after.
  std::uint8_t r = static_cast<std::uint8_t>(tx[0] >> 1);
  const bool read = (tx[0] & 1) != 0;
  rx[0] = 0;
  std::uint32_t fifo_entry = 0;
  for (std::size_t i = 1; i < tx.size(); ++i) {
    if (read && r == kFifoData) {
      const std::size_t byte = (i - 1) % 3;
      if (byte == 0) fifo_entry = pop_entry();
      rx[i] = static_cast<std::uint8_t>(fifo_entry >> (8 * (2 - byte)));
    } else if (read) {
      rx[i] = read_reg(r++);
    } else {
      rx[i] = 0;
      write_reg(r++, tx[i]);
    }
  }
  pass(duration);
  return true;
}

int Adxl355Model::wait(Nanoseconds timeout, std::int64_t& edge_mono_ns) {
  if (queue_count_ == 0) {
    const std::int64_t deadline = now_ + std::max<std::int64_t>(0, timeout.count());
    const std::int64_t next = next_stamp();
    if (next < 0 || next > deadline) {
      pass(deadline - now_);
      return 0;
    }
    pass(next - now_);
  }
  edge_mono_ns = queue_[queue_head_];
  queue_head_ = (queue_head_ + 1) % queue_.size();
  --queue_count_;
  return 1;
}

void Adxl355Model::pass(std::int64_t ns) {
  advance_to(now_ + ns);
  now_ += ns;
}

void Adxl355Model::advance_to(std::int64_t t) {
  while (measuring_ && sample_time(taken_) <= t) take_sample(sample_time(taken_++));
  while (flight_count_ > 0 && in_flight_[flight_head_] <= t) {
    if (queue_count_ < queue_.size()) {
      queue_[(queue_head_ + queue_count_++) % queue_.size()] = in_flight_[flight_head_];
    } else {
      ++events_dropped_;  // the kernel keeps the old events and drops the new one
    }
    flight_head_ = (flight_head_ + 1) % in_flight_.size();
    --flight_count_;
  }
}

std::int64_t Adxl355Model::sample_time(std::uint64_t k) const {
  return t_on_ + std::llround(static_cast<double>(k + 1) * period_ns_);
}

// The stamp of the next edge to reach the kernel's queue, or -1 when none is coming.
std::int64_t Adxl355Model::next_stamp() {
  if (flight_count_ > 0) return in_flight_[flight_head_];
  if (!measuring_ || (regs_[kPowerCtl] & kPowerDrdyOff) != 0) return -1;
  if (next_latency_ < 0) {
    next_latency_ = std::uniform_int_distribution<std::int64_t>(config_.latency_min_ns, config_.latency_max_ns)(rng_);
  }
  return std::max(sample_time(taken_) + next_latency_, last_stamp_ + 1);
}

void Adxl355Model::take_sample(std::int64_t t) {
  const int range = std::max(1, regs_[kRange] & kRangeMask);
  const double lsb_per_g = kLsbPerG2g / static_cast<double>(1 << (range - 1));
  const auto a = signal_(static_cast<double>(t) * 1e-9);
  ModelSample s;
  s.t_ns = t;
  s.mps2_per_lsb = kStandardGravity / lsb_per_g;
  for (std::size_t i = 0; i < 3; ++i) {
    const auto lsb = std::llround(a[i] / kStandardGravity * lsb_per_g);
    s.raw[i] = static_cast<std::int32_t>(std::clamp<long long>(lsb, -(1 << 19), (1 << 19) - 1));
  }
  latest_ = s.raw;
  data_rdy_ = true;
  s.lost = lose_x_;
  const std::size_t index = log_.size() < config_.log_capacity ? log_.size() : kNone;
  if (index != kNone) log_.push_back(s);
  if (!lose_x_) push_entry(entry(s.raw[0], true), index);
  lose_x_ = false;
  push_entry(entry(s.raw[1], false), index);
  push_entry(entry(s.raw[2], false), index);

  if ((regs_[kPowerCtl] & kPowerDrdyOff) != 0) return;
  if (next_latency_ < 0) {
    next_latency_ = std::uniform_int_distribution<std::int64_t>(config_.latency_min_ns, config_.latency_max_ns)(rng_);
  }
  last_stamp_ = std::max(t + next_latency_, last_stamp_ + 1);
  next_latency_ = -1;
  if (flight_count_ == in_flight_.size()) {
    ++events_dropped_;
    return;
  }
  in_flight_[(flight_head_ + flight_count_++) % in_flight_.size()] = last_stamp_;
}

void Adxl355Model::push_entry(std::uint32_t e, std::size_t sample) {
  if (fifo_count_ == fifo_.size()) {
    // Full: the oldest set goes, as FIFO_OVR says ("oldest data is lost").
    for (int i = 0; i < 3 && fifo_count_ > 0; ++i) {
      const std::size_t s = fifo_sample_[fifo_head_];
      if (s != kNone && !log_[s].lost) {
        log_[s].lost = true;
        ++fifo_lost_;
      }
      fifo_head_ = (fifo_head_ + 1) % fifo_.size();
      --fifo_count_;
    }
    fifo_ovr_ = true;
  }
  const std::size_t at = (fifo_head_ + fifo_count_++) % fifo_.size();
  fifo_[at] = e;
  fifo_sample_[at] = sample;
}

std::uint32_t Adxl355Model::pop_entry() {
  if (fifo_count_ == 0) return kEmptyEntry;
  const std::uint32_t e = fifo_[fifo_head_];
  fifo_head_ = (fifo_head_ + 1) % fifo_.size();
  --fifo_count_;
  return e;
}

std::uint8_t Adxl355Model::read_reg(std::uint8_t r) {
  if (r <= kRevId) return ids_[r];
  if (r == kStatus) {
    const bool busy = now_ < busy_until_;
    const bool full = fifo_count_ >= regs_[kFifoSamples];
    const auto v = static_cast<std::uint8_t>((data_rdy_ ? kStatusDataRdy : 0) | (full ? kStatusFifoFull : 0) |
                                             (fifo_ovr_ ? kStatusFifoOvr : 0) | (busy ? kStatusNvmBusy : 0));
    data_rdy_ = false;
    fifo_ovr_ = false;
    return v;
  }
  if (r == kFifoEntries) return static_cast<std::uint8_t>(fifo_count_);
  if (r == kTemp2) return static_cast<std::uint8_t>((kTemp25C >> 8) & 0x0F);
  if (r == kTemp1) return static_cast<std::uint8_t>(kTemp25C & 0xFF);
  if (r >= kXData3 && r < kFifoData) {
    const std::uint32_t word = entry(latest_[(r - kXData3) / 3u], false);
    return static_cast<std::uint8_t>(word >> (8 * (2 - (r - kXData3) % 3u)));
  }
  return r < regs_.size() ? regs_[r] : 0;
}

void Adxl355Model::write_reg(std::uint8_t r, std::uint8_t v) {
  if (r == kReset) {
    if (v == kResetCode) reset();
    return;
  }
  if (now_ < busy_until_ || r < 0x1E || r > 0x2E) return;
  regs_[r] = v;
  if (r != kPowerCtl) return;
  const bool was = measuring_;
  measuring_ = (v & kPowerStandby) == 0;
  if (measuring_ && !was) {
    t_on_ = now_;
    taken_ = 0;
    const double nominal_hz = 4000.0 / static_cast<double>(1 << std::min(regs_[kFilter] & kFilterOdrMask, 10));
    period_ns_ = 1e9 / (nominal_hz * (1.0 + config_.rate_offset_ppm * 1e-6));
  }
}

void Adxl355Model::reset() {
  // What the FIFO held never reaches a reader.
  for (std::size_t i = 0; i < fifo_count_; ++i) {
    const std::size_t s = fifo_sample_[(fifo_head_ + i) % fifo_.size()];
    if (s != kNone) log_[s].lost = true;
  }
  regs_.fill(0);
  regs_[kFifoSamples] = 0x60;
  regs_[kRange] = 0x81;
  regs_[kPowerCtl] = kPowerStandby;
  regs_[0x27] = 0x01;  // ACT_COUNT
  measuring_ = false;
  data_rdy_ = false;
  fifo_ovr_ = false;
  fifo_count_ = 0;
  busy_until_ = now_ + config_.reset_busy_ns;
}

}  // namespace roadload::test
