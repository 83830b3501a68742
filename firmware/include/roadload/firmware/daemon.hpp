#pragma once
// roadloadd's wiring: a thread per source into its rings, a writer thread recording every item, an
// estimator thread running the live CRR filter on the items in capture-time order, and the status
// of all of it on demand. Sources are built by the caller (devices in roadloadd, replays or dummies
// in tests), so the daemon runs the same on a truck, on vcan and in a unit test.
#include <atomic>
#include <memory>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "roadload/drive_analyzer.hpp"
#include "roadload/firmware/channel.hpp"
#include "roadload/firmware/recorder.hpp"
#include "roadload/firmware/shared_reader.hpp"
#include "roadload/firmware/status_report.hpp"
#include "roadload/io/replay_clock.hpp"
#include "roadload/j1939/database.hpp"
#include "roadload/results/provenance.hpp"
#include "roadload/vibration.hpp"

namespace roadload::firmware {

// Ring sizes: about a second of a full bus at ten times its rate, two seconds of a 4 kHz part. The
// writer and the estimator wake every 10 ms at most, so a ring drops only if one of them stalls
// for seconds.
using CanChannel = Channel<CanFrame, 1 << 15>;
using AccelChannel = Channel<AccelSample, 1 << 13>;
using GnssChannel = Channel<GnssFix, 1 << 8>;
using WeatherChannel = Channel<WeatherSample, 1 << 8>;

struct DaemonSources {
  std::vector<std::unique_ptr<CanChannel>> can;
  std::vector<std::unique_ptr<AccelChannel>> accel;
  std::unique_ptr<GnssChannel> gnss;
  std::unique_ptr<WeatherChannel> weather;

  // Every channel in the recording's order: CAN buses, accelerometers, GNSS, weather.
  std::size_t count() const { return can.size() + accel.size() + (gnss ? 1 : 0) + (weather ? 1 : 0); }
  template <typename Fn>
  void for_each(Fn&& fn) {
    for (std::size_t i = 0; i < count(); ++i) visit(i, fn);
  }
  // Calls fn on channel i of that order and returns what it returns.
  template <typename Fn>
  decltype(auto) visit(std::size_t i, Fn&& fn) {
    if (i < can.size()) return fn(*can[i]);
    i -= can.size();
    if (i < accel.size()) return fn(*accel[i]);
    i -= accel.size();
    if (i == 0 && gnss) return fn(*gnss);
    return fn(*weather);
  }
};

struct CanBusInfo {
  double bitrate_bps = 500'000;
};

struct DaemonSetup {
  std::optional<RecorderConfig> recording;  // none: record nothing
  recording::Metadata metadata;
  std::vector<std::string> interfaces;  // CanFrame::iface -> name
  std::vector<CanBusInfo> buses;        // per CAN channel, in order
  const j1939::Database* db = nullptr;  // none: no estimator
  RouteGeometry route;
  std::vector<CellSpan> cells;
  std::vector<std::string> surfaces;  // per cell, as the route file states them (results' cells.csv)
  AnalyzerConfig analyzer;
  // Axles with accelerometers: streaming spectra and the dynamic rolling-resistance power.
  std::optional<AxleLayout> layout;
  std::vector<VibrationSensor> accelerometers;
  std::vector<int> cell_group;  // per cell, for spectra per pavement
  std::size_t group_count = 0;
  // Items are handed to the estimator, and written to a stream's file shared by several sources,
  // once every source has delivered what it stamped up to this long after them, so streams with
  // different latencies, and threads the scheduler delays, merge in order.
  Nanoseconds merge_delay{200'000'000};
  // A source that stops delivering (a hung driver, a starved thread) holds the others back until
  // its thread has not come back from a read for this long, or until another's ring is half full
  // (a second of a 4 kHz accelerometer); then its late items go out of order.
  Nanoseconds max_merge_wait{1'000'000'000};
  // A replay faster than real time: the estimator sees every stamp mapped back onto the
  // recording's timeline, so the force balance keeps its real time steps. The recorder keeps the
  // stamps as they came.
  std::optional<io::ReplayTiming> timeline;
  // What the results were made of (the truck, the route, the calibration); write_results() adds
  // the run's recording id and the drive's UTC span.
  results::Provenance provenance;
};

class Daemon {
 public:
  Daemon(DaemonSetup setup, DaemonSources sources, io::WaitClock& clock);
  ~Daemon();
  Daemon(const Daemon&) = delete;
  Daemon& operator=(const Daemon&) = delete;

  void start();
  // Stops the sources, lets the writer and estimator drain every ring, ends the recording segment.
  void stop();
  // There are replay sources and every one has reached its end (live sources never do).
  bool replays_finished();
  // SIGUSR1: the recording starts a new segment.
  void rotate_recording() { rotate_.store(true, std::memory_order_relaxed); }
  // The status now; rates are over the time since the previous call.
  StatusReport report();
  // After stop(): DIR/cells.csv and DIR/trip.json from the live filter, in `roadload analyze`'s
  // format (each cell's CRR is the filter's at the last usable tick in it). Nothing without an
  // estimator.
  std::optional<ParseError> write_results(const std::string& dir) const;

 private:
  void write_loop();
  void estimate_loop();
  std::size_t write_pending(std::size_t max_items, CaptureTime horizon);
  bool estimate_next(CaptureTime horizon, CaptureTime place_horizon);
  CaptureTime merge_horizon(CaptureTime now);
  CaptureTime can_horizon(CaptureTime now);

  DaemonSetup setup_;
  DaemonSources sources_;
  io::WaitClock& clock_;
  std::optional<Recorder> recorder_;
  std::optional<DriveAnalyzer> analyzer_;
  std::optional<VibrationAnalysis> vibration_;
  double dynamic_power_w_ = -1;  // last window's, under mutex_
  std::atomic<bool> stop_sources_{false}, stop_workers_{false}, rotate_{false};
  std::thread writer_, estimator_;
  // The accelerometers that are devices, not a replay: one thread reads them all.
  SharedReader<AccelChannel> accel_reader_;
  CaptureTime started_{};
  // Shared with the status thread.
  std::mutex mutex_;
  RecorderStatus recorder_status_;
  LiveEstimate estimate_;
  J1939Report j1939_;
  // Estimator thread's own. A daemon that only records (no route or no truck: no analyzer) still
  // watches the bus: its frames go through the cadence monitor and this assembler's transport
  // reassembly, so gaps, incomplete sessions and floods are told all the same.
  j1939::CadenceMonitor cadence_;
  j1939::MessageAssembler bus_watch_;
  // The drive's first and last fix that told UTC, for the results' provenance (read after stop).
  std::int64_t first_fix_utc_ns_ = 0, last_fix_utc_ns_ = 0;
  // Status thread's own memory of the previous report, for rates.
  CaptureTime last_report_{};
  std::vector<std::uint64_t> last_items_, last_bits_, last_dropped_, last_errors_, last_restarts_;
  J1939Report last_j1939_;
  bool running_ = false;
};

}  // namespace roadload::firmware
