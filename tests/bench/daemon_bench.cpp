// roadloadd's load on a gateway: the daemon's threads, rings, recorder and live estimator fed, in
// real time, a fully loaded 500 kbit/s J1939 bus (3,817 frames/s: the simulated MnROAD drive's
// own messages, the rest filled with proprietary frames) and eight three-axis accelerometers at
// 4 kHz. Prints the CPU used as a fraction of one core (goal: under 2 %) and the resident memory
// (goal: under 32 MiB), beside reference runs that record without estimating, in plain text and
// in zstd frames with the accelerometers as text (the default before FLAC), and with them as FLAC
// counts (roadloadd's default): each layout's own cost, side by side.
// usage: bench_daemon [SECONDS]   (default 20)
#include <sys/resource.h>
#include <time.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <thread>
#include <vector>

#include "daemon_setup.hpp"
#include "roadload/definitions.hpp"
#include "roadload/firmware/daemon.hpp"
#include "roadload/sim/scenario.hpp"
#include "roadload/sim/simulation.hpp"
#include "simulated_drive.hpp"

namespace {

using namespace roadload;
using namespace roadload::firmware;

constexpr double kBusFps = 500'000.0 / 131.0;  // unstuffed 29-bit frames of 8 bytes
constexpr double kAccelHz = 4000;
constexpr int kAccelerometers = 8;

// Emits every item due by the monotonic clock: what a driver hands over, at the device's rate.
class CanGenerator final : public io::Source<CanFrame> {
 public:
  CanGenerator(std::vector<CanFrame> drive, CaptureTime start) : drive_(std::move(drive)), start_(start) {
    status_.state = io::SourceState::up;
    span_ = drive_.back().t - drive_.front().t + Nanoseconds{1'000'000};
  }
  std::size_t read(std::span<CanFrame> out, Nanoseconds timeout) override {
    // The kernel queues frames; the source reads them in batches as they come (recvmmsg).
    clock_.sleep_until(clock_.now() + Nanoseconds{5'000'000}, timeout);
    const CaptureTime now = clock_.now();
    std::size_t n = 0;
    while (n < out.size()) {
      const CaptureTime slot = start_ + Nanoseconds{static_cast<std::int64_t>(static_cast<double>(k_) * 1e9 / kBusFps)};
      if (slot > now) break;
      const CanFrame& d = drive_[next_];
      const CaptureTime drive_t = start_ + (d.t - drive_.front().t) + span_ * static_cast<std::int64_t>(lap_);
      if (drive_t <= slot) {
        out[n] = d;
        out[n].t = slot;
        if (++next_ == drive_.size()) {
          next_ = 0;
          ++lap_;
        }
      } else {
        out[n] = filler_;
        out[n].t = slot;
        out[n].data[0] = static_cast<std::uint8_t>(k_);
      }
      ++n;
      ++k_;
    }
    status_.items += n;
    return n;
  }
  const io::SourceStatus& status() const override { return status_; }
  const char* name() const override { return "can0"; }

 private:
  std::vector<CanFrame> drive_;
  CaptureTime start_;
  Nanoseconds span_{};
  std::size_t next_ = 0, lap_ = 0;
  std::uint64_t k_ = 0;
  CanFrame filler_{CaptureTime{}, 0x18FF5500, CanFrameKind::extended, true, 0, 0, 8, {}};
  io::MonotonicClock clock_;
  io::SourceStatus status_;
};

class AccelGenerator final : public io::Source<AccelSample> {
 public:
  // The part's counts are drawn here, a second's worth, and read over and over: drawing the noise
  // in read() would add a tenth to what the benchmark measures as the daemon's CPU. A second is
  // far longer than anything the FLAC predictor looks back on (32 sets).
  AccelGenerator(std::uint8_t sensor, CaptureTime start) : sensor_(sensor), start_(start) {
    status_.state = io::SourceState::up;
    std::array<double, 400> vibration{};
    for (std::size_t i = 0; i < vibration.size(); ++i) vibration[i] = 0.8 * std::sin(2 * M_PI * static_cast<double>(i) / 400.0);
    counts_.resize(static_cast<std::size_t>(kAccelHz));
    for (std::size_t k = 0; k < counts_.size(); ++k) {
      // An ADXL355's output: whole counts, a vibration plus the part's white noise (about 150 counts).
      const double a = vibration[k % vibration.size()] + 0.01 * vibration[(k * 7 + sensor_) % vibration.size()];
      const auto count = [&](double v) { return static_cast<std::int32_t>(std::lround(v / kStep + noise())); };
      counts_[k] = {count(0.1 * a), count(0.2 * a), count(9.80665 + a)};
    }
  }
  std::size_t read(std::span<AccelSample> out, Nanoseconds timeout) override {
    // A FIFO read: the sets the part took since the last. roadloadd reads its parts in turn
    // without waiting; a reader that waits gets a read every 6 ms (24 of the FIFO's 32 sets).
    clock_.sleep_until(clock_.now() + Nanoseconds{6'000'000}, timeout);
    const CaptureTime now = clock_.now();
    std::size_t n = 0;
    while (n < out.size()) {
      const CaptureTime t = start_ + Nanoseconds{static_cast<std::int64_t>(static_cast<double>(k_) * 1e9 / kAccelHz)};
      if (t > now) break;
      const std::array<std::int32_t, 3>& c = counts_[k_ % counts_.size()];
      out[n++] = {t, sensor_, c[0] * kStep, c[1] * kStep, c[2] * kStep};
      ++k_;
    }
    status_.items += n;
    return n;
  }
  const io::SourceStatus& status() const override { return status_; }
  const char* name() const override { return "accel"; }
  static constexpr double kStep = 9.80665 / 256000;  // ±2 g

