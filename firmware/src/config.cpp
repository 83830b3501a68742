#include "roadload/firmware/config.hpp"

#include <cmath>
#include <filesystem>
#include <set>
#include <sstream>

#include "roadload/toml_fields.hpp"
#include "roadload/toml_text.hpp"

namespace roadload::firmware {

namespace {

using detail::TomlFields;

void read_can(const TomlFields& f, const toml::table& root, DaemonConfig& c) {
  const toml::node* n = root.get("can");
  if (n == nullptr) return;
  const toml::array* list = n->as_array();
  if (list == nullptr) f.fail(n, "can", "expected [[can]] tables");
  c.can.clear();
  for (std::size_t i = 0; i < list->size(); ++i) {
    const toml::table* t = (*list)[i].as_table();
    const std::string where = "can[" + std::to_string(i) + "].";
    if (t == nullptr) f.fail(&(*list)[i], where, "expected a table");
    f.only(*t, {"interface", "j1939_only", "bitrate_bps", "receive_buffer_kib"}, where);
    CanBusConfig b;
    b.interface = f.required_text(*t, "interface", where);
    b.j1939_only = f.flag(*t, "j1939_only", where).value_or(b.j1939_only);
    b.bitrate_bps = f.number(*t, "bitrate_bps", where, b.bitrate_bps);
    b.receive_buffer_kib = static_cast<std::int64_t>(f.number(*t, "receive_buffer_kib", where, 2048));
    c.can.push_back(std::move(b));
  }
}

void read_accelerometers(const TomlFields& f, const toml::table& root, DaemonConfig& c) {
  const toml::node* n = root.get("accelerometer");
  if (n == nullptr) return;
  const toml::array* list = n->as_array();
  if (list == nullptr) f.fail(n, "accelerometer", "expected [[accelerometer]] tables");
  for (std::size_t i = 0; i < list->size(); ++i) {
    const toml::table* t = (*list)[i].as_table();
    const std::string where = "accelerometer[" + std::to_string(i) + "].";
    if (t == nullptr) f.fail(&(*list)[i], where, "expected a table");
    f.only(*t, {"id", "name", "position", "spidev", "gpiochip", "line", "range_g", "odr_hz"}, where);
    AccelConfig a;
    const double id = f.required_number(*t, "id", where);
    if (id < 0 || id > 255 || id != std::floor(id)) f.fail(t->get("id"), where + "id", "expected a whole number 0-255");
    a.id = static_cast<std::uint8_t>(id);
    a.name = f.required_text(*t, "name", where);
    a.position = f.text(*t, "position", where).value_or("");
    a.spidev = f.required_text(*t, "spidev", where);
    a.gpiochip = f.required_text(*t, "gpiochip", where);
    const double line = f.required_number(*t, "line", where);
    if (line < 0 || line > 1023 || line != std::floor(line)) f.fail(t->get("line"), where + "line", "expected a line offset 0-1023");
    a.line = static_cast<std::uint32_t>(line);
    a.range_g = f.number(*t, "range_g", where, a.range_g);
    a.odr_hz = f.number(*t, "odr_hz", where, a.odr_hz);
    c.accelerometers.push_back(std::move(a));
  }
}

void read_sections(const TomlFields& f, const toml::table& root, DaemonConfig& c) {
  if (const toml::table* t = f.table(root, "gnss")) {
    f.only(*t, {"enabled", "host", "port"}, "gnss.");
    c.gnss.enabled = f.flag(*t, "enabled", "gnss.").value_or(c.gnss.enabled);
    c.gnss.host = f.text(*t, "host", "gnss.").value_or(c.gnss.host);
    c.gnss.port = f.text(*t, "port", "gnss.").value_or(c.gnss.port);
  }
  if (const toml::table* t = f.table(root, "recording")) {
    const std::string w = "recording.";
    f.only(*t,
           {"enabled", "data_dir", "fsync_interval_s", "segment_max_s", "segment_max_mib", "quota_mib", "compression_level",
            "accel_format"},
           w);
    RecordingConfig& r = c.recording;
    r.enabled = f.flag(*t, "enabled", w).value_or(r.enabled);
    r.data_dir = f.text(*t, "data_dir", w).value_or(r.data_dir);
    r.fsync_interval = Seconds{f.number(*t, "fsync_interval_s", w, r.fsync_interval.count())};
    r.segment_max = Seconds{f.number(*t, "segment_max_s", w, r.segment_max.count())};
    r.segment_max_mib = f.number(*t, "segment_max_mib", w, r.segment_max_mib);
    r.quota_mib = f.number(*t, "quota_mib", w, r.quota_mib);
    const double level = f.number(*t, "compression_level", w, r.compression_level);
    r.compression_level = level >= 0 && level <= 19 && level == std::floor(level) ? static_cast<int>(level) : -1;
    r.accel_format = f.text(*t, "accel_format", w).value_or(r.accel_format);
  }
  if (const toml::table* t = f.table(root, "status")) {
    f.only(*t, {"text_file", "json_file", "interval_s"}, "status.");
    c.status.text_file = f.text(*t, "text_file", "status.").value_or(c.status.text_file);
    c.status.json_file = f.text(*t, "json_file", "status.").value_or(c.status.json_file);
    c.status.interval = Seconds{f.number(*t, "interval_s", "status.", c.status.interval.count())};
  }
  if (const toml::table* t = f.table(root, "replay")) {
    f.only(*t, {"recording", "rate", "can", "origin_file"}, "replay.");
    c.replay.origin_file = f.text(*t, "origin_file", "replay.").value_or("");
    c.replay.recording = f.text(*t, "recording", "replay.").value_or("");
    c.replay.rate = f.number(*t, "rate", "replay.", c.replay.rate);
    c.replay.can = f.flag(*t, "can", "replay.").value_or(c.replay.can);
  }
  if (const toml::table* t = f.table(root, "vehicle")) {
    f.only(*t, {"file"}, "vehicle.");
    c.vehicle.file = f.text(*t, "file", "vehicle.").value_or("");
  }
  if (const toml::table* t = f.table(root, "estimator")) {
    f.only(*t, {"route", "results_dir", "engine_losses", "cda_m2", "cda_sigma_m2", "cda_torque_correlation"}, "estimator.");
    c.estimator.route = f.text(*t, "route", "estimator.").value_or("");
    c.estimator.results_dir = f.text(*t, "results_dir", "estimator.").value_or("");
    c.estimator.engine_losses = f.text(*t, "engine_losses", "estimator.").value_or("");
    c.estimator.cda_m2 = f.number(*t, "cda_m2", "estimator.", c.estimator.cda_m2);
    if (c.estimator.cda_m2 != 0 && (c.estimator.cda_m2 < 0.5 || c.estimator.cda_m2 > 30)) {
      f.fail(t->get("cda_m2"), "estimator.cda_m2", "outside 0.5-30 m^2 (0: the vehicle file's prior)");
    }
    c.estimator.cda_sigma_m2 = f.number(*t, "cda_sigma_m2", "estimator.", c.estimator.cda_sigma_m2);
    if (c.estimator.cda_sigma_m2 < 0 || c.estimator.cda_sigma_m2 > 10) {
      f.fail(t->get("cda_sigma_m2"), "estimator.cda_sigma_m2", "outside 0-10 m^2 (0: the vehicle file's prior's)");
    }
    c.estimator.cda_torque_correlation = f.number(*t, "cda_torque_correlation", "estimator.", c.estimator.cda_torque_correlation);
    if (c.estimator.cda_torque_correlation < -1 || c.estimator.cda_torque_correlation > 1) {
      f.fail(t->get("cda_torque_correlation"), "estimator.cda_torque_correlation", "outside -1..1");
    }
  }
}

ParseError field_error(std::string field, std::string message) {
  return ParseError{"config", 0, std::move(field), std::move(message)};
}

}  // namespace

Parsed<DaemonConfig> load_config(const std::string& path) {
  auto parsed = detail::parse_toml_file(path);
  if (!parsed) return parsed.error();
  const toml::table& root = parsed.value();
  TomlFields f(path);
  DaemonConfig c;
  c.source = path;
  try {
    f.only(root, {"can", "accelerometer", "gnss", "recording", "status", "replay", "vehicle", "estimator"}, "");
    read_can(f, root, c);
    read_accelerometers(f, root, c);
    read_sections(f, root, c);
  } catch (const detail::TomlFailure& e) {
    return e.error;
  }
  if (auto e = validate(c)) {
    e->file = path;
    return *e;
  }
  return c;
}

std::optional<ParseError> validate(const DaemonConfig& c) {
  std::set<std::string> ifaces;
  for (std::size_t i = 0; i < c.can.size(); ++i) {
    const CanBusConfig& b = c.can[i];
    const std::string w = "can[" + std::to_string(i) + "].";
    if (b.interface.empty() || b.interface.size() > 15) return field_error(w + "interface", "expected 1 to 15 characters");
    if (!ifaces.insert(b.interface).second) return field_error(w + "interface", "'" + b.interface + "' listed twice");
    if (!(b.bitrate_bps >= 10'000 && b.bitrate_bps <= 8'000'000)) return field_error(w + "bitrate_bps", "expected 10000 to 8000000");
    if (b.receive_buffer_kib < 64 || b.receive_buffer_kib > 1 << 20)
      return field_error(w + "receive_buffer_kib", "expected 64 to 1048576");
  }
  if (c.can.size() > 8) return field_error("can", "at most 8 buses");
  std::set<int> ids;
  for (std::size_t i = 0; i < c.accelerometers.size(); ++i) {
    const AccelConfig& a = c.accelerometers[i];
    const std::string w = "accelerometer[" + std::to_string(i) + "].";
    if (!ids.insert(a.id).second) return field_error(w + "id", std::to_string(a.id) + " used twice");
    if (a.range_g != 2 && a.range_g != 4 && a.range_g != 8) return field_error(w + "range_g", "the ADXL355 has 2, 4 or 8");
    if (!(a.odr_hz > 3.9 && a.odr_hz <= 4000)) return field_error(w + "odr_hz", "expected 3.906 to 4000");
  }
  if (c.accelerometers.size() > 16) return field_error("accelerometer", "at most 16 accelerometers");
  const RecordingConfig& r = c.recording;
  if (r.data_dir.empty()) return field_error("recording.data_dir", "must not be empty");
  if (!(r.fsync_interval.count() >= 0.05 && r.fsync_interval.count() <= 60)) {
    return field_error("recording.fsync_interval_s", "expected 0.05 to 60");
  }
  // A year at most: a segment's length must convert to the recorder's nanoseconds.
  if (!(r.segment_max.count() >= 10 && r.segment_max.count() <= 31'536'000)) {
    return field_error("recording.segment_max_s", "expected 10 to 31536000 (a year)");
  }
  // Bounded so that their bytes fit the recorder's 64-bit counters with room to spare.
  if (!(r.segment_max_mib >= 1 && r.segment_max_mib <= 1 << 20)) {
    return field_error("recording.segment_max_mib", "expected 1 to 1048576 (1 TiB)");
  }
  if (!(r.quota_mib >= 2 * r.segment_max_mib && r.quota_mib <= 1 << 30)) {
    return field_error("recording.quota_mib", "expected twice segment_max_mib to 1073741824 (1 PiB)");
  }
  if (r.compression_level < 0) return field_error("recording.compression_level", "expected a whole number, 0 (plain text) to 19");
  if (r.accel_format != "flac" && r.accel_format != "text")
    return field_error("recording.accel_format", "expected \"flac\" or \"text\"");
  if (c.status.text_file.empty()) return field_error("status.text_file", "must not be empty");
  if (!(c.status.interval.count() >= 0.1 && c.status.interval.count() <= 60)) {
    return field_error("status.interval_s", "expected 0.1 to 60");
  }
  if (!(c.replay.rate >= 0 && c.replay.rate <= 1000)) return field_error("replay.rate", "expected 0 (as fast as read) to 1000");
  if (c.replay.can && c.replay.recording.empty()) return field_error("replay.can", "needs replay.recording");
  if (!c.replay.origin_file.empty() && c.replay.recording.empty()) return field_error("replay.origin_file", "needs replay.recording");
  if (!c.replay.recording.empty()) {
    std::error_code ec;
    const auto kind = std::filesystem::status(c.replay.recording, ec).type();
    if (kind == std::filesystem::file_type::not_found) {
      return field_error("replay.recording", "'" + c.replay.recording + "' does not exist");
    }
    // A plain file is a can.log alone: it has CAN to replay and nothing else.
    if (kind != std::filesystem::file_type::directory && !c.replay.can) {
      return field_error("replay.recording", "'" + c.replay.recording +
                                                 "' is not a recording folder: accelerometers, GNSS and weather replay from one "
                                                 "(a can.log alone replays with --replay-can)");
    }
  }
  return std::nullopt;
}

std::string format_config(const DaemonConfig& c) {
  std::ostringstream o;
  o << "# roadloadd settings from " << c.source << "\n";
  for (const CanBusConfig& b : c.can) {
    o << "\n[[can]]\ninterface = " << toml_quoted(b.interface) << "\nj1939_only = " << (b.j1939_only ? "true" : "false")
      << "\nbitrate_bps = " << b.bitrate_bps << "\nreceive_buffer_kib = " << b.receive_buffer_kib << "\n";
  }
  for (const AccelConfig& a : c.accelerometers) {
    o << "\n[[accelerometer]]\nid = " << int{a.id} << "\nname = " << toml_quoted(a.name) << "\nposition = " << toml_quoted(a.position)
      << "\nspidev = " << toml_quoted(a.spidev) << "\ngpiochip = " << toml_quoted(a.gpiochip) << "\nline = " << a.line
      << "\nrange_g = " << a.range_g << "\nodr_hz = " << a.odr_hz << "\n";
  }
  o << "\n[gnss]\nenabled = " << (c.gnss.enabled ? "true" : "false") << "\nhost = " << toml_quoted(c.gnss.host)
    << "\nport = " << toml_quoted(c.gnss.port) << "\n";
  const RecordingConfig& r = c.recording;
  o << "\n[recording]\nenabled = " << (r.enabled ? "true" : "false") << "\ndata_dir = " << toml_quoted(r.data_dir)
    << "\nfsync_interval_s = " << r.fsync_interval.count() << "\nsegment_max_s = " << r.segment_max.count()
    << "\nsegment_max_mib = " << r.segment_max_mib << "\nquota_mib = " << r.quota_mib
    << "\ncompression_level = " << r.compression_level << "\naccel_format = " << toml_quoted(r.accel_format) << "\n";
  o << "\n[status]\ntext_file = " << toml_quoted(c.status.text_file) << "\njson_file = " << toml_quoted(c.status.json_file)
    << "\ninterval_s = " << c.status.interval.count() << "\n";
  o << "\n[replay]\nrecording = " << toml_quoted(c.replay.recording) << "\nrate = " << c.replay.rate
    << "\ncan = " << (c.replay.can ? "true" : "false") << "\norigin_file = " << toml_quoted(c.replay.origin_file) << "\n";
  o << "\n[vehicle]\nfile = " << toml_quoted(c.vehicle.file) << "\n";
  o << "\n[estimator]\nroute = " << toml_quoted(c.estimator.route) << "\nresults_dir = " << toml_quoted(c.estimator.results_dir)
    << "\nengine_losses = " << toml_quoted(c.estimator.engine_losses) << "\ncda_m2 = " << c.estimator.cda_m2
    << "\ncda_sigma_m2 = " << c.estimator.cda_sigma_m2 << "\ncda_torque_correlation = " << c.estimator.cda_torque_correlation << "\n";
  return o.str();
}

}  // namespace roadload::firmware
