#pragma once
// One ADXL355 as a source of stamped samples: its FIFO read over SPI, its samples timed from the
// kernel stamps of its data-ready edges through a SampleClock (docs/accelerometer.md).
//
// The part raises data-ready once per sample, so every edge and every FIFO sample has an index on
// the part's sample grid. The part is started with its FIFO and the line's queue empty, so the
// n-th edge and the n-th sample are the same instant, and the two counts stay tied as long as
// neither the FIFO (32 samples) nor the kernel's event queue (16 edges) loses anything. A read
// drains the queued edges and reads the FIFO. The clock gets one edge per stride, the least
// delayed of it, under its index; each sample is timed from the fitted line by its own index.
//
// When a count breaks (FIFO overflow, a full event queue, a line error, a missing edge) the samples
// read are held, untimed, while the next reads collect fresh edges. Then the fresh edges are placed
// on the old grid by their stamps (latency only delays an edge, so the least delayed one lies just
// after its grid instant), and the held samples against the edges by a read that emptied the FIFO
// (every sample taken before it was in the FIFO). The gap between the last sample handed out and
// the first held one is the count of samples the FIFO dropped.
//
// The reader must come back within 16 edges (4 ms at 4 kHz) for edges not to be lost: later, every
// read resyncs. The part's samples are timed within 50 µs of their instants at 4 kHz with up to
// 200 µs of interrupt latency (tests/unit/adxl355_driver_test.cpp).
#include <array>
#include <cstdint>
#include <limits>
#include <memory>
#include <span>
#include <string>

#include "roadload/accel/adxl355.hpp"
#include "roadload/accel/data_ready.hpp"
#include "roadload/accel/spi_bus.hpp"
#include "roadload/clock/sample_clock.hpp"
#include "roadload/io/source.hpp"
#include "roadload/parse_error.hpp"
#include "roadload/samples.hpp"

namespace roadload::accel {

struct Adxl355SourceConfig {
  Adxl355Settings part;
  std::uint8_t sensor = 0;  // AccelSample::sensor of this part's samples
  std::string device;       // the spidev path, named in errors
};

class Adxl355Source final : public io::Source<AccelSample> {
 public:
  static constexpr std::size_t kQueue = 256;       // samples read and not handed out yet
  static constexpr std::size_t kResyncReads = 16;  // reads with fresh edges before the counts are tied again

  // Configures the part. The bus and line outlive the source (tests pass a model for both).
  static Parsed<std::unique_ptr<Adxl355Source>> open(SpiBus& bus, DataReadyLine& line, const Adxl355SourceConfig& config);
  // The same, owning the devices (the daemon's case).
  static Parsed<std::unique_ptr<Adxl355Source>> open(std::unique_ptr<SpiBus> bus, std::unique_ptr<DataReadyLine> line,
                                                     const Adxl355SourceConfig& config);
  Adxl355Source(const Adxl355Source&) = delete;
  Adxl355Source& operator=(const Adxl355Source&) = delete;

  std::size_t read(std::span<AccelSample> out, Nanoseconds timeout) override;
  const io::SourceStatus& status() const override { return status_; }
  const char* name() const override { return name_; }
  const clock::SampleClock& sample_clock() const { return clock_; }

 private:
  struct Queued {
    AccelSample sample;  // t set once the index is on the grid
    std::int64_t index;  // on the part's sample grid; counted from the resync's start while one runs
    bool valid;          // false: a broken FIFO set, counted and never handed out
  };
  // A read during a resync: its least delayed fresh edge and the newest sample held after it.
  struct ResyncRead {
    std::int64_t edge_ns;      // kernel stamp, CLOCK_MONOTONIC ns
    std::int64_t read_ns;      // just before STATUS was read, CLOCK_MONOTONIC ns
    std::int64_t edge;         // local index of that edge
    std::int64_t last_sample;  // local index of the newest sample held
  };

