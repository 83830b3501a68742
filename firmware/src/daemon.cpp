#include "roadload/firmware/daemon.hpp"

#include <filesystem>
#include <type_traits>

#include "roadload/firmware/thread_name.hpp"
#include "roadload/firmware/worker_pacing.hpp"
#include "roadload/io/posix_time.hpp"
#include "roadload/merge.hpp"
#include "roadload/recording/candump.hpp"
#include "roadload/results/results_files.hpp"
#include "roadload/utc_text.hpp"

namespace roadload::firmware {

namespace {

// How often the accelerometers are read: 8 sample sets at 4 kHz, 2 ms short of the kernel's 16
// queued data-ready edges (beyond them a part resyncs its clock) for a round the scheduler delays.
constexpr Nanoseconds kAccelReadPeriod{2'000'000};
constexpr Nanoseconds kPowerWindow{5'000'000'000};
// How long a GNSS fix or a weather sample waits for CAN to catch up with it (its ring holds 25 s).
constexpr Nanoseconds kMaxPlaceWait{10'000'000'000};

template <typename Ring, typename Fn>
std::size_t drain(Ring& ring, std::size_t max, Fn&& fn) {
  std::size_t n = 0;
  typename Ring::value_type item;
  while (n < max && ring.try_pop(item)) {
    fn(item);
    ++n;
  }
  return n;
}

std::int64_t utc_now_ns() { return io::read_clock(CLOCK_REALTIME).count(); }

}  // namespace

std::uint32_t can_frame_bits(const CanFrame& f) {
  switch (f.kind) {
    case CanFrameKind::standard: return 47 + 8u * f.len;
    case CanFrameKind::extended: return 67 + 8u * f.len;
    case CanFrameKind::remote: return f.id29 ? 67u : 47u;
    case CanFrameKind::error: return 0;
    case CanFrameKind::fd: return (f.id29 ? 67u : 47u) + 8u * f.len;
  }
  return 0;
}

Daemon::Daemon(DaemonSetup setup, DaemonSources sources, io::WaitClock& clock)
    : setup_(std::move(setup)), sources_(std::move(sources)), clock_(clock) {
  if (setup_.recording) recorder_.emplace(*setup_.recording, setup_.metadata, setup_.interfaces);
  if (setup_.db != nullptr) {
    AnalyzerConfig cfg = setup_.analyzer;
    cfg.keep_history = false;
    analyzer_.emplace(*setup_.db, setup_.route, setup_.cells, cfg);
    if (setup_.layout) {
      vibration_.emplace(*setup_.layout, setup_.accelerometers, setup_.cells.size(), setup_.cell_group, setup_.group_count);
      analyzer_->attach(&*vibration_);
    }
  }
}

Daemon::~Daemon() { stop(); }

void Daemon::start() {
  started_ = last_report_ = clock_.now();
  running_ = true;
  // The first segment exists before the first item arrives.
  if (recorder_) recorder_->tick(started_);
  // The CAN buses always feed the estimator thread (the bus watch); the sensors only the analyzer.
  const bool feed = analyzer_.has_value();
  for (auto& c : sources_.can) c->start(stop_sources_, true, clock_);
  std::vector<AccelChannel*> devices;
  for (auto& c : sources_.accel) {
    if (c->is_replay()) {
      c->start(stop_sources_, feed, clock_);
    } else {
      devices.push_back(c.get());
    }
  }
  if (!devices.empty()) accel_reader_.start("accel", std::move(devices), kAccelReadPeriod, stop_sources_, feed, clock_);
  if (sources_.gnss) sources_.gnss->start(stop_sources_, feed, clock_);
  if (sources_.weather) sources_.weather->start(stop_sources_, feed, clock_);
  writer_ = std::thread([this] {
    name_this_thread("writer");
    write_loop();
  });
  estimator_ = std::thread([this] {
    name_this_thread("estimator");
    estimate_loop();
  });
}

void Daemon::stop() {
  if (!running_) return;
  running_ = false;
  stop_sources_.store(true);
  accel_reader_.join();
  sources_.for_each([](auto& c) { c.join(); });
  // The workers see the flag only once the sources are quiet, and then drain what is left.
  stop_workers_.store(true);
  writer_.join();
  estimator_.join();
}

bool Daemon::replays_finished() {
  std::size_t replays = 0, ended = 0;
  sources_.for_each([&](auto& c) {
    if (!c.is_replay()) return;
    ++replays;
    if (c.finished()) ++ended;
  });
  return replays > 0 && ended == replays;
}

// Delivered through here by every source heard from within `wait`: one that has not come back
// from a read for longer is hung or starved and stops holding the others back (its late items then
// go out of order). Silence counts from the daemon's start, not from the age of the stamps: a
// source's first read may bring items stamped long before it, which the others must wait for.
template <typename Channel>
void lower_to_delivered(const Channel& c, CaptureTime now, Nanoseconds wait, CaptureTime& through) {
  if (now - c.heard_at() <= wait) through = std::min(through, c.delivered_through());
}

// Items up to here can be merged: every source has delivered what it stamped before it, a device
// less the merge delay for stamps that reach its thread late (a FIFO read, a kernel queue). A
// replay hands its stream on in order, each item as it goes, so it needs no delay: with one, a
// fast replay's full ring (0.1 s of the accelerometers at ten times real time) could lie wholly
// inside the delay, and nothing would ever be merged.
CaptureTime Daemon::merge_horizon(CaptureTime now) {
  CaptureTime through = CaptureTime::max();
  sources_.for_each([&](const auto& c) {
    CaptureTime delivered = CaptureTime::max();
    lower_to_delivered(c, now, setup_.max_merge_wait, delivered);
    if (delivered != CaptureTime::max() && !c.waits_for_room()) delivered -= setup_.merge_delay;
    through = std::min(through, delivered);
  });
  return through;
}

// One file per stream holds several sources (buses, accelerometers), and a recording's streams
// are in time order: the oldest head across the rings goes first, once nothing older can still
// come (every live ring has an item) or it is older than the horizon.
template <typename Channels, typename Fn>
std::size_t merge(Channels& channels, CaptureTime horizon, std::size_t max, Fn&& fn) {
  std::size_t n = 0;
  while (n < max) {
    bool complete = true;
    const auto best = oldest_head(
        channels.size(),
        [&](std::size_t i) {
          if (channels[i]->to_writer().peek() != nullptr) return true;
          complete = complete && channels[i]->finished();
          return false;
        },
        [&](std::size_t i) { return channels[i]->to_writer().peek()->t; });
    if (!best) break;
    auto& ring = channels[*best]->to_writer();
    if (!complete && ring.peek()->t > horizon) break;
    typename std::remove_reference_t<decltype(ring)>::value_type item;
    ring.try_pop(item);
    fn(item);
    ++n;
  }
  return n;
}

std::size_t Daemon::write_pending(std::size_t max_items, CaptureTime horizon) {
  std::size_t n = 0;
  auto write = [this](const auto& item) {
    if (recorder_) recorder_->write(item);
  };
  n += merge(sources_.can, horizon, max_items, write);
  n += merge(sources_.accel, horizon, max_items, write);
  if (sources_.gnss) n += drain(sources_.gnss->to_writer(), max_items, write);
  if (sources_.weather) n += drain(sources_.weather->to_writer(), max_items, write);
  return n;
}

void Daemon::write_loop() {
  for (;;) {
    const bool stopping = stop_workers_.load();
    const bool lifted = stopping || any_half_full(
                                        sources_, [](auto& c) -> auto& { return c.to_writer(); });
    const CaptureTime now = clock_.now();
    const std::size_t wrote = write_pending(kWriteBatch, lifted ? CaptureTime::max() : merge_horizon(now));
    if (recorder_) {
      if (rotate_.exchange(false)) recorder_->end_segment();
      recorder_->tick(now);
      std::lock_guard lock(mutex_);
      recorder_status_ = recorder_->status();
    }
    if (stopping && wrote == 0) break;
    // What has come is written; the rest waits a moment to come in a batch. Taken as it trickles
    // in, a frame or two a round, the rounds' clock readings and locks cost more than the writing.
    if (wrote < kWriteBatch && !stopping) {
      const Nanoseconds pause = idle_sleep(
          sources_, [](auto& c) -> auto& { return c.to_writer(); }, wrote);
      clock_.sleep_until(now + pause, pause);
    }
  }
  if (recorder_) {
    recorder_->end_segment();
    std::lock_guard lock(mutex_);
    recorder_status_ = recorder_->status();
  }
}

// GNSS fixes place the truck by the odometer that CAN's wheel speeds advance, and the weather sets
// the air those ticks meet: both wait for every bus to be delivered through their stamps, longer
// than the other streams wait for one another. A fix taken ahead of the ticks before it, when a
// starved CAN thread falls behind, would put the truck ahead of where it is.
CaptureTime Daemon::can_horizon(CaptureTime now) {
  CaptureTime through = CaptureTime::max();
  for (const auto& c : sources_.can) lower_to_delivered(*c, now, kMaxPlaceWait, through);
  return through;
}

// The oldest item across every estimator ring, if it is at or before `horizon` (GNSS and weather:
// also at or before `place_horizon`).
bool Daemon::estimate_next(CaptureTime horizon, CaptureTime place_horizon) {
  const std::size_t placing = sources_.can.size() + sources_.accel.size();
  const auto best = oldest_head(
      sources_.count(),
      [&](std::size_t i) {
        const CaptureTime limit = i >= placing ? std::min(horizon, place_horizon) : horizon;
        return sources_.visit(i, [&](auto& c) {
          const auto* head = c.to_estimator().peek();
          return head != nullptr && head->t <= limit;
        });
      },
      [&](std::size_t i) { return sources_.visit(i, [](auto& c) { return c.to_estimator().peek()->t; }); });
  if (!best) return false;
  sources_.visit(*best, [this](auto& c) {
    auto& ring = c.to_estimator();
    typename std::remove_reference_t<decltype(ring)>::value_type item;
    if (!ring.try_pop(item)) return;
    if (setup_.timeline) item.t = setup_.timeline->recorded(item.t);
    if constexpr (std::is_same_v<decltype(item), CanFrame>) {
      // On the recording's stamps, so the status counts what a decode of the recording finds.
      CanFrame as_recorded = item;
      as_recorded.t = recording::candump_stamp(item.t);
      cadence_.push(as_recorded);
      if (!analyzer_) bus_watch_.push(item);
    }
    if constexpr (std::is_same_v<decltype(item), GnssFix>) {
      if (item.utc_ns > 0) {
        if (first_fix_utc_ns_ == 0) first_fix_utc_ns_ = item.utc_ns;
        last_fix_utc_ns_ = item.utc_ns;
      }
    }
    if (analyzer_) analyzer_->push(item);
  });
  return true;
}

void Daemon::estimate_loop() {
  CaptureTime window_start = clock_.now();
  for (;;) {
    const bool stopping = stop_workers_.load();
    const CaptureTime now = clock_.now();
    const bool lifted = stopping || any_half_full(
                                        sources_, [](auto& c) -> auto& { return c.to_estimator(); });
    const CaptureTime horizon = lifted ? CaptureTime::max() : merge_horizon(now);
    const CaptureTime place_horizon = lifted ? CaptureTime::max() : can_horizon(now);
    std::size_t n = 0;
    while (n < kWriteBatch && estimate_next(horizon, place_horizon)) ++n;
    // The dynamic power over the last few seconds: spectra need several segments to mean much.
    double window_w = -2;
    if (vibration_ && now - window_start >= kPowerWindow) {
      const DynamicPower p = vibration_->window_power();
      window_w = p.segments > 0 ? p.total_w() : -1;
      vibration_->clear_window();
      window_start = now;
    }
    {
      std::lock_guard lock(mutex_);
      if (analyzer_) estimate_ = analyzer_->live();
      if (window_w > -2) dynamic_power_w_ = window_w;
      const j1939::TpCounters& tp = analyzer_ ? analyzer_->transport() : bus_watch_.transport().counters();
      j1939_.cadence = cadence_.counters();
      j1939_.tp_completed = tp.completed;
      j1939_.tp_incomplete = tp.timed_out + tp.superseded + tp.aborted;
      j1939_.tp_anomalies = tp.orphan_packets + tp.timed_out + tp.superseded + tp.bad_sequence + tp.malformed + tp.no_free_session;
    }
    if (stopping && n == 0) break;
    if (n < kWriteBatch && !stopping) {
      const Nanoseconds pause = idle_sleep(
          sources_, [](auto& c) -> auto& { return c.to_estimator(); }, n);
      clock_.sleep_until(now + pause, pause);
    }
  }
}

StatusReport Daemon::report() {
  StatusReport r;
  const CaptureTime now = clock_.now();
  r.utc_ns = utc_now_ns();
  r.uptime_s = to_seconds(now - started_);
  const double dt_s = std::max(1e-3, to_seconds(now - last_report_));
  last_report_ = now;
  {
    std::lock_guard lock(mutex_);
    r.recording = recorder_status_;
    r.estimate = estimate_;
    r.dynamic_power_w = dynamic_power_w_;
    r.j1939 = j1939_;
  }
  r.j1939.gaps_recent = r.j1939.cadence.gaps - last_j1939_.cadence.gaps;
  r.j1939.repeats_recent = r.j1939.cadence.repeats - last_j1939_.cadence.repeats;
  r.j1939.tp_incomplete_recent = r.j1939.tp_incomplete - last_j1939_.tp_incomplete;
  r.j1939.tp_anomalies_recent = r.j1939.tp_anomalies - last_j1939_.tp_anomalies;
  r.j1939.tp_anomaly_rate = static_cast<double>(r.j1939.tp_anomalies_recent) / dt_s;
  last_j1939_ = r.j1939;
  r.recording_enabled = recorder_.has_value();
  if (r.estimate.cell >= 0 && static_cast<std::size_t>(r.estimate.cell) < setup_.cells.size()) {
    r.cell = setup_.cells[static_cast<std::size_t>(r.estimate.cell)].id;
  }
  std::vector<std::uint64_t> bits;
  for (const auto& c : sources_.can) bits.push_back(c->bits());
  sources_.for_each([&](auto& c) { r.sources.push_back(c.report()); });
  const std::size_t n = r.sources.size();
  last_items_.resize(n, 0);
  last_dropped_.resize(n, 0);
  last_errors_.resize(n, 0);
  last_restarts_.resize(n, 0);
  last_bits_.resize(bits.size(), 0);
  for (std::size_t i = 0; i < n; ++i) {
    SourceReport& s = r.sources[i];
    s.rate_per_s = static_cast<double>(s.status.items - last_items_[i]) / dt_s;
    const std::uint64_t dropped = s.status.dropped + s.ring_dropped;
    s.dropped_recent = dropped - last_dropped_[i];
    last_items_[i] = s.status.items;
    last_dropped_[i] = dropped;
    s.errors_recent = s.status.errors - last_errors_[i];
    last_errors_[i] = s.status.errors;
    s.restarts_recent = s.status.restarts - last_restarts_[i];
    last_restarts_[i] = s.status.restarts;
    r.sync.clock_steps += s.status.clock_steps;
    r.sync.unplaced_stamps += s.status.userspace_stamps;
    if (i < bits.size()) {
      const double bitrate = i < setup_.buses.size() ? setup_.buses[i].bitrate_bps : 500'000.0;
      s.bus_load = static_cast<double>(bits[i] - last_bits_[i]) / dt_s / bitrate;
      last_bits_[i] = bits[i];
    }
  }
  r.warnings = warnings_for(r);
  return r;
}

std::optional<ParseError> Daemon::write_results(const std::string& dir) const {
  if (!analyzer_) return std::nullopt;
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (ec) return ParseError{dir, 0, "folder", ec.message()};
  std::vector<std::string> axles;
  if (setup_.layout) {
    for (const AxleContact& a : setup_.layout->axles) axles.push_back(a.name);
  }
  results::Provenance p = setup_.provenance;
  p.recording_id = recorder_ ? recorder_->recording_id() : setup_.metadata.recording_id;
  if (first_fix_utc_ns_ > 0) p.drive_start_utc = utc_text(first_fix_utc_ns_);
  if (last_fix_utc_ns_ > 0) p.drive_end_utc = utc_text(last_fix_utc_ns_);
  const VibrationAnalysis* va = vibration_ ? &*vibration_ : nullptr;
  if (auto e = results::write_cells_csv(dir + "/cells.csv", analyzer_->cells(), va ? axles : std::vector<std::string>{}, va,
                                        results::cell_places(setup_.route, setup_.cells, setup_.surfaces), &p))
    return e;
  return results::write_trip_json(dir + "/trip.json", analyzer_->trip(),
                                  "  \"estimate\": \"live filter\",\n" + results::provenance_json(p));
}

}  // namespace roadload::firmware
