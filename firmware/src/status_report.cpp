#include "roadload/firmware/status_report.hpp"

#include <cmath>
#include <cstdio>

#include "roadload/results/json.hpp"
#include "roadload/utc_text.hpp"

namespace roadload::firmware {

using results::json_number;

namespace {

std::string fmt(const char* f, double v) {
  char buf[48];
  std::snprintf(buf, sizeof buf, f, v);
  return buf;
}

}  // namespace

const char* to_string(SourceKind k) {
  switch (k) {
    case SourceKind::can: return "can";
    case SourceKind::accelerometer: return "accelerometer";
    case SourceKind::gnss: return "gnss";
    case SourceKind::weather: return "weather";
  }
  return "?";
}

std::vector<std::string> warnings_for(const StatusReport& r) {
  std::vector<std::string> w;
  if (r.recording_enabled && r.recording.error != 0) w.push_back("recording: " + r.recording.error_text);
  for (const SourceReport& s : r.sources) {
    if (s.status.state == io::SourceState::down) w.push_back(s.name + " down: " + s.status.detail);
    if (s.status.state == io::SourceState::waiting && s.status.items > 0) w.push_back(s.name + " waiting: " + s.status.detail);
    if (s.dropped_recent > 0) w.push_back(s.name + " dropped " + std::to_string(s.dropped_recent));
    if (s.errors_recent > 0) w.push_back(s.name + " " + std::to_string(s.errors_recent) + " errors (" + s.status.detail + ")");
    // A source that went down and came back between two lines would otherwise never show it.
    if (s.restarts_recent > 0 && s.status.state != io::SourceState::down) {
      w.push_back(s.name + " recovered " + std::to_string(s.restarts_recent) + "x (" + s.status.detail + ")");
    }
  }
  const J1939Report& j = r.j1939;
  if (j.gaps_recent > 0)
    w.push_back("j1939: " + std::to_string(j.gaps_recent) + " gaps in periodic messages (frames lost before the gateway)");
  if (j.repeats_recent > 0) w.push_back("j1939: " + std::to_string(j.repeats_recent) + " frames repeated");
  if (j.tp_incomplete_recent > 0) w.push_back("j1939: " + std::to_string(j.tp_incomplete_recent) + " transport sessions incomplete");
  if (j.tp_anomaly_rate >= kTpFloodPerSecond) {
    w.push_back("SECURITY j1939: transport-protocol flood, " + fmt("%.0f", j.tp_anomaly_rate) +
                " orphan or unfinished transport frames/s (a denial-of-service pattern; sessions stay bounded)");
  }
  if (r.sync.clock_steps > 0) w.push_back("wall clock stepped " + std::to_string(r.sync.clock_steps) + "x (data unaffected)");
  if (r.estimate.started && !r.estimate.identified) {
    w.push_back(std::string("CRR not identified yet: ") +
                (r.estimate.not_identified ? r.estimate.not_identified : "no check has run"));
  }
  return w;
}

std::string format_text(const StatusReport& r) {
  std::string line = utc_text(r.utc_ns) + " up " + fmt("%.0f", r.uptime_s) + "s";
  const LiveEstimate& e = r.estimate;
  if (e.started) {
    line += " | speed " + fmt("%.2f", e.speed_mps) + " m/s";
    line += " cell " + (r.cell.empty() ? std::string("-") : r.cell);
    line += " crr " + fmt("%.5f", e.crr) + " [" + fmt("%.5f", e.crr_lo) + " " + fmt("%.5f", e.crr_hi) + "]";
  } else {
    line += " | no speed yet";
  }
  if (r.dynamic_power_w >= 0) line += " dyn " + fmt("%.0f", r.dynamic_power_w) + " W";
  for (const SourceReport& s : r.sources) {
    line += " | " + s.name + " " + io::to_string(s.status.state) + " " + fmt("%.0f", s.rate_per_s) + "/s";
    if (s.kind == SourceKind::can) line += " load " + fmt("%.0f", 100 * s.bus_load) + "%";
    line += " drop " + std::to_string(s.status.dropped + s.ring_dropped) + " err " + std::to_string(s.status.errors);
  }
  if (r.recording_enabled) {
    line += " | rec " + (r.recording.segment.empty() ? std::string("none") : r.recording.segment) + " " +
            fmt("%.1f", static_cast<double>(r.recording.bytes_in_dir) / (1 << 20)) + " MiB lost " +
            std::to_string(r.recording.lines_lost);
  }
  const J1939Report& j = r.j1939;
  if (j.cadence.gaps + j.cadence.repeats + j.tp_incomplete > 0) {
    line += " | j1939 gaps " + std::to_string(j.cadence.gaps) + " repeats " + std::to_string(j.cadence.repeats) + " tp-incomplete " +
            std::to_string(j.tp_incomplete);
  }
  line += r.sync.clock_steps == 0 && r.sync.unplaced_stamps == 0 ? " | sync ok" : " | sync degraded";
  for (const std::string& w : r.warnings) line += " | WARN " + w;
  return line + "\n";
}

std::string format_json(const StatusReport& r) {
  const LiveEstimate& e = r.estimate;
  std::string j = "{\"time\":" + results::json_quote(utc_text(r.utc_ns)) + ",\"uptime_s\":" + fmt("%.1f", r.uptime_s);
  if (e.started) {
    j += ",\"speed_mps\":" + json_number(e.speed_mps) + ",\"s_m\":" + json_number(e.s_front_m, "%.1f");
    j += ",\"cell\":" + (r.cell.empty() ? std::string("null") : results::json_quote(r.cell));
    j += ",\"crr\":" + json_number(e.crr) + ",\"crr_lo\":" + json_number(e.crr_lo) + ",\"crr_hi\":" + json_number(e.crr_hi);
    j += std::string(",\"crr_identified\":") + (e.identified ? "true" : "false");
    j += ",\"crr_not_identified\":" + (e.not_identified ? results::json_quote(e.not_identified) : std::string("null"));
  }
  j += ",\"dynamic_power_w\":" + (r.dynamic_power_w >= 0 ? json_number(r.dynamic_power_w, "%.1f") : std::string("null"));
  j += ",\"sources\":[";
  for (std::size_t i = 0; i < r.sources.size(); ++i) {
    const SourceReport& s = r.sources[i];
    j += (i ? ",{" : "{") + std::string("\"name\":") + results::json_quote(s.name) +
         ",\"kind\":" + results::json_quote(to_string(s.kind));
    j += ",\"state\":" + results::json_quote(io::to_string(s.status.state)) + ",\"items\":" + std::to_string(s.status.items);
    j += ",\"rate_per_s\":" + json_number(s.rate_per_s, "%.1f");
    if (s.kind == SourceKind::can) j += ",\"bus_load\":" + json_number(s.bus_load, "%.4f");
    j += ",\"dropped\":" + std::to_string(s.status.dropped) + ",\"ring_dropped\":" + std::to_string(s.ring_dropped);
    j += ",\"errors\":" + std::to_string(s.status.errors) + ",\"restarts\":" + std::to_string(s.status.restarts);
    j += ",\"detail\":" + results::json_quote(s.status.detail) + "}";
  }
  j += "]";
  if (r.recording_enabled) {
    const RecorderStatus& rec = r.recording;
    j += ",\"recording\":{\"segment\":" + results::json_quote(rec.segment) + ",\"lines\":" + std::to_string(rec.lines);
    j += ",\"lines_lost\":" + std::to_string(rec.lines_lost) + ",\"bytes_in_dir\":" + std::to_string(rec.bytes_in_dir);
    j += ",\"segments_deleted\":" + std::to_string(rec.segments_deleted) + ",\"error\":" + results::json_quote(rec.error_text) + "}";
  }
  j += ",\"sync\":{\"clock_steps\":" + std::to_string(r.sync.clock_steps) +
       ",\"unplaced_stamps\":" + std::to_string(r.sync.unplaced_stamps) + "}";
  j += ",\"j1939\":{\"gaps\":" + std::to_string(r.j1939.cadence.gaps) + ",\"repeats\":" + std::to_string(r.j1939.cadence.repeats) +
       ",\"untracked\":" + std::to_string(r.j1939.cadence.untracked) + ",\"too_fast\":" + std::to_string(r.j1939.cadence.too_fast) +
       ",\"tp_completed\":" + std::to_string(r.j1939.tp_completed) + ",\"tp_incomplete\":" + std::to_string(r.j1939.tp_incomplete) +
       ",\"tp_anomalies\":" + std::to_string(r.j1939.tp_anomalies) + ",\"tp_anomaly_rate\":" + fmt("%.1f", r.j1939.tp_anomaly_rate) +
       "}";
  j += ",\"warnings\":[";
  for (std::size_t i = 0; i < r.warnings.size(); ++i) j += (i ? "," : "") + results::json_quote(r.warnings[i]);
  return j + "]}\n";
}

}  // namespace roadload::firmware