  Adxl355Source(std::unique_ptr<SpiBus> owned_bus, std::unique_ptr<DataReadyLine> owned_line, SpiBus& bus, DataReadyLine& line,
                const Adxl355SourceConfig& config);
  static Parsed<std::unique_ptr<Adxl355Source>> finish_open(std::unique_ptr<Adxl355Source> source);

  void take_edge(std::int64_t edge_ns);
  void offer(std::int64_t edge_ns, std::int64_t index);
  void feed(std::int64_t edge_ns, std::int64_t index);
  void restart_clock();
  bool plausible(std::int64_t newest_index, std::int64_t read_ns) const;
  void enqueue(const FifoRead& f);
  void note_read(std::int64_t read_ns, bool drained);
  void begin_resync(bool edges_lost, bool samples_lost);
  void drop_held();
  void extrapolate_held();
  void resolve();
  Adxl355::Fault start_measuring();
  bool healthy(int edges);
  bool recover();
  void go_down(const char* why);
  std::size_t hand_out(std::span<AccelSample> out);
  void compact();
  CaptureTime time_of(std::int64_t index) const;
  void describe();

  std::unique_ptr<SpiBus> owned_bus_;
  std::unique_ptr<DataReadyLine> owned_line_;
  DataReadyLine& line_;
  Adxl355 part_;
  Adxl355Settings settings_;
  std::uint8_t sensor_;
  char name_[24] = {};
  io::SourceStatus status_;
  clock::SampleClock clock_;

  std::array<FifoSample, adxl355::kFifoEntriesMax> burst_{};
  std::array<Queued, kQueue> queue_{};
  std::size_t q_begin_ = 0, q_timed_ = 0, q_end_ = 0;                         // [begin, timed) ready, [timed, end) held
  unsigned fifo_samples_ = 0;                                                 // in the FIFO at the last read
  std::int64_t full_read_ns_ = std::numeric_limits<std::int64_t>::min() / 2;  // last read of a full FIFO
  std::int64_t last_edge_ns_ = 0;                                             // when a read last found an edge
  std::int64_t checked_ns_ = std::numeric_limits<std::int64_t>::min() / 2;    // the last check of a part down or silent

  // The part's grid: sample n was taken at anchor_t_ + (n - anchor_index_) * period_ns_.
  bool have_anchor_ = false;
  CaptureTime anchor_t_{};
  std::int64_t anchor_index_ = 0;
  double period_ns_;
  std::int64_t next_sample_ = 0;  // index of the next sample out of the FIFO
  std::int64_t next_edge_ = 0;    // index of the next data-ready edge
  std::int64_t fed_edge_ = 0;     // index of the newest edge given to clock_
  std::size_t fed_since_restart_ = 0;
  // clock_ gets one edge per stride, the least delayed against the line, so that its window of
  // edges spans about half a second whatever the rate.
  std::int64_t stride_;
  bool have_candidate_ = false;
  std::int64_t group_start_ = 0;  // index of the first edge of the stride being looked at
  std::int64_t candidate_ns_ = 0, candidate_index_ = 0;
  double candidate_delay_ns_ = 0;

  bool resync_ = false;
  bool edges_known_ = false, samples_known_ = false;  // local 0 is next_edge_/next_sample_ of the start
  std::int64_t edge_base_ = 0, sample_base_ = 0;
  std::int64_t local_edges_ = 0, local_samples_ = 0;
  bool fresh_edge_ = false;  // this read took fresh edges of the resync; the least delayed:
  std::int64_t read_edge_ns_ = 0, read_edge_ = 0;
  double read_edge_x_ = 0;  // its stamp against the old line, periods, less its local index
  std::array<ResyncRead, kResyncReads> reads_{};
  std::size_t n_reads_ = 0;
};

// The daemon's accelerometer: the part on `spidev_path`, its data-ready pin on `line` of `gpiochip`.
Parsed<std::unique_ptr<io::Source<AccelSample>>> open_adxl355(const std::string& spidev_path, const std::string& gpiochip,
                                                              unsigned line, std::uint8_t sensor_index, int range_g, double odr_hz);

}  // namespace roadload::accel
