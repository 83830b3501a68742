#pragma once
// A register-level ADXL355 in virtual time, for the driver's tests: it is both the SPI bus the
// driver talks to and the data-ready line it waits on.
//
// Modelled: the ID, STATUS, FIFO_ENTRIES, TEMP, XDATA..ZDATA and FIFO_DATA reads (auto-increment,
// except that FIFO_DATA pops one 3-byte entry per 3 bytes read); the FILTER, FIFO_SAMPLES,
// INT_MAP, SYNC, RANGE, POWER_CTL writes; RESET (defaults back, FIFO cleared, standby, NVM_BUSY
// for a while); an oscillator off nominal by a set ppm; a 96-entry FIFO of x/y/z entries in the
// data sheet's format that drops its oldest set when full (FIFO_OVR); the data-ready pin rising
// at every sample; the kernel stamping each edge after an interrupt latency drawn per edge and
// queueing at most 16 events, dropping new ones while full; SPI transfers that take time and can
// be made to fail. Not modelled: the filters' response and delay, self test, offsets, activity
// detection, external sync, I2C, temperature drift.
//
// Assumed where the data sheet was not checked: the data-ready edge is the sampling instant;
// STATUS bits clear when STATUS is read; writes other than RESET are ignored while NVM_BUSY is set.
#include <array>
#include <cstdint>
#include <functional>
#include <random>
#include <span>
#include <vector>

#include "roadload/accel/data_ready.hpp"
#include "roadload/accel/spi_bus.hpp"

namespace roadload::test {

struct Adxl355ModelConfig {
  double rate_offset_ppm = 0;       // the oscillator against nominal: +20000 is 2 % fast
  std::int64_t latency_min_ns = 0;  // interrupt latency, uniform per edge, added to its stamp
  std::int64_t latency_max_ns = 0;
  std::uint64_t seed = 1;
  double spi_clock_hz = 8e6;                   // a transfer lasts overhead + 8 bits per byte at this clock
  std::int64_t transfer_overhead_ns = 20'000;  // ioctl and controller set-up per transfer
  std::int64_t reset_busy_ns = 1'000'000;      // NVM_BUSY after RESET
  std::int64_t start_ns = 1'000'000'000;       // virtual CLOCK_MONOTONIC at construction
  std::size_t log_capacity = 1 << 20;          // samples logged for the tests; the log never grows past it
};

// What the part measures: acceleration in m/s² per axis at a virtual time in s.
using AccelSignal = std::function<std::array<double, 3>(double t_s)>;

// A sample the part took: when, what it wrote to the FIFO, and whether it was lost there.
struct ModelSample {
  std::int64_t t_ns = 0;              // sampling instant, the data-ready edge, virtual CLOCK_MONOTONIC
  std::array<std::int32_t, 3> raw{};  // LSB
  double mps2_per_lsb = 0;
  bool lost = false;  // overwritten in a full FIFO, or an entry lost on purpose
};

class Adxl355Model final : public accel::SpiBus, public accel::DataReadyLine {
 public:
  Adxl355Model(Adxl355ModelConfig config, AccelSignal signal);

  bool transfer(std::span<const std::uint8_t> tx, std::span<std::uint8_t> rx) override;
  // Advances virtual time to the next stamped edge when none is queued.
  int wait(Nanoseconds timeout, std::int64_t& edge_mono_ns) override;
  std::int64_t now_ns() const override { return now_; }

  void advance(Nanoseconds d);                         // time passes without the reader: a stall
  void fail_transfers(int n) { fail_transfers_ = n; }  // the next n transfers fail before reaching the part
  void set_id(std::uint8_t reg, std::uint8_t value);   // DEVID_AD..REVID read `value`
  void lose_next_x_entry() { lose_x_ = true; }         // the next sample's x entry never reaches the FIFO
  void power_cycle();                                  // registers to defaults, standby, FIFO empty

  std::uint8_t reg(std::uint8_t r) const { return regs_[r]; }
  const std::vector<ModelSample>& samples() const { return log_; }
  std::uint64_t fifo_lost() const { return fifo_lost_; }            // samples overwritten in the FIFO
  std::uint64_t events_dropped() const { return events_dropped_; }  // edges the full kernel queue dropped
  double rate_hz() const { return 1e9 / period_ns_; }

 private:
  static constexpr std::size_t kNone = SIZE_MAX;

  void pass(std::int64_t ns);
  void advance_to(std::int64_t t);
  std::int64_t sample_time(std::uint64_t k) const;
  std::int64_t next_stamp();
  void take_sample(std::int64_t t);
  void push_entry(std::uint32_t entry, std::size_t sample);
  std::uint32_t pop_entry();
  std::uint8_t read_reg(std::uint8_t r);
  void write_reg(std::uint8_t r, std::uint8_t v);
  void reset();

  Adxl355ModelConfig config_;
  AccelSignal signal_;
  std::mt19937_64 rng_;
  std::int64_t now_;
  std::array<std::uint8_t, 0x30> regs_{};
  std::array<std::uint8_t, 4> ids_{0xAD, 0x1D, 0xED, 0x01};
  std::int64_t busy_until_ = 0;
  bool measuring_ = false;
  bool data_rdy_ = false, fifo_ovr_ = false;
  std::int64_t t_on_ = 0;       // measurement started, ns
  std::uint64_t taken_ = 0;     // samples since then
  double period_ns_ = 250'000;  // the oscillator's output period
  std::array<std::int32_t, 3> latest_{};

  std::array<std::uint32_t, 96> fifo_{};       // entries: 20-bit value << 4 | empty << 1 | x
  std::array<std::size_t, 96> fifo_sample_{};  // the log index each entry came from
  std::size_t fifo_head_ = 0, fifo_count_ = 0;

  std::array<std::int64_t, 256> in_flight_{};  // edges raised, stamps not yet reached
  std::size_t flight_head_ = 0, flight_count_ = 0;
  std::array<std::int64_t, accel::DataReadyLine::kKernelQueue> queue_{};  // the kernel's event queue
  std::size_t queue_head_ = 0, queue_count_ = 0;
  std::int64_t last_stamp_ = 0;
  std::int64_t next_latency_ = -1;  // drawn ahead when a wait needs the next edge's stamp

  int fail_transfers_ = 0;
  bool lose_x_ = false;
  std::vector<ModelSample> log_;
  std::uint64_t fifo_lost_ = 0, events_dropped_ = 0;
};

}  // namespace roadload::test
