#include "roadload/accel/adxl355_source.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

namespace roadload::accel {

namespace {

constexpr std::uint32_t kSpiClockHz = 8'000'000;  // under the part's 10 MHz maximum
constexpr std::uint8_t kSpiMode0 = 0;             // CPOL 0, CPHA 0
constexpr double kClockWindowS = 0.5;             // the rate is fitted over this much of the part's output
constexpr std::size_t kSettledEdges = 64;         // edges in the fit before its line can tell a missing edge
constexpr double kLineError = 0.25;               // how far the old line may be off after a resync, periods
constexpr double kRefillSamples = 31;             // the FIFO's 32 samples, less one for a burst's own time

clock::SampleClockConfig clock_config(double odr_hz) {
  clock::SampleClockConfig c;
  c.nominal_rate_hz = odr_hz;
  c.window_edges = clock::SampleClock::kMaxEdges;
  return c;
}

}  // namespace

Adxl355Source::Adxl355Source(std::unique_ptr<SpiBus> owned_bus, std::unique_ptr<DataReadyLine> owned_line, SpiBus& bus,
                             DataReadyLine& line, const Adxl355SourceConfig& config)
    : owned_bus_(std::move(owned_bus)),
      owned_line_(std::move(owned_line)),
      line_(line),
      part_(bus, config.device),
      settings_(config.part),
      sensor_(config.sensor),
      clock_(clock_config(config.part.odr_hz)),
      period_ns_(1e9 / config.part.odr_hz),
      stride_(std::max<std::int64_t>(
          1, std::llround(kClockWindowS * config.part.odr_hz / static_cast<double>(clock::SampleClock::kMaxEdges)))) {
  std::snprintf(name_, sizeof name_, "adxl355-%u", unsigned{config.sensor});
}

Parsed<std::unique_ptr<Adxl355Source>> Adxl355Source::open(SpiBus& bus, DataReadyLine& line, const Adxl355SourceConfig& config) {
  return finish_open(std::unique_ptr<Adxl355Source>(new Adxl355Source(nullptr, nullptr, bus, line, config)));
}

Parsed<std::unique_ptr<Adxl355Source>> Adxl355Source::open(std::unique_ptr<SpiBus> bus, std::unique_ptr<DataReadyLine> line,
                                                           const Adxl355SourceConfig& config) {
  SpiBus& b = *bus;
  DataReadyLine& l = *line;
  return finish_open(std::unique_ptr<Adxl355Source>(new Adxl355Source(std::move(bus), std::move(line), b, l, config)));
}

Parsed<std::unique_ptr<Adxl355Source>> Adxl355Source::finish_open(std::unique_ptr<Adxl355Source> source) {
  Adxl355Source& s = *source;
  if (auto error = s.part_.configure(s.settings_)) return *error;
  if (const Adxl355::Fault f = s.start_measuring(); f != Adxl355::Fault::none) return s.part_.error(f);
  s.describe();
  return source;
}

std::size_t Adxl355Source::read(std::span<AccelSample> out, Nanoseconds timeout) {
  // Samples are waiting: hand them out now, but still take what the line and the FIFO have, so
  // that neither the kernel's queue nor the FIFO fills up while they are handed out.
  if (q_begin_ < q_timed_) timeout = Nanoseconds{0};
  std::int64_t stamp = 0;
  int got = line_.wait(timeout, stamp);
  if (got < 0) {
    go_down("data-ready line failed");
    begin_resync(true, false);
    return hand_out(out);
  }
  fresh_edge_ = false;
  int edges = 0;
  for (; got == 1; got = line_.wait(Nanoseconds{0}, stamp), ++edges) take_edge(stamp);
  // The kernel keeps the oldest edges and drops new ones while its queue is full: the edges
  // drained are a true run, but the next one may not follow the newest of them.
  if (edges >= DataReadyLine::kKernelQueue) begin_resync(true, false);
  if (!healthy(edges) || edges == 0) return hand_out(out);

  compact();
  if (resync_ && kQueue - q_end_ < burst_.size()) {
    // No room to hold more: settle with what the resync has, or give the held samples up.
    if (n_reads_ > 0) {
      resolve();
    } else if (samples_known_ && have_anchor_) {
      extrapolate_held();
    } else {
      drop_held();
    }
    compact();
  }
  const std::int64_t read_ns = line_.now_ns();
  const FifoRead f = part_.read_fifo(std::span(burst_.data(), std::min(burst_.size(), kQueue - q_end_)));
  if (!f.ok) {
    go_down("SPI transfer failed");
    return hand_out(out);
  }
  fifo_samples_ = f.entries / 3u;
  status_.errors += f.misaligned;
  status_.dropped += f.misaligned;
  // A full FIFO may drop its oldest set before the burst pops it, so the burst's first sample is
  // unknown. FIFO_OVR then shows at the next read; it says nothing new unless the FIFO could have
  // filled again since.
  const bool full = f.entries >= adxl355::kFifoEntriesMax;
  const bool stale_overflow = static_cast<double>(read_ns - full_read_ns_) < kRefillSamples * period_ns_;
  if (full) full_read_ns_ = read_ns;
  if (full || (f.overflow && !stale_overflow)) {
    begin_resync(false, true);
  } else if (!resync_ && !plausible(next_sample_ + static_cast<std::int64_t>(f.samples) - 1, read_ns)) {
    // A sample read before its time: an edge went missing without the queue filling up.
    ++status_.errors;
    begin_resync(true, false);
  }
  enqueue(f);
  if (resync_) note_read(read_ns, f.drained);
  describe();
  return hand_out(out);
}

void Adxl355Source::take_edge(std::int64_t edge_ns) {
  if (!resync_) {
    offer(edge_ns, next_edge_++);
    return;
  }
  // The read keeps its least delayed fresh edge, against the old line when there is one.
  const std::int64_t local = local_edges_++;
  const double x = have_anchor_ ? static_cast<double>(edge_ns - to_ns(anchor_t_)) / period_ns_ - static_cast<double>(local) : 0;
  if (!fresh_edge_ || x <= read_edge_x_) {
    read_edge_ns_ = edge_ns;
    read_edge_ = local;
    read_edge_x_ = x;
  }
  fresh_edge_ = true;
}

void Adxl355Source::offer(std::int64_t edge_ns, std::int64_t index) {
  const double delay = have_anchor_ ? static_cast<double>(edge_ns - to_ns(time_of(index))) : 0.0;
  if (!have_candidate_) group_start_ = index;
  if (!have_candidate_ || delay < candidate_delay_ns_) {
    have_candidate_ = true;
    candidate_ns_ = edge_ns;
    candidate_index_ = index;
    candidate_delay_ns_ = delay;
  }
  if (have_anchor_ && index - group_start_ + 1 < stride_) return;
  feed(candidate_ns_, candidate_index_);
  have_candidate_ = false;
}

void Adxl355Source::feed(std::int64_t edge_ns, std::int64_t index) {
  if (have_anchor_ && index <= fed_edge_) return;
  anchor_t_ = clock_.edge(capture_time_from_ns(edge_ns), static_cast<std::uint32_t>(index - fed_edge_));
  anchor_index_ = index;
  fed_edge_ = index;
  period_ns_ = 1e9 / clock_.rate_hz();
  have_anchor_ = true;
  ++fed_since_restart_;
}

void Adxl355Source::restart_clock() {
  clock_.restart();
  have_anchor_ = false;
  fed_since_restart_ = 0;
}

bool Adxl355Source::plausible(std::int64_t newest_index, std::int64_t read_ns) const {
  // A sample is read after it was taken. Until the fit holds enough edges its line may still lie
  // late by a first edge's latency, so it is not asked.
  return fed_since_restart_ < kSettledEdges || to_ns(time_of(newest_index)) <= read_ns + static_cast<std::int64_t>(period_ns_ / 2);
}

void Adxl355Source::enqueue(const FifoRead& f) {
  for (std::size_t i = 0; i < f.samples; ++i) {
    const FifoSample& s = burst_[i];
    Queued& q = queue_[q_end_++];
    q.valid = s.valid;
    q.index = resync_ ? local_samples_++ : next_sample_++;
    q.sample = {resync_ ? CaptureTime{} : time_of(q.index), sensor_, s.x_mps2, s.y_mps2, s.z_mps2};
  }
  if (!resync_) q_timed_ = q_end_;
}

void Adxl355Source::note_read(std::int64_t read_ns, bool drained) {
  // Only a read that emptied the FIFO tells which sample was the newest taken by then.
  if (!fresh_edge_ || !drained) return;
  reads_[n_reads_++] = {read_edge_ns_, read_ns, read_edge_, local_samples_ - 1};
  if (n_reads_ == kResyncReads) resolve();
}

void Adxl355Source::begin_resync(bool edges_lost, bool samples_lost) {
  have_candidate_ = false;
  if (!resync_) {
    resync_ = true;
    edges_known_ = true;
    samples_known_ = true;
    edge_base_ = next_edge_;
    sample_base_ = next_sample_;
    local_edges_ = 0;
    local_samples_ = 0;
    n_reads_ = 0;
  }
  if (edges_lost) {
    edges_known_ = false;
    local_edges_ = 0;
    fresh_edge_ = false;
    n_reads_ = 0;
  }
  if (samples_lost) {
    // Samples held so far are cut off from the ones after the overflow by an unknown gap.
    drop_held();
    samples_known_ = false;
  }
}

void Adxl355Source::drop_held() {
  // With their indices known they are counted here; otherwise the gap resolve() finds holds them.
  if (samples_known_) {
    for (std::size_t i = q_timed_; i < q_end_; ++i) status_.dropped += queue_[i].valid ? 1u : 0u;
    sample_base_ += local_samples_;
  }
  q_end_ = q_timed_;
  local_samples_ = 0;
  n_reads_ = 0;
}

void Adxl355Source::extrapolate_held() {
  // Their indices are known: the old line times them, off by its drift since it was last fitted.
  for (std::size_t i = q_timed_; i < q_end_; ++i) {
    Queued& q = queue_[i];
    q.index += sample_base_;
    q.sample.t = time_of(q.index);
  }
  q_timed_ = q_end_;
  sample_base_ += local_samples_;
  local_samples_ = 0;
}

void Adxl355Source::resolve() {
  // Where the fresh edges sit on the grid: known all along, or from their stamps against the old
  // line. Latency only delays an edge, so the least delayed one lies just after its grid instant
  // (within 3/4 of a period for 16 reads, with the line off by less than kLineError).
  std::size_t least = 0;
  double earliest = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; have_anchor_ && i < n_reads_; ++i) {
    const ResyncRead& r = reads_[i];
    const double x = static_cast<double>(r.edge_ns - to_ns(anchor_t_)) / period_ns_ - static_cast<double>(r.edge);
    if (x < earliest) {
      earliest = x;
      least = i;
    }
  }
  bool continuous = edges_known_;
  std::int64_t edge0 = edge_base_;  // index of local edge 0
  if (!continuous && have_anchor_) {
    edge0 = anchor_index_ + static_cast<std::int64_t>(std::floor(earliest + kLineError));
    continuous = true;
  }
  if (continuous && edge0 + reads_[least].edge > fed_edge_) {
    // The fit goes on. Its edges go through offer() like any others: edges picked another way
    // would be delayed differently from the rest of its window and tilt its line.
    for (std::size_t i = 0; i < n_reads_; ++i) offer(reads_[i].edge_ns, edge0 + reads_[i].edge);
  } else {
    // A new fit on local indices: the clock only uses their differences.
    continuous = false;
    restart_clock();
    edge0 = 0;
    for (std::size_t i = 0; i < n_reads_; ++i) feed(reads_[i].edge_ns, reads_[i].edge);
  }

