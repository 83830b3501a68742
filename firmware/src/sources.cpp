#include "roadload/firmware/sources.hpp"

#include <filesystem>

#include "roadload/accel/adxl355_source.hpp"
#include "roadload/can/socketcan_source.hpp"
#include "roadload/gnss/gpsd_source.hpp"
#include "roadload/io/replay_origin.hpp"
#include "roadload/io/replay_source.hpp"

namespace roadload::firmware {

namespace {

constexpr int kOriginWaitS = 60;

// The timeline `roadload replay --origin` writes as it starts sending; waited for.
Parsed<io::ReplayOrigin> wait_for_origin(const std::string& path, io::WaitClock& clock) {
  for (int i = 0; i < kOriginWaitS * 100 && !std::filesystem::exists(path); ++i) {
    clock.sleep_until(clock.now() + Nanoseconds{10'000'000}, Nanoseconds{10'000'000});
  }
  if (!std::filesystem::exists(path)) {
    return ParseError{path, 0, "replay.origin_file", "no replay started within " + std::to_string(kOriginWaitS) + " s"};
  }
  return io::read_replay_origin(path);
}

// Without an origin file the recording's first stamp maps to now: the replay starts as the daemon does.
Parsed<io::ReplayOrigin> replay_origin(const ReplayConfig& r, io::WaitClock& clock, recording::Metadata& meta) {
  auto reader = recording::RecordingReader::open(r.recording);
  if (!reader) return reader.error();
  meta = reader.value().metadata();
  if (!r.origin_file.empty()) return wait_for_origin(r.origin_file, clock);
  const recording::Record* first = reader.value().next();
  if (first == nullptr) return ParseError{r.recording, 0, "", "the recording holds no samples"};
  io::ReplayOrigin o;
  o.timing.recorded_origin = std::visit([](const auto& s) { return s.t; }, *first);
  o.timing.capture_origin = clock.now();
  o.timing.rate = r.rate;
  return o;
}

template <typename Sample, typename ChannelT>
void add_replay(const std::string& folder, const io::ReplayOrigin& origin, io::WaitClock& clock, SourceKind kind, const char* name,
                std::unique_ptr<ChannelT>& out, std::vector<std::string>& notes) {
  auto src = io::ReplaySource<Sample>::open(folder, origin.timing, clock, name, origin.faults);
  std::string note = name;
  if (!src) {
    notes.push_back(note.append(": none in ").append(folder).append(", skipped"));
    return;
  }
  out = std::make_unique<ChannelT>(std::move(src.value()), kind, name);
  notes.push_back(note.append(": replayed from ").append(folder));
}

}  // namespace

Parsed<BuiltSources> build_sources(const DaemonConfig& c, io::WaitClock& clock, std::vector<std::string>& notes) {
  BuiltSources b;
  const bool can_replayed = !c.replay.recording.empty() && c.replay.can;
  for (std::size_t i = 0; i < c.can.size() && !can_replayed; ++i) {
    can::SocketCanConfig sc;
    sc.interface = c.can[i].interface;
    sc.iface_index = static_cast<std::uint8_t>(i);
    sc.j1939_only = c.can[i].j1939_only;
    sc.receive_buffer_bytes = static_cast<int>(c.can[i].receive_buffer_kib * 1024);
    auto src = can::SocketCanSource::open(sc);
    if (!src) return src.error();
    b.sources.can.push_back(std::make_unique<CanChannel>(std::move(src.value()), SourceKind::can, sc.interface));
    b.interfaces.push_back(sc.interface);
    b.buses.push_back({c.can[i].bitrate_bps});
  }
  if (c.can.empty() && !can_replayed) notes.push_back("can: no bus configured, skipped");

  if (!c.replay.recording.empty()) {
    auto origin = replay_origin(c.replay, clock, b.replayed);
    if (!origin) return origin.error();
    b.replaying = true;
    b.timing = origin.value().timing;
    if (can_replayed) {
      std::unique_ptr<CanChannel> can;
      add_replay<CanFrame>(c.replay.recording, origin.value(), clock, SourceKind::can, "can", can, notes);
      if (can) b.sources.can.push_back(std::move(can));
      b.interfaces = b.replayed.can_interfaces;
      if (b.interfaces.empty()) b.interfaces.push_back("can0");
      b.buses.push_back({});
    }
    std::unique_ptr<AccelChannel> accel;
    add_replay<AccelSample>(c.replay.recording, origin.value(), clock, SourceKind::accelerometer, "accel", accel, notes);
    if (accel) b.sources.accel.push_back(std::move(accel));
    add_replay<GnssFix>(c.replay.recording, origin.value(), clock, SourceKind::gnss, "gnss", b.sources.gnss, notes);
    add_replay<WeatherSample>(c.replay.recording, origin.value(), clock, SourceKind::weather, "weather", b.sources.weather, notes);
    return b;
  }
  if (c.accelerometers.empty()) notes.push_back("accelerometers: none configured, skipped");
  // A part that cannot be opened costs its own stream, not the CAN recording: named and skipped.
  for (const AccelConfig& a : c.accelerometers) {
    auto src = accel::open_adxl355(a.spidev, a.gpiochip, a.line, a.id, static_cast<int>(a.range_g), a.odr_hz);
    if (!src) {
      notes.push_back("accelerometer " + a.name + ": " + src.error().to_string() + "; skipped");
      continue;
    }
    b.sources.accel.push_back(std::make_unique<AccelChannel>(std::move(src.value()), SourceKind::accelerometer, a.name));
  }
  if (!c.gnss.enabled) {
    notes.push_back("gnss: disabled, skipped");
  } else if (auto gps = gnss::GpsdSource::open(c.gnss.host, c.gnss.port)) {
    // An unreachable gpsd is not fatal: the source reconnects on its own and says so in the status.
    b.sources.gnss = std::make_unique<GnssChannel>(std::move(gps.value()), SourceKind::gnss, "gnss");
  } else {
    notes.push_back("gnss: " + gps.error().to_string() + "; skipped");
  }
  notes.push_back("weather: no station driver on this gateway, skipped");
  return b;
}

}  // namespace roadload::firmware
