#include "analyze_provenance.hpp"

#include <cstdint>
#include <cstdio>

#include "roadload/content_hash.hpp"
#include "roadload/utc_text.hpp"
#include "roadload/vehicle_file.hpp"

namespace roadload::cli {

Provenance provenance(const AnalyzeOptions& o, const recording::Metadata& meta, const Vehicle& vehicle, const std::string& assumed,
                      const RecordedTrack& track, const AnalyzerConfig& cfg, const RouteIdentity& road) {
  Provenance p;
  p.program = std::string("roadload ") + ROADLOAD_VERSION;
  p.route_name = road.name;
  p.route_hash = road.hash;
  p.recordings = o.recordings;
  p.recording_id = meta.recording_id;
  p.vehicle = vehicle.name;
  p.vin = vehicle.vin;
  p.vehicle_source = !assumed.empty()     ? assumed
                     : !o.vehicle.empty() ? "--vehicle " + o.vehicle
                                          : std::string("the recording's meta.toml");
  p.route = o.route.empty() ? "traced from the recording's GNSS (" + track.source + ")" : o.route;
  const auto utc_of = [&](const GnssFix& f) -> std::int64_t {
    return f.utc_ns > 0 ? f.utc_ns : meta.utc_offset_ns ? to_ns(f.t) + *meta.utc_offset_ns : 0;
  };
  for (const GnssFix& f : track.fixes) {
    if (utc_of(f) <= 0) continue;
    p.drive_start_utc = utc_text(utc_of(f));
    break;
  }
  for (auto f = track.fixes.rbegin(); f != track.fixes.rend(); ++f) {
    if (utc_of(*f) <= 0) continue;
    p.drive_end_utc = utc_text(utc_of(*f));
    break;
  }
  p.vehicle_hash = content_hash(format_vehicle(vehicle));
  p.engine_losses = results::engine_losses_text(o.losses_file);
  p.cda = results::cda_text(cfg.filter.truck.cda_prior_m2, cfg.filter.truck.cda_sigma_m2, o.cda_m2 ? "--cda" : "the vehicle file");
  if (o.torque_scale || o.torque_scale_sigma) {
    char ts[64];
    std::snprintf(ts, sizeof ts, "%+.4f +- %.4f", o.torque_scale.value_or(0), o.torque_scale_sigma.value_or(0));
    p.torque_scale = ts;
  }
  return p;
}

}  // namespace roadload::cli