  // Where the held samples sit against the edges: a read that emptied the FIFO had every sample
  // taken before it. The read lying furthest from a grid instant says which that was for certain.
  const ResyncRead* best = &reads_[0];
  double best_margin = -1;
  std::int64_t ahead = 0;  // samples taken after the best read's newest edge and before the read
  for (std::size_t i = 0; i < n_reads_; ++i) {
    const double periods = static_cast<double>(reads_[i].read_ns - to_ns(time_of(edge0 + reads_[i].edge))) / period_ns_;
    const double whole = std::floor(periods);
    const double margin = std::min(periods - whole, whole + 1 - periods);
    if (margin > best_margin) {
      best_margin = margin;
      best = &reads_[i];
      ahead = std::max<std::int64_t>(0, static_cast<std::int64_t>(whole));
    }
  }
  const std::int64_t sample0 = edge0 + best->edge + ahead - best->last_sample;

  std::int64_t first = sample_base_;
  if (continuous && !samples_known_) {
    first = sample0;
    if (first < sample_base_) {
      ++status_.errors;  // the held samples would overlap ones handed out: keep the order
      first = sample_base_;
    }
    status_.dropped += static_cast<std::uint64_t>(first - sample_base_);
  }
  // Without a grid the edges are placed from the samples instead.
  const std::int64_t shift = continuous ? 0 : first - sample0;
  anchor_index_ += shift;
  fed_edge_ += shift;
  next_edge_ = edge0 + shift + local_edges_;
  next_sample_ = first + local_samples_;
  for (std::size_t i = q_timed_; i < q_end_; ++i) {
    Queued& q = queue_[i];
    q.index += first;
    q.sample.t = time_of(q.index);
  }
  q_timed_ = q_end_;
  resync_ = false;
  n_reads_ = 0;
}