 private:
  // The sum of four uniforms (xorshift64): near-normal, sigma 150 counts.
  double noise() {
    double sum = 0;
    for (int i = 0; i < 4; ++i) {
      rng_ ^= rng_ << 13;
      rng_ ^= rng_ >> 7;
      rng_ ^= rng_ << 17;
      sum += static_cast<double>(rng_ >> 11) * 0x1.0p-53 - 0.5;
    }
    return sum * 150.0 / std::sqrt(4.0 / 12.0);
  }
  std::uint64_t rng_ = 0x9E3779B97F4A7C15ULL;
  std::uint8_t sensor_;
  CaptureTime start_;
  std::uint64_t k_ = 0;
  std::vector<std::array<std::int32_t, 3>> counts_;
  io::MonotonicClock clock_;
  io::SourceStatus status_;
};

double cpu_s() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return static_cast<double>(u.ru_utime.tv_sec + u.ru_stime.tv_sec) +
         1e-6 * static_cast<double>(u.ru_utime.tv_usec + u.ru_stime.tv_usec);
}

double rss_mib(const char* field) {
  std::ifstream in("/proc/self/status");
  std::string line;
  while (std::getline(in, line)) {
    if (line.rfind(field, 0) == 0) return std::stod(line.substr(std::string(field).size())) / 1024.0;
  }
  return 0;
}

struct Run {
  double cpu_fraction = 0, rss_mib = 0, mb_per_hour = 0;
  std::uint64_t frames = 0, samples = 0, dropped = 0, lost = 0;
};

std::uint64_t bytes_under(const std::filesystem::path& dir) {
  std::uint64_t n = 0;
  for (const auto& e : std::filesystem::recursive_directory_iterator(dir))
    if (e.is_regular_file()) n += e.file_size();
  return n;
}

Run run(const sim::Scenario& sc, const std::vector<CanFrame>& drive, const recording::Metadata& meta, const j1939::Database& db,
        bool estimate, int compression_level, bool flac, double seconds) {
  const auto dir = std::filesystem::temp_directory_path() / ("bench-daemon-" + std::to_string(::getpid()));
  std::filesystem::remove_all(dir);
  io::MonotonicClock clock;
  const CaptureTime start = clock.now();
  DaemonSources sources;
  sources.can.push_back(std::make_unique<CanChannel>(std::make_unique<CanGenerator>(drive, start), SourceKind::can, "can0"));
  for (int i = 0; i < kAccelerometers; ++i) {
    sources.accel.push_back(std::make_unique<AccelChannel>(std::make_unique<AccelGenerator>(static_cast<std::uint8_t>(i), start),
                                                           SourceKind::accelerometer, "accel"));
  }
  DaemonSetup setup = test::simulated_daemon_setup(sc, meta, db, dir.string(), estimate);
  setup.recording->compression_level = compression_level;
  setup.recording->accel_flac.clear();
  for (int i = 0; i < kAccelerometers && flac; ++i)
    setup.recording->accel_flac.push_back({static_cast<std::uint8_t>(i), kAccelHz, AccelGenerator::kStep});
  Daemon daemon(std::move(setup), std::move(sources), clock);
  const double cpu0 = cpu_s();
  timespec w0{};
  clock_gettime(CLOCK_MONOTONIC, &w0);
  daemon.start();
  for (int s = 0; s < static_cast<int>(seconds); ++s) {
    std::this_thread::sleep_for(std::chrono::seconds(1));
    if (s == 0) daemon.report();  // rates from here on
  }
  Run r;
  r.rss_mib = rss_mib("VmRSS:");
  const StatusReport rep = daemon.report();
  daemon.stop();
  timespec w1{};
  clock_gettime(CLOCK_MONOTONIC, &w1);
  const double wall = static_cast<double>(w1.tv_sec - w0.tv_sec) + 1e-9 * static_cast<double>(w1.tv_nsec - w0.tv_nsec);
  r.cpu_fraction = (cpu_s() - cpu0) / wall;
  for (const SourceReport& s : rep.sources) {
    (s.kind == SourceKind::can ? r.frames : r.samples) += s.status.items;
    r.dropped += s.ring_dropped + s.status.dropped;
  }
  r.lost = rep.recording.lines_lost;
  r.mb_per_hour = static_cast<double>(bytes_under(dir)) / 1e6 * 3600.0 / wall;
  std::filesystem::remove_all(dir);
  return r;
}

}  // namespace