Adxl355::Fault Adxl355Source::start_measuring() {
  // Edges queued before the part starts belong to no sample of this session. With them gone and
  // the FIFO empty, the part's n-th edge and n-th sample from now on are the same instant.
  for (std::int64_t t = 0; line_.wait(Nanoseconds{0}, t) == 1;) {
  }
  const Adxl355::Fault f = part_.measure();
  if (f != Adxl355::Fault::none) return f;
  for (std::size_t i = q_timed_; i < q_end_; ++i) status_.dropped += queue_[i].valid ? 1u : 0u;
  q_end_ = q_timed_;
  restart_clock();
  resync_ = false;
  have_candidate_ = false;
  next_edge_ = next_sample_;
  return f;
}

std::size_t Adxl355Source::hand_out(std::span<AccelSample> out) {
  std::size_t n = 0;
  while (n < out.size() && q_begin_ < q_timed_) {
    const Queued& q = queue_[q_begin_++];
    if (q.valid) out[n++] = q.sample;
  }
  status_.items += n;
  if (n > 0 && status_.state == io::SourceState::waiting) status_.state = io::SourceState::up;
  return n;
}

void Adxl355Source::compact() {
  if (q_begin_ == 0) return;
  std::copy(queue_.begin() + static_cast<std::ptrdiff_t>(q_begin_), queue_.begin() + static_cast<std::ptrdiff_t>(q_end_),
            queue_.begin());
  q_timed_ -= q_begin_;
  q_end_ -= q_begin_;
  q_begin_ = 0;
}

CaptureTime Adxl355Source::time_of(std::int64_t index) const {
  return anchor_t_ + Nanoseconds{std::llround(static_cast<double>(index - anchor_index_) * period_ns_)};
}

void Adxl355Source::describe() {
  std::snprintf(status_.detail, sizeof status_.detail, "adxl355 %.1f Hz fifo %u%s", clock_.rate_hz(), fifo_samples_,
                resync_ ? " resync" : "");
}

Parsed<std::unique_ptr<io::Source<AccelSample>>> open_adxl355(const std::string& spidev_path, const std::string& gpiochip,
                                                              unsigned line, std::uint8_t sensor_index, int range_g, double odr_hz) {
  auto bus = SpidevBus::open(spidev_path, kSpiClockHz, kSpiMode0);
  if (!bus) return bus.error();
  auto drdy = GpiodLine::open(gpiochip, line, "roadloadd");
  if (!drdy) return drdy.error();
  auto source = Adxl355Source::open(std::move(bus.value()), std::move(drdy.value()), {{range_g, odr_hz}, sensor_index, spidev_path});
  if (!source) return source.error();
  return std::unique_ptr<io::Source<AccelSample>>(std::move(source.value()));
}

}  // namespace roadload::accel