int main(int argc, char** argv) {
  const double seconds = argc > 1 ? std::atof(argv[1]) : 20.0;
  j1939::Database db;
  if (auto e = load_dbc_file(db, core_dbc_path())) {
    std::fprintf(stderr, "bench_daemon: %s\n", e->to_string().c_str());
    return 1;
  }
  auto sc = sim::load_scenario("mnroad-mainline-30mph", ROADLOAD_CONFIG_DIR);
  if (!sc) {
    std::fprintf(stderr, "bench_daemon: %s\n", sc.error().to_string().c_str());
    return 1;
  }
  sc.value().duration = Seconds{60};
  sc.value().accelerometers = 0;
  sim::Simulation simulation(sc.value(), 1, db);
  recording::Metadata meta = simulation.metadata();
  sim::test::MemorySink sink;
  simulation.run(sink, nullptr);
  // The simulated truck's accelerometer layout, at this benchmark's rate.
  meta.sensors.clear();
  const char* positions[kAccelerometers] = {"tractor-front-axle-left",   "tractor-front-frame-left", "tractor-drive1-axle-left",
                                            "tractor-drive1-frame-left", "tractor-drive2-axle-left", "trailer-axle1-left",
                                            "trailer-axle1-frame-left",  "trailer-axle2-left"};
  for (int i = 0; i < kAccelerometers; ++i)
    meta.sensors.push_back({i, "A" + std::to_string(i), "accelerometer", positions[i], "ADXL355", kAccelHz});

  std::printf("bench_daemon: %.0f s real time, 500 kbit/s bus at %.0f frames/s + %d accelerometers x 3 axes at %.0f Hz\n", seconds,
              kBusFps, kAccelerometers, kAccelHz);
  const RecorderConfig defaults;
  const int zstd = defaults.compression_level;
  const Run plain = run(sc.value(), sink.frames, meta, db, false, 0, false, seconds);
  const Run text = run(sc.value(), sink.frames, meta, db, false, zstd, false, seconds);
  const Run flac = run(sc.value(), sink.frames, meta, db, false, zstd, true, seconds);
  const Run full = run(sc.value(), sink.frames, meta, db, true, zstd, true, seconds);
  const auto count = [](std::uint64_t n) { return static_cast<unsigned long long>(n); };
  std::printf("  %-30s %12s %12s %12s %12s %8s %8s\n", "", "record plain", "zstd, text", "zstd + FLAC", "+ estimator", "FLAC/txt",
              "est/FLAC");
  std::printf("  %-30s %11.2f%% %11.2f%% %11.2f%% %11.2f%% %8.2f %8.2f   (goal < 2 %%)\n", "CPU, fraction of one core",
              100 * plain.cpu_fraction, 100 * text.cpu_fraction, 100 * flac.cpu_fraction, 100 * full.cpu_fraction,
              flac.cpu_fraction / text.cpu_fraction, full.cpu_fraction / flac.cpu_fraction);
  std::printf("  %-30s %12.1f %12.1f %12.1f %12.1f %8.2f %8.2f   (goal < 32 MiB)\n", "resident memory, MiB", plain.rss_mib,
              text.rss_mib, flac.rss_mib, full.rss_mib, flac.rss_mib / text.rss_mib, full.rss_mib / flac.rss_mib);
  std::printf("  %-30s %12.0f %12.0f %12.0f %12.0f %8.2f\n", "written, MB per hour", plain.mb_per_hour, text.mb_per_hour,
              flac.mb_per_hour, full.mb_per_hour, flac.mb_per_hour / text.mb_per_hour);
  std::printf("  %-30s %12llu %12llu %12llu %12llu\n", "CAN frames", count(plain.frames), count(text.frames), count(flac.frames),
              count(full.frames));
  std::printf("  %-30s %12llu %12llu %12llu %12llu\n", "accelerometer samples", count(plain.samples), count(text.samples),
              count(flac.samples), count(full.samples));
  std::printf("  %-30s %12llu %12llu %12llu %12llu\n", "dropped or lost", count(plain.dropped + plain.lost),
              count(text.dropped + text.lost), count(flac.dropped + flac.lost), count(full.dropped + full.lost));
  std::printf(
      "  (the synthetic sources' own work is included; resident memory includes the benchmark's simulated drive; the\n"
      "   synthetic accelerometers repeat a second of counts, a vibration plus 150 counts of noise; tests/bench/streams.sh and\n"
      "   analyze_speed.sh measure sizes on the simulator's samples)\n");
  return 0;
}
